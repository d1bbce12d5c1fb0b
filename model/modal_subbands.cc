// SubBandEdges and NearInnerEdge (model/modal_subbands.h).
#include "model/modal_subbands.h"

#include <algorithm>
#include <cmath>

namespace shapebench::model {

std::vector<std::size_t> SubBandEdges(const std::vector<std::vector<std::complex<double>>>& frfs) {
  const std::size_t lines = frfs.front().size();
  std::vector<double> sum(lines, 0.0);
  for (const auto& frf : frfs) {
    for (std::size_t k = 0; k < lines; ++k) sum[k] += std::abs(frf[k]);
  }
  const std::size_t parts = (lines + kSubBandLines - 1) / kSubBandLines;
  const std::size_t reach = lines / (8 * parts);
  std::vector<std::size_t> edges = {0};
  for (std::size_t i = 1; i < parts; ++i) {
    const std::size_t nominal = i * lines / parts;
    const auto first = sum.begin() + static_cast<std::ptrdiff_t>(nominal - reach);
    const auto last = sum.begin() + static_cast<std::ptrdiff_t>(nominal + reach + 1);
    edges.push_back(static_cast<std::size_t>(std::min_element(first, last) - sum.begin()));
  }
  edges.push_back(lines - 1);
  return edges;
}

bool NearInnerEdge(double frequency_hz, const std::vector<double>& edges_hz, double line_spacing_hz) {
  for (std::size_t i = 1; i + 1 < edges_hz.size(); ++i) {
    if (std::abs(frequency_hz - edges_hz[i]) <= 2.0 * line_spacing_hz) return true;
  }
  return false;
}

}  // namespace shapebench::model

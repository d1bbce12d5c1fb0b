// ReadSlice (bench/sweep/sweep_slice.h).
#include "bench/sweep/sweep_slice.h"

#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#include "common/csv.h"
#include "common/fd_stream.h"
#include "bench/output/report.h"

namespace shapebench::bench {
namespace {

const double kNoValue = std::numeric_limits<double>::quiet_NaN();

}  // namespace

bool ParseNumber(const std::string& text, double* value) {
  if (text.empty()) return false;
  char* end = nullptr;
  *value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && std::isfinite(*value);
}

Slice ReadSlice(const SweepLayout& layout, const std::string& results_csv, const std::string& metric,
                const std::string& x_key, const std::string& y_key, bool scaled) {
  auto key_index = [&](const std::string& key) {
    for (std::size_t i = 0; i < layout.keys.size(); ++i) {
      if (layout.keys[i] == key) return i;
    }
    throw std::runtime_error("plot key '" + key + "' is not a column of " + results_csv);
  };
  const std::size_t kx = key_index(x_key);
  const std::size_t ax = layout.key_axis[kx];
  const bool has_y = !y_key.empty();
  const std::size_t ky = has_y ? key_index(y_key) : 0;
  const std::size_t ay = has_y ? layout.key_axis[ky] : layout.axis_sizes.size();
  const std::size_t nx = layout.axis_sizes[ax];
  const std::size_t ny = has_y ? layout.axis_sizes[ay] : 1;

  std::size_t metric_column = 0;
  for (std::size_t i = 0; i < layout.metrics.size(); ++i) {
    if (layout.metrics[i] == metric) metric_column = 1 + layout.keys.size() + i;
  }
  if (metric_column == 0) throw std::runtime_error("metric '" + metric + "' is not a column of " + results_csv);

  Slice slice;
  slice.x.texts.assign(nx, "");
  slice.y.texts.assign(ny, "");
  slice.x.log = layout.key_log[kx];
  slice.y.log = has_y && layout.key_log[ky];
  slice.z.assign(nx * ny, kNoValue);

  InputFile in(results_csv);
  CsvReader reader(in.stream());
  std::vector<std::string> fields;
  reader.Next(&fields);  // header
  const double scale = scaled ? MetricScale(metric) : 1.0;
  bool fixed_done = false;
  while (reader.Next(&fields)) {
    if (fields.size() != 3 + layout.keys.size() + layout.metrics.size()) continue;
    std::uint64_t point = std::strtoull(fields[0].c_str(), nullptr, 10);
    std::vector<std::uint64_t> digits(layout.axis_sizes.size(), 0);
    for (std::size_t a = layout.axis_sizes.size(); a-- > 0;) {
      digits[a] = point % layout.axis_sizes[a];
      point /= layout.axis_sizes[a];
    }
    bool in_slice = true;
    for (std::size_t a = 0; a < digits.size(); ++a) {
      if (a != ax && a != ay && digits[a] != 0) in_slice = false;
    }
    if (!in_slice) continue;
    const std::size_t ix = digits[ax];
    const std::size_t iy = has_y ? digits[ay] : 0;
    slice.x.texts[ix] = fields[1 + kx];
    if (has_y) slice.y.texts[iy] = fields[1 + ky];
    double value = kNoValue;
    if (ParseNumber(fields[metric_column], &value)) slice.z[iy * nx + ix] = value * scale;
    if (!fixed_done) {
      for (std::size_t k = 0; k < layout.keys.size(); ++k) {
        const std::size_t a = layout.key_axis[k];
        if (a == ax || a == ay) continue;
        slice.fixed += (slice.fixed.empty() ? "" : ", ") + layout.keys[k] + "=" + fields[1 + k];
      }
      fixed_done = true;
    }
  }
  in.ThrowIfFailed();
  slice.x.Finish();
  slice.y.Finish();
  return slice;
}

bool AxisValues::Uniform() const {
  if (!numeric || log || numbers.size() < 2) return numeric && !log;
  const double step = (numbers.back() - numbers.front()) / static_cast<double>(numbers.size() - 1);
  if (step == 0.0) return false;
  for (std::size_t i = 1; i < numbers.size(); ++i) {
    if (std::abs(numbers[i] - numbers[i - 1] - step) > 1e-9 * std::abs(step)) return false;
  }
  return true;
}

void AxisValues::Finish() {
  numbers.assign(texts.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < texts.size(); ++i) numeric = numeric && ParseNumber(texts[i], &numbers[i]);
}

double MetricScale(const std::string& metric) { return MetricUnit(metric) == "m" ? 1e6 : 1.0; }

}  // namespace shapebench::bench

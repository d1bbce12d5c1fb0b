// RunPlotTitle, DeflectionIsZero, PathIsSingleAxisLine (bench/output/report.h).
#include <algorithm>
#include <string>

#include "bench/output/report.h"
#include "controller/path_geometry.h"

namespace shapebench::bench {
namespace {

// `text` cut to `limit` characters with "..." at the cut (on a UTF-8 lead byte, so no
// character is split).
std::string Shortened(const std::string& text, std::size_t limit) {
  if (text.size() <= limit) return text;
  std::size_t cut = limit - 3;
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;
  return text.substr(0, cut) + "...";
}

}  // namespace

std::string RunPlotTitle(const Scenario& scenario, const std::vector<Override>& overrides) {
  std::string title = scenario.name + ", method " + scenario.controller.pattern.method;
  std::string sets;
  for (const Override& set : overrides) {
    sets += (sets.empty() ? "" : " ") + set.key_path + "=" + Shortened(set.value_yaml, 24);
  }
  if (!sets.empty()) title += ", --set " + Shortened(sets, 160);
  return title;
}

bool DeflectionIsZero(const RunResult& result) {
  const auto& deflection = result.trace.deflection_m;
  return std::all_of(deflection.begin(), deflection.end(), [](double d) { return d == 0.0; });
}

bool PathIsSingleAxisLine(const RunResult& result) {
  const controller::PathGeometry path(result.program);
  const Eigen::Vector3d start = path.start_m();
  bool same_x = true;
  bool same_y = true;
  for (const controller::PathElement& element : path.elements()) {
    if (element.is_arc()) return false;
    const Eigen::Vector3d end = element.PointAtFraction(1.0);
    same_x = same_x && end.x() == start.x();
    same_y = same_y && end.y() == start.y();
  }
  return same_x || same_y;
}

}  // namespace shapebench::bench

// AttributeSources, SourceText (bench/run/metric_sources.h).
#include "bench/run/metric_sources.h"

#include <algorithm>
#include <cmath>

#include "common/format.h"

namespace shapebench::bench {
namespace {

// The site at time `tick` x period: the interpolator's block then (-1 past its ticks).
ProgramSite SiteAt(const controller::MultiAxisCommand& command, const controller::Program& program,
                   std::size_t tick) {
  ProgramSite site;
  site.time_s = static_cast<double>(tick) * command.period_s;
  site.block = tick < command.block.size() ? command.block[tick] : -1;
  if (site.block >= 0 && static_cast<std::size_t>(site.block) < program.blocks.size() &&
      !program.source_file.empty() && program.gcode_lines) {
    site.file = program.source_file;
    site.line = program.blocks[static_cast<std::size_t>(site.block)].source_line;
  }
  return site;
}

MetricSource Attribute(const controller::MultiAxisCommand& command, const controller::Program& program,
                       std::size_t tick, double lookback_s, double threshold_m_s2) {
  MetricSource source;
  source.present = true;
  source.at = SiteAt(command, program, tick);
  // accel_m_s2(k) is held over period k, from (k - 1) T to k T: a change between periods
  // k - 1 and k happens at (k - 1) T, in the block the interpolator is in then (at a corner
  // taken at speed, the block that leaves it: the line that turns).
  const std::size_t last = std::min(tick, command.num_ticks());
  const auto ticks_back = static_cast<std::size_t>(std::ceil(lookback_s / command.period_s));
  const std::size_t first = last > ticks_back + 1 ? last - ticks_back : 1;
  // At rest before the first period.
  const auto accel = [&](std::size_t k) { return k == 0 ? Eigen::Vector3d::Zero().eval() : command.accel_m_s2(k); };
  const auto changes = [&](std::size_t k) { return (accel(k) - accel(k - 1)).norm() > threshold_m_s2; };
  source.cause = source.at;
  for (std::size_t k = last; k >= first && k >= 1; --k) {
    if (!changes(k)) continue;
    source.cause = SiteAt(command, program, k - 1);  // the tick at which it happened
    break;
  }
  return source;
}

std::string SiteText(const ProgramSite& site) {
  std::string text = "at " + EngineeringText(site.time_s, "s", 6);
  if (site.block < 0) return text + " after the program";
  text += " in block " + std::to_string(site.block);
  if (!site.file.empty()) text += " (" + site.file + ":" + std::to_string(site.line) + ")";
  return text;
}

}  // namespace

MetricSources AttributeSources(const controller::MultiAxisCommand& command, const controller::Program& program,
                               std::size_t peak_tick, std::size_t contour_tick, std::size_t cruise_tick,
                               bool has_cruise, double lookback_s) {
  // A change is one above the rounding of the velocity differences: 1e-9 of the largest
  // commanded acceleration.
  double largest_m_s2 = 0.0;
  std::size_t largest_tick = 0;
  for (std::size_t k = 1; k <= command.num_ticks(); ++k) {
    const double here = command.accel_m_s2(k).norm();
    if (here > largest_m_s2) {
      largest_m_s2 = here;
      largest_tick = k;
    }
  }
  const double threshold = 1e-9 * largest_m_s2;
  MetricSources sources;
  if (largest_tick > 0) {
    sources.peak_command_acceleration = Attribute(command, program, largest_tick, lookback_s, threshold);
  }
  sources.peak_deflection = Attribute(command, program, peak_tick, lookback_s, threshold);
  sources.max_contour_error = Attribute(command, program, contour_tick, lookback_s, threshold);
  if (has_cruise) sources.cruise_residual = Attribute(command, program, cruise_tick, lookback_s, threshold);
  return sources;
}

std::string SourceText(const MetricSource& source) {
  if (!source.present) return "n/a";
  return SiteText(source.at) + "; cause " + SiteText(source.cause);
}

}  // namespace shapebench::bench

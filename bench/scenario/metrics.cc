#include "bench/scenario/metrics.h"

#include <iterator>

namespace shapebench::bench {

namespace {

using M = Metrics;

// MetricTable's rows: a constant table (constexpr: built at compile time), not code; the
// number of metrics is its size.
constexpr MetricInfo kMetricRows[] = {
      {"static_displacement_m", "m", Better::kLower,
       "the deflection under the run's largest commanded acceleration held constant (a static "
       "solve of the model; a program: the acc/dec's configured acceleration along the direction "
       "of the program that deflects most, [concepts](concepts.md#static-displacement-peak-and-"
       "residual-the-metrics)): the reference of every ratio (the ratios are n/a when it is 0: a "
       "model whose static deflections cancel in the output view)",
       &M::static_displacement_m},
      {"peak_deflection_m", "m", Better::kLower,
       "the largest absolute deflection over the run (motion and tail)", &M::peak_deflection_m},
      {"peak_ratio", "1", Better::kLower,
       "peak_deflection_m / static_displacement_m (the patent's aim: 1; an unshaped step: 2)",
       &M::peak_ratio},
      {"residual_amplitude_m", "m", Better::kLower,
       "the amplitude of the free vibration the structure holds when commanded motion ends, from "
       "its state then (input 0 after): with A = V diag(lambda) V^-1 and x = V z, per pole of "
       "the plant the modulus of 2 C v z (a pair: its envelope) or of C v z (a real pole) in the "
       "output view, summed (one modal mode: abs(gain) sqrt(q^2 + ((q' + zeta w q) / w_d)^2)); a "
       "pair's envelope is capped at K times the largest absolute value of its free response, K = "
       "exp(pi z / sqrt(1 - z^2)), z = min(zeta, 1 - zeta) (the cap never acts for zeta <= 0.5; as "
       "zeta -> 1, where the envelope grows as 1 / w_d, the amplitude tends to that largest value); "
       "a bound of every later deflection. A plant with nonlinear elements has no modes: half the "
       "peak-to-peak of its deflection sampled from motion end to the run's end (its free "
       "response; one undamped mode's amplitude exactly)",
       &M::residual_amplitude_m},
      {"residual_ratio", "1", Better::kLower,
       "residual_amplitude_m / static_displacement_m (the input-shaping literature's residual "
       "vibration; independent of where in its cycle the vibration is when motion ends)",
       &M::residual_ratio},
      {"residual_peak_m", "m", Better::kLower,
       "the largest absolute deflection sampled from the end of commanded motion to three periods "
       "of the lowest mode later",
       &M::residual_peak_m},
      {"residual_peak_ratio", "1", Better::kLower, "residual_peak_m / static_displacement_m",
       &M::residual_peak_ratio},
      {"cruise_residual_ratio", "1", Better::kLower,
       "the amplitude of the free vibration about the cruise equilibrium (the static state at the "
       "cruise velocity, x_eq = -A^-1 B_vel v), as residual_amplitude_m, from the state one "
       "lowest-mode period into each stretch where the commanded feed stays constant and non-zero "
       "for at least that long; the largest stretch's, / static_displacement_m (n/a for a plant "
       "with nonlinear elements)",
       &M::cruise_residual_ratio},
      {"motion_time_s", "s", Better::kLower, "when commanded motion ends", &M::motion_time_s},
      {"settling_time_s", "s", Better::kLower,
       "from the end of motion until the absolute deflection stays below 5% of static_displacement_m",
       &M::settling_time_s},
      {"max_contour_error_m", "m", Better::kLower,
       "the largest distance of the actual tool path from the programmed path",
       &M::max_contour_error_m},
      {"radial_error_m", "m", Better::kLower,
       "programmed radius minus the mean actual radius over the middle half of each arc, the "
       "worst arc (signed; smaller magnitude is better)",
       &M::radial_error_m},
      {"peak_deflection_x_m", "m", Better::kLower, "the largest absolute deflection along X",
       &M::peak_deflection_x_m},
      {"peak_deflection_y_m", "m", Better::kLower, "the largest absolute deflection along Y",
       &M::peak_deflection_y_m},
      {"peak_deflection_z_m", "m", Better::kLower, "the largest absolute deflection along Z",
       &M::peak_deflection_z_m},
      {"static_displacement_x_m", "m", Better::kLower,
       "the X component of the static tool deflection vector C a under the held commanded "
       "acceleration a that gives static_displacement_m (C: the machine's static compliance, "
       "cross terms included), signed, a taken in the positive sense of the axis it mostly lies "
       "along, whatever the output view; 0 off the moved axis of an uncoupled machine",
       &M::static_displacement_x_m},
      {"static_displacement_y_m", "m", Better::kLower, "as static_displacement_x_m, along Y",
       &M::static_displacement_y_m},
      {"static_displacement_z_m", "m", Better::kLower, "as static_displacement_x_m, along Z",
       &M::static_displacement_z_m},
      {"short_block_clamps", "count", Better::kLower,
       "blocks whose feed the short-block clamp lowered (CN104175175, seed 002)",
       &M::short_block_clamps},
      {"stroke_overshoot_m", "m", Better::kLower,
       "the largest travel beyond a stroke end, 0 if none (EP0646852, seed 001)",
       &M::stroke_overshoot_m},
      {"stroke_alarm", "bool", Better::kLower,
       "true when the stroke check stopped the tool before the program's end",
       &M::stroke_alarm},
      {"peak_command_acceleration_m_s2", "m/s^2", Better::kLower,
       "the largest norm of the commanded acceleration vector over the run (the acceleration "
       "held over an interpolation period, the axes' components together); where it happened: "
       "`peak_command_acceleration_source` ([attribution](views.md#attribution))",
       &M::peak_command_acceleration_m_s2},
      {"pattern_frequency_hz", "Hz", Better::kLower,
       "the natural frequency the pattern was designed for (the lowest of several; given, or the "
       "machine's lowest participating mode); n/a for a pattern without one (none, custom, mode off)",
       &M::pattern_frequency_hz},
      {"pattern_damping_ratio", "1", Better::kLower,
       "the damping ratio that design frequency's shaper was designed for (methods 1-4: 0); n/a "
       "as pattern_frequency_hz",
       &M::pattern_damping_ratio},
};

}  // namespace

const std::vector<MetricInfo>& MetricTable() {
  static const std::vector<MetricInfo> table(std::begin(kMetricRows), std::end(kMetricRows));
  return table;
}

const std::vector<MetricInfo>& NonlinearMetricTable() {
  using M = Metrics;
  static const std::vector<MetricInfo> table = {
      {"dead_band_m", "m", Better::kLower,
       "the final resting deflection: the absolute deflection in the view at the run's last "
       "sample, where friction left the structure stuck (n/a for a linear plant, which comes "
       "to rest at 0)",
       &M::dead_band_m},
      {"quadrant_glitch_m", "m", Better::kLower,
       "on arcs: the largest radial spike at an axis reversal, the actual radius's largest "
       "deviation within +-5 degrees of each angle where the tangent lies along an axis (at "
       "least 5 degrees inside the arc), from the median radial deviation over the arc's "
       "middle half; n/a without such a reversal or for a linear plant",
       &M::quadrant_glitch_m},
  };
  return table;
}

const MetricInfo* FindMetric(std::string_view name) {
  for (const MetricInfo& info : MetricTable()) {
    if (info.name == name) return &info;
  }
  for (const MetricInfo& info : NonlinearMetricTable()) {
    if (info.name == name) return &info;
  }
  return nullptr;
}

std::vector<std::string> AllMetricNames() {
  std::vector<std::string> names = MetricNames();
  for (const MetricInfo& info : NonlinearMetricTable()) names.emplace_back(info.name);
  return names;
}

std::vector<std::string> MetricNames() {
  std::vector<std::string> names;
  for (const MetricInfo& info : MetricTable()) names.emplace_back(info.name);
  return names;
}

std::string_view BetterName(Better better) { return better == Better::kLower ? "lower" : "higher"; }

std::vector<std::pair<std::string, double>> Metrics::Named() const {
  std::vector<std::pair<std::string, double>> named;
  named.reserve(MetricTable().size());
  for (const MetricInfo& info : MetricTable()) named.emplace_back(std::string(info.name), this->*info.field);
  return named;
}

}  // namespace shapebench::bench

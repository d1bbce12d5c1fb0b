// The metrics of one run (SPEC section 4), SI units. NaN means "not defined for this run"
// (no cruise phase; never settled within the simulated time) and is written as null.
#pragma once

#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace shapebench::bench {

struct Metrics {
  double static_displacement_m = NAN;
  double peak_deflection_m = NAN;
  double peak_ratio = NAN;
  double residual_amplitude_m = NAN;
  double residual_ratio = NAN;
  double cruise_residual_ratio = NAN;
  double motion_time_s = NAN;
  double settling_time_s = NAN;
  // Pipeline metrics (SPEC section 4).
  double max_contour_error_m = NAN;  // distance of the tool path from the programmed path
  double radial_error_m = NAN;       // programmed minus mean actual radius, worst arc
  // Peak |deflection| per axis component.
  double peak_deflection_x_m = NAN;
  double peak_deflection_y_m = NAN;
  double peak_deflection_z_m = NAN;
  // Feed-rate safeguards (seeds 002, 001).
  double short_block_clamps = NAN;  // blocks whose feed the clamp lowered (a count)
  double stroke_overshoot_m = NAN;  // largest travel beyond a stroke end, 0 if none
  double stroke_alarm = NAN;        // 1 when the stroke check stopped the tool, else 0 (JSON: bool)

  // (name, value) in the SPEC's order: the one list the table, JSON, CSV and checks use.
  std::vector<std::pair<std::string, double>> Named() const;
};

}  // namespace shapebench::bench

#include "bench/sim/metrics.h"

namespace shapebench::bench {

std::vector<std::pair<std::string, double>> Metrics::Named() const {
  return {{"static_displacement_m", static_displacement_m},
          {"peak_deflection_m", peak_deflection_m},
          {"peak_ratio", peak_ratio},
          {"residual_amplitude_m", residual_amplitude_m},
          {"residual_ratio", residual_ratio},
          {"cruise_residual_ratio", cruise_residual_ratio},
          {"motion_time_s", motion_time_s},
          {"settling_time_s", settling_time_s},
          {"max_contour_error_m", max_contour_error_m},
          {"radial_error_m", radial_error_m},
          {"peak_deflection_x_m", peak_deflection_x_m},
          {"peak_deflection_y_m", peak_deflection_y_m},
          {"peak_deflection_z_m", peak_deflection_z_m},
          {"short_block_clamps", short_block_clamps},
          {"stroke_overshoot_m", stroke_overshoot_m},
          {"stroke_alarm", stroke_alarm}};
}

}  // namespace shapebench::bench

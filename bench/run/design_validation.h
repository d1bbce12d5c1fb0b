// `design --validate`: the designed pattern run by the bench itself over every band. For
// each band, at evenly spaced frequencies (and the band's damping ends), the scenario's
// driven axis is replaced by that one mode (its static deflection kept), and the scenario
// runs unshaped and with the design (profile_table: post_interp's table, pattern off;
// impulses: a custom pattern, controller.period_s set to the design's grid so that the
// impulses fall on interpolation periods). The ratio of the two runs' residual_amplitude_m
// is the bench's V; their peak_ratio beside it.
#pragma once

#include <string>
#include <vector>

#include "bench/scenario/scenario.h"
#include "controller/pattern_design.h"

namespace shapebench::bench {

constexpr int kValidationFrequencies = 9;  // per band, edges included

struct BandValidation {
  double worst_residual_ratio = 0.0;  // shaped / unshaped residual_amplitude_m, the largest
  double worst_at_hz = 0.0;
  double worst_at_damping = 0.0;
  double worst_peak_ratio = 0.0;  // the shaped runs' largest peak_ratio
  int runs = 0;
};

// `impulses_form`: the design as a custom pattern (else as a profile table). Throws
// ConfigError / ValidationError (a run the pattern does not fit) and model::SolverError.
std::vector<BandValidation> ValidateDesign(const Scenario& scenario, const controller::DesignSpec& spec,
                                           const controller::DesignResult& design, bool impulses_form);

}  // namespace shapebench::bench

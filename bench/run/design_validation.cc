// The validation runs of `design --validate` (see the header).
#include "bench/run/design_validation.h"

#include <algorithm>

#include "bench/run/run_scenario.h"
#include "common/math_constants.h"
#include "model/multi_axis_machine.h"

namespace shapebench::bench {
namespace {

// The scenario with the driven axis' model replaced by one mode of `frequency_hz` and
// `damping_ratio` whose static deflection is the axis' own.
Scenario OneModeScenario(const Scenario& base, double static_deflection, double frequency_hz, double damping_ratio) {
  Scenario s = base;
  model::ModalMachineConfig machine;
  const double w = 2.0 * kPi * frequency_hz;
  // gain / w^2 is the static deflection per m/s^2.
  machine.modes = {model::ModalMode{frequency_hz, damping_ratio, static_deflection * w * w}};
  s.machine.axes[s.machine.driven_axis] = model::MachineConfig{machine};
  return s;
}

Metrics RunOnce(const Scenario& s) {
  RunOptions options;
  options.record_trace = false;
  return RunScenario(s, options).metrics;
}

}  // namespace

std::vector<BandValidation> ValidateDesign(const Scenario& scenario, const controller::DesignSpec& spec,
                                           const controller::DesignResult& design, bool impulses_form) {
  double static_deflection = 0.0;
  for (const model::AxisModes& axis : model::AnalyzeMachineModes(scenario.machine)) {
    if (axis.axis == scenario.machine.driven_axis) static_deflection = axis.analysis.static_deflection_per_accel_s2;
  }
  if (!(static_deflection > 0.0)) static_deflection = 1e-6;  // a rigid driven axis: any scale does
  Scenario unshaped = scenario;
  unshaped.controller.pattern.method = controller::kNoShaping;
  unshaped.controller.post_interp = controller::PostInterpConfig{};
  Scenario shaped = unshaped;
  if (impulses_form) {
    shaped.controller.period_s = design.grid_s;
    unshaped.controller.period_s = design.grid_s;
    shaped.controller.pattern.method = "custom";
    for (std::size_t k = 0; k < design.coefficients.size(); ++k) {
      if (design.coefficients[k] != 0.0) shaped.controller.pattern.impulses.push_back({k * design.grid_s, design.coefficients[k]});
    }
  } else {
    shaped.controller.post_interp.type = controller::PostInterpType::kProfileTable;
    shaped.controller.post_interp.table = design.coefficients;
    shaped.controller.post_interp.max_table_length =
        std::max<int>(shaped.controller.post_interp.max_table_length, static_cast<int>(design.coefficients.size()));
  }
  std::vector<BandValidation> bands;
  for (const controller::DesignBand& band : spec.bands) {
    BandValidation v;
    std::vector<double> dampings{band.damping_lo};
    if (band.damping_hi > band.damping_lo) dampings.push_back(band.damping_hi);
    const int count = band.frequency_hi_hz > band.frequency_lo_hz ? kValidationFrequencies : 1;
    for (int i = 0; i < count; ++i) {
      const double f = count == 1 ? band.frequency_lo_hz
                                  : band.frequency_lo_hz + (band.frequency_hi_hz - band.frequency_lo_hz) * i / (count - 1);
      for (double z : dampings) {
        const Metrics none = RunOnce(OneModeScenario(unshaped, static_deflection, f, z));
        const Metrics with = RunOnce(OneModeScenario(shaped, static_deflection, f, z));
        const double ratio = with.residual_amplitude_m / none.residual_amplitude_m;
        if (ratio > v.worst_residual_ratio) {
          v.worst_residual_ratio = ratio;
          v.worst_at_hz = f;
          v.worst_at_damping = z;
        }
        v.worst_peak_ratio = std::max(v.worst_peak_ratio, with.peak_ratio);
        v.runs += 2;
      }
    }
    bands.push_back(v);
  }
  return bands;
}

}  // namespace shapebench::bench

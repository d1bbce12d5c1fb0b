#include "bench/run/unit_slips.h"

#include <cmath>
#include <variant>

#include "common/format.h"

namespace shapebench::bench {
namespace {

// "1 s ... did you mean 1 ms (KEY: 0.001)?": a time written in milliseconds.
std::string MillisecondSlip(const std::string& key, double value_s, const std::string& what, double threshold_s) {
  return key + ": " + FormatNumber(value_s) + " s is " + what + " (warned above " + FormatNumber(threshold_s) +
         " s): did you mean " + FormatNumber(value_s) + " ms (" + key + ": " + FormatNumber(value_s * 1e-3) + ")?";
}

// A YAML mode below kUnitSlipModeHz, by its key; the lowest of any other form (lumped
// bodies, a modal or FRF file) without one. True when any was found.
bool AddLowModeWarnings(const RunPlan& plan, std::vector<std::string>* warnings) {
  const model::MultiAxisMachineConfig& machine = plan.scenario.machine;
  bool named = false;
  for (int a = 0; a < model::kNumAxes; ++a) {
    if (!machine.axes[a]) continue;
    const auto* modal = std::get_if<model::ModalMachineConfig>(&machine.axes[a]->form);
    if (modal == nullptr || !modal->modal_file.empty()) continue;
    const std::string prefix = machine.AxisPrefix(a);
    for (std::size_t i = 0; i < modal->modes.size(); ++i) {
      const double hz = modal->modes[i].frequency_hz;
      if (!(hz > 0.0 && hz < kUnitSlipModeHz)) continue;
      const std::string key = "machine." + (prefix.empty() ? "" : prefix + ".") + "modes[" + std::to_string(i) +
                              "].frequency_hz";
      warnings->push_back(key + ": " + FormatNumber(hz) + " Hz is below any machine structure's mode (warned below " +
                          FormatNumber(kUnitSlipModeHz) + " Hz): did you give its period in seconds (1/" +
                          FormatNumber(hz) + " s is " + FormatNumber(1.0 / hz) + " Hz) or kHz?");
      named = true;
    }
  }
  if (named) return true;
  double lowest_hz = INFINITY;
  for (const model::AxisModes& axis : plan.dynamics.axes) {
    for (const model::ModeInfo& mode : axis.analysis.modes) {
      if (mode.frequency_hz > 0.0) lowest_hz = std::min(lowest_hz, mode.frequency_hz);
    }
  }
  if (!(lowest_hz < kUnitSlipModeHz)) return false;
  warnings->push_back("machine: its lowest mode is at " + FormatNumber(lowest_hz) +
                      " Hz, below any machine structure's (warned below " + FormatNumber(kUnitSlipModeHz) +
                      " Hz): check the units of the masses (kg), stiffnesses (N/m) or the file's frequencies (Hz)");
  return true;
}

}  // namespace

std::vector<std::string> UnitSlipWarnings(const RunPlan& plan, const Metrics& metrics) {
  std::vector<std::string> warnings;
  const controller::ControllerConfig& controller = plan.scenario.controller;
  if (controller.period_s > kUnitSlipPeriodS) {
    warnings.push_back(MillisecondSlip("controller.period_s", controller.period_s,
                                       "longer than any CNC's interpolation period, 0.1 to 10 ms", kUnitSlipPeriodS));
  }
  if (controller.accel_time_s > kUnitSlipAccelTimeS) {
    warnings.push_back(MillisecondSlip("controller.accel_time_s", controller.accel_time_s,
                                       "longer than any machine tool's acc/dec time", kUnitSlipAccelTimeS));
  }
  const bool low_mode = AddLowModeWarnings(plan, &warnings);
  if (metrics.static_displacement_m > kUnitSlipStaticM) {
    warnings.push_back("static_displacement_m: " + EngineeringText(metrics.static_displacement_m, "m") +
                       " is no machine tool's deflection (warned above " + EngineeringText(kUnitSlipStaticM, "m") +
                       "; they deflect micrometres): " +
                       (low_mode ? "the mode above is the likely cause"
                                 : "check the units of the modes' frequency_hz (Hz) and gain, or the masses and "
                                   "stiffnesses"));
  }
  return warnings;
}

}  // namespace shapebench::bench

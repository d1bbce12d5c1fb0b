#include "bench/scenario/scenario_guards.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <variant>

#include "bench/scenario/run_memory.h"
#include "common/format.h"
#include "common/math_constants.h"
#include "common/shown_text.h"
#include "common/validation_error.h"
#include "controller/controller.h"
#include "controller/path_geometry.h"
#include "controller/shaper_registry.h"
#include "model/multi_axis_machine.h"
#include "model/nonlinear_integrator.h"

namespace shapebench::bench {
namespace {

std::string Seconds(double seconds) { return FormatNumber(seconds, 4) + " s"; }

model::MachinePlant BuildMachineAt(const Scenario& scenario) {
  try {
    return model::BuildMachinePlant(scenario.machine, scenario.drive);
  } catch (const ValidationError& error) {
    // The drive is validated already: what is left is the structure's (machine.elements[i]).
    throw error.Prefixed("machine");
  }
}

// Uncoupled modal forms under the kinematic drive: the plant's entries are w^2, 2 zeta w,
// 1 and the gains, its static gains gain / w^2 (model/machine.cc BuildFormPlant); finite
// when those are, with no plant to build (a sweep checks every point's numbers). False:
// another machine, or a number that is not finite (the plant's check then says so).
bool FiniteModalForms(const Scenario& scenario) {
  if (scenario.drive.type != model::DriveType::kKinematic) return false;
  for (const auto& axis : scenario.machine.axes) {
    if (!axis) continue;
    const auto* modal = std::get_if<model::ModalMachineConfig>(&axis->form);
    if (modal == nullptr || modal->coupled()) return false;
    for (const model::ModalMode& mode : modal->modes) {
      const double w = 2.0 * kPi * mode.frequency_hz;
      if (!std::isfinite(w * w) || !std::isfinite(2.0 * mode.damping_ratio * w) ||
          !std::isfinite(mode.gain / (w * w))) {
        return false;
      }
    }
  }
  return true;
}

// Guard rail: a run whose command, samples and trace would need more than
// limits.max_memory_mb (a tiny period within max_ticks) is refused before allocating.
void CheckRunMemory(const ConfigDocument& document, const Scenario& scenario, double seconds,
                    const std::string& breakdown) {
  const double ticks = seconds / scenario.controller.period_s;
  if (!(ticks > MemoryTickLimit(scenario.limits))) return;
  char text[96];
  std::snprintf(text, sizeof text, "%.4g MB (%.4g interpolation periods of %.4g s, %.0f bytes each",
                RunBytes(ticks) / MegabytesToBytes(1.0), ticks, scenario.controller.period_s,
                kRunBytesPerTick);
  throw document.ErrorAtPath(
      "limits.max_memory_mb",
      "scenario '" + ClippedForMessage(scenario.name) + "' would need at least " + text +
          " for its command, samples and trace; " + breakdown + "), more than limits.max_memory_mb (" +
          std::to_string(scenario.limits.max_memory_mb) +
          " MB a run; a sweep needs about --jobs times it); raise it or lengthen controller.period_s");
}

}  // namespace

void CheckPlantFinite(const Scenario& scenario) {
  if (FiniteModalForms(scenario)) return;
  const model::MachinePlant plant = BuildMachineAt(scenario);
  if (!plant.plant.A.allFinite() || !plant.plant.B_accel.allFinite() ||
      !plant.plant.B_vel.allFinite() || !plant.plant.C.allFinite() ||
      !plant.static_gain.allFinite()) {
    throw ValidationError("machine",
                          "degenerate model: its state-space matrices or static gain are not "
                          "finite (a frequency, stiffness, damping or gain too large, or a "
                          "mass too small, for double precision)");
  }
  // integrator.method: exact cannot take a nonlinear element (docs/nonlinear.md).
  try {
    model::CheckMethodFitsPlant(scenario.integrator.method, plant.nonlinear);
  } catch (const ValidationError& error) {
    throw error.Prefixed("integrator");
  }
}

bool RunLengthWithinLimits(const Scenario& scenario, double seconds) {
  const double ticks = seconds / scenario.controller.period_s;
  return !(seconds > scenario.limits.max_simulated_s) &&
         !(ticks > static_cast<double>(scenario.limits.max_ticks)) &&
         !(ticks > MemoryTickLimit(scenario.limits));
}

void CheckRunLength(const ConfigDocument& document, const Scenario& scenario) {
  std::string breakdown;
  const double seconds = MinimumRunSeconds(scenario, &breakdown);
  if (RunLengthWithinLimits(scenario, seconds)) return;
  const double ticks = seconds / scenario.controller.period_s;
  const RunLimits& limits = scenario.limits;
  // Both exceeded: the message names the limit that binds (the fewer ticks).
  const bool ticks_bind = ticks > static_cast<double>(limits.max_ticks) &&
                          static_cast<double>(limits.max_ticks) * scenario.controller.period_s <
                              limits.max_simulated_s;
  if (seconds > limits.max_simulated_s && !ticks_bind) {
    // The suggested limit as text (a double: the bound may exceed any integer type).
    char suggested[32];
    std::snprintf(suggested, sizeof suggested, "%.3g", std::ceil(seconds * 2.0));
    throw document.ErrorAtPath(
        "limits.max_simulated_s",
        "scenario '" + ClippedForMessage(scenario.name) + "' would simulate at least " + Seconds(seconds) + " (" +
            breakdown + "), more than limits.max_simulated_s (" + Seconds(limits.max_simulated_s) +
            (std::isfinite(seconds) ? "); raise it (e.g. --set limits.max_simulated_s=" +
                                          std::string(suggested) + ") to run it anyway"
                                    : "); its path is too long to simulate"));
  }
  if (ticks > static_cast<double>(limits.max_ticks)) {
    char count[32];
    std::snprintf(count, sizeof count, "%.4g", ticks);
    throw document.ErrorAtPath(
        "limits.max_ticks",
        "scenario '" + ClippedForMessage(scenario.name) + "' would take at least " + count +
            " interpolation periods of " + Seconds(scenario.controller.period_s) + " (" +
            breakdown + "), more than limits.max_ticks (" + std::to_string(limits.max_ticks) +
            "); raise it or lengthen controller.period_s");
  }
  CheckRunMemory(document, scenario, seconds, breakdown);
}

controller::GcodeLimits ParseLimits(const Scenario& scenario) {
  const RunLimits& limits = scenario.limits;
  const double period_s = scenario.controller.period_s;
  double ticks = limits.max_simulated_s / period_s;
  std::string key = "limits.max_simulated_s";
  if (static_cast<double>(limits.max_ticks) < ticks) {
    ticks = static_cast<double>(limits.max_ticks);
    key = "limits.max_ticks";
  }
  if (MemoryTickLimit(limits) < ticks) {
    ticks = MemoryTickLimit(limits);
    key = "limits.max_memory_mb";
  }
  controller::GcodeLimits parse;
  parse.max_path_s = ticks * period_s;
  parse.max_path_key = key;
  parse.default_feed_m_s = scenario.controller.feed_m_s();
  parse.rapid_feed_m_s = scenario.controller.rapid_feed_mm_min / 60000.0;
  const double memory_blocks = MegabytesToBytes(static_cast<double>(limits.max_memory_mb)) / kBytesPerBlock;
  const double blocks = std::min(ticks, memory_blocks);
  parse.max_blocks = static_cast<std::size_t>(std::max(1.0, std::floor(blocks)));
  parse.max_blocks_key = memory_blocks < ticks ? "limits.max_memory_mb (about " +
                                                     std::to_string(static_cast<long>(kBytesPerBlock)) +
                                                     " bytes a block)"
                                               : key + " (every block takes an interpolation period at least)";
  return parse;
}

double MinimumRunSeconds(const Scenario& scenario, std::string* breakdown) {
  const double motion_s = MinimumMotionSeconds(scenario, breakdown);
  const double tail_s = ResidualWindowSeconds(scenario);
  if (breakdown != nullptr) *breakdown += "; residual window " + Seconds(tail_s);
  return motion_s + tail_s;
}

namespace {
// ResidualWindowSeconds of a machine validated already (MachineChecksPass: a sweep point
// validated it a line before).
double ResidualWindowOfValidMachine(const Scenario& scenario) {
  const double lowest_hz = model::LowestModeHz(scenario.machine);
  return 3.0 * (std::isfinite(lowest_hz) && lowest_hz > 0.0 ? 1.0 / lowest_hz : 0.1);
}
}  // namespace

double ResidualWindowSeconds(const Scenario& scenario) {
  // Three periods of the lowest mode (0.1 s for a rigid machine).
  scenario.machine.validate();  // as AnalyzeMachineModes does first
  return ResidualWindowOfValidMachine(scenario);
}

double MinimumMotionSeconds(const Scenario& scenario, std::string* breakdown) {
  const controller::ControllerConfig& c = scenario.controller;
  const controller::Program program = scenario.RunProgram();
  const controller::PathGeometry path(program);
  // The path at its programmed feeds (nothing runs faster; clamps only slow it down).
  double feed_s = 0.0;
  double length_m = 0.0;
  for (const controller::PathElement& e : path.elements()) {
    const auto block = static_cast<std::size_t>(e.block);
    double feed = c.feed_m_s();
    if (block < program.blocks.size()) {
      const controller::ProgramBlock& b = program.blocks[block];
      feed = b.kind == controller::MotionKind::kRapid ? c.rapid_feed_mm_min / 60000.0
             : std::isnan(b.feed_m_s)                 ? c.feed_m_s()
                                                      : b.feed_m_s;
    }
    if (feed > 0.0 && std::isfinite(e.length_m)) feed_s += e.length_m / feed;
    if (std::isfinite(e.length_m)) length_m += e.length_m;
  }
  // From rest to rest with an acceleration of at most a (twice the acc/dec's, for a
  // grid correction or a table's overshoot): 2 sqrt(L / a) at least.
  const double accel = 2.0 * c.accel_m_s2();
  const double accel_s = accel > 0.0 ? 2.0 * std::sqrt(length_m / accel) : 0.0;
  double dwell_s = 0.0;
  for (const controller::ProgramBlock& b : program.blocks) dwell_s += b.dwell_s;
  // A shaped speed change lasts the shaper's duration at least.
  double pattern_s = 0.0;
  if (controller::MakeStepPattern(c.pattern).shapes()) {
    const std::vector<controller::Impulse> impulses = controller::ShaperImpulses(c.pattern);
    if (!impulses.empty()) pattern_s = impulses.back().time_s - impulses.front().time_s;
  }
  // Post-interpolation filters add their length (the exponential runs until 1e-12 m is
  // left of the path).
  double filter_s = 0.0;
  const controller::PostInterpConfig& post = c.post_interp;
  if (post.type == controller::PostInterpType::kExponential && length_m > 1e-12) {
    filter_s = post.time_constant_s * std::log(length_m / 1e-12);
  } else if (post.type == controller::PostInterpType::kProfileTable) {
    filter_s = post.table.empty() ? post.moving_average_s
                                  : static_cast<double>(post.table.size()) * c.period_s;
  }
  const double motion_s = std::max(feed_s, accel_s) + dwell_s + pattern_s + filter_s;
  if (breakdown != nullptr) {
    *breakdown = "motion " + Seconds(motion_s) + ": the path at its feeds " + Seconds(feed_s) +
                 " or acc/dec " + Seconds(accel_s) + ", dwells " + Seconds(dwell_s) +
                 ", pattern " + Seconds(pattern_s) + ", post-interpolation " + Seconds(filter_s);
  }
  return motion_s;
}

bool MachineChecksPass(const Scenario& scenario, std::optional<double> motion_s) {
  try {
    scenario.machine.validate();
    CheckPlantFinite(scenario);
    const double motion = motion_s ? *motion_s : MinimumMotionSeconds(scenario);
    return RunLengthWithinLimits(scenario, motion + ResidualWindowOfValidMachine(scenario));
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace shapebench::bench

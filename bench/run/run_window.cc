#include "bench/run/run_window.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "bench/fmi/fmu_machine.h"
#include "bench/scenario/run_memory.h"
#include "common/validation_error.h"

namespace shapebench::bench {
namespace {

// Per cruise stretch (a run of steady ticks at least a lowest-mode period long,
// SampleCommand's steady_runs), the tick one period into it. (No per-tick flags: a
// point's cost must not grow with the move, issue 41.)
std::vector<std::size_t> CruiseProbes(const CommandSamples& s, std::size_t period_ticks) {
  std::vector<std::size_t> probes;
  for (const auto& [run_start, end] : s.steady_runs) {
    if (end - run_start >= period_ticks) probes.push_back(run_start - 1 + period_ticks);
  }
  return probes;
}

}  // namespace

RunWindow PlanRunWindow(const Scenario& scenario, const CommandSamples& samples,
                        const model::MachineDynamics& dynamics, double period_s) {
  const double lowest_hz = dynamics.LowestHz();
  const double lowest_period_s = std::isfinite(lowest_hz) ? 1.0 / lowest_hz : RunWindow::kRigidTailPeriodS;
  RunWindow w;
  w.motion_ticks = samples.motion_ticks;
  w.residual_ticks = static_cast<std::size_t>(std::ceil(3.0 * lowest_period_s / period_s));
  w.period_ticks = static_cast<std::size_t>(std::ceil(lowest_period_s / period_s));
  const double seconds_ticks = scenario.limits.max_simulated_s / period_s;
  const double limit_ticks = std::min(seconds_ticks, static_cast<double>(scenario.limits.max_ticks));
  if (static_cast<double>(w.window_end()) > limit_ticks) {
    // Named after the limit that binds, the one the user has to raise.
    const bool ticks_bind = static_cast<double>(scenario.limits.max_ticks) < seconds_ticks;
    throw ValidationError(ticks_bind ? "limits.max_ticks" : "limits.max_simulated_s",
                          "the command and its residual window take " + std::to_string(w.window_end()) +
                              " periods, more than limits allow (max_simulated_s, max_ticks)");
  }
  // Again on the generated command, before the trace grows (the load-time check used a
  // lower bound of the run's length).
  if (static_cast<double>(w.window_end()) > MemoryTickLimit(scenario.limits)) {
    throw ValidationError("limits.max_memory_mb",
                          "the command and its residual window take " + std::to_string(w.window_end()) +
                              " periods, about " + std::to_string(static_cast<long>(
                                  RunBytes(static_cast<double>(w.window_end())) / MegabytesToBytes(1.0))) +
                              " MB with the trace, more than limits.max_memory_mb (" +
                              std::to_string(scenario.limits.max_memory_mb) + " MB a run)");
  }
  w.max_ticks = static_cast<std::size_t>(std::min(
      static_cast<double>(w.motion_ticks + RunWindow::kMaxTailPeriods * w.period_ticks), limit_ticks));
  // A foreign plant FMU's damping is unknown (its machine here has no modes): its tail is simulated.
  w.never_settles_late = scenario.drive.type == model::DriveType::kKinematic && dynamics.conserves_energy &&
                         (!scenario.fmu || scenario.fmu->model_known);
  w.cruise_probe_ticks = CruiseProbes(samples, w.period_ticks);
  return w;
}

int AutoSubsteps(const model::MachineDynamics& dynamics, double period_s) {
  const double fastest_hz = dynamics.FastestParticipatingHz();
  const int substeps = static_cast<int>(std::ceil(period_s * fastest_hz * 200.0));
  return std::clamp(substeps, 1, 64);
}

}  // namespace shapebench::bench

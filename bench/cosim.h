// The co-simulation master: t_k = k * period from the integer tick; at each tick the
// drive input is set, the plant steps to the next communication point (in output
// substeps), then the outputs are read.
#pragma once

#include <vector>

#include "bench/metrics.h"
#include "bench/scenario.h"
#include "controller/command_trajectory.h"
#include "model/integrator.h"

namespace shapebench::bench {

// Sampled at every output substep, from t = 0 to the end of the simulated tail.
struct Trace {
  std::vector<double> time_s;
  std::vector<double> command_position_m;
  std::vector<double> command_velocity_m_s;
  std::vector<double> command_accel_m_s2;  // held over the period the sample ends
  std::vector<double> deflection_m;
};

struct RunResult {
  controller::CommandTrajectory command;
  Trace trace;
  Metrics metrics;
  model::IntegratorStats stats;
  int substeps = 0;
};

// Throws ValidationError (bad scenario), model::SolverError (CVODE failure).
RunResult RunScenario(const Scenario& scenario);

// Output substeps per period when integrator.output_substeps is 0: at least 200 samples
// per period of the fastest mode that carries >= 1% of the static deflection, at most 64.
int AutoSubsteps(const model::MachineConfig& machine, double period_s);

}  // namespace shapebench::bench

// The co-simulation master: t_k = k * period from the integer tick; at each tick the
// drive input is set, the plant steps to the next communication point (in output
// substeps), then the outputs are read. RunScenario is a short list of named stages
// (cosim.cc): the command, its samples, the run window, the plant, the tick loop, the
// metrics.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "bench/sim/command_samples.h"
#include "bench/sim/metrics.h"
#include "bench/sim/output_view.h"
#include "bench/sim/scenario.h"
#include "controller/controller.h"
#include "model/free_response.h"
#include "model/integrator.h"

namespace shapebench::bench {

// Sampled at every output substep, from t = 0 to the end of the simulated tail.
struct Trace {
  std::vector<double> time_s;
  // The scalar view of the run (OutputDirection): along the view's axis, the command
  // position, velocity and acceleration; for the magnitude view, the distance the
  // command has travelled, its speed and |acceleration|. Deflection as the metrics see it.
  std::vector<double> command_position_m;
  std::vector<double> command_velocity_m_s;
  std::vector<double> command_accel_m_s2;  // held over the period the sample ends
  std::vector<double> deflection_m;
  // Per axis: the commanded (drive reference) position, the actual tool position
  // relative to the workpiece, and the structural deflection.
  std::vector<Eigen::Vector3d> command_m;
  std::vector<Eigen::Vector3d> actual_m;
  std::vector<Eigen::Vector3d> deflection_axes_m;
  // The block the interpolator is in (-1 after the program) and its planned feed.
  std::vector<int> block;
  std::vector<double> planned_feed_mm_min;
};

struct RunResult {
  controller::Program program;
  controller::MultiAxisCommand command;
  Trace trace;
  Metrics metrics;
  // Per pole of the plant the output view sees (ascending frequency): the free vibration at
  // motion end in the view, amplitude in m; they sum to metrics.residual_amplitude_m. Empty
  // for a machine without states.
  std::vector<model::PoleAmplitude> residual_modes;
  model::IntegratorStats stats;
  int substeps = 0;
  double simulated_s = 0.0;  // the time of the last sample (motion and tail)
  bool tail_in_closed_form = false;  // the settling tail found without simulating it
  // Periods whose inner output substeps were never stepped: no metric could read them
  // (bench/sim/deferred_substeps.h).
  long deferred_periods = 0;
  // The metrics (and residual_modes) are the closed forms' of one mode along one line
  // (single_mode_run.h); a trace, if any, is the general exact path's.
  bool single_mode = false;
  // What the user must be told beside the metrics (a failed CVODE cross-check under
  // integrator.cross_check: warn).
  std::vector<std::string> warnings;
};

struct RunOptions {
  // Record the Trace (every output substep: run --out's trace.csv and plots). Sweeps and
  // checks need only the metrics, which are the same bit for bit either way.
  bool record_trace = true;
  // The command of this scenario's controller and program, generated before (a sweep's
  // points that differ only in keys the controller does not read share it): used as it is,
  // and RunResult::command is then left empty. Null: generated here.
  const controller::MultiAxisCommand* command = nullptr;
  // SampleCommand(*command), computed before with it (a sweep shares both, read-only,
  // between its points and threads). Null: computed here. Ignored without `command`.
  const CommandSamples* samples = nullptr;
  // A run of one mode along one line takes its metrics from its closed forms
  // (single_mode_run.h; without a trace, nothing else runs). False: the general exact
  // path's metrics (the same to rounding).
  bool single_mode = true;
};

// The command RunScenario generates for the scenario's controller and program (the CNC's
// stroke check and the memory budget included): what a sweep generates once and shares.
controller::MultiAxisCommand GenerateScenarioCommand(const Scenario& scenario, const controller::Program& program);

// The largest deflection a held commanded acceleration gives, in the view (the static
// displacement the ratios divide by), and into *vector the deflection under that
// acceleration (the first sample reaching it), oriented so that its component in the view
// (magnitude: along the acceleration) is positive.
double StaticDisplacement(const CommandSamples& s, const Eigen::Matrix3d& static_gain, const OutputView& view,
                          Eigen::Vector3d* vector);

// What the pattern was designed for: its lowest design frequency and that mode's damping
// ratio (methods 1-4: undamped), into *m. NaN for a pattern that does not shape for a
// frequency (none, custom, mode off).
void SetPatternMetrics(const controller::PatternConfig& pattern, Metrics* m);

// Throws ValidationError (bad scenario), model::SolverError (CVODE failure).
RunResult RunScenario(const Scenario& scenario, const RunOptions& options = {});

}  // namespace shapebench::bench

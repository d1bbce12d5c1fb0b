// What a run returns: the metrics, the trace (every output substep, when recorded), what
// the plant and the sampler report beside them.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "bench/scenario/metrics.h"
#include "bench/run/metric_sources.h"
#include "bench/run/run_plan.h"
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
  double work = 0.0;  // limits.max_work's count for the run (bench/run/run_work.h)
  int substeps = 0;
  double simulated_s = 0.0;  // the time of the last sample (motion and tail)
  bool tail_in_closed_form = false;  // the settling tail found without simulating it
  // Periods whose inner output substeps were never stepped: no metric could read them
  // (bench/run/deferred_substeps.h).
  long deferred_periods = 0;
  // The sampler the metrics come from (sampler.h); with the closed form, a trace, if any,
  // is the general sampler's.
  SamplerKind sampler = SamplerKind::kGeneral;
  bool single_mode = false;  // sampler == kClosedForm
  // What the user must be told beside the metrics (a failed CVODE cross-check under
  // integrator.cross_check: warn).
  std::vector<std::string> warnings;
  // The rtol CVODE ran with: the scenario's, or the default tightened until the cross-check
  // passed (IntegratorConfig::rtol_given). NaN where no CVODE ran (the exact path, the
  // closed form, a machine without states).
  double integrator_rtol_used = std::numeric_limits<double>::quiet_NaN();
  // Where in the program the peak deflection, the largest contour error and the largest
  // cruise vibration come from (metric_sources.h); absent where no sampler stepped every
  // tick (a closed-form run without a trace).
  MetricSources sources;
};

}  // namespace shapebench::bench

// The one place the metrics are computed from a run's tally: every sampler ends here, so a
// metric added here is defined on every sampler (tests/bench/run/sampler_guard_test.cc).
#pragma once

#include <Eigen/Dense>

#include "bench/run/command_samples.h"
#include "bench/run/metric_tally.h"
#include "bench/scenario/metrics.h"
#include "bench/run/output_view.h"
#include "bench/run/run_plan.h"
#include "controller/pattern_config.h"

namespace shapebench::bench {

// The largest deflection a held commanded acceleration gives, in the view (the static
// displacement the ratios divide by), and into *vector the deflection under that
// acceleration (the first sample reaching it), that acceleration taken in the positive sense
// of the axis it mostly lies along: the vector does not depend on the view.
double StaticDisplacement(const CommandSamples& s, const Eigen::Matrix3d& static_gain, const OutputView& view,
                          Eigen::Vector3d* vector);

// A program's static displacement: the largest deflection, in the view, under the acc/dec's
// acceleration `accel_m_s2` along a direction the program moves in (each line's, each
// arc's tangent every degree), and into *vector that deflection as StaticDisplacement's.
double ProgramStaticDisplacement(const controller::PathGeometry& path, double accel_m_s2,
                                 const Eigen::Matrix3d& static_gain, const OutputView& view,
                                 Eigen::Vector3d* vector);

// The tally's static reference from the model's static gain, in the plan's view: a single
// straight move's from its commanded samples (StaticDisplacement), a program's from the
// acc/dec's acceleration along its directions (ProgramStaticDisplacement).
void SetStaticReference(const RunPlan& plan, const Eigen::Matrix3d& static_gain, MetricTally* tally);

// What the pattern was designed for: its lowest design frequency and that mode's damping
// ratio (methods 1-4: undamped), into *m. NaN for a pattern that does not shape for a
// frequency (none, custom, mode off).
void SetPatternMetrics(const controller::PatternConfig& pattern, Metrics* m);

// Every metric of the run from its plan and tally. Throws model::SolverError when a metric
// overflowed to infinity (a degenerate model, never a number).
Metrics FinishMetrics(const RunPlan& plan, const MetricTally& tally);

}  // namespace shapebench::bench

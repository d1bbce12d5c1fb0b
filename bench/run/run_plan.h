// The prepared run, built once and constant while the samplers run (MuJoCo's mjModel next
// to mjData): the command's samples, the output view, the machine's modes, the run window,
// the output substeps, and which samplers can take the run.
#pragma once

#include <chrono>
#include <cstddef>
#include <string_view>
#include <vector>

#include "bench/run/command_samples.h"
#include "bench/run/output_view.h"
#include "bench/run/run_window.h"
#include "bench/scenario/scenario.h"
#include "controller/controller.h"
#include "controller/path_geometry.h"
#include "model/machine.h"
#include "model/multi_axis_machine.h"

namespace shapebench::bench {

// The strategies that turn the plant's outputs into the metric tally (sampler.h).
enum class SamplerKind {
  kGeneral,           // every output of every substep (general_sampler.cc)
  kSingleAxis,        // one axis' scalars while the others stay exactly 0 (single_axis_sampler.cc)
  kDeferredSubsteps,  // inner substeps only where they can change a metric (deferred_substeps_sampler.cc)
  kClosedForm,        // one mode along one line, in closed form (closed_form_sampler.cc)
};
inline constexpr SamplerKind kAllSamplers[] = {SamplerKind::kGeneral, SamplerKind::kSingleAxis,
                                               SamplerKind::kDeferredSubsteps, SamplerKind::kClosedForm};
std::string_view SamplerName(SamplerKind kind);

// A run of one structural mode under the kinematic drive along one straight line, with
// the view on that line's axis: what the closed-form sampler takes (null mode otherwise).
struct SingleModeCase {
  const model::ModalMode* mode = nullptr;
  const controller::PathElement* line = nullptr;
  int axis = -1;
};

class RunPlan {
 public:
  // `samples`: SampleCommand(command), computed before (a sweep shares them), or null to
  // compute them here. Throws ValidationError (an invalid machine or drive, the run's
  // limits) before anything runs.
  RunPlan(const Scenario& scenario, const controller::MultiAxisCommand& command,
          const controller::PathGeometry& path, const CommandSamples* samples, bool record_trace);
  RunPlan(const RunPlan&) = delete;
  RunPlan& operator=(const RunPlan&) = delete;

  const Scenario& scenario;
  const controller::MultiAxisCommand& command;
  const controller::PathGeometry& path;

 private:
  const CommandSamples own_samples_;  // before `samples`, which may refer to it

 public:
  const CommandSamples& samples;
  const double dt_s;                   // the command's interpolation period
  const model::MachineDynamics dynamics;
  const OutputView view;
  const RunWindow window;
  const int substeps;                  // output substeps per period
  const std::vector<double> taus_s;    // their times within a period, dt j / substeps
  const bool has_stroke;               // any stroke limit
  const bool record_trace;
  const SingleModeCase single_mode;    // what the closed form takes, if it can
  // When the plan was made: limits.max_wall_s counts from here (run_work.h).
  const std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();

  // The time of sample `count` (from t = 0) on the run's grid, dt count / substeps.
  double SampleTime(long count) const { return dt_s * static_cast<double>(count) / substeps; }
};

}  // namespace shapebench::bench

// The samplers that step the plant's integrator period by period (FMI order: set the
// input, step to t_k, read the outputs): the set-up, the stepping, the probes of the free
// vibration and the closed-form tail are here (plant_sampler.cc); how a period's outputs
// become the tally is the strategy's: general_sampler.cc (every output),
// single_axis_sampler.cc (one axis' scalars while the others stay exactly 0),
// deferred_substeps_sampler.cc (inner substeps only where they can change a metric).
#pragma once

#include <cstddef>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "bench/run/damped_tail.h"
#include "bench/run/metric_tally.h"
#include "bench/run/path_tallies.h"
#include "bench/run/residual_vibration.h"
#include "bench/run/run_plan.h"
#include "bench/run/run_result.h"
#include "bench/run/sampler.h"
#include "bench/run/single_axis.h"
#include "model/integrator.h"
#include "model/multi_axis_machine.h"

namespace shapebench::bench {

class FmuPlant;  // bench/fmi/fmu_plant.h

class PlantSampler final : public Sampler {
 public:
  // The fastest strategy at or below `fastest` that qualifies (result->sampler tells).
  PlantSampler(const RunPlan& plan, SamplerKind fastest, RunResult* result);

  MetricTally Run() override;
  std::size_t Tick(std::size_t k);
  // After tick k: at the residual window's end, the settling tail in closed form when the
  // plant allows (DampedTail); then the run ends where the simulated tail would.
  bool SettleTail(std::size_t k);
  // limits.max_work through tick k (run_work.h); the ticks until the next look.
  std::size_t CheckWork(std::size_t k) const;

 private:
  void SetUpPlant();
  void SetUpFmu();  // fmu_sampling.cc: a plant FMU (scenario.fmu) in place of the model
  double FmuResidual() const;  // its residual_amplitude output in the view now (NaN: none)
  void CrossCheckCvode(const model::LinearPlant& plant, double scale_accel);
  void SetUpSampling(SamplerKind fastest);
  void SetUpSingleAxis();
  bool StepPlant(std::size_t k);  // true: the other axes' outputs are all exactly 0
  long SameInput(std::size_t k);
  void CheckFinite(std::size_t k) const;
  template <RunPhase P> void SampleTick(std::size_t k, bool others_zero);
  void Probes(std::size_t k);
  void ProbeMotionEnd();
  void ProbeCruise(std::size_t k);
  void TrackFreeResponse(std::size_t k, bool others_zero);
  void Conclude();
  // general_sampler.cc
  template <RunPhase P> void SampleGeneral(std::size_t k, TickTally* tick);
  void Record(double t, const Eigen::Vector3d& p, const Eigen::Vector3d& v, const Eigen::Vector3d& a,
              const Eigen::Vector3d& deflection, const Eigen::Vector3d& actual, int block);
  void StartTrace();
  // single_axis_sampler.cc
  template <RunPhase P> void SampleSingleAxis(std::size_t k, TickTally* tick);
  // deferred_substeps_sampler.cc
  bool QualifiesForDeferredSubsteps() const;
  template <RunPhase P> void DeferredTick(std::size_t k);
  template <RunPhase P> bool InnerSamplesMatter(std::size_t k, double y_end, double inside) const;

  const RunPlan& plan_;
  const CommandSamples& samples_;
  const RunWindow& window_;
  RunResult& result_;
  const double dt_;
  const int substeps_;
  SamplerKind kind_ = SamplerKind::kGeneral;
  MetricTally tally_;
  ContourGauge contour_gauge_;
  const model::MachinePlant machine_;
  // The scenario's integrator settings, rtol as CrossCheckCvode leaves it.
  model::IntegratorConfig integrator_config_;
  // What a nonlinear run integrates: machine_ without the structures of axes the command
  // never moves (IdleAxesRigid).
  model::MachinePlant integrated_;
  std::unique_ptr<model::PlantIntegrator> integrator_;
  // The free vibration of the plant's state (residual_ratio, cruise_residual_ratio), read at
  // motion end and at the cruise probes (RunWindow::cruise_probe_ticks), never per tick.
  std::unique_ptr<ResidualVibration> residual_vibration_;
  std::unique_ptr<DampedTail> damped_tail_;
  FmuPlant* fmu_ = nullptr;  // integrator_ when it is a plant FMU: its residual outputs  // a linear plant on the exact path, no trace
  std::size_t next_probe_ = 0;  // index into cruise_probe_ticks
  std::size_t next_probe_tick_ = std::numeric_limits<std::size_t>::max();
  int rows_ = 0;
  std::vector<double> outputs_;  // one period's substeps (AdvancePeriod), rows as in MachinePlant
  std::vector<ArcWindow> arcs_;
  // The first arc (glitch window) the path position has not passed yet: arcs_ and
  // glitches_ are in path order and the position never decreases, so a sample looks at
  // the few around it, not at every arc of the program.
  std::size_t next_arc_ = 0, next_glitch_ = 0;
  SingleAxis single_;
  SingleAxisSampling single_sampling_{};
  double period_start_m_ = 0.0;    // the deflection at the current period's start (deferred)
  std::vector<int> watched_rows_;  // other axes' rows the single-axis samples must see at 0
  int width_ = 0;                  // outputs per substep in outputs_
  int deflection_at_ = 0;
  int tool_error_at_ = 0;
  bool holds_ = false;           // the integrator integrates across held inputs (SameInput)
  bool exact_extrema_ = false;   // the integrator finds the view's extrema inside a period
  // Ticks between looks at the work: CVODE's tick can be long (stiff elements), the exact
  // path's is bounded (model/tick_extremum.h) and cheap enough that a look would show.
  std::size_t work_stride_ = 64;  // 1 on CVODE (SetUpPlant)
  std::size_t next_change_ = 0;  // the first tick after k whose acceleration differs from a_k
  // A plant with nonlinear elements (docs/nonlinear.md): its free response after motion
  // end, sample by sample (the residual and the dead band), and its quadrant glitches.
  bool nonlinear_ = false;
  FreeResponse free_;
  std::vector<ReversalWindows> glitches_;
  Eigen::Vector3d peak_axes_ = Eigen::Vector3d::Zero();
  double overshoot_ = 0.0;
  double travelled_m_ = 0.0;  // the command's distance along its own path (magnitude view)
  std::string unchecked_;     // why CVODE's accuracy is unknown (its check pulse failed)
};

}  // namespace shapebench::bench

#include "bench/sim/cosim.h"

#include "bench/sim/run_memory.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>

#include "bench/sim/command_samples.h"
#include "bench/sim/damped_tail.h"
#include "bench/sim/deferred_substeps.h"
#include "bench/sim/metric_accumulator.h"
#include "bench/sim/output_view.h"
#include "bench/sim/residual_vibration.h"
#include "bench/sim/run_memory.h"
#include "bench/sim/run_window.h"
#include "bench/sim/single_mode_run.h"
#include "controller/path_geometry.h"
#include "controller/shaper_registry.h"
#include "controller/stroke_end.h"
#include "model/cvode_cross_check.h"
#include "model/multi_axis_machine.h"
#include "model/nonlinear_integrator.h"

namespace shapebench::bench {
namespace {

// Mean radius over the middle half of one arc (radial_error_m).
struct ArcWindow {
  const controller::PathElement* arc = nullptr;
  double sum_radius_m = 0.0;
  long samples = 0;
};

// The deflection of a nonlinear plant after motion end, in the view: its extremes
// (residual_amplitude_m, half their difference) and its last value (dead_band_m).
struct FreeResponse {
  double min = HUGE_VAL;
  double max = -HUGE_VAL;
  double last = 0.0;
  bool any = false;
  void Add(double d) {
    min = std::min(min, d);
    max = std::max(max, d);
    last = d;
    any = true;
  }
};

// quadrant_glitch_m on one arc: the axis reversals (tangent along an axis) at least 5
// degrees inside the arc, the largest and smallest radial deviation (actual radius less
// programmed) within +-5 degrees of each, and the deviations over the arc's middle half
// (by the command's path position, as radial_error_m), whose median is the baseline: robust
// to the spikes themselves, clear of the arc's start and end.
struct ReversalWindows {
  static constexpr double kHalfWidthRad = 5.0 * 3.14159265358979323846 / 180.0;
  const controller::PathElement* arc = nullptr;
  std::vector<double> angle_rad;  // the reversals' angles on the arc's turn
  std::vector<double> max_radius_m;
  std::vector<double> min_radius_m;
  std::vector<double> middle_m;  // deviations over the middle half

  explicit ReversalWindows(const controller::PathElement& element);
  void Add(double path_s, const Eigen::Vector3d& actual);
  double Glitch() const;  // NaN without a reversal or a baseline
};

ReversalWindows::ReversalWindows(const controller::PathElement& element) : arc(&element) {
  const double quarter = 0.5 * 3.14159265358979323846;
  const double a0 = element.start_angle_rad;
  const double a1 = a0 + element.sweep_rad;
  const double lo = std::min(a0, a1) + kHalfWidthRad;
  const double hi = std::max(a0, a1) - kHalfWidthRad;
  for (double k = std::ceil(lo / quarter); k * quarter <= hi; k += 1.0) angle_rad.push_back(k * quarter);
  max_radius_m.assign(angle_rad.size(), -HUGE_VAL);
  min_radius_m.assign(angle_rad.size(), HUGE_VAL);
}

void ReversalWindows::Add(double path_s, const Eigen::Vector3d& actual) {
  const controller::PathElement& e = *arc;
  if (path_s < e.start_s_m || path_s > e.end_s_m() || !(e.length_m > 0.0)) return;
  const double u = (path_s - e.start_s_m) / e.length_m;
  const double commanded = e.start_angle_rad + u * e.sweep_rad;
  const double dx = actual(e.axis0) - e.center_m(e.axis0);
  const double dy = actual(e.axis1) - e.center_m(e.axis1);
  // The sample's angle on the commanded angle's turn (the command and the tool are close).
  const double angle = commanded + std::remainder(std::atan2(dy, dx) - commanded, 2.0 * 3.14159265358979323846);
  const double fraction = e.sweep_rad != 0.0 ? std::clamp((angle - e.start_angle_rad) / e.sweep_rad, 0.0, 1.0) : 0.0;
  const double programmed = e.start_radius_m + (e.end_radius_m - e.start_radius_m) * fraction;
  const double deviation = std::hypot(dx, dy) - programmed;
  if (u >= 0.25 && u <= 0.75) middle_m.push_back(deviation);
  for (std::size_t i = 0; i < angle_rad.size(); ++i) {
    if (std::abs(angle - angle_rad[i]) <= kHalfWidthRad) {
      max_radius_m[i] = std::max(max_radius_m[i], deviation);
      min_radius_m[i] = std::min(min_radius_m[i], deviation);
    }
  }
}

double ReversalWindows::Glitch() const {
  double glitch = NAN;
  if (middle_m.empty()) return glitch;
  std::vector<double> sorted = middle_m;
  const auto mid = sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2);
  std::nth_element(sorted.begin(), mid, sorted.end());
  const double baseline = *mid;
  for (std::size_t i = 0; i < angle_rad.size(); ++i) {
    if (max_radius_m[i] < min_radius_m[i]) continue;  // no sample in this window
    const double spike = std::max(max_radius_m[i] - baseline, baseline - min_radius_m[i]);
    if (std::isnan(glitch) || spike > glitch) glitch = spike;
  }
  return glitch;
}

// The contour error of a sample: its distance from the programmed path, squared (the
// largest distance is the square root of the largest square, bit for bit: norm() is the
// square root of squaredNorm(), and the square root is monotone). A single straight
// element (a `move:`, a one-block program) is measured on it directly: the whole path's
// search gives the same point there.
//
// Only the run's largest contour error is kept, so a sample that cannot exceed the largest
// so far need not be searched for: the last nearest point found lies on the path, so the
// distance to it bounds the sample's from above. That bound is exact only where the
// search is (lines and plane circular arcs: controller/path_geometry.cc, a helix's or a
// spiral's nearest point is an estimate), and is applied with a margin far above the
// rounding of the points (1e-12 m plus 1e-13 of the coordinates), so the largest error is
// the same bit for bit.
class ContourGauge {
 public:
  explicit ContourGauge(const controller::PathGeometry& path) : path_(path) {
    const auto& elements = path.elements();
    if (elements.size() == 1 && !elements.front().is_arc()) single_ = &elements.front();
    exact_ = true;
    for (const controller::PathElement& e : elements) {
      if (e.is_arc() && (e.rise_m != 0.0 || e.start_radius_m != e.end_radius_m)) exact_ = false;
    }
  }
  // The sample's squared contour error, or 0 when it is provably below `largest_sq`.
  double SquaredDistanceTo(const Eigen::Vector3d& p, double largest_sq) const {
    if (exact_ && has_last_ && largest_sq > 0.0) {
      const double margin = 1e-12 + 1e-13 * p.cwiseAbs().maxCoeff();
      const double bound = (p - last_).norm() + margin;
      if (bound * bound < largest_sq) return 0.0;
    }
    last_ = single_ != nullptr ? single_->NearestPoint(p) : path_.NearestPoint(p);
    has_last_ = true;
    return (p - last_).squaredNorm();
  }
  const controller::PathElement* single() const { return single_; }

 private:
  const controller::PathGeometry& path_;
  const controller::PathElement* single_ = nullptr;
  bool exact_ = false;  // the search is exact on every element (no helix, no spiral)
  mutable Eigen::Vector3d last_;  // the last nearest point found
  mutable bool has_last_ = false;
};

// A run whose command moves one axis only, along a single straight element of that axis,
// with the metrics' view on that axis: every other component of command, deflection and
// tool error stays exactly 0 (checked per period on the outputs), so the samples need only
// that axis' scalars. The arithmetic is the general samples', component by component
// (tests/bench/cosim_fast_path_test.cc compares the two bit for bit).
struct SingleAxis {
  int axis = -1;
  double start_m = 0.0;      // the element's start on the axis
  double direction = 0.0;    // +1 or -1
  double length_m = 0.0;
};

SingleAxis FindSingleAxis(const CommandSamples& samples, const OutputView& view,
                          const ContourGauge& gauge, bool has_stroke) {
  SingleAxis none;
  const controller::PathElement* e = gauge.single();
  if (e == nullptr || view.magnitude || has_stroke) return none;
  const int axis = view.axis;
  if (axis < 0 || std::abs(e->direction(axis)) != 1.0) return none;
  for (int a = 0; a < controller::kNumAxes; ++a) {
    if (a == axis) continue;
    if (e->direction(a) != 0.0 || samples.axis_moves[a]) return none;
    // Its velocities all (+ or -) 0, the axis' positions are its start plus sums of
    // zeros: each equals (==) the first.
    if (samples.positions.front()(a) != e->start_m(a)) return none;
  }
  return {axis, e->start_m(axis), e->direction(axis), e->length_m};
}

// One tick of single-axis samples (SingleAxis): the general samples' arithmetic, the other
// components left out; the same operations in the same order. A function of its own, kept
// out of line, so that its loop keeps every value in registers (inlined into the master's
// loop it spilled them). Returns whether a value was not finite (or a square overflowed).
struct SingleAxisSampling {  // what stays the same from tick to tick
  const double* deflections;
  const double* tool_errors;
  const double* taus;
  int width;
  int substeps;
  SingleAxis single;
};

template <RunPhase P>
[[gnu::noinline]] bool SampleSingleAxisTick(const SingleAxisSampling& in, double p0, double v0,
                                            double half_a, TickAccumulator* out) {
  TickAccumulator tick = *out;
  // An `or` of comparisons, not a running sum, keeps the samples independent.
  bool not_finite = false;
  for (int j = 0; j < in.substeps; ++j) {
    const double tau = in.taus[j];
    const double p = p0 + v0 * tau + half_a * tau * tau;
    const double actual = p + in.tool_errors[j * in.width];
    const double magnitude = std::abs(in.deflections[j * in.width]);
    const double along = std::clamp((actual - in.single.start_m) * in.single.direction, 0.0, in.single.length_m);
    const double off = actual - (in.single.start_m + along * in.single.direction);
    const double square = off * off;
    not_finite |= !(square + magnitude <= std::numeric_limits<double>::max());
    tick.Add<P>(j, magnitude, square);
  }
  *out = tick;
  return not_finite;
}

// The machine a nonlinear run integrates: an axis the command never moves starts at rest
// and is never driven, so its structure, its servo and its elements stay exactly at rest
// (every element's force is 0 there): it is left out like a rigid axis, whose outputs are
// the same exact zeros. A third fewer states on an XY program of a three-axis machine.
model::MachinePlant IdleAxesRigid(const Scenario& scenario, const CommandSamples& samples) {
  model::MultiAxisMachineConfig machine = scenario.machine;
  for (int axis = 0; axis < model::kNumAxes; ++axis) {
    bool idle = true;
    for (std::size_t k = 0; k <= samples.n && idle; ++k) {
      idle = samples.accel[k](axis) == 0.0 && samples.velocity[k](axis) == 0.0;
    }
    // Coupled modes sit at the driven axis but answer every axis: never left out.
    if (idle && machine.CoupledModes() == nullptr) machine.axes[axis].reset();
  }
  return model::BuildMachinePlant(machine, scenario.drive);
}


void ReserveTrace(Trace* trace, std::size_t expected) {
  trace->time_s.reserve(expected);
  trace->command_position_m.reserve(expected);
  trace->command_velocity_m_s.reserve(expected);
  trace->command_accel_m_s2.reserve(expected);
  trace->deflection_m.reserve(expected);
  trace->command_m.reserve(expected);
  trace->actual_m.reserve(expected);
  trace->deflection_axes_m.reserve(expected);
  trace->block.reserve(expected);
  trace->planned_feed_mm_min.reserve(expected);
}

// The master's state for one run: the plant stepping tick by tick, its outputs read into
// the metric accumulator by one of two samplers (every output, or a single axis' scalars).
class CoSimulation {
 public:
  CoSimulation(const Scenario& scenario, const controller::MultiAxisCommand& command,
               const controller::PathGeometry& path, const RunOptions& options, RunResult* result);

  // Sets the input held over (t_{k-1}, t_k], steps the plant to t_k, reads the outputs.
  void Tick(std::size_t k);
  bool Done(std::size_t k, bool* settled) const { return window_.Done(k, acc_.quiet_since_tick, settled); }
  std::size_t max_ticks() const { return window_.max_ticks; }
  // After tick k: at the residual window's end, the settling tail in closed form when the
  // plant allows (DampedTail); then the run ends at *last_tick as the simulated tail would.
  bool SettleTail(std::size_t k, bool* settled, std::size_t* last_tick);
  void Finish(std::size_t last_tick, bool settled);

 private:
  void SetUpPlant();
  void CrossCheckCvode(const model::LinearPlant& plant, double scale_accel);
  void SetUpSampling();
  bool StepPlant(std::size_t k);  // true: the other axes' outputs are all exactly 0
  long SameInput(std::size_t k);
  void CheckFinite(std::size_t k) const;
  template <RunPhase P> void SampleSingleAxis(std::size_t k, TickAccumulator* tick);
  template <RunPhase P> void SampleGeneral(std::size_t k, TickAccumulator* tick);
  template <RunPhase P> void SampleTick(std::size_t k, bool others_zero);
  template <RunPhase P> void DeferredTick(std::size_t k);
  template <RunPhase P> bool InnerSamplesMatter(std::size_t k, double y_end, double inside) const;
  void Record(double t, const Eigen::Vector3d& p, const Eigen::Vector3d& v, const Eigen::Vector3d& a,
              const Eigen::Vector3d& deflection, const Eigen::Vector3d& actual, int block);
  void ProbeMotionEnd();
  void ProbeCruise(std::size_t k);
  void TrackFreeResponse(std::size_t k, bool others_zero);
  void FinishMetrics(Metrics* m) const;
  void FinishNonlinearMetrics(Metrics* m) const;

  const Scenario& scenario_;
  const controller::MultiAxisCommand& command_;
  const RunOptions& options_;
  RunResult& result_;
  const double dt_;
  const ContourGauge contour_gauge_;
  const model::MachinePlant machine_;
  // What a nonlinear run integrates: machine_ without the structures of axes the command
  // never moves (IdleAxesRigid).
  model::MachinePlant integrated_;
  const model::MachineDynamics dynamics_;
  // The command's samples: computed here (own_samples_) unless given (RunOptions::samples).
  const CommandSamples own_samples_;
  const CommandSamples& samples_;
  const OutputView view_;
  const RunWindow window_;
  const bool has_stroke_;
  int substeps_ = 1;
  std::unique_ptr<model::PlantIntegrator> integrator_;
  // The free vibration of the plant's state (residual_ratio, cruise_residual_ratio), read at
  // motion end and at the cruise probes (RunWindow::cruise_probe_ticks), never per tick.
  std::unique_ptr<ResidualVibration> residual_vibration_;
  std::unique_ptr<DampedTail> damped_tail_;  // a linear plant on the exact path, no trace
  std::size_t next_probe_ = 0;  // index into cruise_probe_ticks
  std::size_t next_probe_tick_ = std::numeric_limits<std::size_t>::max();
  double residual_m_ = 0.0;     // at rest, or a rigid machine: none
  double cruise_m_ = NAN;       // NaN until a cruise probe
  int rows_ = 0;
  std::vector<double> outputs_;  // one period's substeps (AdvancePeriod), rows as in MachinePlant
  std::vector<double> taus_;     // the substeps' times within a period
  std::vector<ArcWindow> arcs_;
  SingleAxis single_;
  SingleAxisSampling single_sampling_{};
  // Inner substeps stepped only where they can change a metric (deferred_substeps.h):
  // a single-axis run whose tool error is its deflection, exact path, no trace.
  bool defer_substeps_ = false;
  double period_start_m_ = 0.0;        // the deflection at the current period's start
  std::vector<int> watched_rows_;  // other axes' rows the single-axis samples must see at 0
  int width_ = 0;                  // outputs per substep in outputs_
  int deflection_at_ = 0;
  int tool_error_at_ = 0;
  bool holds_ = false;           // the integrator integrates across held inputs (SameInput)
  bool exact_extrema_ = false;   // the integrator finds the view's extrema inside a period
  std::size_t next_change_ = 0;  // the first tick after k whose acceleration differs from a_k
  RunAccumulator acc_;
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

CoSimulation::CoSimulation(const Scenario& scenario, const controller::MultiAxisCommand& command,
                           const controller::PathGeometry& path, const RunOptions& options,
                           RunResult* result)
    : scenario_(scenario),
      command_(command),
      options_(options),
      result_(*result),
      dt_(command.period_s),
      contour_gauge_(path),
      machine_(model::BuildMachinePlant(scenario.machine, scenario.drive)),
      dynamics_(model::AnalyzeMachine(scenario.machine)),
      own_samples_(options.command != nullptr && options.samples != nullptr ? CommandSamples{}
                                                                          : SampleCommand(command)),
      samples_(options.command != nullptr && options.samples != nullptr ? *options.samples : own_samples_),
      view_(MakeOutputView(scenario.output, samples_.axis_moves)),
      window_(PlanRunWindow(scenario, samples_, dynamics_, dt_)),
      has_stroke_(std::any_of(scenario.machine.stroke_m.begin(), scenario.machine.stroke_m.end(),
                              [](const auto& limits) { return limits.has_value(); })) {
  nonlinear_ = !machine_.nonlinear.empty();
  for (const controller::PathElement& e : path.elements()) {
    if (e.is_arc()) arcs_.push_back({&e, 0.0, 0});
    if (e.is_arc() && nonlinear_) glitches_.emplace_back(e);
  }
  Eigen::Vector3d static_vector;
  result_.metrics.static_displacement_m = StaticDisplacement(samples_, machine_.static_gain, view_, &static_vector);
  result_.metrics.static_displacement_x_m = static_vector(0);
  result_.metrics.static_displacement_y_m = static_vector(1);
  result_.metrics.static_displacement_z_m = static_vector(2);
  acc_.band = RunWindow::kSettlingBand * result_.metrics.static_displacement_m;
  acc_.quiet_since_tick = window_.motion_ticks;
  SetUpPlant();
  SetUpSampling();
  if (!window_.cruise_probe_ticks.empty()) next_probe_tick_ = window_.cruise_probe_ticks.front();
  if (window_.motion_ticks == 0) ProbeMotionEnd();  // no motion: the state at rest
}

void CoSimulation::SetUpPlant() {
  substeps_ = scenario_.integrator.output_substeps > 0 ? scenario_.integrator.output_substeps
                                                       : AutoSubsteps(dynamics_, dt_);
  result_.substeps = substeps_;
  if (nonlinear_) integrated_ = IdleAxesRigid(scenario_, samples_);
  const model::LinearPlant& plant = nonlinear_ ? integrated_.plant : machine_.plant;
  if (plant.num_states() > 0) {
    const double scale_accel = std::max(samples_.max_accel_m_s2, 1e-12);
    CrossCheckCvode(plant, scale_accel);
    if (nonlinear_) {
      // CVODE with events; its free response is read sample by sample (TrackFreeResponse).
      integrator_ = model::MakePlantIntegrator({plant, integrated_.nonlinear}, scenario_.integrator, dt_, substeps_,
                                               scale_accel, samples_.max_speed_m_s);
    } else {
      integrator_ = model::MakeIntegrator(plant, scenario_.integrator, dt_, substeps_, scale_accel,
                                          samples_.max_speed_m_s);
      residual_vibration_ = std::make_unique<ResidualVibration>(plant, view_);
      // The peaks of the view's axis exactly (one sign change of its rate a period, closed
      // form per mode: model/tick_extremum.h), not only at the substeps.
      if (view_.axis >= 0) exact_extrema_ = integrator_->WatchExtremum(model::kDeflectionRow + view_.axis);
      // The trace shows the tail: simulated then.
      if (exact_extrema_ && !options_.record_trace && !window_.never_settles_late &&
          plant.num_outputs() == model::kNumOutputRows) {
        damped_tail_ = std::make_unique<DampedTail>(plant, view_);
      }
    }
    integrator_->Reset(Eigen::VectorXd::Zero(plant.num_inputs()));
    holds_ = integrator_->UsesInputHolds();
  }
  rows_ = plant.num_outputs();
  width_ = rows_;
  outputs_.assign(static_cast<std::size_t>(substeps_) * std::max(rows_, model::kNumOutputRows), 0.0);
  taus_.resize(substeps_);
  for (int j = 1; j <= substeps_; ++j) taus_[j - 1] = dt_ * static_cast<double>(j) / substeps_;
}

// CVODE on a linear plant is checked against the exact discretisation once per distinct
// plant and settings (model/cvode_cross_check.h): beyond the documented accuracy the run is
// refused, or warned about.
void CoSimulation::CrossCheckCvode(const model::LinearPlant& plant, double scale_accel) {
  const model::IntegratorConfig& config = scenario_.integrator;
  // A plant with nonlinear elements runs on CVODE whatever auto says; its linear part is
  // checked through the same integrator (docs/nonlinear.md).
  const model::CheckedIntegrator checked =
      nonlinear_ ? model::CheckedIntegrator::kNonlinear : model::CheckedIntegrator::kLinear;
  if (config.cross_check == model::CrossCheckPolicy::kOff ||
      (!nonlinear_ && model::ResolveMethod(config.method, plant) != model::IntegratorMethod::kCvode)) {
    return;
  }
  model::CheckMethodFitsPlant(config.method, integrated_.nonlinear);
  const model::CrossCheckResult check = model::CachedCrossCheckCvode(
      plant, config, dt_, substeps_, scale_accel, samples_.max_speed_m_s, checked);
  // The metrics are read up to the end of the residual window.
  const double run_s = static_cast<double>(window_.window_end()) * dt_;
  if (check.Passed(run_s)) return;
  std::string message = model::CrossCheckMessage(check, config, run_s, checked);
  if (!check.solver_failure.empty()) {
    // The run's own CVODE failure, if it has one, is the better report: it comes first.
    unchecked_ = std::move(message);
  } else if (config.cross_check == model::CrossCheckPolicy::kRefuse) {
    throw model::SolverError("CROSS_CHECK_FAILED", message);
  } else {
    result_.warnings.push_back(std::move(message));
  }
}

void CoSimulation::SetUpSampling() {
  if (options_.record_trace) {
    // Every run simulates the motion and the residual window; most settle a period later
    // (reserved up to a few million samples; a longer trace grows as it goes).
    const std::size_t expected = std::min<std::size_t>(
        std::min(window_.max_ticks, window_.window_end() + window_.period_ticks) * substeps_ + 1, 4'000'000);
    ReserveTrace(&result_.trace, expected);
    Record(0.0, samples_.positions.front(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
           Eigen::Vector3d::Zero(), samples_.positions.front(), command_.block.empty() ? -1 : command_.block.front());
    return;
  }
  single_ = FindSingleAxis(samples_, view_, contour_gauge_, has_stroke_);
  if (single_.axis < 0 || rows_ != model::kNumOutputRows) return;
  for (int r = 0; r < rows_; ++r) {
    if (r % 3 != single_.axis && !(integrator_ && integrator_->OutputRowIsZero(r))) watched_rows_.push_back(r);
  }
  deflection_at_ = model::kDeflectionRow + single_.axis;
  tool_error_at_ = model::kToolErrorRow + single_.axis;
  // When every other row is 0 by the integrator's structure, only the axis' deflection
  // and tool error are asked for.
  if (watched_rows_.empty() && integrator_) {
    integrator_->SelectOutputs({deflection_at_, tool_error_at_});
    width_ = 2;
    deflection_at_ = 0;
    tool_error_at_ = 1;
  }
  single_sampling_ = {outputs_.data() + deflection_at_, outputs_.data() + tool_error_at_, taus_.data(),
                      width_, substeps_, single_};
  // The tool error bounded by the deflection's bound needs the two rows to be one.
  const model::LinearPlant& plant = machine_.plant;
  defer_substeps_ = exact_extrema_ && watched_rows_.empty() && width_ == 2 && substeps_ > 1 &&
                    integrator_->DefersSubsteps() && view_.axis == single_.axis &&
                    plant.C.row(model::kDeflectionRow + single_.axis) == plant.C.row(model::kToolErrorRow + single_.axis);
}

// For how many periods from tick k on the held acceleration stays a_k (the tail's is
// zero): an integrator that can (CVODE) integrates across those ticks (AdvancePeriod).
long CoSimulation::SameInput(std::size_t k) {
  if (!holds_) return 1;
  if (k >= next_change_) {
    const Eigen::Vector3d& here = samples_.AccelAt(k);
    next_change_ = k + 1;
    while (next_change_ <= window_.max_ticks) {
      const Eigen::Vector3d& next = samples_.AccelAt(next_change_);
      if (next(0) != here(0) || next(1) != here(1) || next(2) != here(2)) break;
      ++next_change_;
    }
  }
  return static_cast<long>(next_change_ - k);
}

// Every output of period k finite, else the run fails (a degenerate model: never reported
// as numbers), at the first substep that is not.
void CoSimulation::CheckFinite(std::size_t k) const {
  for (int i = 0; i < substeps_ * width_; ++i) {
    if (!std::isfinite(outputs_[i])) {
      const long count = static_cast<long>((k - 1) * substeps_) + i / width_ + 1;
      throw model::SolverError("NON_FINITE_STATE",
                               "the plant's deflection became non-finite at t = " +
                                   std::to_string(dt_ * static_cast<double>(count) / substeps_) +
                                   " s (a degenerate model)");
    }
  }
}

bool CoSimulation::StepPlant(std::size_t k) {
  bool others_zero = single_.axis >= 0 && rows_ == model::kNumOutputRows;
  if (!integrator_) return others_zero;
  integrator_->AdvancePeriod(samples_.AccelAt(k).data(), SameInput(k), outputs_.data());
  if (others_zero && !watched_rows_.empty()) {
    // Branch-free: the other rows' bits all zero (rows the integrator guarantees 0 are
    // not even looked at). Anything else (-0.0 included) takes the general samples.
    std::uint64_t other_bits = 0;
    for (int j = 0; j < substeps_; ++j) {
      const double* out = outputs_.data() + static_cast<std::ptrdiff_t>(j) * rows_;
      for (int r : watched_rows_) {
        std::uint64_t bits;
        std::memcpy(&bits, out + r, sizeof bits);
        other_bits |= bits;
      }
    }
    others_zero = other_bits == 0;
  }
  // The single-axis samples check their own values' finiteness.
  if (!others_zero) CheckFinite(k);
  return others_zero;
}

void CoSimulation::Tick(std::size_t k) {
  if (defer_substeps_) {
    if (k < window_.motion_ticks) {
      DeferredTick<RunPhase::kMotion>(k);
      if (k == next_probe_tick_) ProbeCruise(k);
    } else if (k <= window_.window_end()) {
      DeferredTick<RunPhase::kWindow>(k);
      if (k == window_.motion_ticks) ProbeMotionEnd();
    } else {
      DeferredTick<RunPhase::kTail>(k);
    }
    return;
  }
  const bool others_zero = StepPlant(k);
  if (k < window_.motion_ticks) {
    SampleTick<RunPhase::kMotion>(k, others_zero);
    if (k == next_probe_tick_) ProbeCruise(k);
  } else if (k <= window_.window_end()) {
    SampleTick<RunPhase::kWindow>(k, others_zero);
    if (k == window_.motion_ticks) ProbeMotionEnd();
  } else {
    SampleTick<RunPhase::kTail>(k, others_zero);
  }
  if (nonlinear_ && k >= window_.motion_ticks) TrackFreeResponse(k, others_zero);
}

// A nonlinear plant's deflection in the view from the end of motion on (at the motion-end
// tick only its last sample, as the residual window counts it).
void CoSimulation::TrackFreeResponse(std::size_t k, bool others_zero) {
  const int first = k == window_.motion_ticks ? substeps_ - 1 : 0;
  for (int j = first; j < substeps_; ++j) {
    if (others_zero) {
      free_.Add(outputs_[static_cast<std::size_t>(j * width_ + deflection_at_)]);
    } else {
      const double* out = outputs_.data() + static_cast<std::ptrdiff_t>(j) * rows_;
      free_.Add(view_.Of(Eigen::Vector3d(out[model::kDeflectionRow], out[model::kDeflectionRow + 1],
                                         out[model::kDeflectionRow + 2])));
    }
  }
}

template <RunPhase P>
void CoSimulation::SampleTick(std::size_t k, bool others_zero) {
  // Two accumulators, so that the single-axis one never has its address taken by the
  // general samples (an out-of-line call): it then stays in registers.
  TickAccumulator tick = acc_.StartTick(P, k, window_.motion_ticks, substeps_);
  if (others_zero) {
    SampleSingleAxis<P>(k, &tick);
  } else {
    TickAccumulator general = tick;
    SampleGeneral<P>(k, &general);
    tick = general;
  }
  if (exact_extrema_) {
    // An extremum inside the period (its ends are samples); at the motion-end tick it is
    // the motion's (only that tick's last sample counts as after the motion).
    const double inside = integrator_->PeriodExtremum();
    tick.peak = std::max(tick.peak, inside);
    if constexpr (P == RunPhase::kWindow) {
      if (k != window_.motion_ticks) tick.residual = std::max(tick.residual, inside);
    }
  }
  acc_.Merge(tick, k, substeps_);
}

// SampleTick of a run with deferred substeps: the period stepped to its end; its inner
// substeps written and sampled only where they can change a metric (InnerSamplesMatter).
template <RunPhase P>
void CoSimulation::DeferredTick(std::size_t k) {
  integrator_->AdvancePeriodToEnd(samples_.AccelAt(k).data(), outputs_.data());
  const double y_end = outputs_[static_cast<std::size_t>((substeps_ - 1) * width_ + deflection_at_)];
  const double inside = integrator_->PeriodExtremum();
  // The motion-end tick's end sample alone opens the residual window: sampled in full.
  const bool inner = k == window_.motion_ticks || InnerSamplesMatter<P>(k, y_end, inside);
  period_start_m_ = y_end;
  if (!inner) {
    // No sample of the period, its end included, reaches a maximum so far; the end sample
    // can still be the last outside the settling band.
    ++result_.deferred_periods;
    if constexpr (P != RunPhase::kMotion) {
      if (std::abs(y_end) >= acc_.band) {
        acc_.last_outside_band = static_cast<long>(k) * substeps_;
        acc_.quiet_since_tick = k;
      }
    }
    return;
  }
  integrator_->WriteDeferredSubsteps(outputs_.data());
  TickAccumulator tick = acc_.StartTick(P, k, window_.motion_ticks, substeps_);
  SampleSingleAxis<P>(k, &tick);
  tick.peak = std::max(tick.peak, inside);
  if constexpr (P == RunPhase::kWindow) {
    if (k != window_.motion_ticks) tick.residual = std::max(tick.residual, inside);
  }
  acc_.Merge(tick, k, substeps_);
}

// Whether a sample of period k (its end included) can change a metric: raise the peak,
// the residual peak or the contour error so far, or be the last outside the settling band
// while the period's end is inside it (the end sample alone, outside, is taken without the
// others). The deflection (= the tool error) of every sample is within InnerSampleBound;
// the tool position within that of the command's range over the period. NaN anywhere:
// they matter (the samples then check finiteness).
template <RunPhase P>
bool CoSimulation::InnerSamplesMatter(std::size_t k, double y_end, double inside) const {
  const double bound = InnerSampleBound(period_start_m_, y_end, inside, result_.metrics.static_displacement_m);
  if (!(bound < acc_.peak)) return true;
  if constexpr (P != RunPhase::kMotion) {
    if (P == RunPhase::kWindow && !(bound < acc_.residual)) return true;
    if (!(bound < acc_.band) && !(std::abs(y_end) >= acc_.band)) return true;
  }
  const bool commanded = k <= samples_.n;
  const int ax = single_.axis;
  const double p0 = (commanded ? samples_.positions[k - 1] : samples_.positions.back())(ax);
  const double v0 = commanded ? samples_.velocity[k - 1](ax) : 0.0;
  double lo = 0.0;
  double hi = 0.0;
  QuadraticRange(p0, v0, 0.5 * samples_.AccelAt(k)(ax), dt_, &lo, &hi);
  const double off = OffLineBound(single_.start_m, single_.direction, single_.length_m, lo - bound, hi + bound);
  return off != 0.0 && !(off * off < acc_.contour_sq);
}

template <RunPhase P>
void CoSimulation::SampleSingleAxis(std::size_t k, TickAccumulator* tick) {
  const bool commanded = k <= samples_.n;
  const int ax = single_.axis;
  const double p0 = (commanded ? samples_.positions[k - 1] : samples_.positions.back())(ax);
  const double v0 = commanded ? samples_.velocity[k - 1](ax) : 0.0;
  const bool not_finite = SampleSingleAxisTick<P>(single_sampling_, p0, v0, 0.5 * samples_.AccelAt(k)(ax), tick);
  if (integrator_ && not_finite) CheckFinite(k);  // throws for a non-finite output
}

template <RunPhase P>
void CoSimulation::SampleGeneral(std::size_t k, TickAccumulator* tick) {
  const bool commanded = k <= samples_.n;
  const Eigen::Vector3d& a = samples_.AccelAt(k);
  const Eigen::Vector3d& v0 = commanded ? samples_.velocity[k - 1] : samples_.accel[0];
  const Eigen::Vector3d& p0 = commanded ? samples_.positions[k - 1] : samples_.positions.back();
  const std::size_t interpolated_ticks = command_.path_position_m.size();
  const int block = k < interpolated_ticks ? command_.block[k] : -1;
  const double path_s =
      command_.path_position_m.empty() ? 0.0 : command_.path_position_m[std::min(k, interpolated_ticks - 1)];
  const double largest_sq = acc_.contour_sq;  // the run's so far (the tick's is merged after it)
  for (int j = 0; j < substeps_; ++j) {
    const double* out = outputs_.data() + static_cast<std::ptrdiff_t>(j) * rows_;
    const double tau = taus_[j];
    const Eigen::Vector3d p = p0 + v0 * tau + 0.5 * a * tau * tau;
    const Eigen::Vector3d deflection(out[model::kDeflectionRow], out[model::kDeflectionRow + 1],
                                     out[model::kDeflectionRow + 2]);
    const Eigen::Vector3d actual =
        p + Eigen::Vector3d(out[model::kToolErrorRow], out[model::kToolErrorRow + 1], out[model::kToolErrorRow + 2]);
    if (options_.record_trace) {
      const Eigen::Vector3d v = v0 + a * tau;
      travelled_m_ += v.norm() * dt_ / substeps_;
      const long count = static_cast<long>((k - 1) * substeps_) + j + 1;
      Record(dt_ * static_cast<double>(count) / substeps_, p, v, a, deflection, actual, block);
    }
    peak_axes_ = peak_axes_.cwiseMax(deflection.cwiseAbs());
    if (has_stroke_) overshoot_ = std::max(overshoot_, controller::StrokeOvershoot(p, scenario_.machine.stroke_m));
    for (ReversalWindows& g : glitches_) g.Add(path_s, actual);
    for (ArcWindow& w : arcs_) {
      const double from_start = path_s - w.arc->start_s_m;
      if (from_start >= 0.25 * w.arc->length_m && from_start <= 0.75 * w.arc->length_m) {
        w.sum_radius_m += std::hypot(actual(w.arc->axis0) - w.arc->center_m(w.arc->axis0),
                                     actual(w.arc->axis1) - w.arc->center_m(w.arc->axis1));
        ++w.samples;
      }
    }
    tick->Add<P>(j, std::abs(view_.Of(deflection)), contour_gauge_.SquaredDistanceTo(actual, largest_sq));
  }
}

bool CoSimulation::SettleTail(std::size_t k, bool* settled, std::size_t* last_tick) {
  if (!damped_tail_ || k != window_.window_end() || !damped_tail_->Split(integrator_->PlantState())) return false;
  // The tail adds nothing to the peaks or the contour error (the path's end is the command's
  // last position): every row's envelope within what the run has already seen, with a
  // margin for rounding.
  constexpr double kMargin = 1.0 + 1e-9;
  double tool_error_sq = 0.0;
  for (int b = 0; b < model::kNumAxes; ++b) {
    const double seen = b == view_.axis ? std::max(acc_.peak, peak_axes_(b)) : peak_axes_(b);
    if (!(damped_tail_->Envelope(model::kDeflectionRow + b) * kMargin <= seen)) return false;
    tool_error_sq += std::pow(damped_tail_->Envelope(model::kToolErrorRow + b), 2);
  }
  if (!(tool_error_sq * kMargin <= acc_.contour_sq)) return false;
  const double crossing = damped_tail_->LastCrossing(acc_.band);
  if (std::isnan(crossing)) return false;
  // The last sample on the run's grid (dt / substeps) at or before the crossing outside
  // the band: settling_time_s as the simulated tail had it.
  long last_outside = acc_.last_outside_band;
  std::size_t quiet = acc_.quiet_since_tick;
  const long from = crossing >= 0.0 ? static_cast<long>(std::floor(crossing * substeps_ / dt_)) + 1 : 0;
  for (long j = from; j >= 1; --j) {
    if (std::abs(damped_tail_->ViewAt(dt_ * static_cast<double>(j) / substeps_)) >= acc_.band) {
      last_outside = static_cast<long>(k) * substeps_ + j;
      quiet = static_cast<std::size_t>((last_outside - 1) / substeps_ + 1);
      break;
    }
  }
  const std::size_t stop = quiet + window_.period_ticks;  // > k: Done(k) was false
  const std::size_t end = std::min(stop, window_.max_ticks);
  if (end < k || !integrator_->AdvanceAtRest(static_cast<long>(end - k))) return false;
  acc_.last_outside_band = last_outside;
  acc_.quiet_since_tick = quiet;
  *settled = stop <= window_.max_ticks;
  *last_tick = end;
  result_.tail_in_closed_form = true;
  return true;
}

// The free vibration at motion end (the acceleration 0 from here on: equilibrium 0), per
// pole into the result, their sum into residual_amplitude_m.
void CoSimulation::ProbeMotionEnd() {
  if (!residual_vibration_) return;
  result_.residual_modes = residual_vibration_->Amplitudes(integrator_->PlantState(), Eigen::Vector3d::Zero());
  residual_m_ = ResidualVibration::Total(result_.residual_modes);
  if (std::isnan(residual_m_)) {
    result_.warnings.push_back(
        "the plant's state does not split into its modes (a critically damped pole?): residual_ratio is n/a");
  }
}

// Cruise probe k: the vibration about the equilibrium at the cruise velocity v_k.
void CoSimulation::ProbeCruise(std::size_t k) {
  ++next_probe_;
  next_probe_tick_ = next_probe_ < window_.cruise_probe_ticks.size() ? window_.cruise_probe_ticks[next_probe_]
                                                                      : std::numeric_limits<std::size_t>::max();
  // A nonlinear plant's state does not split into modes: no cruise amplitude (n/a).
  const double amplitude =
      residual_vibration_ ? ResidualVibration::Total(residual_vibration_->Amplitudes(
                                integrator_->PlantState(), samples_.velocity[k]))
      : nonlinear_        ? NAN
                          : 0.0;
  // The largest; a failed split (NaN) stays.
  if (next_probe_ == 1 || std::isnan(amplitude) || amplitude > cruise_m_) cruise_m_ = amplitude;
}

void CoSimulation::Record(double t, const Eigen::Vector3d& p, const Eigen::Vector3d& v,
                          const Eigen::Vector3d& a, const Eigen::Vector3d& deflection,
                          const Eigen::Vector3d& actual, int block) {
  Trace& trace = result_.trace;
  trace.time_s.push_back(t);
  trace.command_position_m.push_back(view_.magnitude ? travelled_m_ : view_.Of(p));
  trace.command_velocity_m_s.push_back(view_.Of(v));
  trace.command_accel_m_s2.push_back(view_.Of(a));
  trace.deflection_m.push_back(view_.Of(deflection));
  trace.command_m.push_back(p);
  trace.actual_m.push_back(actual);
  trace.deflection_axes_m.push_back(deflection);
  trace.block.push_back(block);
  trace.planned_feed_mm_min.push_back(
      block >= 0 ? command_.block_feed_m_s[static_cast<std::size_t>(block)] * 60000.0 : 0.0);
}

void CoSimulation::Finish(std::size_t last_tick, bool settled) {
  result_.simulated_s = static_cast<double>(last_tick) * dt_;
  Metrics& m = result_.metrics;
  m.motion_time_s = static_cast<double>(window_.motion_ticks) * dt_;
  if (settled) {
    // The sample's time as the samples have it: dt * count / substeps.
    m.settling_time_s = acc_.last_outside_band < 0
                            ? 0.0
                            : dt_ * static_cast<double>(acc_.last_outside_band) / substeps_ + dt_ / substeps_ -
                                  m.motion_time_s;
  }
  FinishMetrics(&m);
  if (integrator_) result_.stats = integrator_->Stats();
  if (!unchecked_.empty()) {
    if (scenario_.integrator.cross_check == model::CrossCheckPolicy::kRefuse) {
      throw model::SolverError("CROSS_CHECK_FAILED", unchecked_);
    }
    result_.warnings.push_back(unchecked_);
  }
}


// A nonlinear plant (docs/metrics.md): the residual from its free response after motion end
// (half its peak-to-peak: one undamped mode's amplitude exactly), where it comes to rest, and
// the quadrant glitches of its arcs.
void CoSimulation::FinishNonlinearMetrics(Metrics* m) const {
  if (free_.any) {
    m->residual_amplitude_m = 0.5 * (free_.max - free_.min);
    m->residual_ratio = m->static_displacement_m > 0.0 ? m->residual_amplitude_m / m->static_displacement_m : NAN;
    m->dead_band_m = std::abs(free_.last);
  }
  for (const ReversalWindows& g : glitches_) {
    const double glitch = g.Glitch();
    if (!std::isnan(glitch) && !(glitch <= m->quadrant_glitch_m)) m->quadrant_glitch_m = glitch;
  }
}

void CoSimulation::FinishMetrics(Metrics* m) const {
  Eigen::Vector3d peak_axes = peak_axes_;
  if (single_.axis >= 0) peak_axes(single_.axis) = std::max(peak_axes(single_.axis), acc_.peak);
  // The view's axis: its peak found inside the periods too (|deflection| of that axis).
  if (exact_extrema_) peak_axes(view_.axis) = std::max(peak_axes(view_.axis), acc_.peak);
  m->peak_deflection_m = acc_.peak;
  m->peak_ratio = acc_.peak / m->static_displacement_m;
  m->residual_amplitude_m = residual_m_;
  m->residual_ratio = residual_m_ / m->static_displacement_m;
  m->residual_peak_m = acc_.residual;
  m->residual_peak_ratio = acc_.residual / m->static_displacement_m;
  m->cruise_residual_ratio = cruise_m_ / m->static_displacement_m;
  m->max_contour_error_m = std::sqrt(acc_.contour_sq);
  for (const ArcWindow& w : arcs_) {
    if (w.samples == 0) continue;
    const double programmed = 0.5 * (w.arc->start_radius_m + w.arc->end_radius_m);
    const double error = programmed - w.sum_radius_m / static_cast<double>(w.samples);
    if (std::isnan(m->radial_error_m) || std::abs(error) > std::abs(m->radial_error_m)) m->radial_error_m = error;
  }
  if (nonlinear_) FinishNonlinearMetrics(m);
  m->peak_deflection_x_m = peak_axes(0);
  m->peak_deflection_y_m = peak_axes(1);
  m->peak_deflection_z_m = peak_axes(2);
  m->short_block_clamps = command_.short_block_clamps;
  m->stroke_overshoot_m = overshoot_;
  m->stroke_alarm = command_.stroke_alarm ? 1.0 : 0.0;
  SetPatternMetrics(scenario_.controller.pattern, m);
}

// A metric that overflowed is a degenerate model, never a number (NaN is "undefined").
void RefuseInfiniteMetrics(const Metrics& m) {
  for (const MetricInfo& info : MetricTable()) {
    if (std::isinf(m.*info.field)) {
      throw model::SolverError("NON_FINITE_STATE",
                               std::string(info.name) + " overflowed to infinity (a degenerate model)");
    }
  }
}

}  // namespace

double StaticDisplacement(const CommandSamples& s, const Eigen::Matrix3d& static_gain, const OutputView& view,
                          Eigen::Vector3d* vector) {
  double static_m = 0.0;
  std::size_t at = 0;
  // Once per held acceleration (the same a, the same value: the first tick reaching the
  // largest is the first of its run).
  for (const std::size_t k : s.accel_changes) {
    const double here = std::abs(view.Of(static_gain * s.accel[k]));
    if (here > static_m) {
      static_m = here;
      at = k;
    }
  }
  *vector = Eigen::Vector3d::Zero();
  if (at == 0) return static_m;
  const Eigen::Vector3d deflection = static_gain * s.accel[at];
  const double along = view.magnitude ? deflection.dot(s.accel[at]) : view.Of(deflection);
  for (int b = 0; b < 3; ++b) {
    const double entry = along < 0.0 ? -deflection(b) : deflection(b);
    (*vector)(b) = entry == 0.0 ? 0.0 : entry;  // no -0 for the axes it does not deflect
  }
  return static_m;
}

void SetPatternMetrics(const controller::PatternConfig& pattern, Metrics* m) {
  const controller::ShaperKind kind = controller::FindShaper(pattern.method).kind;
  if (pattern.mode == controller::PatternMode::kOff ||
      (kind != controller::ShaperKind::kPatentStep && kind != controller::ShaperKind::kImpulse)) {
    return;
  }
  const std::vector<double> frequencies = pattern.DesignFrequencies();
  const std::size_t lowest = static_cast<std::size_t>(
      std::min_element(frequencies.begin(), frequencies.end()) - frequencies.begin());
  m->pattern_frequency_hz = frequencies[lowest];
  m->pattern_damping_ratio =
      kind == controller::ShaperKind::kPatentStep ? 0.0 : pattern.DesignDampingRatios()[lowest];
}

controller::MultiAxisCommand GenerateScenarioCommand(const Scenario& scenario, const controller::Program& program) {
  controller::ControllerConfig controller = scenario.controller;
  controller.stroke_limits = scenario.machine.stroke_m;  // the CNC's stroke check
  // The memory budget again, on the planned length, before the per-tick command exists.
  controller::CommandLimits limits;
  limits.max_ticks = static_cast<std::size_t>(std::min(MemoryTickLimit(scenario.limits), 1e18));
  limits.key = "limits.max_memory_mb";
  return controller::GenerateProgramCommand(controller, program, limits);
}

RunResult RunScenario(const Scenario& scenario, const RunOptions& options) {
  RunResult result;
  // Stage 1, the command: generated here, or shared by a sweep's points.
  result.program = scenario.RunProgram();
  if (options.command == nullptr) result.command = GenerateScenarioCommand(scenario, result.program);
  const controller::MultiAxisCommand& command = options.command != nullptr ? *options.command : result.command;
  const controller::PathGeometry path(result.program);
  // One mode along one line: the metrics from the closed forms of single_mode_run.h; with a
  // trace, the general path below records it and the metrics stay the closed forms' (one
  // answer whatever a run records: run, run --json, a sweep's point, the Python API).
  CommandSamples own_samples;
  RunOptions sampled = options;
  RunResult closed;
  if (options.single_mode && SingleModeQualifies(scenario, path)) {
    if (options.command == nullptr || options.samples == nullptr) {
      own_samples = SampleCommand(command);
      sampled.command = &command;
      sampled.samples = &own_samples;
    }
    closed.single_mode = RunSingleMode(scenario, command, *sampled.samples, path, &closed);
    if (closed.single_mode) RefuseInfiniteMetrics(closed.metrics);
    if (closed.single_mode && !options.record_trace) {
      closed.program = std::move(result.program);
      closed.command = std::move(result.command);
      return closed;
    }
  }
  // Stage 2, the set-up: the plant, the command's samples, the run window, the samplers.
  CoSimulation sim(scenario, command, path, sampled, &result);
  // Stage 3, the tick loop (FMI order in Tick: set the input, step, read the outputs).
  bool settled = false;
  std::size_t last_tick = 0;
  for (std::size_t k = 1; k <= sim.max_ticks(); ++k) {
    sim.Tick(k);
    last_tick = k;
    if (sim.Done(k, &settled)) break;
    if (sim.SettleTail(k, &settled, &last_tick)) break;
  }
  // Stage 4, the metrics.
  sim.Finish(last_tick, settled);
  RefuseInfiniteMetrics(result.metrics);
  if (closed.single_mode) {
    result.metrics = closed.metrics;
    result.residual_modes = std::move(closed.residual_modes);
    result.single_mode = true;
  }
  return result;
}

}  // namespace shapebench::bench

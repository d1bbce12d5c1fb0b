// NonlinearCvodeIntegrator: CVODE (SUNDIALS 6.4.1) BDF with root finding on a NonlinearPlant.
#include "model/nonlinear_integrator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <variant>

#include <sunmatrix/sunmatrix_dense.h>

#include "common/validation_error.h"
#include "model/cvode_integrator.h"
#include "model/cvode_memory.h"

namespace shapebench::model {
namespace {

// Events at one instant beyond this are a chattering model (two elements handing a force
// back and forth forever), not physics: the run fails instead of looping.
constexpr long kMaxEventsPerSubstep = 10000;

// The split (CvodeTuning::split_linear_part) pays where e stays a small correction to z:
// LuGre friction, smooth, no modes. Not for the others: a stuck Coulomb or Stribeck element
// holds its w at 0 exactly only in the whole state (split, row (z_p + e) would stay 0 only
// to CVODE's tolerance while z_p moves: a stuck body would creep); a saturated drive or an
// open backlash gap replaces the linear part's force, so e ~ -z_p and CVODE's rtol on e is
// loose on z (measured: the force-limit run of tests/bench/nonlinear_run_test.cc overshot
// its limit by 0.19% at rtol 1e-8 split, within 0.1% whole).
bool SplitPays(const NonlinearPlant& plant) {
  if (plant.elements.empty()) return false;  // nothing to split off
  for (const NonlinearElement& e : plant.elements) {
    const auto* friction = std::get_if<FrictionElement>(&e.law);
    if (friction == nullptr || !friction->HasBristle()) return false;
  }
  return true;
}

}  // namespace

NonlinearCvodeIntegrator::NonlinearCvodeIntegrator(const NonlinearPlant& plant, const IntegratorConfig& config,
                                                   double period_s, int substeps, double scale_accel_m_s2,
                                                   double scale_velocity_m_s)
    : num_states_(plant.linear.num_states()),
      num_inputs_(plant.linear.num_inputs()),
      period_s_(period_s),
      substeps_(substeps),
      C_(plant.linear.C),
      B_z_(plant.linear.AugmentedB()),
      accel_(Eigen::VectorXd::Zero(plant.linear.num_inputs())),
      all_outputs_(plant.linear.C.rows()),
      dynamics_(plant),
      roots_found_(std::max(dynamics_.num_roots(), 1), 0) {
  for (int c = 0; c < C_.cols(); ++c) {
    for (int r = 0; r < C_.rows(); ++r) {
      if (C_(r, c) != 0.0) c_entries_.push_back({r, c, C_(r, c)});
    }
  }
  // Newton's matrix I - gamma J is a dense SUNMatrix (the storage LinSys fills), solved by
  // blocks (the axes are uncoupled).
  CvodeProblem problem;
  problem.size = dynamics_.size();
  problem.solver = CvodeSolver::kBlockLu;
  problem.blocks = dynamics_.Blocks();
  memory_ = std::make_unique<CvodeMemory>(std::make_shared<CvodeContext>(), std::move(problem), Rhs);
  jacobian_ = Eigen::MatrixXd::Zero(dynamics_.size(), dynamics_.size());
  void* mem = memory_->cvode();
  Check(CVodeSetErrHandlerFn(mem, RecordError, this), "CVodeSetErrHandlerFn");
  Check(CVodeSetUserData(mem, this), "CVodeSetUserData");
  Eigen::Map<Eigen::VectorXd>(N_VGetArrayPointer(memory_->atol()), dynamics_.size()) =
      AbsoluteTolerances(plant, config, scale_accel_m_s2, scale_velocity_m_s);
  Check(CVodeSVtolerances(mem, config.rtol, memory_->atol()), "CVodeSVtolerances");
  // The plant's Jacobian (NonlinearDynamics::Jacobian), I - gamma J formed here.
  Check(CVodeSetLinSysFn(mem, LinSys), "CVodeSetLinSysFn");
  Check(CVodeSetMaxNumSteps(mem, config.max_num_steps), "CVodeSetMaxNumSteps");
  if (dynamics_.num_roots() > 0) {
    Check(CVodeRootInit(mem, dynamics_.num_roots(), RootFn), "CVodeRootInit");
    // A root function at 0 where integration (re)starts (a stuck element's w, an edge just
    // reached) is expected: CVODE waits for it to move away before looking again.
    Check(CVodeSetNoInactiveRootWarn(mem), "CVodeSetNoInactiveRootWarn");
    std::vector<int> directions = dynamics_.RootDirections();
    Check(CVodeSetRootDirection(mem, directions.data()), "CVodeSetRootDirection");
  }
  if (config.tuning.split_linear_part && SplitPays(plant)) {
    Eigen::MatrixXd probes(dynamics_.num_elements(), dynamics_.num_augmented());
    for (int i = 0; i < dynamics_.num_elements(); ++i) {
      probes.row(i) << plant.elements[i].row_x.transpose(), plant.elements[i].row_v.transpose();
    }
    particular_ = std::make_unique<HeldInputResponse>(plant.linear, period_s, substeps, probes);
    // Split, e's Newton matrix I - gamma J may wait for gamma to change by 100% (CVODE's
    // default 30%): the steps truncated at every tick's end change gamma each tick. Measured
    // on benchmark case 4: 72,000 steps instead of 88,000, 5,400 Newton set-ups instead of
    // 20,800, the deflection as close to the tight run (2.0e-5 against 2.1e-5 of its scale).
    Check(CVodeSetDeltaGammaMaxLSetup(mem, 1.0), "CVodeSetDeltaGammaMaxLSetup");
    probe_values_.assign(dynamics_.num_elements(), 0.0);
    probe_rates_.assign(dynamics_.num_elements(), 0.0);
  } else {
    // Whole state: a following error e and its rate e' are integrated as the motor's
    // position e + u and velocity e' + v, exactly 0 while friction holds the motor (e = -u
    // would take CVODE's rtol |u| into the tool position: issue 32). Split, e stays a
    // correction.
    for (std::size_t i = 0; i < plant.following_error_axis.size(); ++i) {
      const int axis = plant.following_error_axis[i];
      if (axis < 0) continue;
      // e' (a velocity) as the motor's velocity e' + v, exactly 0 while the motor is held.
      auto* kind = plant.linear.state_kinds[i] == StateKind::kVelocity ? &velocity_lags_ : &lags_;
      kind->emplace_back(static_cast<int>(i), axis);
    }
    plant_y_.assign(dynamics_.size(), 0.0);
    if (!lags_.empty()) {
      rtol_ = config.rtol;
      atol_ = Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(memory_->atol()), dynamics_.size());
      Check(CVodeWFtolerances(mem, ErrorWeights), "CVodeWFtolerances");
    }
  }
  Reset(Eigen::VectorXd::Zero(num_inputs_));
}

NonlinearCvodeIntegrator::~NonlinearCvodeIntegrator() = default;

// The linear part's tolerances (CvodeAbsoluteTolerances), a bristle deflection's from its
// largest value F_s / sigma0.
Eigen::VectorXd NonlinearCvodeIntegrator::AbsoluteTolerances(const NonlinearPlant& plant,
                                                             const IntegratorConfig& config,
                                                             double scale_accel_m_s2,
                                                             double scale_velocity_m_s) const {
  const Eigen::VectorXd linear = CvodeAbsoluteTolerances(plant.linear, config, scale_accel_m_s2, scale_velocity_m_s);
  Eigen::VectorXd atol(dynamics_.size());
  atol.head(linear.size()) = linear;
  const std::vector<double> bristles = dynamics_.BristleScales();
  for (std::size_t i = 0; i < bristles.size(); ++i) {
    atol(linear.size() + static_cast<Eigen::Index>(i)) = config.rtol * config.atol_scale * bristles[i];
  }
  return atol;
}

int NonlinearCvodeIntegrator::Rhs(double t, N_Vector y, N_Vector ydot, void* user_data) {
  auto* self = static_cast<NonlinearCvodeIntegrator*>(user_data);
  self->OffsetsAt(t);
  const double* state = N_VGetArrayPointer(y);
  double* rate = N_VGetArrayPointer(ydot);
  self->dynamics_.Rhs(self->PlantY(t, state), rate);
  // (e + u)' = e' + v, v the drive velocity state.
  for (const auto& [i, axis] : self->lags_) rate[i] += state[self->num_states_ + axis];
  for (const auto& [i, axis] : self->velocity_lags_) rate[i] += rate[self->num_states_ + axis];
  return 0;
}

// CVODE's weights rtol |y_i| + atol_i, but for a motor position s = e + u from the smaller
// of |s| and |e|: a moving motor's e keeps the accuracy it had as a state of its own (rtol
// of a following error of millimetres, not of the distance travelled), a held motor's
// position that of a position near 0. The position's own rounding is always allowed (an e
// of 0, full feedforward, has a 1e-20 m atol; 1e-17 of u is what a double holds: CVODE
// would stop, too much accuracy requested).
int NonlinearCvodeIntegrator::ErrorWeights(N_Vector y, N_Vector ewt, void* user_data) {
  auto* self = static_cast<NonlinearCvodeIntegrator*>(user_data);
  double t = 0.0;
  if (CVodeGetCurrentTime(self->memory_->cvode(), &t) < 0) return -1;  // the step's start
  const double* whole = N_VGetArrayPointer(y);
  const double* state = self->PlantY(t, whole);
  double* weight = N_VGetArrayPointer(ewt);
  for (Eigen::Index i = 0; i < self->atol_.size(); ++i) {
    const double rounding = 100.0 * std::numeric_limits<double>::epsilon() * std::abs(whole[i]);
    const double size = std::min(std::abs(state[i]), std::abs(whole[i]));
    const double allowed = self->rtol_ * size + self->atol_(i) + rounding;
    if (!(allowed > 0.0)) return -1;
    weight[i] = 1.0 / allowed;
  }
  return 0;
}

int NonlinearCvodeIntegrator::RootFn(double t, N_Vector y, double* gout, void* user_data) {
  auto* self = static_cast<NonlinearCvodeIntegrator*>(user_data);
  self->OffsetsAt(t);
  self->dynamics_.Roots(self->PlantY(t, N_VGetArrayPointer(y)), gout);
  return 0;
}

// The elements read row . (z_p + e): z_p's rows at t from this tick's series.
void NonlinearCvodeIntegrator::OffsetsAt(double t, bool with_rates) {
  if (!particular_) return;
  particular_->Probe(t - TickStart(), probe_values_.data(),
                     with_rates || dynamics_.ReadsRates() ? probe_rates_.data() : nullptr);
  dynamics_.SetOffsets(probe_values_.data(), probe_rates_.data());
}

double NonlinearCvodeIntegrator::CommandAt(int axis, double t) const {
  const double tau = t - command_t_;
  return command_position_(axis) + tau * (command_velocity_(axis) + 0.5 * tau * accel_(axis));
}

void NonlinearCvodeIntegrator::ShiftFollowingErrors(double t, double sign, double* y) const {
  for (const auto& [i, axis] : lags_) y[i] += sign * CommandAt(axis, t);
  for (const auto& [i, axis] : velocity_lags_) y[i] += sign * y[num_states_ + axis];
}

const double* NonlinearCvodeIntegrator::PlantY(double t, const double* y) {
  if (lags_.empty()) return y;
  std::copy(y, y + plant_y_.size(), plant_y_.begin());
  ShiftFollowingErrors(t, -1.0, plant_y_.data());
  return plant_y_.data();
}

void NonlinearCvodeIntegrator::SyncParticular(long tick) {
  for (; particular_tick_ < tick; ++particular_tick_) particular_->NextTick();
}

Eigen::VectorXd NonlinearCvodeIntegrator::ParticularState() const {
  return particular_->StateAt(Time() - TickStart()).head(num_states_);
}

// CVODE's Newton matrix I - gamma J: the Jacobian evaluated when CVODE says it is stale
// (jok false: the first step after a restart, a failed convergence, 50 steps), else the
// last one kept; SUNDenseMatrix data is column-major, like Eigen's default.
int NonlinearCvodeIntegrator::LinSys(double t, N_Vector y, N_Vector /*fy*/, SUNMatrix a, booleantype jok,
                                     booleantype* jcur, double gamma, void* user_data, N_Vector /*tmp1*/,
                                     N_Vector /*tmp2*/, N_Vector /*tmp3*/) {
  auto* self = static_cast<NonlinearCvodeIntegrator*>(user_data);
  if (!jok) self->OffsetsAt(t);
  if (!jok) {
    self->dynamics_.Jacobian(self->PlantY(t, N_VGetArrayPointer(y)), self->jacobian_.data());
    // In the shifted states (e' + v: column v less column e'; v' = a has no row to add).
    for (const auto& [i, axis] : self->velocity_lags_) {
      self->jacobian_.col(self->num_states_ + axis) -= self->jacobian_.col(i);
    }
    for (const auto& [i, axis] : self->lags_) self->jacobian_(i, self->num_states_ + axis) += 1.0;
  }
  *jcur = jok ? SUNFALSE : SUNTRUE;
  const Eigen::Index n = self->jacobian_.rows();
  Eigen::Map<Eigen::MatrixXd> m(SUNDenseMatrix_Data(a), n, n);
  m.noalias() = -gamma * self->jacobian_;
  m.diagonal().array() += 1.0;
  return 0;
}

void NonlinearCvodeIntegrator::RecordError(int /*code*/, const char* /*module*/, const char* /*function*/,
                                           char* msg, void* user_data) {
  if (user_data == nullptr) return;
  static_cast<NonlinearCvodeIntegrator*>(user_data)->last_message_ = msg != nullptr ? msg : "";
}

void NonlinearCvodeIntegrator::Check(int flag, const char* call) const {
  if (flag >= 0) return;
  ThrowCvodeFailure(flag, call, Time(), last_message_, true);
}

void NonlinearCvodeIntegrator::Reset(const Eigen::VectorXd& drive_velocity) {
  if (drive_velocity.size() != num_inputs_) {
    throw std::invalid_argument("NonlinearCvodeIntegrator::Reset: wrong drive velocity size");
  }
  double* y = N_VGetArrayPointer(memory_->y());
  std::fill(y, y + dynamics_.size(), 0.0);
  accel_.setZero();
  dynamics_.SetForcing(Eigen::VectorXd::Zero(num_states_ + num_inputs_));
  if (particular_) {
    // z_p starts at rest at the drive's velocity; e = 0.
    Eigen::VectorXd z0 = Eigen::VectorXd::Zero(num_states_ + num_inputs_);
    z0.tail(num_inputs_) = drive_velocity;
    particular_->Reset(z0);
    particular_tick_ = 0;
    OffsetsAt(0.0, true);
  } else {
    std::copy(drive_velocity.data(), drive_velocity.data() + num_inputs_, y + num_states_);
  }
  command_t_ = 0.0;
  command_position_ = Eigen::VectorXd::Zero(num_inputs_);
  command_velocity_ = drive_velocity;
  count_ = 0;
  events_ = 0;
  dynamics_.InitModes(y);  // e = s = 0: the same in either form
  Check(CVodeReInit(memory_->cvode(), 0.0, memory_->y()), "CVodeReInit");
  stop_set_ = false;
  finished_ = {};
  need_reinit_ = false;
  pending_event_ = false;
}

// CVODE restarted at t from memory_->y(), its counts so far kept.
void NonlinearCvodeIntegrator::RestartAt(double t) {
  long steps = 0;
  long rhs_evals = 0;
  CVodeGetNumSteps(memory_->cvode(), &steps);
  CVodeGetNumRhsEvals(memory_->cvode(), &rhs_evals);
  finished_.steps += steps;
  finished_.rhs_evals += rhs_evals;
  Check(CVodeReInit(memory_->cvode(), t, memory_->y()), "CVodeReInit");
  stop_set_ = false;  // CVodeReInit forgets the stop time (SUNDIALS 6.4.1)
}

void NonlinearCvodeIntegrator::Reinit() {
  ++finished_.reinits;
  RestartAt(Time());
  need_reinit_ = false;
  pending_event_ = false;  // beyond Time(): found again from the new start if still there
}

void NonlinearCvodeIntegrator::ApplyInput(const double* drive_accel) {
  const Eigen::Map<const Eigen::VectorXd> accel(drive_accel, num_inputs_);
  if (particular_) SyncParticular(count_ / substeps_);  // under the input held so far
  if (accel == accel_) return;
  if (!lags_.empty()) {  // the command so far, before the new input takes over
    const double t = Time();
    for (int axis = 0; axis < num_inputs_; ++axis) command_position_(axis) = CommandAt(axis, t);
    command_velocity_ += (t - command_t_) * accel_;
    command_t_ = t;
  }
  if (particular_) {
    // The jump goes into z_p; e's equation has no forcing. Only a stuck element's holding
    // force jumps with the input (its rate offset): it may break loose.
    accel_ = accel;
    particular_->SetInput(accel_.data());
    OffsetsAt(Time(), true);
    if (dynamics_.ReleaseOverloaded(N_VGetArrayPointer(memory_->y()))) need_reinit_ = true;
    return;
  }
  // As CvodeIntegrator: a change of rounding size (1e-12 of the input) keeps the history;
  // any other jump restarts it. Stepping over small jumps (a circle's acceleration turns
  // 6e-4 of itself a tick) was measured: a fifth faster on benchmark case 4, but 40 times
  // further from a tight reference (9e-4 of the deflection scale against 2e-5 at rtol
  // 1e-8), the error gathered where the guides stick (docs/performance.md).
  bool small = true;
  for (int i = 0; i < num_inputs_; ++i) {
    const double scale = std::max(std::abs(accel(i)), std::abs(accel_(i)));
    small = small && std::abs(accel(i) - accel_(i)) <= 1e-12 * scale;
  }
  accel_ = accel;
  dynamics_.SetForcing(B_z_ * accel_);
  // The new forcing may break a stuck element loose (its holding force jumps with it).
  const bool modes = dynamics_.ReleaseOverloaded(PlantY(Time(), N_VGetArrayPointer(memory_->y())));
  if (!small || modes) need_reinit_ = true;
}

void NonlinearCvodeIntegrator::SetInput(const Eigen::VectorXd& drive_accel) {
  if (drive_accel.size() != num_inputs_) {
    throw std::invalid_argument("NonlinearCvodeIntegrator::SetInput: wrong drive acceleration size");
  }
  ApplyInput(drive_accel.data());
}

// To the output substep `count`, through the events on the way: at each, CVODE's state
// there gets the new modes (and a sticking element's impulse) and integration restarts.
void NonlinearCvodeIntegrator::Advance(long count) {
  if (particular_) {
    AdvanceOneStep(count);
    return;
  }
  const double t_out = TimeAt(count);
  for (long events = 0;;) {
    if (need_reinit_) Reinit();
    double t_reached = 0.0;
    if (CallCvode(t_out, memory_->y(), CV_NORMAL, &t_reached) != CV_ROOT_RETURN) return;
    event_s_ = t_reached;
    ApplyEvent(memory_->y(), &events);
    if (OnSubstepEnd(t_out, t_reached)) return;
  }
}

// CVode towards t_out in `mode` (the stop time set again where CVODE forgot it), the roots
// found recorded; its return flag.
int NonlinearCvodeIntegrator::CallCvode(double t_out, N_Vector out, int mode, double* t_reached) {
  void* mem = memory_->cvode();
  if (!stop_set_) {
    Check(CVodeSetStopTime(mem, stop_s_), "CVodeSetStopTime");
    stop_set_ = true;
  }
  const int flag = CVode(mem, t_out, out, t_reached, mode);
  Check(flag, "CVode");
  if (flag == CV_TSTOP_RETURN) stop_set_ = false;
  if (flag == CV_ROOT_RETURN) Check(CVodeGetRootInfo(mem, roots_found_.data()), "CVodeGetRootInfo");
  return flag;
}

// An event on the substep's end (to rounding): the state there is the output.
bool NonlinearCvodeIntegrator::OnSubstepEnd(double t_out, double t) {
  return t_out - t <= 1e-13 * std::max(1.0, std::abs(t_out));
}

// Split: CVODE steps one internal step at a time (CV_ONE_STEP) and the substep's state is
// interpolated from its history (CVodeGetDky). In CV_NORMAL mode CVODE would also evaluate
// the root functions at every output time: on benchmark case 4 (26 substeps a tick) 358,000
// root evaluations a run instead of 88,000. A root found beyond the output time stays
// pending: the output before it is interpolated from the same history, and the event is
// applied when time reaches it. (The whole-state path keeps CV_NORMAL: a stuck body's
// state then stays the same to the bit, which its tests read.)
void NonlinearCvodeIntegrator::AdvanceOneStep(long count) {
  const double t_out = TimeAt(count);
  void* mem = memory_->cvode();
  SyncParticular((count - 1) / substeps_);
  for (long events = 0;;) {
    if (pending_event_) {
      if (event_s_ > t_out) break;  // after this substep
      pending_event_ = false;
      ApplyEvent(memory_->step(), &events);
      if (OnSubstepEnd(t_out, event_s_)) return;
      continue;
    }
    if (need_reinit_) Reinit();
    double t_now = 0.0;
    Check(CVodeGetCurrentTime(mem, &t_now), "CVodeGetCurrentTime");
    if (t_now >= t_out) break;
    double t_reached = 0.0;
    if (CallCvode(t_out, memory_->step(), CV_ONE_STEP, &t_reached) == CV_ROOT_RETURN) {
      pending_event_ = true;
      event_s_ = t_reached;
    }
  }
  Check(CVodeGetDky(mem, t_out, 0, memory_->y()), "CVodeGetDky");
}

// The event at event_s_ (roots_found_), CVODE's state there in `state`: the new modes (and
// a sticking element's impulse) there, and a restart from it.
void NonlinearCvodeIntegrator::ApplyEvent(N_Vector state, long* events) {
  if (*events == kMaxEventsPerSubstep) {
    last_message_ = "more than " + std::to_string(kMaxEventsPerSubstep) +
                    " switching events (stick/slip, contact, limit) within one output substep";
    Check(CV_TOO_MUCH_WORK, "CVode");
  }
  ++*events;
  ++events_;
  if (state != memory_->y()) N_VScale(1.0, state, memory_->y());
  OffsetsAt(event_s_, true);  // the modes may change: a new stuck element reads its rate
  double* y = N_VGetArrayPointer(memory_->y());
  ShiftFollowingErrors(event_s_, -1.0, y);  // the impulses act on the plant's state
  dynamics_.HandleRoots(roots_found_.data(), y);
  ShiftFollowingErrors(event_s_, 1.0, y);
  RestartAt(event_s_);
}

void NonlinearCvodeIntegrator::Step() {
  stop_s_ = TimeAt((count_ / substeps_ + 1) * substeps_);  // the input may jump there
  stop_set_ = false;
  Advance(count_ + 1);
  ++count_;
}

void NonlinearCvodeIntegrator::AdvancePeriod(const double* drive_accel, long same_input_periods,
                                             double* outputs) {
  ApplyInput(drive_accel);
  const long period_start = count_ / substeps_ * substeps_;
  // Split: z_p's series covers one tick, so CVODE stops at each tick's end (its history
  // goes on across it).
  const long periods = particular_ ? 1L : std::max(1L, same_input_periods);
  const double stop = TimeAt(period_start + periods * substeps_);
  if (stop != stop_s_) {
    stop_s_ = stop;
    stop_set_ = false;
  }
  const int width = output_width();
  for (int j = 0; j < substeps_; ++j) {
    Advance(count_ + 1);
    ++count_;
    if (particular_) {
      particular_->OutputsAt(j + 1, all_outputs_.data());
    } else {
      all_outputs_.setZero();
    }
    // C y over C's entries that are not 0 (an axis' rows read that axis' states).
    const double* y = PlantY(Time(), N_VGetArrayPointer(memory_->y()));
    for (const OutputEntry& c : c_entries_) all_outputs_(c.row) += c.value * y[c.column];
    WriteSelected(all_outputs_.data(), outputs + static_cast<std::ptrdiff_t>(j) * width);
  }
}

Eigen::VectorXd NonlinearCvodeIntegrator::Output() const {
  return C_ * PlantState();
}

Eigen::VectorXd NonlinearCvodeIntegrator::PlantState() const {
  // The whole of CVODE's state: a motor velocity is shifted by the integrated input v,
  // stored after the plant's states (ShiftFollowingErrors reads it there).
  Eigen::VectorXd y = Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(memory_->y()), dynamics_.size());
  ShiftFollowingErrors(Time(), -1.0, y.data());
  const Eigen::VectorXd e = y.head(num_states_);
  return particular_ ? Eigen::VectorXd(e + ParticularState()) : e;
}

IntegratorStats NonlinearCvodeIntegrator::Stats() const {
  IntegratorStats stats = finished_;
  long steps = 0;
  long rhs_evals = 0;
  CVodeGetNumSteps(memory_->cvode(), &steps);
  CVodeGetNumRhsEvals(memory_->cvode(), &rhs_evals);
  stats.steps += steps;
  stats.rhs_evals += rhs_evals;
  stats.events = events_;
  return stats;
}

void CheckMethodFitsPlant(IntegratorMethod method, const std::vector<NonlinearElement>& elements) {
  if (method != IntegratorMethod::kExact || elements.empty()) return;
  throw ValidationError("method", "exact cannot integrate a plant with nonlinear elements (" + elements.front().name +
                                      (elements.size() > 1 ? " and " + std::to_string(elements.size() - 1) + " more" : "") +
                                      "): the exact discretisation holds for linear plants only; use cvode or auto "
                                      "(docs/nonlinear.md)");
}

std::unique_ptr<PlantIntegrator> MakePlantIntegrator(const NonlinearPlant& plant, const IntegratorConfig& config,
                                                     double period_s, int substeps, double scale_accel_m_s2,
                                                     double scale_velocity_m_s) {
  if (plant.IsLinear()) {
    return MakeIntegrator(plant.linear, config, period_s, substeps, scale_accel_m_s2, scale_velocity_m_s);
  }
  config.validate();
  CheckMethodFitsPlant(config.method, plant.elements);
  return std::make_unique<NonlinearCvodeIntegrator>(plant, config, period_s, substeps, scale_accel_m_s2,
                                                    scale_velocity_m_s);
}

}  // namespace shapebench::model

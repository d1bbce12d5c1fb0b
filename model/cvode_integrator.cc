#include "model/cvode_integrator.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <sunmatrix/sunmatrix_dense.h>

#include "model/cvode_memory.h"

namespace shapebench::model {
namespace {

Eigen::Map<Eigen::VectorXd> View(N_Vector v) {
  return {N_VGetArrayPointer(v), static_cast<Eigen::Index>(N_VGetLength(v))};
}

// The longest step over which the Hermite output (CvodeOutput::kHermite) is used. Its
// error is at most |y^(8)| h^8 / (8! 2^8) (the two-point remainder, largest mid-step); a
// linear plant's state is a sum of modes, each of whose derivatives grow by at most the
// spectral radius rho of its matrix per order, so relative to a state's amplitude the error
// is at most (rho h)^8 / (8! 2^8). Below rtol / 10 of it (and rho h <= 1, a sixth of a cycle)
// it is well under what CVODE's own step and interpolation allow (about rtol).
double HermiteMaxStep(const Eigen::MatrixXd& a, double rtol) {
  const double rho = a.eigenvalues().cwiseAbs().maxCoeff();
  const double rho_h = std::min(1.0, std::pow(0.1 * rtol * 40320.0 * 256.0, 1.0 / 8.0));
  return rho > 0.0 ? rho_h / rho : std::numeric_limits<double>::infinity();
}

}  // namespace

namespace cvode_detail {

struct Pool;

// A memory and the pool it goes back to (null: freed with its integrator).
struct Workspace {
  CvodeMemory memory;
  Pool* pool = nullptr;
  Workspace(std::shared_ptr<CvodeContext> context, CvodeProblem problem, CVRhsFn rhs)
      : memory(std::move(context), std::move(problem), rhs) {}
};

// One per thread: its SUNContext (a context is used by one thread at a time) and the
// workspaces not in use. A sweep's runs have one problem size: one workspace, reused.
struct Pool {
  static constexpr std::size_t kKept = 4;
  std::shared_ptr<CvodeContext> context;
  std::vector<std::unique_ptr<Workspace>> idle;  // most recently returned last

  std::unique_ptr<Workspace> Take(const CvodeProblem& problem, CVRhsFn rhs, bool* reused) {
    for (std::size_t i = idle.size(); i-- > 0;) {
      if (idle[i]->memory.problem() == problem) {
        std::unique_ptr<Workspace> taken = std::move(idle[i]);
        idle.erase(idle.begin() + static_cast<std::ptrdiff_t>(i));
        *reused = true;
        return taken;
      }
    }
    if (!context) context = std::make_shared<CvodeContext>();
    auto created = std::make_unique<Workspace>(context, problem, rhs);
    created->pool = this;
    *reused = false;
    return created;
  }
  void Give(std::unique_ptr<Workspace> workspace) {
    if (idle.size() == kKept) idle.erase(idle.begin());
    idle.push_back(std::move(workspace));
  }
  ~Pool();
};

thread_local bool pool_gone = false;  // this thread's pool has been destroyed (thread exit)

Pool::~Pool() {
  idle.clear();
  pool_gone = true;
}

Pool* ThisThreadsPool() {
  thread_local Pool pool;
  return pool_gone ? nullptr : &pool;
}

void WorkspaceReturn::operator()(Workspace* workspace) const {
  std::unique_ptr<Workspace> owned(workspace);
  if (owned && owned->pool != nullptr && owned->pool == ThisThreadsPool()) {
    owned->pool->Give(std::move(owned));
  }
}

}  // namespace cvode_detail

namespace {

std::unique_ptr<cvode_detail::Workspace, cvode_detail::WorkspaceReturn> TakeWorkspace(
    int nz, const IntegratorConfig& config, CVRhsFn rhs, bool* reused) {
  CvodeProblem problem;
  problem.size = nz;
  problem.bdf = config.lmm == CvodeLmm::kBdf;
  problem.optimized_ops = config.tuning.optimized_vector_ops;
  problem.solver = config.tuning.fixed_point ? CvodeSolver::kFixedPoint : CvodeSolver::kDense;
  cvode_detail::Pool* pool = config.tuning.reuse_memory ? cvode_detail::ThisThreadsPool() : nullptr;
  if (pool != nullptr) return {pool->Take(problem, rhs, reused).release(), {}};
  *reused = false;
  return {new cvode_detail::Workspace(std::make_shared<CvodeContext>(), problem, rhs), {}};
}

}  // namespace

CvodeIntegrator::CvodeIntegrator(const LinearPlant& plant, const IntegratorConfig& config,
                                 double period_s, int substeps, double scale_accel_m_s2,
                                 double scale_velocity_m_s)
    : num_states_(plant.num_states()),
      num_inputs_(plant.num_inputs()),
      period_s_(period_s),
      substeps_(substeps),
      tuning_(config.tuning),
      C_(plant.C) {
  const int m = num_inputs_;
  const int nz = num_states_ + m;
  A_z_ = plant.AugmentedA();
  B_z_ = plant.AugmentedB();
  accel_ = Eigen::VectorXd::Zero(m);
  forcing_ = Eigen::VectorXd::Zero(nz);
  a_sparse_.Assign(A_z_);
  c_sparse_.Assign(C_);
  workspace_ = TakeWorkspace(nz, config, Rhs, &reused_);
  void* mem = memory();

  const Eigen::VectorXd atol =
      AbsoluteTolerances(plant, config, scale_accel_m_s2, scale_velocity_m_s);
  Check(CVodeSetErrHandlerFn(mem, RecordError, this), "CVodeSetErrHandlerFn");
  Check(CVodeSetUserData(mem, this), "CVodeSetUserData");
  if (tuning_.per_state_atol) {
    View(workspace_->memory.atol()) = atol;
    Check(CVodeSVtolerances(mem, config.rtol, workspace_->memory.atol()), "CVodeSVtolerances");
  } else {
    Check(CVodeSStolerances(mem, config.rtol, atol.minCoeff()), "CVodeSStolerances");
  }
  if (!tuning_.fixed_point) {
    // After CVodeSetUserData: the Jacobian's user data is taken from it here.
    Check(CVodeSetJacFn(mem, tuning_.jacobian ? Jacobian : nullptr), "CVodeSetJacFn");
  }
  Check(CVodeSetMaxNumSteps(mem, config.max_num_steps), "CVodeSetMaxNumSteps");
  max_num_steps_ = config.max_num_steps;
  // Every integrator sets the order limit (a reused memory keeps the last one's).
  const int max_order = tuning_.max_order > 0 ? tuning_.max_order
                        : config.lmm == CvodeLmm::kBdf ? 5 : 12;
  Check(CVodeSetMaxOrd(mem, max_order), "CVodeSetMaxOrd");
  Check(CVodeSetEtaFixedStepBounds(mem, 0.0, tuning_.eta_max_fixed_step),
        "CVodeSetEtaFixedStepBounds");
  hermite_max_step_s_ = HermiteMaxStep(A_z_, config.rtol);
  ends_.assign(2 * kHermiteOrders * nz, 0.0);
  Reset(Eigen::VectorXd::Zero(m));
}

CvodeIntegrator::~CvodeIntegrator() {
  if (workspace_) {
    // The memory may serve another integrator: nothing of this one may be called back.
    CVodeSetErrHandlerFn(workspace_->memory.cvode(), nullptr, nullptr);
    CVodeSetUserData(workspace_->memory.cvode(), nullptr);
  }
}

void* CvodeIntegrator::memory() const { return workspace_->memory.cvode(); }

// Error weights: CVODE's norm is |e_i| / (rtol |y_i| + atol_i), and deflection states start
// at 0, so atol sets the accuracy near rest. Scale it by what each state reaches statically
// under the run's largest acceleration (held, A x = -B_accel a) or under its largest
// commanded speed (held, A x = -B_vel v: a servo's following error lives on the velocity,
// a structure's only on the acceleration), whichever is larger: positions x_s, velocities
// x_s times the group's frequency (a mode's velocity amplitude is w times its displacement
// amplitude). States share the scale within their tolerance group (LinearPlant), so a
// group's states that happen to be 0 statically still get a sane atol; a group that is 0
// altogether gets a 1 pm floor.
Eigen::VectorXd CvodeIntegrator::AbsoluteTolerances(const LinearPlant& plant,
                                                    const IntegratorConfig& config,
                                                    double scale_accel_m_s2,
                                                    double scale_velocity_m_s) const {
  return CvodeAbsoluteTolerances(plant, config, scale_accel_m_s2, scale_velocity_m_s);
}

Eigen::VectorXd CvodeAbsoluteTolerances(const LinearPlant& plant, const IntegratorConfig& config,
                                        double scale_accel_m_s2, double scale_velocity_m_s) {
  const int num_states = plant.num_states();
  const int num_inputs = plant.num_inputs();
  // One column per driven axis: the static state under that axis' acceleration alone.
  const auto lu = plant.A.fullPivLu();
  const Eigen::MatrixXd x_static = lu.solve(-plant.B_accel) * scale_accel_m_s2;
  // With a velocity scale: the static state under the largest speed held, and the offset a
  // held acceleration adds through the velocity ramping meanwhile (x = p + q t with
  // A q = -B_vel a, A p = q - B_accel a): under a servo's ideal inner loops the structure
  // sees the acceleration only through that.
  Eigen::MatrixXd x_static_v = Eigen::MatrixXd::Zero(num_states, num_inputs);
  Eigen::MatrixXd x_ramp = Eigen::MatrixXd::Zero(num_states, num_inputs);
  if (scale_velocity_m_s > 0.0) {
    const Eigen::MatrixXd x_per_velocity = lu.solve(-plant.B_vel);
    x_static_v = x_per_velocity * scale_velocity_m_s;
    x_ramp = lu.solve(x_per_velocity) * scale_accel_m_s2;
  }
  const int groups = plant.NumToleranceGroups();
  std::vector<double> position_m(groups, 0.0);
  for (int i = 0; i < num_states; ++i) {
    if (plant.state_kinds[i] == StateKind::kPosition) {
      double& scale = position_m[plant.ToleranceGroup(i)];
      scale = std::max(scale, x_static.row(i).cwiseAbs().maxCoeff());
      scale = std::max(scale, x_static_v.row(i).cwiseAbs().maxCoeff());
      scale = std::max(scale, x_ramp.row(i).cwiseAbs().maxCoeff());
    }
  }
  std::vector<double> base(groups);
  std::vector<double> velocity(groups);
  for (int g = 0; g < groups; ++g) {
    if (!(position_m[g] > 0.0)) position_m[g] = 1.0e-12;  // nothing moves it: a 1 pm floor
    base[g] = config.rtol * config.atol_scale * position_m[g];
    velocity[g] = base[g] * std::max(plant.GroupFrequency(g), 1.0);
  }
  Eigen::VectorXd atol(num_states + num_inputs);
  for (int i = 0; i < num_states; ++i) {
    const int g = plant.ToleranceGroup(i);
    atol(i) = plant.state_kinds[i] == StateKind::kPosition ? base[g] : velocity[g];
  }
  // The drive velocity is linear in t between re-inits, which every LMM integrates exactly,
  // and it reaches the deflection only through B_vel (damping over mass, at most ~2 w); the
  // velocity-state tolerance (the tightest group's) keeps its share of the deflection error
  // below `base`.
  atol.tail(num_inputs).setConstant(*std::min_element(velocity.begin(), velocity.end()));
  return atol;
}

void CvodeIntegrator::Sparse::Assign(const Eigen::MatrixXd& m) {
  row_start.assign(1, 0);
  col.clear();
  value.clear();
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    for (Eigen::Index j = 0; j < m.cols(); ++j) {
      if (m(i, j) != 0.0) {
        col.push_back(static_cast<int>(j));
        value.push_back(m(i, j));
      }
    }
    row_start.push_back(static_cast<int>(col.size()));
  }
}

void CvodeIntegrator::Sparse::Multiply(const double* x, double* y) const {
  for (std::size_t i = 0; i + 1 < row_start.size(); ++i) {
    double sum = 0.0;
    for (int e = row_start[i]; e < row_start[i + 1]; ++e) sum += value[e] * x[col[e]];
    y[i] = sum;
  }
}

int CvodeIntegrator::Rhs(sunrealtype /*t*/, N_Vector y, N_Vector ydot, void* user_data) {
  const auto* self = static_cast<const CvodeIntegrator*>(user_data);
  double* out = N_VGetArrayPointer(ydot);
  self->a_sparse_.Multiply(N_VGetArrayPointer(y), out);
  const double* forcing = self->forcing_.data();
  for (Eigen::Index i = 0; i < self->forcing_.size(); ++i) out[i] += forcing[i];
  return 0;
}

int CvodeIntegrator::Jacobian(sunrealtype /*t*/, N_Vector /*y*/, N_Vector /*fy*/, SUNMatrix jac,
                              void* user_data, N_Vector /*tmp1*/, N_Vector /*tmp2*/,
                              N_Vector /*tmp3*/) {
  const auto* self = static_cast<const CvodeIntegrator*>(user_data);
  const Eigen::Index nz = self->A_z_.rows();
  // SUNDenseMatrix data is column-major, like Eigen's default.
  Eigen::Map<Eigen::MatrixXd>(SUNDenseMatrix_Data(jac), nz, nz) = self->A_z_;
  return 0;
}

void CvodeIntegrator::RecordError(int /*code*/, const char* /*module*/, const char* /*function*/,
                                  char* msg, void* user_data) {
  if (user_data == nullptr) return;
  static_cast<CvodeIntegrator*>(user_data)->last_message_ = msg != nullptr ? msg : "";
}

void CvodeIntegrator::Check(int flag, const char* call) const {
  if (flag >= 0) return;
  sunrealtype t_now = Time();
  if (workspace_) CVodeGetCurrentTime(memory(), &t_now);
  ThrowCvodeFailure(flag, call, t_now, last_message_, false);
}

double CvodeIntegrator::TimeAt(long count) const {
  return static_cast<double>(count) * period_s_ / substeps_;
}

void CvodeIntegrator::Reset(const Eigen::VectorXd& drive_velocity) {
  if (drive_velocity.size() != num_inputs_) {
    throw std::invalid_argument("CvodeIntegrator::Reset: wrong drive velocity size");
  }
  Eigen::Map<Eigen::VectorXd> y = View(workspace_->memory.y());
  y.head(num_states_).setZero();
  y.tail(num_inputs_) = drive_velocity;
  accel_.setZero();
  forcing_.setZero();
  count_ = 0;
  // Restart from t = 0 now (this also zeroes CVODE's counters); SetInput re-initialises
  // again only if the first acceleration is not 0.
  Check(CVodeReInit(memory(), 0.0, workspace_->memory.y()), "CVodeReInit");
  stop_set_ = false;  // CVodeReInit forgets the stop time (SUNDIALS 6.4.1)
  finished_ = {};
  need_reinit_ = false;
  have_step_ = false;
}

void CvodeIntegrator::SetInput(const Eigen::VectorXd& drive_accel) {
  if (drive_accel.size() != num_inputs_) {
    throw std::invalid_argument("CvodeIntegrator::SetInput: wrong drive acceleration size");
  }
  // A new held value is a jump of the RHS: restart the multistep history there. An
  // unchanged value keeps the RHS smooth, so CVODE integrates straight through the tick.
  if (drive_accel != accel_) {
    accel_ = drive_accel;
    forcing_.noalias() = B_z_ * accel_;
    need_reinit_ = true;
  }
}

void CvodeIntegrator::Reinit() {
  void* mem = memory();
  long steps = 0;
  long rhs_evals = 0;
  CVodeGetNumSteps(mem, &steps);
  CVodeGetNumRhsEvals(mem, &rhs_evals);
  finished_.steps += steps;
  finished_.rhs_evals += rhs_evals;
  ++finished_.reinits;
  Check(CVodeReInit(mem, Time(), workspace_->memory.y()), "CVodeReInit");
  stop_set_ = false;  // CVodeReInit forgets the stop time (SUNDIALS 6.4.1)
  need_reinit_ = false;
  have_step_ = false;
}

// SUNDIALS 6.4.1 forgets the stop time once reached (CV_TSTOP_RETURN) and on reinit; until
// then it holds, so it is set again only after either, or when it moves.
void CvodeIntegrator::SetStopTime(double t_stop) {
  if (stop_set_ && stop_s_ == t_stop) return;
  Check(CVodeSetStopTime(memory(), t_stop), "CVodeSetStopTime");
  stop_set_ = true;
  stop_s_ = t_stop;
}

// The state and its first three derivatives at `t` from the state y there: y' = A y + f,
// and, the input held over a step, y^(k+1) = A y^(k).
void CvodeIntegrator::SetEnd(int end, double t, const double* y) {
  const int nz = num_states_ + num_inputs_;
  double* d = ends_.data() + static_cast<std::size_t>(end) * kHermiteOrders * nz;
  std::copy(y, y + nz, d);
  a_sparse_.Multiply(d, d + nz);
  for (int i = 0; i < nz; ++i) d[nz + i] += forcing_[i];
  a_sparse_.Multiply(d + nz, d + 2 * nz);
  a_sparse_.Multiply(d + 2 * nz, d + 3 * nz);
  end_time_s_[end] = t;
}

// CV_ONE_STEP: CVODE's internal steps, each a Hermite interval for the substeps it covers.
void CvodeIntegrator::AdvanceByHermite(double t_out) {
  const int nz = num_states_ + num_inputs_;
  const std::size_t stride = static_cast<std::size_t>(kHermiteOrders) * nz;
  if (!have_step_) {
    // After a (re)start: an empty interval at the current state.
    SetEnd(1, Time(), N_VGetArrayPointer(workspace_->memory.y()));
    have_step_ = true;
  }
  for (long steps = 0; end_time_s_[1] < t_out; ++steps) {
    if (steps == max_num_steps_) {
      // CV_NORMAL's limit per call (integrator.max_num_steps), kept per substep here.
      last_message_ = "more than " + std::to_string(max_num_steps_) +
                      " internal steps to reach the output substep at t = " + std::to_string(t_out);
      Check(CV_TOO_MUCH_WORK, "CVode");
    }
    sunrealtype t_reached = 0.0;
    // tout only sets the direction and the first step after a restart, as CV_NORMAL's did.
    const int flag = CVode(memory(), t_out, workspace_->memory.step(), &t_reached, CV_ONE_STEP);
    Check(flag, "CVode");
    if (flag == CV_TSTOP_RETURN) stop_set_ = false;
    std::copy(ends_.begin() + static_cast<std::ptrdiff_t>(stride), ends_.end(), ends_.begin());
    end_time_s_[0] = end_time_s_[1];
    SetEnd(1, t_reached, N_VGetArrayPointer(workspace_->memory.step()));
  }
  double* y = N_VGetArrayPointer(workspace_->memory.y());
  const double* left = ends_.data();
  const double* right = ends_.data() + stride;
  if (t_out == end_time_s_[1]) {
    std::copy(right, right + nz, y);  // a step's end (a stop, a restart): CVODE's own state
    return;
  }
  const double h = end_time_s_[1] - end_time_s_[0];
  if (h > hermite_max_step_s_) {
    Check(CVodeGetDky(memory(), t_out, 0, workspace_->memory.y()), "CVodeGetDky");
    ++cvode_interpolated_;
    return;
  }
  // The two-point Hermite basis of degree 7 in s = (t - t0) / h, u = 1 - s; derivative k
  // weighted by h^k / k!, the right end's odd ones negative.
  const double s = (t_out - end_time_s_[0]) / h;
  const double u = 1.0 - s;
  const double s4 = (s * s) * (s * s);
  const double u4 = (u * u) * (u * u);
  const double h2 = 0.5 * h * h;
  const double h3 = h * h * h / 6.0;
  const double w[2 * kHermiteOrders] = {
      u4 * (1.0 + s * (4.0 + s * (10.0 + 20.0 * s))),
      h * s * u4 * (1.0 + s * (4.0 + 10.0 * s)),
      h2 * s * s * u4 * (1.0 + 4.0 * s),
      h3 * s * s * s * u4,
      s4 * (1.0 + u * (4.0 + u * (10.0 + 20.0 * u))),
      -h * u * s4 * (1.0 + u * (4.0 + 10.0 * u)),
      h2 * u * u * s4 * (1.0 + 4.0 * u),
      -h3 * u * u * u * s4,
  };
  for (int i = 0; i < nz; ++i) {
    double sum = 0.0;
    for (int k = 0; k < kHermiteOrders; ++k) {
      sum += w[k] * left[k * nz + i] + w[kHermiteOrders + k] * right[k * nz + i];
    }
    y[i] = sum;
  }
}

void CvodeIntegrator::Advance(long count) {
  if (tuning_.output == CvodeOutput::kHermite) {
    AdvanceByHermite(TimeAt(count));
    return;
  }
  sunrealtype t_reached = 0.0;
  // CV_SUCCESS and CV_TSTOP_RETURN (tout == tstop) are both normal returns.
  const int flag = CVode(memory(), TimeAt(count), workspace_->memory.y(), &t_reached, CV_NORMAL);
  Check(flag, "CVode");
  if (flag == CV_TSTOP_RETURN) stop_set_ = false;
}

void CvodeIntegrator::Step() {
  if (need_reinit_) Reinit();
  // Never step past the end of the current interpolation period: the input may jump there.
  SetStopTime(TimeAt((count_ / substeps_ + 1) * substeps_));
  Advance(count_ + 1);
  ++count_;
}

void CvodeIntegrator::AdvancePeriod(const double* drive_accel, long same_input_periods,
                                    double* outputs) {
  const Eigen::Map<const Eigen::VectorXd> accel(drive_accel, num_inputs_);
  if (accel != accel_) {
    // A change of rounding size (the command's accelerations are differences of its tick
    // velocities: a held level wanders by an ulp or so) is taken on without a restart: the
    // history is off by that much, 1e-12 of the input at most, far below any tolerance,
    // where a restart costs dozens of small steps. Anything larger restarts.
    bool rounding = true;
    for (int i = 0; i < num_inputs_; ++i) {
      const double scale = std::max(std::abs(accel(i)), std::abs(accel_(i)));
      rounding = rounding && std::abs(accel(i) - accel_(i)) <= 1e-12 * scale;
    }
    accel_ = accel;
    forcing_.noalias() = B_z_ * accel_;
    if (!rounding) need_reinit_ = true;
  }
  const long period_start = count_ / substeps_ * substeps_;
  long stop = period_start + substeps_;
  switch (tuning_.input_mode) {
    case CvodeInputMode::kContinuous:
      // The input is held beyond this period: integrate across the ticks up to its change.
      stop = period_start + std::max(1L, same_input_periods) * substeps_;
      break;
    case CvodeInputMode::kStopEveryTick:
      break;
    case CvodeInputMode::kRestartEveryTick:
      if (count_ > 0) need_reinit_ = true;
      break;
  }
  if (need_reinit_) Reinit();
  SetStopTime(TimeAt(stop));
  const int width = output_width();
  all_outputs_.resize(C_.rows());
  for (int j = 0; j < substeps_; ++j) {
    Advance(count_ + 1);
    ++count_;
    if (selected_rows_.empty()) {
      c_sparse_.Multiply(N_VGetArrayPointer(workspace_->memory.y()), outputs + j * width);
    } else {
      c_sparse_.Multiply(N_VGetArrayPointer(workspace_->memory.y()), all_outputs_.data());
      WriteSelected(all_outputs_.data(), outputs + j * width);
    }
  }
}

Eigen::VectorXd CvodeIntegrator::Output() const {
  return C_ * View(workspace_->memory.y()).head(num_states_);
}

// The state at the last output substep (Advance leaves it in y, interpolated or not).
Eigen::VectorXd CvodeIntegrator::PlantState() const { return View(workspace_->memory.y()).head(num_states_); }

double CvodeIntegrator::Time() const { return TimeAt(count_); }

IntegratorStats CvodeIntegrator::Stats() const {
  IntegratorStats stats = finished_;
  long steps = 0;
  long rhs_evals = 0;
  CVodeGetNumSteps(memory(), &steps);
  CVodeGetNumRhsEvals(memory(), &rhs_evals);
  stats.steps += steps;
  stats.rhs_evals += rhs_evals;
  return stats;
}

}  // namespace shapebench::model

#include "model/cvode_integrator.h"

#include <algorithm>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace shapebench::model {
namespace {

Eigen::Map<Eigen::VectorXd> View(N_Vector v) {
  return {N_VGetArrayPointer(v), static_cast<Eigen::Index>(N_VGetLength(v))};
}

std::string FlagName(int flag) {
  char* name = CVodeGetReturnFlagName(flag);  // malloc'ed by CVODE
  std::string result = name != nullptr ? name : "CV_UNKNOWN";
  std::free(name);
  return result;
}

std::string PlainWords(int flag) {
  switch (flag) {
    case CV_TOO_MUCH_WORK:
      return "integrator.max_num_steps internal steps were not enough to reach the next "
             "output time; raise integrator.max_num_steps or loosen integrator.rtol";
    case CV_TOO_MUCH_ACC:
      return "the accuracy asked for is below what double precision can deliver; loosen "
             "integrator.rtol or raise integrator.atol_scale";
    case CV_ERR_FAILURE:
      return "the local error test failed repeatedly (step size hit its minimum)";
    case CV_CONV_FAILURE:
      return "the corrector iteration failed to converge repeatedly";
    case CV_LSETUP_FAIL:
    case CV_LSOLVE_FAIL:
      return "the dense linear solver failed (singular iteration matrix)";
    case CV_ILL_INPUT:
      return "CVODE rejected an input (see its message)";
    default:
      return "see the CVODE documentation for this flag";
  }
}

}  // namespace

CvodeIntegrator::CvodeIntegrator(const LinearPlant& plant, const IntegratorConfig& config,
                                 double period_s, int substeps, double scale_accel_m_s2,
                                 double scale_velocity_m_s)
    : num_states_(plant.num_states()),
      num_inputs_(plant.num_inputs()),
      period_s_(period_s),
      substeps_(substeps),
      C_(plant.C) {
  const int n = num_states_;
  const int m = num_inputs_;
  const int nz = n + m;
  A_z_ = plant.AugmentedA();
  B_z_ = plant.AugmentedB();
  accel_ = Eigen::VectorXd::Zero(m);

  SUNContext ctx = nullptr;
  Check(SUNContext_Create(nullptr, &ctx), "SUNContext_Create");
  context_.reset(ctx);
  y_.reset(N_VNew_Serial(nz, ctx));
  atol_.reset(N_VNew_Serial(nz, ctx));
  matrix_.reset(SUNDenseMatrix(nz, nz, ctx));
  if (!y_ || !atol_ || !matrix_) throw std::bad_alloc();
  solver_.reset(SUNLinSol_Dense(y_.get(), matrix_.get(), ctx));
  memory_.reset(CVodeCreate(config.lmm == CvodeLmm::kBdf ? CV_BDF : CV_ADAMS, ctx));
  if (!solver_ || !memory_) throw std::bad_alloc();
  void* mem = memory_.get();

  View(y_.get()).setZero();
  View(atol_.get()) = AbsoluteTolerances(plant, config, scale_accel_m_s2, scale_velocity_m_s);
  Check(CVodeSetErrHandlerFn(mem, RecordError, this), "CVodeSetErrHandlerFn");
  Check(CVodeInit(mem, Rhs, 0.0, y_.get()), "CVodeInit");
  Check(CVodeSetUserData(mem, this), "CVodeSetUserData");
  Check(CVodeSVtolerances(mem, config.rtol, atol_.get()), "CVodeSVtolerances");
  Check(CVodeSetLinearSolver(mem, solver_.get(), matrix_.get()), "CVodeSetLinearSolver");
  Check(CVodeSetJacFn(mem, Jacobian), "CVodeSetJacFn");
  Check(CVodeSetMaxNumSteps(mem, config.max_num_steps), "CVodeSetMaxNumSteps");
  Reset(Eigen::VectorXd::Zero(m));
}

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
  // One column per driven axis: the static state under that axis' acceleration alone.
  const auto lu = plant.A.fullPivLu();
  const Eigen::MatrixXd x_static = lu.solve(-plant.B_accel) * scale_accel_m_s2;
  // With a velocity scale: the static state under the largest speed held, and the offset a
  // held acceleration adds through the velocity ramping meanwhile (x = p + q t with
  // A q = -B_vel a, A p = q - B_accel a): under a servo's ideal inner loops the structure
  // sees the acceleration only through that.
  Eigen::MatrixXd x_static_v = Eigen::MatrixXd::Zero(num_states_, num_inputs_);
  Eigen::MatrixXd x_ramp = Eigen::MatrixXd::Zero(num_states_, num_inputs_);
  if (scale_velocity_m_s > 0.0) {
    const Eigen::MatrixXd x_per_velocity = lu.solve(-plant.B_vel);
    x_static_v = x_per_velocity * scale_velocity_m_s;
    x_ramp = lu.solve(x_per_velocity) * scale_accel_m_s2;
  }
  const int groups = plant.NumToleranceGroups();
  std::vector<double> position_m(groups, 0.0);
  for (int i = 0; i < num_states_; ++i) {
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
  Eigen::VectorXd atol(num_states_ + num_inputs_);
  for (int i = 0; i < num_states_; ++i) {
    const int g = plant.ToleranceGroup(i);
    atol(i) = plant.state_kinds[i] == StateKind::kPosition ? base[g] : velocity[g];
  }
  // The drive velocity is linear in t between re-inits, which every LMM integrates exactly,
  // and it reaches the deflection only through B_vel (damping over mass, at most ~2 w); the
  // velocity-state tolerance (the tightest group's) keeps its share of the deflection error
  // below `base`.
  atol.tail(num_inputs_).setConstant(*std::min_element(velocity.begin(), velocity.end()));
  return atol;
}

int CvodeIntegrator::Rhs(sunrealtype /*t*/, N_Vector y, N_Vector ydot, void* user_data) {
  const auto* self = static_cast<const CvodeIntegrator*>(user_data);
  Eigen::Map<Eigen::VectorXd> out = View(ydot);
  out.noalias() = self->A_z_ * View(y);
  out.noalias() += self->B_z_ * self->accel_;
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
  static_cast<CvodeIntegrator*>(user_data)->last_message_ = msg != nullptr ? msg : "";
}

void CvodeIntegrator::Check(int flag, const char* call) const {
  if (flag >= 0) return;
  sunrealtype t_now = Time();
  if (memory_) CVodeGetCurrentTime(memory_.get(), &t_now);
  std::ostringstream what;
  const std::string name = FlagName(flag);
  what << "CVODE failed at t = " << t_now << " s: " << name << ": " << PlainWords(flag) << " ("
       << call;
  if (!last_message_.empty()) what << ": " << last_message_;
  what << ")";
  throw SolverError(name, what.str());
}

double CvodeIntegrator::TimeAt(long count) const {
  return static_cast<double>(count) * period_s_ / substeps_;
}

void CvodeIntegrator::Reset(const Eigen::VectorXd& drive_velocity) {
  if (drive_velocity.size() != num_inputs_) {
    throw std::invalid_argument("CvodeIntegrator::Reset: wrong drive velocity size");
  }
  Eigen::Map<Eigen::VectorXd> y = View(y_.get());
  y.head(num_states_).setZero();
  y.tail(num_inputs_) = drive_velocity;
  accel_.setZero();
  count_ = 0;
  // Restart from t = 0 now (this also zeroes CVODE's counters); SetInput re-initialises
  // again only if the first acceleration is not 0.
  Check(CVodeReInit(memory_.get(), 0.0, y_.get()), "CVodeReInit");
  finished_ = {};
  need_reinit_ = false;
}

void CvodeIntegrator::SetInput(const Eigen::VectorXd& drive_accel) {
  if (drive_accel.size() != num_inputs_) {
    throw std::invalid_argument("CvodeIntegrator::SetInput: wrong drive acceleration size");
  }
  // A new held value is a jump of the RHS: restart the multistep history there. An
  // unchanged value keeps the RHS smooth, so CVODE integrates straight through the tick.
  if (drive_accel != accel_) {
    accel_ = drive_accel;
    need_reinit_ = true;
  }
}

void CvodeIntegrator::Reinit() {
  void* mem = memory_.get();
  long steps = 0;
  long rhs_evals = 0;
  CVodeGetNumSteps(mem, &steps);
  CVodeGetNumRhsEvals(mem, &rhs_evals);
  finished_.steps += steps;
  finished_.rhs_evals += rhs_evals;
  ++finished_.reinits;
  Check(CVodeReInit(mem, Time(), y_.get()), "CVodeReInit");
  need_reinit_ = false;
}

void CvodeIntegrator::Step() {
  if (need_reinit_) Reinit();
  void* mem = memory_.get();
  // Never step past the end of the current interpolation period: the input may jump there.
  // SUNDIALS 6.4.1 forgets the stop time once reached (and on reinit): set it every call.
  const long period_end = (count_ / substeps_ + 1) * substeps_;
  Check(CVodeSetStopTime(mem, TimeAt(period_end)), "CVodeSetStopTime");
  sunrealtype t_reached = 0.0;
  // CV_SUCCESS and CV_TSTOP_RETURN (tout == tstop) are both normal returns.
  Check(CVode(mem, TimeAt(count_ + 1), y_.get(), &t_reached, CV_NORMAL), "CVode");
  ++count_;
}

Eigen::VectorXd CvodeIntegrator::Output() const { return C_ * View(y_.get()).head(num_states_); }

double CvodeIntegrator::Time() const { return TimeAt(count_); }

IntegratorStats CvodeIntegrator::Stats() const {
  IntegratorStats stats = finished_;
  long steps = 0;
  long rhs_evals = 0;
  CVodeGetNumSteps(memory_.get(), &steps);
  CVodeGetNumRhsEvals(memory_.get(), &rhs_evals);
  stats.steps += steps;
  stats.rhs_evals += rhs_evals;
  return stats;
}

}  // namespace shapebench::model

// Integrators of a LinearPlant driven tick by tick (FMI-style co-simulation slave):
// the master sets the input held over the coming interpolation period, then advances the
// plant one output substep at a time, reading the outputs after each.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "model/linear_plant.h"
#include "common/field_list.h"

namespace shapebench::model {

// kAuto: the exact discretisation for a linear plant (every plant LinearPlant describes is
// linear: the machine forms, both drives), CVODE for a plant with a nonlinear element
// (MakeIntegrator resolves kAuto with ResolveMethod; model/nonlinear_integrator.h's
// MakePlantIntegrator takes a plant with elements to CVODE and refuses exact for it).
enum class IntegratorMethod { kCvode, kExact, kAuto };
enum class CvodeLmm { kAdams, kBdf };
// What a run does when CVODE disagrees with the exact discretisation of its linear plant
// beyond the documented accuracy (model/cvode_cross_check.h): refuse it (solver trouble),
// run it with a warning, or not check.
enum class CrossCheckPolicy { kRefuse, kWarn, kOff };

// How CvodeIntegrator drives CVODE. The defaults are the measured choices (docs/performance.md,
// "CVODE's choices at equal accuracy"); the others exist to measure them against (benchmarks/).
enum class CvodeInputMode {
  // Integrate across ticks while the held acceleration stays the same (the master says for
  // how long, PlantIntegrator::AdvancePeriod); stop and restart only where it changes.
  kContinuous,
  // Stop at every tick (CVodeSetStopTime), restart only where the acceleration changes:
  // what Step() does, which does not know the next input.
  kStopEveryTick,
  // Stop and restart (CVodeReInit) at every tick: a co-simulation slave that knows nothing.
  kRestartEveryTick,
};

// Where the output substeps between CVODE's internal steps come from.
enum class CvodeOutput {
  // A two-point Hermite polynomial of degree 7 over the step, from the state and its first
  // three derivatives at both ends (a linear plant's derivatives are products with A), where
  // its error bound is below rtol / 10 of the state's amplitude; CVODE's interpolation
  // elsewhere (CvodeIntegrator::Advance).
  kHermite,
  // CVODE's own interpolation (CVode in CV_NORMAL mode, CVodeGetDky) at every substep.
  kCvodeInterpolation,
};

struct CvodeTuning {
  CvodeInputMode input_mode = CvodeInputMode::kContinuous;
  bool jacobian = true;        // the plant's constant Jacobian; false: CVODE's difference quotients
  bool per_state_atol = true;  // AbsoluteTolerances per state; false: one scalar (their minimum)
  bool reuse_memory = true;    // CVODE memory from this thread's pool; false: created per integrator
  bool fixed_point = false;    // fixed-point (functional) iteration instead of Newton's
  int max_order = 0;           // CVodeSetMaxOrd; 0: CVODE's (Adams 12, BDF 5)
  CvodeOutput output = CvodeOutput::kHermite;
  // The upper bound of the step-size ratios CVODE answers by keeping the step
  // (CVodeSetEtaFixedStepBounds; CVODE's own is 1.5): at 1.1 Adams grows its steps and
  // order on an oscillating structure instead of staying at order 5 (docs/performance.md).
  double eta_max_fixed_step = 1.1;
  // shapebench's kernels for the serial vector operations (model/serial_vector_ops.h);
  // false: those of the libsundials package.
  bool optimized_vector_ops = true;
  // A plant with nonlinear elements (model/nonlinear_integrator.h): CVODE integrates only
  // the elements' correction to the linear part's exact response (held_input_response.h),
  // which carries every jump of the held input; false: the whole state, restarted at each.
  bool split_linear_part = true;
};

// The tightest rtol CVODE is run with: below it double precision cannot resolve a run's
// steps (IntegratorConfig::validate; docs/accuracy.md).
constexpr double kTightestRtol = 1.0e-12;

struct IntegratorConfig {
  IntegratorMethod method = IntegratorMethod::kCvode;
  double rtol = 1.0e-8;
  // False when the scenario left `rtol` out (the loader says so): the default may then be
  // tightened by decades, down to kTightestRtol, where CVODE fails its cross-check with it
  // (bench/run/plant_sampler.cc). Not a key: a tolerance the user wrote is used as written.
  bool rtol_given = true;
  // Per-state absolute tolerances are rtol * atol_scale * (the static magnitude, under the
  // run's largest acceleration or its largest speed, of the state's tolerance group; times
  // the group's frequency for velocity states). See CvodeIntegrator::AbsoluteTolerances.
  double atol_scale = 1.0;
  // Adams: at the same rtol it tracks the exact solution ~20x closer than BDF on these
  // lightly damped, non-stiff plants (measured in tests/model/cvode_integrator_test.cc).
  CvodeLmm lmm = CvodeLmm::kAdams;
  long max_num_steps = 100000;  // CVODE internal steps to reach one output substep
  CrossCheckPolicy cross_check = CrossCheckPolicy::kRefuse;
  int output_substeps = 0;      // samples per interpolation period; 0 = automatic
  CvodeTuning tuning;           // not a scenario key: what the benchmarks compare
  void validate() const;        // throws ValidationError naming the field

  template <typename Archive>
  void Serialize(Archive* a) {  // the field list (common/field_list.h)
    a->Visit("method", &method, Choices<IntegratorMethod>{{"cvode", IntegratorMethod::kCvode},
                                                          {"exact", IntegratorMethod::kExact},
                                                          {"auto", IntegratorMethod::kAuto}});
    a->Visit("rtol", &rtol);
    a->Visit("atol_scale", &atol_scale);
    a->Visit("lmm", &lmm, Choices<CvodeLmm>{{"adams", CvodeLmm::kAdams}, {"bdf", CvodeLmm::kBdf}});
    a->Visit("max_num_steps", &max_num_steps);
    a->Visit("output_substeps", &output_substeps);
    a->Visit("cross_check", &cross_check,
             Choices<CrossCheckPolicy>{{"refuse", CrossCheckPolicy::kRefuse},
                                       {"warn", CrossCheckPolicy::kWarn},
                                       {"off", CrossCheckPolicy::kOff}});
  }
};

struct IntegratorStats {
  long steps = 0;
  long rhs_evals = 0;
  long reinits = 0;
  long events = 0;  // root returns of a plant with nonlinear elements (stick, slip, contact)
};

// CVODE trouble: `flag_name` is CVODE's own name for the return flag (CV_TOO_MUCH_WORK...).
class SolverError : public std::runtime_error {
 public:
  SolverError(std::string flag_name, const std::string& what)
      : std::runtime_error(what), flag_name_(std::move(flag_name)) {}
  const std::string& flag_name() const { return flag_name_; }

 private:
  std::string flag_name_;
};

// What a PlantIntegrator offers the co-simulation master beyond SetInput/Step and
// AdvancePeriod (PlantIntegrator::Capabilities): one query instead of a hook per fast path.
struct IntegratorCapabilities {
  bool input_holds = false;        // AdvancePeriod integrates across same_input_periods
  bool period_extremum = false;    // WatchExtremum / PeriodExtremum
  bool advance_at_rest = false;    // AdvanceAtRest
  bool deferred_substeps = false;  // AdvancePeriodToEnd / WriteDeferredSubsteps
};

class PlantIntegrator {
 public:
  virtual ~PlantIntegrator() = default;
  // Rest state (zero deflection) at t = 0 with the drive at the given velocity.
  virtual void Reset(const Eigen::VectorXd& drive_velocity) = 0;
  // The drive acceleration held constant over the coming interpolation period.
  virtual void SetInput(const Eigen::VectorXd& drive_accel) = 0;
  // Advances one output substep (period / substeps). Time is computed from the integer
  // substep count, never accumulated.
  virtual void Step() = 0;
  virtual Eigen::VectorXd Output() const = 0;  // deflection, C x
  // The plant's states x (LinearPlant::A's, without the drive velocity) at Time(). For the
  // occasional look (the residual vibration at motion end), never per tick: it allocates.
  virtual Eigen::VectorXd PlantState() const = 0;
  virtual double Time() const = 0;
  virtual IntegratorStats Stats() const { return {}; }
  // The work it did beyond its output samples, for limits.max_work (bench/run/run_work.h):
  // CVODE's internal steps plus right-hand-side evaluations, the exact path's passes over
  // the poles in its in-tick extremum search (model/tick_extremum.h). Counted, never timed.
  virtual long Work() const { return 0; }
  // The least of that work every period costs, known before the first (the exact path's
  // extremum grid: a pass per inner grid point), for the estimate before a run starts.
  virtual long PeriodWorkAtLeast() const { return 0; }
  virtual int num_inputs() const = 0;
  virtual int num_outputs() const = 0;
  virtual int substeps() const = 0;  // output substeps per interpolation period
  // True when output `row` is exactly 0 whatever the input (its row of C reaches no
  // integrated state): the master need not look at it.
  virtual bool OutputRowIsZero(int /*row*/) const { return false; }

  // One whole interpolation period (the co-simulation master's fast path): holds
  // `drive_accel` (num_inputs values) over it, advances its `substeps` output substeps and
  // writes the outputs after each to `outputs` (substep after substep, num_outputs each).
  // `same_input_periods` (>= 1): the master's promise that this input is held for this
  // period and the next same_input_periods - 1; CVODE then integrates across the ticks in
  // between (Capabilities().input_holds). Results are those of SetInput and Step/Output per
  // substep up to rounding (the exact integrator of a small plant computes the period's
  // substeps from its start state; CVODE may take other, longer steps, within its tolerances).
  virtual void AdvancePeriod(const double* drive_accel, long same_input_periods,
                             double* outputs);

  // The master's other fast paths, asked once: what this integrator offers beyond
  // AdvancePeriod. Calling one it does not offer throws std::logic_error.
  virtual IntegratorCapabilities Capabilities() const { return {}; }

  // period_extremum: watches output `row`; each AdvancePeriod then also finds
  // PeriodExtremum(), the largest |output| at a stationary point strictly inside that period,
  // exactly (no substeps: model/tick_extremum.h). False for a row no state reaches.
  virtual bool WatchExtremum(int row);
  virtual double PeriodExtremum() const { return 0.0; }

  // advance_at_rest: `periods` (>= 0) whole periods under a zero input at once, outputs
  // unread (the master has the tail's metrics in closed form: bench/run/damped_tail.h).
  virtual void AdvanceAtRest(long periods);

  // deferred_substeps, while an extremum is watched (a master that needs a period's inner
  // substeps only now and then): AdvancePeriodToEnd is AdvancePeriod (same_input_periods 1)
  // that writes only the last substep's outputs, at their place in `outputs` (substep
  // substeps() - 1), and the extremum; WriteDeferredSubsteps then writes the period's other
  // substeps, as AdvancePeriod would have written them, bit for bit.
  virtual void AdvancePeriodToEnd(const double* drive_accel, double* outputs);
  virtual void WriteDeferredSubsteps(double* outputs) const;

  // From now on AdvancePeriod writes only these output rows, in this order (rows.size()
  // values per substep); empty: all of them. The master asks for what it reads.
  virtual void SelectOutputs(const std::vector<int>& rows) { selected_rows_ = rows; }
  int output_width() const {
    return selected_rows_.empty() ? num_outputs() : static_cast<int>(selected_rows_.size());
  }

 protected:
  // Writes `all` (num_outputs values) as AdvancePeriod's selection to `outputs`.
  void WriteSelected(const double* all, double* outputs) const;
  std::vector<int> selected_rows_;
};

// The method kAuto stands for with this plant: kExact (every LinearPlant is linear).
IntegratorMethod ResolveMethod(IntegratorMethod method, const LinearPlant& plant);

// `scale_accel_m_s2`: the largest acceleration magnitude of the run, `scale_velocity_m_s`
// its largest commanded speed; together they set the tolerances (a servo's following error
// is proportional to the speed, so pass it whenever the plant has a servo).
// Inputs that reach no state (the columns of an axis without states, e.g. a rigid axis
// under the kinematic drive) are left out of the integration: the result is then exactly
// that of the plant without them.
std::unique_ptr<PlantIntegrator> MakeIntegrator(const LinearPlant& plant,
                                                const IntegratorConfig& config,
                                                double period_s, int substeps,
                                                double scale_accel_m_s2,
                                                double scale_velocity_m_s = 0.0);

}  // namespace shapebench::model

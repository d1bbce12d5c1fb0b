// CVODE checked against the exact discretisation of the same linear plant, so that a loose
// tolerance or a stiff mode never yields a wrong metric without a word (docs/accuracy.md).
//
// Why a sample and not the run: the check must cost little and be shared by every run of a
// sweep with the same plant and integrator settings (the sample depends on nothing else).
// Why this sample: half a period of the lowest mode accelerating, half decelerating back to
// rest, then two periods free: the unshaped pulse that excites every mode hardest per unit
// of acceleration (transient and free vibration both), driven the way runs drive CVODE
// (AdvancePeriod with the held inputs announced).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "model/integrator.h"
#include "model/linear_plant.h"

namespace shapebench::model {

// The largest deviation of CVODE from the exact discretisation on the sample, relative to
// each output's largest exact value, that still keeps a run's ratio metrics within
// kCvodeMetricAccuracy of the exact path's. Calibrated on every shipped scenario at rtol
// 1e-5 .. 1e-10, Adams and BDF (docs/accuracy.md has the table and the script).
constexpr double kCrossCheckLimit = 5.0e-5;
// The documented accuracy of a CVODE run's ratio metrics (fractions of the static
// displacement) against the exact path's, at settings the cross-check passes.
constexpr double kCvodeMetricAccuracy = 1.0e-4;

struct CrossCheckResult {
  // max over outputs and substeps of |y_cvode - y_exact| / max |y_exact| of that output.
  double deviation = 0.0;
  long sample_ticks = 0;
  double sample_s = 0.0;
  // How long an error CVODE makes lasts: the slowest pole's decay time 1/(-Re lambda),
  // infinite for an undamped mode (its phase error only grows).
  double memory_s = 0.0;
  // CVODE's own failure on the pulse (flag and message), "" when it ran: no verdict then.
  std::string solver_failure;
  // The deviation a run of `run_s` seconds may reach: errors committed as on the sample,
  // adding up over the run or over the memory, whichever is shorter.
  double Predicted(double run_s) const {
    return deviation * std::max(1.0, std::min(run_s, memory_s) / sample_s);
  }
  bool Passed(double run_s) const {
    return solver_failure.empty() && Predicted(run_s) <= kCrossCheckLimit;
  }
};

// Which CVODE integrator is checked: CvodeIntegrator (a linear plant), or the integrator
// of a plant with nonlinear elements (NonlinearCvodeIntegrator: BDF, root finding, CVODE's
// interpolation) on that plant's linear part, the elements left out (docs/nonlinear.md:
// what a nonlinear run is promised).
enum class CheckedIntegrator { kLinear, kNonlinear };

// Runs the sample through CVODE (`config` as the run gives it) and through the exact
// discretisation, with the run's period, substeps and tolerance scales (an acceleration
// scale of 0 is taken as 1).
CrossCheckResult CrossCheckCvode(const LinearPlant& plant, const IntegratorConfig& config,
                                 double period_s, int substeps, double scale_accel_m_s2,
                                 double scale_velocity_m_s,
                                 CheckedIntegrator checked = CheckedIntegrator::kLinear);

// The same, remembered per distinct (plant, settings): the points of a sweep that do not
// change the plant pay for it once. Thread-safe; the result does not depend on which
// thread computes it first.
CrossCheckResult CachedCrossCheckCvode(const LinearPlant& plant, const IntegratorConfig& config,
                                       double period_s, int substeps, double scale_accel_m_s2,
                                       double scale_velocity_m_s,
                                       CheckedIntegrator checked = CheckedIntegrator::kLinear);

// One check for a family of plants that differ only in one number of the structure (a
// mode's frequency or damping ratio, swept by a sweep over [lo, hi]): the check's error
// model is scale-free (the pulse follows the slowest pole, the tolerances the static
// state), so the deviation on the pulse varies little over the family. It is checked at
// the band's ends, at kFamilyInterior values evenly between, and at the midpoints beside
// the largest; the family's deviation is the largest of these. A member is covered when
// that deviation times kFamilyMargin, projected over its own run with its own memory and
// pulse length (FamilyCovers), is within kCrossCheckLimit; a member that is not covered
// gets its own check (CachedCrossCheckCvode), which alone refuses. The margin: on the
// calibration sweeps (tests/model/cvode_cross_check_test.cc, docs/accuracy.md) no member's
// own deviation exceeded the family's by more than kFamilyMarginSeen (1.35 at the most,
// BDF at rtol 1e-7; 1.00-1.02 under Adams).
constexpr int kFamilyInterior = 9;
constexpr double kFamilyMargin = 2.0;
constexpr double kFamilyMarginSeen = 1.4;

// A member of the family at value v: its plant and the output substeps its run uses
// (nullopt: no such member, the family is not usable).
struct FamilyMember {
  LinearPlant plant;
  int substeps = 1;
};

struct CrossCheckFamily {
  bool usable = false;     // every member checked ran and gave a finite deviation
  double deviation = 0.0;  // the largest member's
  double worst_value = 0.0;
  std::vector<double> values;  // where it was checked, in order of checking
};

CrossCheckFamily CrossCheckCvodeFamily(double lo, double hi,
                                       const std::function<std::optional<FamilyMember>(double)>& member,
                                       const IntegratorConfig& config, double period_s,
                                       double velocity_per_accel_s,
                                       CheckedIntegrator checked = CheckedIntegrator::kLinear);

// The same, remembered under `identity` (everything but the family's number that makes its
// plants and settings: the caller's). Thread-safe; one computation per identity.
CrossCheckFamily CachedCrossCheckCvodeFamily(const std::string& identity, double lo, double hi,
                                             const std::function<std::optional<FamilyMember>(double)>& member,
                                             const IntegratorConfig& config, double period_s,
                                             double velocity_per_accel_s,
                                             CheckedIntegrator checked = CheckedIntegrator::kLinear);

// Whether the family's check covers a run of `run_s` on `plant` (a member): the family's
// deviation times kFamilyMargin, projected as CrossCheckResult::Predicted with the plant's
// own memory and pulse length, within kCrossCheckLimit.
bool FamilyCovers(const CrossCheckFamily& family, const LinearPlant& plant, double period_s, double run_s);

// What a user reads when the check fails: the disagreement, the allowance and the ways out.
std::string CrossCheckMessage(const CrossCheckResult& result, const IntegratorConfig& config,
                              double run_s, CheckedIntegrator checked = CheckedIntegrator::kLinear);

}  // namespace shapebench::model

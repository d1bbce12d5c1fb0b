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

#include <string>

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

// What a user reads when the check fails: the disagreement, the allowance and the ways out.
std::string CrossCheckMessage(const CrossCheckResult& result, const IntegratorConfig& config,
                              double run_s, CheckedIntegrator checked = CheckedIntegrator::kLinear);

}  // namespace shapebench::model

// residual_ratio as the input-shaping literature means it (bench/run/residual_vibration.h):
// the amplitude of the free vibration at motion end, against oracles built here: the
// shaper's V(w, zeta) from its impulses, a least-squares fit of the simulated free
// response on independently computed poles, and the windowed maximum's bounds.
#include <cmath>
#include <complex>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <unsupported/Eigen/Polynomials>

#include "bench/run/run_scenario.h"
#include "common/math_constants.h"
#include "controller/shaper_registry.h"
#include "tests/support/sdof_fixture.h"

namespace shapebench::bench {
namespace {


// One 22 Hz mode, 103 mm at 6 m/min with 50 ms acc/dec on a 1 ms grid: every phase and,
// at 25 Hz, every impulse of the shapers below on a tick, so the shaped command is the
// unshaped one convolved with the shaper's impulses exactly.
Scenario ShaperScenario(double zeta, const std::string& method) {
  Scenario s = testing::SdofScenario(22.0, zeta);
  s.controller.feed_mm_min = 6000;
  s.controller.accel_time_s = 0.05;
  s.move.distance_mm = 103;
  s.controller.pattern.method = method;
  s.controller.pattern.frequency_hz = 25.0;
  s.controller.pattern.design_damping_ratio = 0.0;
  s.controller.pattern.mode = controller::PatternMode::kBoth;
  return s;
}

// V(w, zeta) = exp(-zeta w t_n) sqrt(C^2 + S^2), C = sum A_i exp(zeta w t_i) cos(w_d t_i),
// S the same with sin: the free vibration a shaper leaves, relative to the unshaped step's.
double ShaperResidual(const std::vector<controller::Impulse>& impulses, double frequency_hz, double zeta) {
  const double w = kTwoPi * frequency_hz;
  const double wd = w * std::sqrt(1.0 - zeta * zeta);
  double c = 0.0, s = 0.0;
  for (const controller::Impulse& i : impulses) {
    c += i.amplitude * std::exp(zeta * w * i.time_s) * std::cos(wd * i.time_s);
    s += i.amplitude * std::exp(zeta * w * i.time_s) * std::sin(wd * i.time_s);
  }
  return std::exp(-zeta * w * impulses.back().time_s) * std::hypot(c, s);
}

struct ShaperCase {
  double zeta;
  std::string method;
};

void PrintTo(const ShaperCase& c, std::ostream* os) { *os << c.method << " at zeta " << c.zeta; }

class ShapedResidual : public ::testing::TestWithParam<ShaperCase> {};

// Tests that the shaped residual_ratio over the unshaped one is the shaper's V(w, zeta),
// computed from its impulses (method 1, the patent's a/2 for T/2: impulses 1/2 at 0 and
// T/2), to 1e-6, for zeta up to 0.5 (where the residual is the envelope: its cap for
// near-critical damping never acts, model/free_response.h): the amplitude no longer
// depends on where in its cycle the vibration is when motion ends.
TEST_P(ShapedResidual, RatioIsTheShapersResidualVibration) {
  const ShaperCase c = GetParam();
  RunOptions options;
  options.record_trace = false;
  const Scenario unshaped = ShaperScenario(c.zeta, "none");
  const Scenario shaped = ShaperScenario(c.zeta, c.method);
  const double r0 = RunScenario(unshaped, options).metrics.residual_ratio;
  const double r1 = RunScenario(shaped, options).metrics.residual_ratio;
  const std::vector<controller::Impulse> impulses = controller::ShaperImpulses(shaped.controller.pattern);
  for (const controller::Impulse& i : impulses) {
    ASSERT_NEAR(std::remainder(i.time_s, 0.001), 0.0, 1e-12) << c.method << ": not on the grid";
  }
  if (c.method == "1") {
    // Para. 38's a/2 for T/2, then a: jerk impulses 1/2 at 0 and 1/2 at T/2 = 20 ms (a ZV).
    double at_0 = 0.0, at_half = 0.0;
    for (const controller::Impulse& i : impulses) (i.time_s < 0.01 ? at_0 : at_half) += i.amplitude;
    EXPECT_DOUBLE_EQ(at_0, 0.5);
    EXPECT_DOUBLE_EQ(at_half, 0.5);
    EXPECT_NEAR(impulses.back().time_s, 0.02, 1e-15);
  }
  ASSERT_GT(r0, 0.1);
  EXPECT_NEAR(r1 / r0, ShaperResidual(impulses, 22.0, c.zeta), 1e-6) << c.method << " zeta " << c.zeta;
}

std::vector<ShaperCase> ShaperCases() {
  std::vector<ShaperCase> cases;
  for (double zeta : {0.0, 0.05, 0.1, 0.3, 0.5}) {
    for (const char* method : {"zv", "zvd", "mzv", "ei", "1"}) cases.push_back({zeta, method});
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Shapers, ShapedResidual, ::testing::ValuesIn(ShaperCases()),
                         [](const ::testing::TestParamInfo<ShaperCase>& info) {
                           return "zeta" + std::to_string(static_cast<int>(info.param.zeta * 100)) + "_" +
                                  (info.param.method == "1" ? std::string("method1") : info.param.method);
                         });

constexpr double kM1 = 80.0, kM2 = 20.0, kK1 = 4.0e6, kC1 = 900.0, kK2 = 1.5e6, kC3 = 250.0;

// Two masses, a spring and dashpot from the drive to the first, a spring from it to the
// second and a dashpot from the second to the ground: damping that is not proportional
// (complex mode shapes).
Scenario TwoMassScenario() {
  Scenario s = testing::SdofScenario();
  model::LumpedMachineConfig lumped;
  lumped.bodies = {{"carriage", kM1}, {"tool", kM2}};
  lumped.elements = {{"screw", "driven", "carriage", kK1, kC1},
                     {"arm", "carriage", "tool", kK2, 0.0},
                     {"air", "tool", "ground", 0.0, kC3}};
  lumped.output_body = "tool";
  s.machine.axes[s.machine.driven_axis] = model::MachineConfig{lumped};
  s.controller.pattern.method = "none";
  return s;
}

// The two-mass model's poles with the driven point held, upper members: the roots of
// det(lambda^2 M + lambda C + K) = (m1 l^2 + c1 l + k1 + k2)(m2 l^2 + c3 l + k2) - k2^2, a
// quartic (not the state-space eigenproblem); `damped` false: C = 0.
std::vector<std::complex<double>> TwoMassPoles(bool damped = true) {
  const double c1 = damped ? kC1 : 0.0, c3 = damped ? kC3 : 0.0;
  Eigen::VectorXd poly(5);  // ascending
  poly << (kK1 + kK2) * kK2 - kK2 * kK2, c1 * kK2 + (kK1 + kK2) * c3, kM1 * kK2 + c1 * c3 + (kK1 + kK2) * kM2,
      kM1 * c3 + c1 * kM2, kM1 * kM2;
  Eigen::PolynomialSolver<double, 4> solver(poly);
  std::vector<std::complex<double>> poles;
  for (const auto& root : solver.roots()) {
    if (root.imag() > 0.0) poles.push_back(root);
  }
  if (std::abs(poles[0]) > std::abs(poles[1])) std::swap(poles[0], poles[1]);
  return poles;
}

// Fits y(t0 + tau) = [y0 +] sum_k 2 Re(c_k e^{lambda_k tau}) to the trace over
// [t0, t0 + span] (least squares; `offset`: with the constant y0) and returns the c_k; the
// fit must be exact to 1e-9 of the samples (the trace is a free response there).
std::vector<std::complex<double>> FitFreeResponse(const Trace& trace, const std::vector<std::complex<double>>& poles,
                                                  double t0, double span, bool offset) {
  std::vector<double> tau, y;
  for (std::size_t i = 0; i < trace.time_s.size(); ++i) {
    const double t = trace.time_s[i] - t0;
    if (t >= -1e-12 && t <= span) {
      tau.push_back(t);
      y.push_back(trace.deflection_m[i]);
    }
  }
  EXPECT_GT(tau.size(), 100u);
  const int columns = 2 * static_cast<int>(poles.size()) + (offset ? 1 : 0);
  Eigen::MatrixXd a(tau.size(), columns);
  for (std::size_t j = 0; j < tau.size(); ++j) {
    for (std::size_t k = 0; k < poles.size(); ++k) {
      const std::complex<double> e = std::exp(poles[k] * tau[j]);
      a(j, 2 * k) = 2.0 * e.real();
      a(j, 2 * k + 1) = -2.0 * e.imag();
    }
    if (offset) a(j, columns - 1) = 1.0;
  }
  const Eigen::VectorXd b = Eigen::Map<const Eigen::VectorXd>(y.data(), static_cast<Eigen::Index>(y.size()));
  const Eigen::VectorXd c = a.colPivHouseholderQr().solve(b);
  EXPECT_LT((a * c - b).cwiseAbs().maxCoeff(), 1e-9 * b.cwiseAbs().maxCoeff()) << "not a free response";
  std::vector<std::complex<double>> coefficients;
  for (std::size_t k = 0; k < poles.size(); ++k) coefficients.emplace_back(c(2 * k), c(2 * k + 1));
  return coefficients;
}

// Tests that, for the two-mass model, residual_amplitude_m is sum_k 2 |c_k| of the free
// response y(t) = sum_k 2 Re(c_k e^{lambda_k t}) after motion end, its c_k fitted (least
// squares) to the simulated deflection over two lowest periods, the poles lambda_k from
// the quartic (TwoMassPoles); 1e-6 of the amplitude. The per-pole amplitudes are
// reported too.
TEST(ResidualVibration, TwoMassesWithDashpotsMatchAFittedFreeResponse) {
  const RunResult result = RunScenario(TwoMassScenario());
  const std::vector<std::complex<double>> poles = TwoMassPoles();
  const std::vector<std::complex<double>> c =
      FitFreeResponse(result.trace, poles, result.metrics.motion_time_s, 2.0 * kTwoPi / std::abs(poles[0]), false);
  const double oracle = 2.0 * (std::abs(c[0]) + std::abs(c[1]));
  EXPECT_NEAR(result.metrics.residual_amplitude_m, oracle, 1e-6 * oracle);
  EXPECT_NEAR(result.metrics.residual_ratio, oracle / result.metrics.static_displacement_m,
              1e-6 * oracle / result.metrics.static_displacement_m);
  ASSERT_EQ(result.residual_modes.size(), 2u);
  double sum = 0.0;
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_NEAR(result.residual_modes[k].frequency_hz, std::abs(poles[k]) / kTwoPi, 1e-6 * std::abs(poles[k]));
    EXPECT_NEAR(result.residual_modes[k].damping_ratio, -poles[k].real() / std::abs(poles[k]), 1e-6);
    sum += result.residual_modes[k].amplitude;
  }
  EXPECT_DOUBLE_EQ(sum, result.metrics.residual_amplitude_m);
}

// Tests that, for the two-mass model (whose dashpot to the ground loads it in cruise: an
// offset at constant velocity), cruise_residual_ratio is the amplitude about that offset:
// sum_k 2 |c_k| of y = y0 + sum_k 2 Re(c_k e^{lambda_k tau}) fitted over the cruise from
// its probe (one lowest undamped period, in whole ticks, after the acceleration's end at
// 0.3 s), / static; 1e-6.
TEST(ResidualVibration, TwoMassCruiseIsAboutTheVelocityLoadedEquilibrium) {
  const RunResult result = RunScenario(TwoMassScenario());
  const double lowest_hz = std::abs(TwoMassPoles(false)[0]) / kTwoPi;
  const double probe_s = 0.3 + std::ceil(1.0 / lowest_hz / 0.001) * 0.001;
  const std::vector<std::complex<double>> poles = TwoMassPoles();
  const std::vector<std::complex<double>> c = FitFreeResponse(result.trace, poles, probe_s, 0.4 - probe_s, true);
  const double oracle = 2.0 * (std::abs(c[0]) + std::abs(c[1])) / result.metrics.static_displacement_m;
  ASSERT_GT(oracle, 1e-3);
  EXPECT_NEAR(result.metrics.cruise_residual_ratio, oracle, 1e-6 * oracle);
}

// Tests that CVODE's state gives the exact integrator's residual and cruise amplitudes (to
// 1e-5, its rtol 1e-10 and the state's interpolation), for the two-mass model under the
// kinematic drive and under the servo with ideal inner loops (a real pole, and the
// dashpot to the ground loading the cruise equilibrium).
TEST(ResidualVibration, CvodeAgreesWithExact) {
  for (model::DriveType drive : {model::DriveType::kKinematic, model::DriveType::kServo}) {
    Scenario s = TwoMassScenario();
    s.drive.type = drive;
    s.drive.servo.velocity_loop_hz = 0.0;  // the dashpot to the ground needs ideal inner loops
    s.integrator.method = model::IntegratorMethod::kExact;
    const Metrics exact = RunScenario(s).metrics;
    s.integrator.method = model::IntegratorMethod::kCvode;
    const Metrics cvode = RunScenario(s).metrics;
    ASSERT_GT(exact.residual_ratio, 1e-3);
    EXPECT_NEAR(cvode.residual_ratio, exact.residual_ratio, 1e-5 * exact.residual_ratio);
    EXPECT_NEAR(cvode.cruise_residual_ratio, exact.cruise_residual_ratio, 1e-5 * exact.cruise_residual_ratio);
  }
}

// Tests that the windowed maximum survives as residual_peak_ratio and lies between the
// bounds the amplitude sets for one damped mode: at most the amplitude (its free vibration
// never exceeds its envelope), at least the envelope half a damped period later, less the
// sampling's 1.2e-4.
TEST(ResidualVibration, WindowedPeakIsBoundedByTheAmplitude) {
  for (double zeta : {0.0, 0.05}) {
    const Scenario s = testing::SdofScenario(25.0, zeta);
    const Metrics m = RunScenario(s).metrics;
    const double w = kTwoPi * 25.0;
    const double half_period_s = 0.5 * kTwoPi / (w * std::sqrt(1.0 - zeta * zeta));
    EXPECT_LE(m.residual_peak_ratio, m.residual_ratio * (1.0 + 1e-9)) << zeta;
    EXPECT_GE(m.residual_peak_ratio, m.residual_ratio * std::exp(-zeta * w * half_period_s) * (1.0 - 1.2e-4))
        << zeta;
    EXPECT_DOUBLE_EQ(m.residual_peak_ratio, m.residual_peak_m / m.static_displacement_m);
    EXPECT_DOUBLE_EQ(m.residual_ratio, m.residual_amplitude_m / m.static_displacement_m);
  }
}

// Tests that cruise_residual_ratio is the amplitude about the cruise equilibrium: for one
// undamped mode whose acceleration phase of n whole natural periods leaves no vibration,
// 0 (to rounding), while the windowed-peak view saw the deflection of the cruise.
TEST(ResidualVibration, CruiseAmplitudeIsAboutTheEquilibrium) {
  Scenario s = testing::SdofScenario(25.0, 0.0);
  s.controller.accel_time_s = 0.08;  // two whole periods of 40 ms: no vibration in cruise
  s.controller.pattern.method = "none";
  const Metrics m = RunScenario(s).metrics;
  EXPECT_LT(m.cruise_residual_ratio, 1e-6);
  s.controller.accel_time_s = 0.1;  // two and a half: the largest, 2 x static peak to peak
  const Metrics half = RunScenario(s).metrics;
  EXPECT_NEAR(half.cruise_residual_ratio, 2.0, 1e-3);
}

}  // namespace
}  // namespace shapebench::bench

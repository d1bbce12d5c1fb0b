// The complex-mode split of a plant's free response (model/free_response.h) and the
// integrators' PlantState, against closed forms.
#include "common/math_constants.h"
#include "model/free_response.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "model/exact_integrator.h"
#include "model/integrator.h"
#include "model/machine.h"

namespace shapebench::model {
namespace {


// The envelope of a modal mode's free vibration from (q, q'): |gain| sqrt(q^2 + ((q' + zeta w q) / w_d)^2).
double ModalEnvelope(const ModalMode& mode, double q, double qdot) {
  const double w = kTwoPi * mode.frequency_hz;
  const double wd = w * std::sqrt(1.0 - mode.damping_ratio * mode.damping_ratio);
  const double s = (qdot + mode.damping_ratio * w * q) / wd;
  return std::abs(mode.gain) * std::sqrt(q * q + s * s);
}

LinearPlant Modal(const std::vector<ModalMode>& modes) {
  MachineConfig machine;
  machine.form = ModalMachineConfig{modes};
  return BuildPlant(machine);
}

// Tests that, for a modal plant, each pole's amplitude is its mode's envelope
// |gain| sqrt(q^2 + ((q' + zeta w q) / w_d)^2), with the mode's frequency and damping.
TEST(ModalDecomposition, ModalPlantGivesEachModesEnvelope) {
  const std::vector<ModalMode> modes = {{41.0, 0.1, -0.4}, {22.0, 0.05, 1.3}, {97.0, 0.0, 0.2}};
  const LinearPlant plant = Modal(modes);
  Eigen::VectorXd x(6);
  x << 1.1e-6, -3.0e-4, 2.0e-6, 4.0e-4, -7.0e-7, 1.0e-3;
  const ModalDecomposition modal(plant.A);
  const std::vector<PoleAmplitude> amplitudes =
      modal.Amplitudes(plant.C.cast<std::complex<double>>() * modal.eigenvectors(), modal.Coordinates(x));
  ASSERT_EQ(amplitudes.size(), 3u);
  const int order[3] = {1, 0, 2};  // ascending frequency
  for (int k = 0; k < 3; ++k) {
    const ModalMode& mode = modes[order[k]];
    const int q = 2 * order[k];
    EXPECT_NEAR(amplitudes[k].frequency_hz, mode.frequency_hz, 1e-9 * mode.frequency_hz);
    EXPECT_NEAR(amplitudes[k].damping_ratio, mode.damping_ratio, 1e-9);
    const double expected = ModalEnvelope(mode, x(q), x(q + 1));
    EXPECT_NEAR(amplitudes[k].amplitude, expected, 1e-9 * expected) << "mode " << k;
  }
}

// Tests that two equal modes (one of two axes each) form one pole, whose amplitude is that
// of their sum as the output reads it (not a split that depends on the eigenvector basis).
TEST(ModalDecomposition, EqualModesAreOnePole) {
  const ModalMode mode{30.0, 0.02, 1.0};
  const LinearPlant one = Modal({mode});
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(4, 4);
  a.topLeftCorner(2, 2) = one.A;
  a.bottomRightCorner(2, 2) = one.A;
  Eigen::MatrixXd c(1, 4);
  c << 1.0, 0.0, 1.0, 0.0;
  Eigen::VectorXd x(4);
  x << 1e-6, 0.0, 0.0, 2e-4;
  const ModalDecomposition modal(a);
  const std::vector<PoleAmplitude> amplitudes =
      modal.Amplitudes(c.cast<std::complex<double>>() * modal.eigenvectors(), modal.Coordinates(x));
  ASSERT_EQ(amplitudes.size(), 1u);
  const double expected = ModalEnvelope(mode, x(0) + x(2), x(1) + x(3));
  EXPECT_NEAR(amplitudes[0].amplitude, expected, 1e-8 * expected);
}

// Tests that a decomposition of an equal matrix is handed out again (the per-thread cache).
TEST(ModalDecomposition, CachedPerMatrix) {
  const LinearPlant plant = Modal({{25.0, 0.03, 1.0}});
  const auto first = DecomposeModes(plant.A);
  EXPECT_EQ(DecomposeModes(plant.A).get(), first.get());
  EXPECT_NE(DecomposeModes(Modal({{26.0, 0.03, 1.0}}).A).get(), first.get());
}

// Tests that a state the modes cannot represent (a defective A: a critically damped pair)
// gives NaN amplitudes instead of huge cancelling ones.
TEST(ModalDecomposition, DefectiveMatrixGivesNaN) {
  const double w = 100.0;
  Eigen::MatrixXd a(2, 2);
  a << 0.0, 1.0, -w * w, -2.0 * w;  // zeta = 1: a double pole at -w
  Eigen::MatrixXd c(1, 2);
  c << 1.0, 0.0;
  const ModalDecomposition modal(a);
  Eigen::VectorXd x(2);
  x << 1e-6, 0.0;
  const std::vector<PoleAmplitude> amplitudes =
      modal.Amplitudes(c.cast<std::complex<double>>() * modal.eigenvectors(), modal.Coordinates(x));
  ASSERT_FALSE(amplitudes.empty());
  double total = 0.0;
  for (const PoleAmplitude& p : amplitudes) total += p.amplitude;
  EXPECT_TRUE(std::isnan(total)) << total;
}

// The free response of one damped mode from (q0, q0'), written in its phase form
// y(t) = E e^{-sigma t} cos(w_d t + phi): E = sqrt(q0^2 + ((q0' + sigma q0) / w_d)^2), cos phi =
// q0 / E, sin phi = -(q0' + sigma q0) / (w_d E). Its stationary points: y' = 0 where
// tan(w_d t + phi) = -sigma / w_d = -zeta / sqrt(1 - zeta^2), i.e. w_d t + phi = -asin(zeta)
// + k pi, where |y| = E cos(asin zeta) e^{-sigma t} = E sqrt(1 - zeta^2) e^{-sigma t}: each
// smaller than the one before (by e^{-sigma pi / w_d}), so the largest |y(t)|, t >= 0, is
// |q0| or the first of them. In long double, apart from the code's formula.
struct FreeOscillation {
  long double envelope = 0.0L;
  long double peak = 0.0L;
};

FreeOscillation ModeFreeResponse(double frequency_hz, double zeta, double q0, double v0) {
  const long double w = 2.0L * 3.14159265358979323846264338327950288L * frequency_hz;
  const long double z = zeta;
  const long double sigma = z * w;
  const long double wd = w * std::sqrt(1.0L - z * z);
  const long double s = (v0 + sigma * q0) / wd;
  FreeOscillation f;
  f.envelope = std::sqrt(static_cast<long double>(q0) * q0 + s * s);
  const long double pi = 3.14159265358979323846264338327950288L;
  const long double phi = std::atan2(-s, static_cast<long double>(q0));
  long double angle = std::fmod(-std::asin(z) - phi, pi);
  if (angle < 0.0L) angle += pi;
  const long double t1 = angle / wd;
  f.peak = std::max(std::abs(static_cast<long double>(q0)),
                    f.envelope * std::sqrt(1.0L - z * z) * std::exp(-sigma * t1));
  return f;
}

// The oracle's own check: max |y| on a grid of 20,001 points over the first half damped
// period (later extrema are smaller) and at most 60 decay times, y(t) = e^{-sigma t} (q0
// cos(w_d t) + (q0' + sigma q0) sin(w_d t) / w_d).
long double SampledPeak(double frequency_hz, double zeta, double q0, double v0) {
  const long double w = 2.0L * 3.14159265358979323846264338327950288L * frequency_hz;
  const long double sigma = zeta * w;
  const long double wd = w * std::sqrt(1.0L - static_cast<long double>(zeta) * zeta);
  long double span = 3.14159265358979323846264338327950288L / wd;
  if (sigma > 0.0L) span = std::min(span, 60.0L / sigma);
  long double peak = 0.0L;
  for (int i = 0; i <= 20000; ++i) {
    const long double t = span * i / 20000.0L;
    const long double y = std::exp(-sigma * t) * (q0 * std::cos(wd * t) + (v0 + sigma * q0) * std::sin(wd * t) / wd);
    peak = std::max(peak, std::abs(y));
  }
  return peak;
}

// The factor the residual may exceed the free response's largest |value| by (stated in
// model/free_response.h and docs/metrics.md): e^{pi z / sqrt(1 - z^2)}, z = min(zeta, 1 -
// zeta), at most 6.13 (zeta = 1/2).
double StatedCap(double zeta) {
  const double z = std::min(zeta, 1.0 - zeta);
  return std::exp(kPi * z / std::sqrt(1.0 - z * z));
}

// Tests that a mode's residual amplitude (the residual metrics' per-pole term, from
// ModalDecomposition::Amplitudes and from the real basis of AmplitudesOfState, taken where
// a cap acts or V^{-1} cancels) is finite for every damping in [0, 1) up to 1 - 1e-15
// (Amplitudes up to 0.9999999; beyond, at 25 Hz, its split gives way), never below the
// largest |value| P of the mode's free response from the state (t >= 0) and never above
// StatedCap(zeta) P (at most 6.13 P; P (1 + 1e-6) at zeta = 0.9999999, where the envelope
// is up to 2236 P), and the envelope itself for zeta <= 0.5 (so shaped / unshaped stays
// V). P from the closed form of the damped free response (ModeFreeResponse, itself
// checked on a grid, 1e-5); states at twelve phases; 1e-9 (the cap's own margin 1e-9: 2e-9).
TEST(ModalDecomposition, ResidualIsTheEnvelopeCappedByTheFreeResponsesPeak) {
  const double f = 25.0, w = kTwoPi * f;
  for (double zeta : {0.0, 1e-3, 0.03, 0.1, 0.3, 0.5, 0.55, 0.7, 0.9, 0.99, 0.999999, 0.9999999, 1.0 - 1e-10,
                      1.0 - 1e-15}) {
    Eigen::MatrixXd a(2, 2);
    a << 0.0, 1.0, -w * w, -2.0 * zeta * w;
    Eigen::MatrixXd c(1, 2);
    c << 1.0, 0.0;
    const ModalDecomposition modal(a);
    const Eigen::MatrixXcd cv = c.cast<std::complex<double>>() * modal.eigenvectors();
    for (int k = 0; k < 12; ++k) {
      const double alpha = kTwoPi * k / 12.0;
      const double q0 = 1e-6 * std::cos(alpha), v0 = 1e-6 * w * std::sin(alpha);
      SCOPED_TRACE("zeta 1 - " + std::to_string(1.0 - zeta) + ", phase " + std::to_string(k) + "/12");
      const FreeOscillation oracle = ModeFreeResponse(f, zeta, q0, v0);
      const double p = static_cast<double>(oracle.peak), e = static_cast<double>(oracle.envelope);
      const long double sampled = SampledPeak(f, zeta, q0, v0);
      ASSERT_LE(sampled, oracle.peak * (1.0L + 1e-12L));
      ASSERT_GE(sampled, oracle.peak * (1.0L - 1e-5L));
      Eigen::VectorXd x(2);
      x << q0, v0;
      const std::vector<PoleAmplitude> complex_split = modal.Amplitudes(cv, modal.Coordinates(x));
      const std::vector<PoleAmplitude> real_basis = modal.AmplitudesOfState(c, x);
      ASSERT_EQ(complex_split.size(), 1u);
      ASSERT_EQ(real_basis.size(), 1u);
      if (zeta <= 0.9999999) {
        EXPECT_TRUE(std::isfinite(complex_split[0].amplitude));
      }
      EXPECT_TRUE(std::isfinite(real_basis[0].amplitude));
      // The complex split where it is accurate (at 1 - 1e-10 it still splits some states,
      // its parts off by 3e-7: ResidualVibration takes the real basis wherever a cap acts).
      for (const double r : {zeta <= 0.9999999 ? complex_split[0].amplitude : NAN, real_basis[0].amplitude}) {
        if (std::isnan(r)) continue;
        EXPECT_GE(r, p * (1.0 - 1e-9));
        EXPECT_LE(r, StatedCap(zeta) * p * (1.0 + 2e-9));
        EXPECT_LE(r, 6.14 * p);
        if (zeta <= 0.5) {
          EXPECT_NEAR(r, e, 1e-9 * e);
        }
        if (zeta == 0.9999999) {
          EXPECT_LE(r, p * (1.0 + 1e-6));
        }
      }
    }
  }
}

// Tests that up to zeta = 1/2 the residual cap never acts, bit for bit: for a mode's free
// response from any state, CappedResidual(envelope, PairPeak, ResidualCap(zeta)) is the
// envelope itself (the closed-form sampler returns the envelope there without PairPeak).
// States of every phase and of magnitudes 1e-9 to 1e-3, 15 to 35 Hz, zeta from 0 to 0.5.
TEST(ModalDecomposition, CapNeverActsUpToHalfDamping) {
  int checked = 0;
  for (const double f : {15.0, 19.3, 25.0, 35.0}) {
    for (const double zeta : {0.0, 1e-6, 0.02, 0.1, 0.3, 0.45, 0.499, 0.5}) {
      const double w = kTwoPi * f;
      const double sigma = zeta * w;
      const double wd = w * std::sqrt(1.0 - zeta * zeta);
      const double cap = ResidualCap(zeta);
      EXPECT_FALSE(ResidualCapCanAct(zeta)) << zeta;
      for (int k = 0; k < 97; ++k) {
        const double alpha = kTwoPi * k / 97.0;
        for (const double scale : {1e-9, 3.7e-6, 1e-3}) {
          const double q = scale * std::cos(alpha);
          const double v = scale * w * std::sin(alpha);
          const double envelope = std::hypot(q, (v + sigma * q) / wd);
          const double amplitude = CappedResidual(envelope, PairPeak(q, v, sigma, wd), cap);
          EXPECT_EQ(amplitude, envelope) << f << " Hz, zeta " << zeta << ", phase " << k << ", scale " << scale;
          ++checked;
        }
      }
    }
  }
  EXPECT_EQ(checked, 4 * 8 * 97 * 3);
}

// Tests that PlantState gives the plant's states x at the integrator's time: the exact
// integrator's against the closed form, CVODE's (also through the input-selecting wrapper
// of a plant with an unused input) against the exact integrator's.
TEST(PlantState, ExactAndCvodeGiveTheStateAtTheirTime) {
  const double f = 25.0, zeta = 0.05, a = 2.0, period_s = 0.001;
  const double w = kTwoPi * f, wd = w * std::sqrt(1.0 - zeta * zeta);
  LinearPlant plant = Modal({{f, zeta, 1.0}});
  // A second input that reaches no state: MakeIntegrator wraps CVODE to drop it.
  plant.B_accel.conservativeResize(Eigen::NoChange, 2);
  plant.B_accel.col(1).setZero();
  plant.B_vel = Eigen::MatrixXd::Zero(2, 2);
  IntegratorConfig exact_config;
  exact_config.method = IntegratorMethod::kExact;
  IntegratorConfig cvode_config;
  cvode_config.rtol = 1e-10;
  auto exact = MakeIntegrator(plant, exact_config, period_s, 3, a);
  auto cvode = MakeIntegrator(plant, cvode_config, period_s, 3, a);
  const double in[2] = {a, 0.0};
  std::vector<double> out(6 * 2);
  for (auto* integrator : {exact.get(), cvode.get()}) {
    integrator->Reset(Eigen::VectorXd::Zero(2));
    for (int k = 0; k < 37; ++k) integrator->AdvancePeriod(in, 37 - k, out.data());
  }
  const double t = 0.037, decay = std::exp(-zeta * w * t), s = a / (w * w);
  const double q = -s * (1.0 - decay * (std::cos(wd * t) + zeta * w / wd * std::sin(wd * t)));
  const double qdot = -s * decay * (w * w / wd) * std::sin(wd * t);
  const Eigen::VectorXd x_exact = exact->PlantState();
  const Eigen::VectorXd x_cvode = cvode->PlantState();
  ASSERT_EQ(x_exact.size(), 2);
  ASSERT_EQ(x_cvode.size(), 2);
  EXPECT_NEAR(x_exact(0), q, 1e-10 * s);
  EXPECT_NEAR(x_exact(1), qdot, 1e-10 * s * w);
  EXPECT_NEAR(x_cvode(0), q, 1e-6 * s);
  EXPECT_NEAR(x_cvode(1), qdot, 1e-6 * s * w);
}

}  // namespace
}  // namespace shapebench::model

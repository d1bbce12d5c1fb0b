// The complex-mode split of a plant's free response (model/free_response.h) and the
// integrators' PlantState, against closed forms.
#include "common/math_constants.h"
#include "model/free_response.h"

#include <cmath>
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

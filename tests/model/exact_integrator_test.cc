// The exact (matrix-exponential) integrator against closed-form responses.
#include "common/math_constants.h"
#include "model/exact_integrator.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "model/machine.h"

namespace shapebench::model {
namespace {


// Response from rest of q'' + 2 z w q' + w^2 q = -a (a held from t = 0), t >= 0.
double StepResponse(double a, double w, double zeta, double t) {
  if (t < 0.0) return 0.0;
  const double wd = w * std::sqrt(1.0 - zeta * zeta);
  const double decay = std::exp(-zeta * w * t);
  return -(a / (w * w)) * (1.0 - decay * (std::cos(wd * t) +
                                          zeta / std::sqrt(1.0 - zeta * zeta) * std::sin(wd * t)));
}

LinearPlant Sdof(double frequency_hz, double zeta) {
  MachineConfig machine;
  machine.form = ModalMachineConfig{{{frequency_hz, zeta, 1.0}}};
  return BuildPlant(machine);
}

class ExactSdof : public testing::TestWithParam<double> {};

// Tests the response to a constant acceleration from rest against the closed form, at
// every output substep over 12 natural periods, to 1e-12 of the static deflection.
TEST_P(ExactSdof, ConstantAccelerationFromRest) {
  const double zeta = GetParam();
  const double f_hz = 25.0, a = 1.667, period_s = 0.001;
  const int substeps = 4;
  const double w = kTwoPi * f_hz;
  const double static_m = a / (w * w);
  ExactIntegrator integrator(Sdof(f_hz, zeta), period_s, substeps);
  integrator.Reset(Eigen::VectorXd::Zero(1));
  for (int tick = 0; tick < 480; ++tick) {
    integrator.SetInput(Eigen::VectorXd::Constant(1, a));
    for (int s = 0; s < substeps; ++s) {
      integrator.Step();
      const double t = integrator.Time();
      ASSERT_EQ(t, static_cast<double>(tick * substeps + s + 1) * period_s / substeps);
      ASSERT_NEAR(integrator.Output()(0), StepResponse(a, w, zeta, t), 1e-12 * static_m)
          << "t = " << t;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Damping, ExactSdof, testing::Values(0.0, 0.05));

// Tests a piecewise-constant acceleration (held over several ticks, then changed, then
// zero) against the superposition of closed-form step responses.
TEST(ExactIntegrator, PiecewiseConstantBySuperposition) {
  const double f_hz = 31.0, zeta = 0.03, period_s = 0.001;
  const int substeps = 3;
  const double w = kTwoPi * f_hz;
  const std::vector<double> accel = {2.0, 2.0, 2.0, 0.5, 0.5, -1.0, -1.0, -1.0, 0.0};
  const int ticks_per_value = 7;
  ExactIntegrator integrator(Sdof(f_hz, zeta), period_s, substeps);
  integrator.Reset(Eigen::VectorXd::Zero(1));
  auto reference = [&](double t) {
    double q = 0.0, previous = 0.0;
    for (size_t i = 0; i < accel.size(); ++i) {
      const double t_start = static_cast<double>(i * ticks_per_value) * period_s;
      q += StepResponse(accel[i] - previous, w, zeta, t - t_start);
      previous = accel[i];
    }
    return q;
  };
  for (size_t i = 0; i < accel.size(); ++i) {
    for (int tick = 0; tick < ticks_per_value; ++tick) {
      integrator.SetInput(Eigen::VectorXd::Constant(1, accel[i]));
      for (int s = 0; s < substeps; ++s) {
        integrator.Step();
        ASSERT_NEAR(integrator.Output()(0), reference(integrator.Time()), 1e-12 * 2.0 / (w * w));
      }
    }
  }
}

// Tests the velocity path B_vel: a table driven through a screw spring k, sliding on a
// viscous way c to ground, m y'' + c y' + k y = -m a - c v with v = v0 + a t (the drive
// starts moving at v0 and accelerates). Closed form: y = alpha + beta t + transient.
TEST(ExactIntegrator, VelocityRampThroughDamperToGround) {
  const double m = 20.0, k = 8e5, c = 600.0, v0 = 0.05, a = 1.5;
  const double period_s = 0.001;
  const int substeps = 5;
  MachineConfig machine;
  LumpedMachineConfig config;
  config.bodies = {{"table", m}};
  config.elements = {{"screw", "driven", "table", k, 0.0}, {"way", "table", "ground", 0.0, c}};
  config.output_body = "table";
  machine.form = config;

  const double w = std::sqrt(k / m);
  const double zeta = c / (2.0 * std::sqrt(k * m));
  const double wd = w * std::sqrt(1.0 - zeta * zeta);
  // Particular solution of the linear forcing -m a - c v0 - c a t.
  const double beta = -c * a / k;
  const double alpha = (-m * a - c * v0 - c * beta) / k;
  // Homogeneous part from y(0) = 0, y'(0) = 0.
  const double p = -alpha;
  const double q = (zeta * w * p - beta) / wd;
  auto reference = [&](double t) {
    return alpha + beta * t +
           std::exp(-zeta * w * t) * (p * std::cos(wd * t) + q * std::sin(wd * t));
  };

  ExactIntegrator integrator(BuildPlant(machine), period_s, substeps);
  integrator.Reset(Eigen::VectorXd::Constant(1, v0));
  const double scale_m = std::abs(alpha) + std::abs(beta) * 0.3;
  for (int tick = 0; tick < 300; ++tick) {
    integrator.SetInput(Eigen::VectorXd::Constant(1, a));
    for (int s = 0; s < substeps; ++s) {
      integrator.Step();
      ASSERT_NEAR(integrator.Output()(0), reference(integrator.Time()), 1e-12 * scale_m)
          << "t = " << integrator.Time();
    }
  }
}

// Tests that Reset returns to rest at t = 0 and the same run repeats bit for bit.
TEST(ExactIntegrator, ResetRepeatsTheRun) {
  ExactIntegrator integrator(Sdof(25.0, 0.02), 0.001, 2);
  std::vector<double> first;
  for (int run = 0; run < 2; ++run) {
    integrator.Reset(Eigen::VectorXd::Zero(1));
    EXPECT_EQ(integrator.Time(), 0.0);
    EXPECT_EQ(integrator.Output()(0), 0.0);
    for (int tick = 0; tick < 50; ++tick) {
      integrator.SetInput(Eigen::VectorXd::Constant(1, tick < 20 ? 1.0 : 0.0));
      integrator.Step();
      integrator.Step();
      if (run == 0) {
        first.push_back(integrator.Output()(0));
      } else {
        ASSERT_EQ(integrator.Output()(0), first[tick]);
      }
    }
  }
}

}  // namespace
}  // namespace shapebench::model

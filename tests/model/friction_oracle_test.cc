// Friction laws against their closed forms (docs/nonlinear.md), through the whole path a run
// takes: the lumped form, BuildMachinePlant, NonlinearCvodeIntegrator. A body hangs on a
// damped spring from the driven point and rubs on the ground through the element under
// test; under the kinematic drive the body's deflection y (relative to the driven point) is
// -F_spring / k, and at rest relative to the drive the spring carries exactly the friction.
#include <cmath>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "model/integrator.h"
#include "model/multi_axis_machine.h"
#include "model/nonlinear_integrator.h"

namespace shapebench::model {
namespace {

constexpr double kMassKg = 10.0;
constexpr double kCoulombN = 60.0;
constexpr double kStaticN = 100.0;
constexpr double kStribeckMS = 1.0e-3;
constexpr double kViscousNSM = 50.0;
constexpr double kSigma0NM = 1.0e7;
constexpr double kSigma1NSM = 2.0e3;
constexpr int kY = 1;

FrictionConfig Friction(FrictionModel model) {
  FrictionConfig f;
  f.model = model;
  f.coulomb_n = kCoulombN;
  f.static_n = kStaticN;
  f.stribeck_velocity_m_s = kStribeckMS;
  f.viscous_n_s_m = kViscousNSM;
  if (model == FrictionModel::kLuGre) {
    f.sigma0_n_m = kSigma0NM;
    f.sigma1_n_s_m = kSigma1NSM;
  }
  return f;
}

// The body on its spring and damper from the driven point, `friction` to the ground; Y.
NonlinearPlant BodyOnGround(const FrictionConfig& friction, double spring_n_m, double damper_n_s_m) {
  LumpedMachineConfig lumped;
  lumped.bodies = {{"body", kMassKg}};
  LumpedElement ground{"ways", "body", "ground"};
  ground.friction = friction;
  lumped.elements = {{"spring", "body", "driven", spring_n_m, damper_n_s_m}, ground};
  lumped.output_body = "body";
  MultiAxisMachineConfig machine;
  machine.axes[kY] = MachineConfig{lumped};
  const MachinePlant built = BuildMachinePlant(machine, DriveConfig{});
  return {built.plant, built.nonlinear};
}

std::unique_ptr<PlantIntegrator> Integrator(const NonlinearPlant& plant, double period_s) {
  IntegratorConfig config;
  config.method = IntegratorMethod::kAuto;
  return MakePlantIntegrator(plant, config, period_s, 1, 1.0, 1.0);
}

// Tests that steady sliding at a held drive speed v gives the Stribeck curve
// F_c + (F_s - F_c) exp(-(v/v_s)^2) + sigma2 v within 0.5%, from 1e-5 to 1 m/s, for LuGre
// (after its bristles settle: ten times F_s / (sigma0 v), at least 0.2 s) and for the
// event-based Stribeck law. The body starts sliding with the drive (Reset at speed v) on a
// stiff, critically damped spring (1e9 N/m, 2e5 N s/m): steady sliding is then stable (the
// curve's steepest fall, 3.4e4 N s/m, is far below the damper's 2e5), where a soft spring
// would stick and slip.
TEST(FrictionOracle, SteadySlidingFollowsTheStribeckCurve) {
  constexpr double kSpringNM = 1.0e9;
  for (FrictionModel model : {FrictionModel::kLuGre, FrictionModel::kStribeck}) {
    const NonlinearPlant plant = BodyOnGround(Friction(model), kSpringNM, 2.0e5);
    for (double v : {1e-5, 3e-5, 1e-4, 3e-4, 1e-3, 2e-3, 1e-2, 1e-1, 1.0}) {
      const double settle_s = std::max(0.2, 10.0 * kStaticN / (kSigma0NM * v));
      const double period_s = 0.01;
      auto integrator = Integrator(plant, period_s);
      integrator->Reset(Eigen::Vector3d(0.0, v, 0.0));
      const long ticks = std::lround(settle_s / period_s);
      std::vector<double> out(static_cast<std::size_t>(integrator->num_outputs()));
      const double zero[3] = {0.0, 0.0, 0.0};
      for (long k = 0; k < ticks; ++k) integrator->AdvancePeriod(zero, ticks - k, out.data());
      const double spring_n = -kSpringNM * out[kDeflectionRow + kY];
      const double expected = kCoulombN + (kStaticN - kCoulombN) * std::exp(-std::pow(v / kStribeckMS, 2)) +
                              kViscousNSM * v;
      EXPECT_NEAR(spring_n, expected, 0.005 * expected)
          << (model == FrictionModel::kLuGre ? "lugre" : "stribeck") << " at v = " << v << " m/s";
      EXPECT_DOUBLE_EQ(Friction(model).SteadyForce(v), expected);
    }
  }
}

// Tests LuGre's presliding: from rest, the drive creeping at 1 um/s loads the bristles, and
// the body's displacement x at friction force F (the spring's, quasi-static) is the closed
// form of dz/dx = 1 - sigma0 z / F_s (|w| << v_s, so g = F_s): x = -(F_s/sigma0) ln(1 - F/F_s)
// within 1% for F up to 0.1 F_c; and F / sigma0 within 1% where that form is (F <= 0.015
// F_s: the log's second term is F/(2 F_s) of it, 0.75% there; at 0.1 F_c it is 3%).
TEST(FrictionOracle, LuGrePreslidingIsTheBristleDeflection) {
  // No damper: the spring alone carries the friction force (the bristles' sigma1 damps).
  constexpr double kSpringNM = 1.0e6;
  const NonlinearPlant plant = BodyOnGround(Friction(FrictionModel::kLuGre), kSpringNM, 0.0);
  const double period_s = 0.001;
  const double creep_m_s = 1e-6;
  auto integrator = Integrator(plant, period_s);
  integrator->Reset(Eigen::Vector3d::Zero());
  std::vector<double> out(static_cast<std::size_t>(integrator->num_outputs()));
  // One tick of acceleration to the creep speed: u(t) = creep (t - period / 2) after it.
  const double start[3] = {0.0, creep_m_s / period_s, 0.0};
  integrator->AdvancePeriod(start, 1, out.data());
  const double zero[3] = {0.0, 0.0, 0.0};
  const long ticks = 8000;  // 8 s: F reaches 0.11 F_c
  int checked = 0;
  int linear = 0;
  for (long k = 2; k <= ticks; ++k) {
    integrator->AdvancePeriod(zero, ticks - k + 1, out.data());
    if (k % 500 != 0) continue;
    const double t = static_cast<double>(k) * period_s;
    const double y = out[kDeflectionRow + kY];
    const double force = -kSpringNM * y;
    const double x = creep_m_s * (t - 0.5 * period_s) + y;  // the body's own displacement
    if (force > 0.1 * kCoulombN) break;
    const double closed = -(kStaticN / kSigma0NM) * std::log(1.0 - force / kStaticN);
    EXPECT_NEAR(x, closed, 0.01 * closed) << "F = " << force << " N";
    if (force <= 0.015 * kStaticN) {
      EXPECT_NEAR(x, force / kSigma0NM, 0.01 * force / kSigma0NM) << "F = " << force;
      ++linear;
    }
    ++checked;
  }
  EXPECT_GE(checked, 10);
  EXPECT_GE(linear, 2);
}

}  // namespace
}  // namespace shapebench::model

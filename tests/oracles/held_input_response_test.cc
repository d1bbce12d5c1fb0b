// HeldInputResponse (model/held_input_response.h) against the matrix exponential computed
// here, and the split nonlinear integration it serves against the whole-state one.
#include "model/held_input_response.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>
#include <unsupported/Eigen/MatrixFunctions>

#include "model/integrator.h"
#include "model/multi_axis_machine.h"
#include "model/nonlinear_integrator.h"
#include "tests/support/axes.h"

namespace shapebench::model {
namespace {


// A 100 kg column on a 1e6 N/m spring from the driven point (100 rad/s) carrying a 1 kg tip
// on 2.5e7 N/m (5000 rad/s: rho h = 5 at 1 ms, so the series needs two pieces a tick),
// light damping, LuGre friction from the column to the ground; the tip's deflection out.
NonlinearPlant ColumnWithTip() {
  LumpedMachineConfig lumped;
  lumped.bodies = {{"column", 100.0}, {"tip", 1.0}};
  LumpedElement ways{"ways", "column", "ground"};
  ways.friction.model = FrictionModel::kLuGre;
  ways.friction.coulomb_n = 60.0;
  ways.friction.static_n = 100.0;
  ways.friction.stribeck_velocity_m_s = 1.0e-3;
  ways.friction.viscous_n_s_m = 50.0;
  ways.friction.sigma0_n_m = 1.0e7;
  ways.friction.sigma1_n_s_m = 2.0e3;
  lumped.elements = {{"spring", "column", "driven", 1.0e6, 200.0}, {"tip", "tip", "column", 2.5e7, 10.0}, ways};
  lumped.output_body = "tip";
  MultiAxisMachineConfig machine;
  machine.axes[kY] = MachineConfig{lumped};
  const MachinePlant built = BuildMachinePlant(machine, DriveConfig{});
  return {built.plant, built.nonlinear, built.following_error_axis};
}

// z_p(tau) = [Phi(tau) z + Gamma(tau) a] from exp([[A_z, B_z a], [0, 0]] tau) applied to
// [z; 1], the positions scaled by the fastest frequency first (x~ = 5000 x: A_z's entries
// then of one size, so Eigen's Pade exponential keeps its accuracy on every state).
Eigen::VectorXd Exact(const LinearPlant& plant, const Eigen::VectorXd& z, const Eigen::VectorXd& a, double tau) {
  const Eigen::Index nz = z.size();
  Eigen::VectorXd d = Eigen::VectorXd::Ones(nz + 1);
  for (int i = 0; i < plant.num_states(); ++i) {
    if (plant.state_kinds[i] == StateKind::kPosition) d(i) = 5000.0;
  }
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(nz + 1, nz + 1);
  m.topLeftCorner(nz, nz) = plant.AugmentedA();
  m.topRightCorner(nz, 1) = plant.AugmentedB() * a;
  const Eigen::MatrixXd scaled = d.asDiagonal() * m * d.cwiseInverse().asDiagonal();
  Eigen::VectorXd start(nz + 1);
  start << z, 1.0;
  const Eigen::VectorXd end = Eigen::MatrixXd(scaled * tau).exp() * (d.asDiagonal() * start);
  return (d.cwiseInverse().asDiagonal() * end).head(nz);
}

// Tests that the probes' values and rates at instants between the Chebyshev nodes, over
// ticks with different held inputs, equal row . z_p and row . (A_z z_p + B_z a) of the
// exponential computed here within 1e-11 of the rows' largest value (the series interpolate
// to ~1e-16; the oracle's own exponential carries ~1e-13), the rates within 1e-10 (the
// derivative of a degree-16 interpolant loses up to 16^2 of its accuracy), and the outputs
// at the substeps C z_p within 1e-11.
TEST(HeldInputResponse, ProbesAndOutputsFollowTheExponential) {
  const NonlinearPlant nonlinear = ColumnWithTip();
  const LinearPlant& plant = nonlinear.linear;
  const int nz = plant.num_states() + plant.num_inputs();
  const double period_s = 0.001;
  const int substeps = 7;
  Eigen::MatrixXd probes = Eigen::MatrixXd::Zero(2, nz);
  probes.row(0) << nonlinear.elements[0].row_x.transpose(), nonlinear.elements[0].row_v.transpose();
  probes.row(1).setLinSpaced(nz, 1.0, 2.0);
  HeldInputResponse response(plant, period_s, substeps, probes);
  EXPECT_GE(response.pieces(), 2) << "the tip's 5000 rad/s over 1 ms needs pieces";

  Eigen::VectorXd z = Eigen::VectorXd::Zero(nz);
  z(plant.num_states() + kY) = 0.01;  // under way at the drive's speed
  response.Reset(z);
  const Eigen::MatrixXd c_z = [&] {
    Eigen::MatrixXd c = Eigen::MatrixXd::Zero(plant.num_outputs(), nz);
    c.leftCols(plant.num_states()) = plant.C;
    return c;
  }();
  double worst_value = 0.0;
  double worst_rate = 0.0;
  double worst_output = 0.0;
  double scale_value = 0.0;
  double scale_rate = 0.0;
  double scale_output = 0.0;
  for (int tick = 0; tick < 6; ++tick) {
    Eigen::VectorXd a = Eigen::VectorXd::Zero(plant.num_inputs());
    a(kY) = std::sin(1.0 + tick) * 3.0;  // a different held input each tick
    response.SetInput(a.data());
    ASSERT_LE((response.start() - z).norm(), 1e-11 * z.norm()) << "tick " << tick;
    for (double fraction : {0.0, 0.013, 0.29, 0.5, 0.61, 0.987, 1.0}) {
      const double tau = fraction * period_s;
      const Eigen::VectorXd exact = Exact(plant, z, a, tau);
      const Eigen::VectorXd rate = plant.AugmentedA() * exact + plant.AugmentedB() * a;
      double values[2];
      double rates[2];
      response.Probe(tau, values, rates);
      for (int i = 0; i < 2; ++i) {
        worst_value = std::max(worst_value, std::abs(values[i] - probes.row(i).dot(exact)));
        worst_rate = std::max(worst_rate, std::abs(rates[i] - probes.row(i).dot(rate)));
        scale_value = std::max(scale_value, std::abs(probes.row(i).dot(exact)));
        scale_rate = std::max(scale_rate, std::abs(probes.row(i).dot(rate)));
      }
    }
    for (int j = 1; j <= substeps; ++j) {
      const Eigen::VectorXd exact = c_z * Exact(plant, z, a, period_s * j / substeps);
      std::vector<double> out(static_cast<std::size_t>(plant.num_outputs()));
      response.OutputsAt(j, out.data());
      for (int r = 0; r < plant.num_outputs(); ++r) {
        worst_output = std::max(worst_output, std::abs(out[r] - exact(r)));
        scale_output = std::max(scale_output, std::abs(exact(r)));
      }
    }
    z = Exact(plant, z, a, period_s);
    response.NextTick();
  }
  EXPECT_GT(scale_value, 0.0);
  EXPECT_GT(scale_output, 1e-6);  // the tip deflects by ~m a / k
  EXPECT_LE(worst_value, 1e-11 * scale_value);
  EXPECT_LE(worst_rate, 1e-10 * scale_rate);
  EXPECT_LE(worst_output, 1e-11 * scale_output);
}

struct Response {
  std::vector<double> tip_m;  // the tip's deflection at every substep
  IntegratorStats stats;
};

// The plant dragged through velocity reversals: a held acceleration 0.5 sin(2 pi 4 t) m/s^2
// changing every 1 ms tick (speed up to 2 cm/s, a reversal every 0.125 s), 0.5 s.
Response HeldDrag(const NonlinearPlant& plant, double rtol, bool split) {
  IntegratorConfig config;
  config.method = IntegratorMethod::kCvode;
  config.rtol = rtol;
  config.tuning.split_linear_part = split;
  const double period_s = 0.001;
  const int substeps = 10;
  auto integrator = MakePlantIntegrator(plant, config, period_s, substeps, 0.5, 0.02);
  integrator->Reset(Eigen::Vector3d::Zero());
  std::vector<double> out(static_cast<std::size_t>(integrator->num_outputs() * substeps));
  Response response;
  for (long k = 0; k < 500; ++k) {
    const double a[3] = {0.0, 0.5 * std::sin(2.0 * M_PI * 4.0 * k * period_s), 0.0};
    integrator->AdvancePeriod(a, 1, out.data());
    for (int j = 0; j < substeps; ++j) {
      response.tip_m.push_back(out[static_cast<std::size_t>(j * integrator->num_outputs() + kDeflectionRow + kY)]);
    }
  }
  response.stats = integrator->Stats();
  return response;
}

double LargestDifference(const Response& a, const Response& b) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.tip_m.size(); ++i) worst = std::max(worst, std::abs(a.tip_m[i] - b.tip_m[i]));
  return worst;
}

// Tests that the split integration (CVODE on the LuGre element's correction to the linear
// part's exact response) and the whole-state one converge to the same motion: at rtol 1e-11
// the two agree within 1e-6 of the deflection's largest value, and at the default rtol 1e-8
// each is within 1e-4 of the tight whole-state run (the accuracy CVODE's cross-check
// promises the ratio metrics, docs/accuracy.md). The split run never restarts at an input
// change (the whole-state one restarts at nearly every tick), and both see the reversals
// (LuGre's root at w = 0).
TEST(SplitIntegration, ConvergesToTheWholeStateMotion) {
  const NonlinearPlant plant = ColumnWithTip();
  const Response tight_whole = HeldDrag(plant, 1e-11, false);
  const Response tight_split = HeldDrag(plant, 1e-11, true);
  const Response split = HeldDrag(plant, 1e-8, true);
  const Response whole = HeldDrag(plant, 1e-8, false);
  double scale = 0.0;
  for (double y : tight_whole.tip_m) scale = std::max(scale, std::abs(y));
  ASSERT_GT(scale, 0.0);
  EXPECT_LE(LargestDifference(tight_split, tight_whole), 1e-6 * scale);
  EXPECT_LE(LargestDifference(split, tight_whole), 1e-4 * scale);
  EXPECT_LE(LargestDifference(whole, tight_whole), 1e-4 * scale);
  EXPECT_EQ(split.stats.reinits, 0);
  EXPECT_GT(whole.stats.reinits, 400);
  EXPECT_GE(split.stats.events, 4);
  EXPECT_EQ(split.stats.events, whole.stats.events);
}

}  // namespace
}  // namespace shapebench::model

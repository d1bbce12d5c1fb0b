// The CVODE integrator against the exact integrator (itself checked against closed forms
// in exact_integrator_test.cc).
#include "model/cvode_integrator.h"

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "model/machine.h"

namespace shapebench::model {
namespace {

constexpr double kPeriodS = 0.001;
constexpr int kSubsteps = 4;

MachineConfig ThreeModeMachine() {
  MachineConfig machine;
  machine.form = ModalMachineConfig{{{25.0, 0.02, 1.0}, {70.0, 0.05, -0.4}, {140.0, 0.0, 0.3}}};
  return machine;
}

// Bed on damped mounts, column on damped guides driven from the bed, a damper from the
// column to ground so the drive velocity loads the structure too (B_vel != 0).
MachineConfig DampedLumpedMachine() {
  LumpedMachineConfig config;
  config.bodies = {{"bed", 3000.0}, {"column", 1200.0}, {"head", 300.0}};
  config.elements = {{"mounts", "bed", "ground", 8e8, 4e5},
                     {"guides", "column", "driven", 3.5e7, 8e3},
                     {"z_guides", "head", "column", 2e8, 1.5e3},
                     {"cover", "column", "ground", 0.0, 2e3}};
  config.driven_relative_to = "bed";
  config.output_body = "head";
  config.output_relative_to = "bed";
  MachineConfig machine;
  machine.form = config;
  return machine;
}

// Acceleration held per tick (m/s^2): runs of equal values (CVODE integrates through the
// tick) and changes of every kind (step up, partial step, sign reversal, back to zero).
std::vector<double> AccelerationSequence() {
  std::vector<double> accel;
  auto hold = [&](double a, int ticks) { accel.insert(accel.end(), ticks, a); };
  hold(0.0, 3);
  hold(0.8, 1);
  hold(1.667, 17);
  hold(0.9, 4);
  hold(1.667, 9);
  hold(0.0, 30);
  hold(-1.667, 12);
  hold(-0.3, 1);
  hold(0.0, 60);
  return accel;
}

struct CvodeCase {
  std::string name;
  MachineConfig machine;
  CvodeLmm lmm;
  double initial_velocity_m_s;
  double max_error_ratio;  // allowed max |CVODE - exact| / static deflection
};

void PrintTo(const CvodeCase& c, std::ostream* os) { *os << c.name; }

class CvodeVersusExact : public testing::TestWithParam<CvodeCase> {};

// Tests that CVODE at rtol 1e-8 tracks the exact discretisation at every output substep.
// CVODE bounds the local error of each step to about rtol of the static deflection (the
// position weights); in lightly damped modes these errors add up rather than decay, so the
// global error grows with the number of steps: ~30 rtol for Adams (few, long steps) and
// ~300 rtol for BDF (larger error constants, numerical dissipation of oscillatory modes) on
// this 0.14 s sequence. Bounds: 1e-6 of static for Adams, 1e-5 for BDF; a wrong RHS or a
// missed reinit is off by 1e-2 of static and more.
TEST_P(CvodeVersusExact, PiecewiseConstantAcceleration) {
  const CvodeCase& c = GetParam();
  const LinearPlant plant = BuildPlant(c.machine);
  const double scale_accel = 1.667;
  const double static_m = std::abs(plant.StaticGain()(0, 0)) * scale_accel;
  IntegratorConfig config;
  config.rtol = 1e-8;
  config.lmm = c.lmm;
  auto cvode = MakeIntegrator(plant, config, kPeriodS, kSubsteps, scale_accel);
  config.method = IntegratorMethod::kExact;
  auto exact = MakeIntegrator(plant, config, kPeriodS, kSubsteps, scale_accel);
  const Eigen::VectorXd v0 = Eigen::VectorXd::Constant(1, c.initial_velocity_m_s);
  cvode->Reset(v0);
  exact->Reset(v0);

  const std::vector<double> accel = AccelerationSequence();
  double max_error_m = 0.0;
  double peak_m = 0.0;
  int changes = 0;
  for (size_t tick = 0; tick < accel.size(); ++tick) {
    const Eigen::VectorXd a = Eigen::VectorXd::Constant(1, accel[tick]);
    changes += accel[tick] != (tick == 0 ? 0.0 : accel[tick - 1]);
    cvode->SetInput(a);
    exact->SetInput(a);
    for (int s = 0; s < kSubsteps; ++s) {
      cvode->Step();
      exact->Step();
      ASSERT_EQ(cvode->Time(), exact->Time());
      max_error_m = std::max(max_error_m, std::abs(cvode->Output()(0) - exact->Output()(0)));
      peak_m = std::max(peak_m, std::abs(exact->Output()(0)));
    }
  }
  EXPECT_GT(peak_m, static_m);  // the sequence does excite the machine
  EXPECT_LE(max_error_m, c.max_error_ratio * static_m) << "error/static " << max_error_m / static_m;
  const IntegratorStats stats = cvode->Stats();
  EXPECT_EQ(stats.reinits, changes);
  EXPECT_GT(stats.steps, 0);
  EXPECT_GE(stats.rhs_evals, stats.steps);
}

INSTANTIATE_TEST_SUITE_P(
    Grid, CvodeVersusExact,
    testing::Values(CvodeCase{"ModalBdf", ThreeModeMachine(), CvodeLmm::kBdf, 0.0, 1e-5},
                    CvodeCase{"ModalAdams", ThreeModeMachine(), CvodeLmm::kAdams, 0.0, 1e-6},
                    CvodeCase{"LumpedBdf", DampedLumpedMachine(), CvodeLmm::kBdf, 0.02, 1e-5},
                    CvodeCase{"LumpedAdams", DampedLumpedMachine(), CvodeLmm::kAdams, 0.02, 1e-6}),
    [](const testing::TestParamInfo<CvodeCase>& info) { return info.param.name; });

// Tests that running out of internal steps raises SolverError carrying CVODE's flag name,
// with either output: CVODE's own limit per call (CV_NORMAL), or the same limit per output
// substep that the Hermite output (CV_ONE_STEP, one step per call) keeps itself.
TEST(CvodeIntegrator, TooMuchWorkIsReported) {
  for (CvodeOutput output : {CvodeOutput::kCvodeInterpolation, CvodeOutput::kHermite}) {
    IntegratorConfig config;
    config.rtol = 1e-12;
    config.max_num_steps = 1;
    config.tuning.output = output;
    auto cvode = MakeIntegrator(BuildPlant(ThreeModeMachine()), config, kPeriodS, kSubsteps, 1.0);
    cvode->SetInput(Eigen::VectorXd::Constant(1, 1.0));
    try {
      for (int s = 0; s < kSubsteps; ++s) cvode->Step();
      ADD_FAILURE() << "no SolverError";
    } catch (const SolverError& e) {
      EXPECT_EQ(e.flag_name(), "CV_TOO_MUCH_WORK");
      EXPECT_NE(std::string(e.what()).find("CVODE failed at t = "), std::string::npos) << e.what();
    }
  }
}

// Tests that Reset restarts from rest at t = 0 and reproduces the run.
TEST(CvodeIntegrator, ResetRepeatsTheRun) {
  IntegratorConfig config;
  auto cvode = MakeIntegrator(BuildPlant(ThreeModeMachine()), config, kPeriodS, 2, 1.0);
  std::vector<double> first;
  for (int run = 0; run < 2; ++run) {
    cvode->Reset(Eigen::VectorXd::Zero(1));
    EXPECT_EQ(cvode->Time(), 0.0);
    EXPECT_EQ(cvode->Output()(0), 0.0);
    for (int tick = 0; tick < 40; ++tick) {
      cvode->SetInput(Eigen::VectorXd::Constant(1, tick < 15 ? 1.0 : 0.0));
      cvode->Step();
      cvode->Step();
      if (run == 0) {
        first.push_back(cvode->Output()(0));
      } else {
        ASSERT_EQ(cvode->Output()(0), first[tick]);
      }
    }
    EXPECT_EQ(cvode->Stats().reinits, 2);
  }
}

}  // namespace
}  // namespace shapebench::model

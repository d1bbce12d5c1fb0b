#include "model/cvode_cross_check.h"

#include <cmath>

#include <gtest/gtest.h>

#include "model/machine.h"

namespace shapebench::model {
namespace {

constexpr double kCrossCheckPeriodS = 0.001;
constexpr int kCrossCheckSubsteps = 4;

LinearPlant OneMode(double frequency_hz, double damping_ratio, double gain) {
  MachineConfig machine;
  machine.form = ModalMachineConfig{{{frequency_hz, damping_ratio, gain}}};
  return BuildPlant(machine);
}

// Tests that the deviation the check reports is the integrators' own: at a tight rtol it is
// tiny, it grows as rtol loosens, and an undamped mode (errors never forgotten) predicts a
// run's deviation growing with the run while a damped one stops at its memory.
TEST(CvodeCrossCheck, DeviationFollowsTheTolerance) {
  IntegratorConfig config;
  double last = 0.0;
  for (double rtol : {1e-10, 1e-8, 1e-6}) {
    config.rtol = rtol;
    const CrossCheckResult r = CrossCheckCvode(OneMode(25.0, 0.0, 1.0), config, kCrossCheckPeriodS, kCrossCheckSubsteps, 1.7, 0.5);
    EXPECT_TRUE(r.solver_failure.empty());
    EXPECT_GT(r.deviation, last) << rtol;
    EXPECT_LT(r.deviation, 1000 * rtol) << rtol;
    last = r.deviation;
    EXPECT_EQ(r.sample_ticks, 80);  // 4 half periods of 25 Hz at 1 ms
    EXPECT_TRUE(std::isinf(r.memory_s));
    EXPECT_DOUBLE_EQ(r.Predicted(0.8), r.deviation * 10.0);
  }
  const CrossCheckResult damped = CrossCheckCvode(OneMode(25.0, 0.05, 1.0), config, kCrossCheckPeriodS, kCrossCheckSubsteps, 1.7, 0.5);
  const double memory_s = 1.0 / (0.05 * 2.0 * M_PI * 25.0);
  EXPECT_NEAR(damped.memory_s, memory_s, 1e-12);
  EXPECT_DOUBLE_EQ(damped.Predicted(100.0), damped.deviation * memory_s / 0.08);
}

// Tests that the cached check stands for every acceleration scale (a linear plant and its
// tolerances scale together) and is computed at unit acceleration.
TEST(CvodeCrossCheck, CacheIsScaleFree) {
  IntegratorConfig config;
  const LinearPlant plant = OneMode(31.0, 0.02, 1.0);
  const CrossCheckResult unit = CrossCheckCvode(plant, config, kCrossCheckPeriodS, kCrossCheckSubsteps, 1.0, 0.25);
  const CrossCheckResult cached = CachedCrossCheckCvode(plant, config, kCrossCheckPeriodS, kCrossCheckSubsteps, 4.0, 1.0);
  EXPECT_EQ(cached.deviation, unit.deviation);
  const CrossCheckResult scaled = CrossCheckCvode(plant, config, kCrossCheckPeriodS, kCrossCheckSubsteps, 4.0, 1.0);
  EXPECT_NEAR(scaled.deviation, unit.deviation, 1e-3 * unit.deviation) << "equal up to rounding";
}

// Tests that CVODE's own failure on the pulse is kept as the check's verdict-less result
// (the run then reports its own failure first) and that the message says the accuracy is
// unknown.
TEST(CvodeCrossCheck, SolverFailureIsNoVerdict) {
  IntegratorConfig config;
  config.max_num_steps = 1;
  const CrossCheckResult r = CrossCheckCvode(OneMode(25.0, 0.02, 1.0), config, kCrossCheckPeriodS, kCrossCheckSubsteps, 1.0, 0.0);
  EXPECT_NE(r.solver_failure.find("CV_TOO_MUCH_WORK"), std::string::npos) << r.solver_failure;
  EXPECT_FALSE(r.Passed(1.0));
  EXPECT_NE(CrossCheckMessage(r, config, 1.0).find("accuracy on this plant is unknown"), std::string::npos);
}

}  // namespace
}  // namespace shapebench::model

#include "model/cvode_cross_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>

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

// A family over one mode's frequency (or damping ratio) as a natural-period sweep has it.
struct FamilyCase {
  const char* name;
  bool frequency;  // else the damping ratio is swept
  double lo, hi;
  double other;  // the damping ratio (frequency swept) or the frequency
  double rtol;
  CvodeLmm lmm;
};

std::optional<FamilyMember> MemberOf(const FamilyCase& c, double value) {
  const double hz = c.frequency ? value : c.other;
  FamilyMember m;
  m.plant = OneMode(hz, c.frequency ? c.other : value, 1.0);
  m.substeps = std::clamp(static_cast<int>(std::ceil(kCrossCheckPeriodS * hz * 200.0)), 1, 64);
  return m;
}

// Tests that one check of a family stands for its members: on the calibration families
// (case 4d's band, undamped, BDF, loose and tight rtol, a band of damping ratios) every
// member's own deviation at 201 values across the band is within kFamilyMarginSeen of the
// family's (the documented margin kFamilyMargin is above it), so a member the family covers
// would pass its own check.
TEST(CvodeCrossCheckFamily, FamilyDeviationBoundsEveryMember) {
  const FamilyCase cases[] = {
      {"case 4d", true, 15.0, 35.0, 0.02, 1e-8, CvodeLmm::kAdams},
      {"undamped", true, 15.0, 35.0, 0.0, 1e-8, CvodeLmm::kAdams},
      {"loose", true, 15.0, 35.0, 0.02, 1e-6, CvodeLmm::kAdams},
      {"bdf", true, 15.0, 35.0, 0.02, 1e-7, CvodeLmm::kBdf},
      {"wide", true, 5.0, 100.0, 0.03, 1e-8, CvodeLmm::kAdams},
      {"damping", false, 0.0, 0.1, 25.0, 1e-7, CvodeLmm::kAdams},
  };
  double worst_ratio = 0.0;
  for (const FamilyCase& c : cases) {
    IntegratorConfig config;
    config.rtol = c.rtol;
    config.lmm = c.lmm;
    auto member = [&c](double v) { return MemberOf(c, v); };
    const CrossCheckFamily family = CrossCheckCvodeFamily(c.lo, c.hi, member, config, kCrossCheckPeriodS, 0.05);
    ASSERT_TRUE(family.usable) << c.name;
    EXPECT_EQ(family.values.size(), static_cast<std::size_t>(kFamilyInterior + 2) + 2 -
                                        (family.worst_value == c.lo || family.worst_value == c.hi ? 1 : 0))
        << c.name;
    double ratio = 0.0;
    for (int i = 0; i <= 200; ++i) {
      const double v = c.lo + (c.hi - c.lo) * i / 200.0;
      const FamilyMember m = *MemberOf(c, v);
      const CrossCheckResult own = CrossCheckCvode(m.plant, config, kCrossCheckPeriodS, m.substeps, 1.0, 0.05);
      ratio = std::max(ratio, own.deviation / family.deviation);
    }
    std::printf("%s: family deviation %.3g at %g, largest member / family %.3f\n", c.name, family.deviation,
                family.worst_value, ratio);
    worst_ratio = std::max(worst_ratio, ratio);
  }
  EXPECT_LE(worst_ratio, kFamilyMarginSeen);
  EXPECT_LT(kFamilyMarginSeen, kFamilyMargin);
}

// Tests that a family with a member that cannot be built (its value invalid for the
// machine: the member throws) gives no verdict instead of failing the point being run.
TEST(CvodeCrossCheckFamily, AMemberThatThrowsLeavesTheFamilyUnusable) {
  IntegratorConfig config;
  const FamilyCase c{"throwing", true, 15.0, 35.0, 0.02, 1e-8, CvodeLmm::kAdams};
  auto member = [&c](double v) -> std::optional<FamilyMember> {
    if (v > 30.0) throw std::runtime_error("no such machine");
    return MemberOf(c, v);
  };
  CrossCheckFamily family;
  EXPECT_NO_THROW(family = CrossCheckCvodeFamily(c.lo, c.hi, member, config, kCrossCheckPeriodS, 0.05));
  EXPECT_FALSE(family.usable);
  EXPECT_FALSE(FamilyCovers(family, OneMode(20.0, 0.02, 1.0), kCrossCheckPeriodS, 1.0));
}

// Tests that a member is covered only where the family's deviation times the margin,
// projected over its own run, passes: an undamped member's projection grows with its
// frequency (its pulse is shorter), so the top of a band can fall out of cover while the
// bottom stays in.
TEST(CvodeCrossCheckFamily, CoverFollowsTheMembersOwnProjection) {
  CrossCheckFamily family;
  family.usable = true;
  family.deviation = 1e-6;
  const LinearPlant slow = OneMode(15.0, 0.0, 1.0);
  const LinearPlant fast = OneMode(35.0, 0.0, 1.0);
  // Pulses of 132 ticks at 15 Hz and 56 at 35 Hz (4 half periods rounded to 1 ms ticks);
  // a run of 1.2 s projects 9.1 and 21.4 pulses: 1e-6 passes both, this one only 15 Hz's.
  const double run_s = 1.2;
  EXPECT_TRUE(FamilyCovers(family, slow, kCrossCheckPeriodS, run_s));
  EXPECT_TRUE(FamilyCovers(family, fast, kCrossCheckPeriodS, run_s));
  family.deviation = kCrossCheckLimit / kFamilyMargin * (0.1 / run_s);
  EXPECT_FALSE(FamilyCovers(family, fast, kCrossCheckPeriodS, run_s));
  EXPECT_TRUE(FamilyCovers(family, slow, kCrossCheckPeriodS, run_s));
  family.usable = false;
  EXPECT_FALSE(FamilyCovers(family, slow, kCrossCheckPeriodS, run_s));
}

}  // namespace
}  // namespace shapebench::model

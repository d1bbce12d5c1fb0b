#include "controller/profile_table.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "common/validation_error.h"
#include "controller/pulse_filter.h"
#include "controller/shaper_registry.h"

namespace shapebench::controller {
namespace {

StepPattern TablePattern(const std::string& method) {
  PatternConfig c;
  c.method = method;
  c.mode = PatternMode::kBoth;
  return MakeStepPattern(c);
}

// Tests para. 61's example: method 1 at 25 Hz on a 1 ms period is alpha_0 = alpha_20 =
// 0.5 and every other coefficient 0.
TEST(ProfileTableTest, MethodOneAtTwentyFiveHertzIsTwoHalves) {
  const std::vector<double> table = ProfileTableFromPattern(TablePattern("1"), 0.001, 25.0);
  ASSERT_EQ(table.size(), 21u);
  for (std::size_t n = 0; n < table.size(); ++n) {
    EXPECT_DOUBLE_EQ(table[n], n == 0 || n == 20 ? 0.5 : 0.0) << "alpha_" << n;
  }
}

// Tests that every patent method's table sums to 1, is at most 64 long at 1 ms, and keeps
// the design frequency's zero of vibration on the grid (method 2's 6.67/13.33 ms fall
// between ticks): residual below 1e-9 of an unshaped step's.
TEST(ProfileTableTest, PatentTablesKeepTheirZero) {
  for (const char* method : {"1", "2", "3", "4"}) {
    const std::vector<double> table = ProfileTableFromPattern(TablePattern(method), 0.001, 25.0);
    EXPECT_NEAR(std::accumulate(table.begin(), table.end(), 0.0), 1.0, 1e-12);
    EXPECT_LE(table.size(), 64u);
    std::vector<Impulse> impulses;
    for (std::size_t n = 0; n < table.size(); ++n) impulses.push_back({n * 0.001, table[n]});
    EXPECT_LT(ResidualVibration(impulses, 25.0), 1e-9) << method;
  }
}

// Tests the moving-average table and its validation messages.
TEST(ProfileTableTest, MovingAverageAndValidation) {
  const std::vector<double> table = MovingAverageTable(0.032, 0.001);
  ASSERT_EQ(table.size(), 32u);
  EXPECT_DOUBLE_EQ(table[0], 1.0 / 32.0);
  EXPECT_NO_THROW(ValidateProfileTable(table, 64));
  EXPECT_THROW(ValidateProfileTable(table, 16), ValidationError);
  EXPECT_THROW(ValidateProfileTable({0.5, 0.4}, 64), ValidationError);
  EXPECT_THROW(ValidateProfileTable({}, 64), ValidationError);
}

// Tests that convolving pulses with any table (and the exponential) conserves the total
// distance to 1e-12 m, including signed pulses (reversals).
TEST(ProfileTableTest, FiltersConserveTheDistance) {
  std::vector<double> pulses;
  for (int k = 0; k < 3000; ++k) pulses.push_back(1e-4 * std::sin(0.01 * k) + 2e-5);
  const double total = std::accumulate(pulses.begin(), pulses.end(), 0.0);
  std::vector<double> uneven = {0.1, 0.0, 0.3, 0.05, 0.25, 0.3};
  for (const std::vector<double>& table :
       {MovingAverageTable(0.05, 0.001), ProfileTableFromPattern(TablePattern("2"), 0.001, 25.0),
        uneven}) {
    for (double tau : {0.0, 1.0 / 30.0}) {
      PulseFilter filter{table, tau};
      const std::vector<double> out = filter.Apply(pulses, 0.001);
      EXPECT_NEAR(std::accumulate(out.begin(), out.end(), 0.0), total, 1e-12);
    }
  }
}

}  // namespace
}  // namespace shapebench::controller

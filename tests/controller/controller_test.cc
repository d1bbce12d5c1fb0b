#include "controller/controller.h"

#include <gtest/gtest.h>

#include "common/key_rule_error.h"
#include "common/validation_error.h"

namespace shapebench::controller {
namespace {

ControllerConfig Method1() {
  ControllerConfig c;
  c.feed_mm_min = 30000;
  c.accel_time_s = 0.3;
  c.pattern.method = "1";
  return c;
}

std::string FieldOf(const ControllerConfig& c, const MoveConfig& m) {
  try {
    GenerateCommand(c, m);
  } catch (const ValidationError& e) {
    return e.field();
  }
  return "";
}

// Tests that a move too short to keep step 1 after para. 50's shortening is refused
// naming move.distance_mm, while one just long enough is planned.
TEST(ControllerTest, TooShortMoveForThePatternIsRefused) {
  // Method 1 at both ends: lowest speed 2 * a * 0.5 * T/2 = a T / 2; phase T (no steady).
  const double a = 0.5 / 0.3;
  const double shortest_mm = (a * 0.04 / 2) * 0.04 * 1e3;
  MoveConfig move;
  move.distance_mm = shortest_mm * 0.9;
  EXPECT_EQ(FieldOf(Method1(), move), "move.distance_mm");
  move.distance_mm = shortest_mm * 1.1;
  EXPECT_EQ(FieldOf(Method1(), move), "");
}

// Tests that an acc/dec time too short for the pattern's step 1 is refused as a rule
// between controller.accel_time_s and the pattern's frequency, whatever the feed (the
// lowest shaped speed a T / 2 = feed T / (2 accel_time_s) scales with it).
TEST(ControllerTest, TooShortAccelTimeForThePatternIsRefused) {
  ControllerConfig c = Method1();
  c.accel_time_s = 0.3;
  c.feed_mm_min = 60;
  // Lowest shaped speed a T / 2 = feed * 0.04 / (2 * 0.3): below the feed, so it passes.
  EXPECT_EQ(FieldOf(c, MoveConfig{}), "");
  for (const double feed_mm_min : {60.0, 6e6}) {
    c.feed_mm_min = feed_mm_min;
    c.accel_time_s = 0.01;  // a T / 2 = feed * 0.04 / 0.02 = 2 x feed: refused
    try {
      GenerateCommand(c, MoveConfig{});
      ADD_FAILURE() << "not refused at feed " << feed_mm_min;
    } catch (const KeyRuleError& e) {
      EXPECT_EQ(e.field(), "controller.accel_time_s");
      ASSERT_EQ(e.keys().size(), 2u);
      EXPECT_EQ(e.keys()[1].field, "controller.pattern.frequency_hz");
      EXPECT_EQ(e.message().rfind("0.01 s is too short for controller.pattern.frequency_hz = 25 Hz: ", 0), 0u)
          << e.message();
    }
  }
}

// Tests that validate() names the offending field with its sub-struct path.
TEST(ControllerTest, ValidateNamesNestedFields) {
  ControllerConfig c;
  c.period_s = 0.0;
  EXPECT_THROW(c.validate(), ValidationError);
  c = ControllerConfig{};
  c.pattern.method = "3";
  c.pattern.k1 = 2.0;
  try {
    c.validate();
    FAIL();
  } catch (const ValidationError& e) {
    EXPECT_EQ(e.field(), "pattern.k1");
  }
  c = ControllerConfig{};
  c.pattern.method = "1";
  c.accel_time_s = 0.0;
  try {
    c.validate();
    FAIL();
  } catch (const ValidationError& e) {
    EXPECT_EQ(e.field(), "accel_time_s");
  }
}

// Tests that a pattern tuned above the period's Nyquist frequency is refused naming the
// pattern's frequency, the period and the Nyquist frequency (5000 Hz at 1 ms was accepted:
// issue 32 item 15), per design frequency; at the Nyquist frequency it is accepted.
TEST(ControllerTest, PatternAboveTheNyquistFrequencyIsRefused) {
  ControllerConfig c = Method1();
  c.period_s = 0.001;
  c.pattern.frequency_hz = 5000.0;
  try {
    c.validate();
    FAIL() << "accepted";
  } catch (const ValidationError& e) {
    EXPECT_EQ(e.field(), "pattern.frequency_hz");
    EXPECT_NE(std::string(e.what()).find("5000 Hz is above the Nyquist frequency of period_s 0.001 s (500 Hz)"),
              std::string::npos)
        << e.what();
  }
  c.pattern.frequency_hz = 500.0;
  EXPECT_NO_THROW(c.validate());
  c.pattern.method = "zv";
  c.pattern.frequencies_hz = {25.0, 600.0};
  try {
    c.validate();
    FAIL() << "accepted";
  } catch (const ValidationError& e) {
    EXPECT_EQ(e.field(), "pattern.frequencies_hz[1]");
  }
  c.pattern.method = "none";
  c.pattern.frequencies_hz.clear();
  c.pattern.frequency_hz = 5000.0;
  EXPECT_NO_THROW(c.validate());  // no pattern, no frequency to realize
}

// Tests that a negative distance moves the other way, the same profile mirrored.
TEST(ControllerTest, NegativeDistanceMirrorsTheMove) {
  MoveConfig forward, backward;
  forward.distance_mm = 50;
  backward.distance_mm = -50;
  const CommandTrajectory f = GenerateCommand(Method1(), forward);
  const CommandTrajectory b = GenerateCommand(Method1(), backward);
  ASSERT_EQ(f.velocity_m_s.size(), b.velocity_m_s.size());
  for (std::size_t k = 0; k < f.velocity_m_s.size(); ++k) EXPECT_EQ(f.velocity_m_s[k], -b.velocity_m_s[k]);
  EXPECT_NEAR(b.Positions().back(), -0.05, 1e-15);
}

}  // namespace
}  // namespace shapebench::controller

// A damping ratio per design mode (controller/pattern_config.h: damping_ratios): each
// mode's shaper is designed for its own damping, the lengths are checked, and the grid
// design carries the ratios.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/validation_error.h"
#include "controller/impulse.h"
#include "controller/pattern_config.h"
#include "controller/shaper_registry.h"

namespace shapebench::controller {
namespace {

PatternConfig TwoModeZvd() {
  PatternConfig config;
  config.method = "zvd";
  config.frequencies_hz = {18.0, 55.0};
  config.damping_ratios = {0.02, 0.04};
  return config;
}

// Tests that the convolved shaper leaves no vibration in either mode at its own damping,
// while one ratio for both (the mean) leaves some in each.
TEST(PerModeDamping, EachModeIsDesignedForItsOwnDamping) {
  const PatternConfig config = TwoModeZvd();
  ASSERT_NO_THROW(config.validate());
  const std::vector<Impulse> impulses = ShaperImpulses(config);
  EXPECT_LT(ResidualVibration(impulses, 18.0, 0.02), 1e-12);
  EXPECT_LT(ResidualVibration(impulses, 55.0, 0.04), 1e-12);
  PatternConfig shared = config;
  shared.damping_ratios.clear();
  shared.design_damping_ratio = 0.03;
  const std::vector<Impulse> mean = ShaperImpulses(shared);
  EXPECT_GT(ResidualVibration(mean, 18.0, 0.02), 1e-6);
  EXPECT_GT(ResidualVibration(mean, 55.0, 0.04), 1e-6);
}

// Tests that ForMode gives mode i's frequency and damping alone, and that the grid design
// carries one ratio per frequency.
TEST(PerModeDamping, ForModeAndGridDesign) {
  const PatternConfig config = TwoModeZvd();
  const PatternConfig second = config.ForMode(1);
  EXPECT_EQ(second.frequency_hz, 55.0);
  EXPECT_EQ(second.design_damping_ratio, 0.04);
  EXPECT_TRUE(second.frequencies_hz.empty());
  EXPECT_TRUE(second.damping_ratios.empty());
  const GridDesign design = ShaperGridDesign(config);
  EXPECT_EQ(design.DampingAt(0), 0.02);
  EXPECT_EQ(design.DampingAt(1), 0.04);
  EXPECT_EQ(config.DesignDampingRatios(), (std::vector<double>{0.02, 0.04}));
}

// Tests that a list of another length than frequencies_hz, a ratio out of [0, 1), a
// damped ratio for a patent method, and both ratio keys at once are refused, naming the field.
TEST(PerModeDamping, BadListsAreRefused) {
  auto field_of = [](const PatternConfig& config) {
    try {
      config.validate();
    } catch (const ValidationError& error) {
      return error.field();
    }
    return std::string("(none)");
  };
  PatternConfig config = TwoModeZvd();
  config.damping_ratios = {0.02};
  EXPECT_EQ(field_of(config), "damping_ratios");
  config = TwoModeZvd();
  config.damping_ratios = {0.02, 1.0};
  EXPECT_EQ(field_of(config), "damping_ratios[1]");
  config = TwoModeZvd();
  config.method = "1";
  EXPECT_EQ(field_of(config), "damping_ratios[0]");
  config = TwoModeZvd();
  config.design_damping_ratio = 0.01;
  EXPECT_EQ(field_of(config), "damping_ratios");
  config = TwoModeZvd();
  config.method = "1";
  config.damping_ratios = {0.0, 0.0};
  EXPECT_EQ(field_of(config), "(none)");
}

}  // namespace
}  // namespace shapebench::controller

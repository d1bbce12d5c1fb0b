// CN104175175's short-block clamp: each embodiment's feed formula, and what the clamp does
// to the interpolation points of a zigzag of blocks shorter than one period's travel.
#include "controller/short_block_clamp.h"

#include <gtest/gtest.h>

#include <cmath>

#include "common/validation_error.h"
#include "controller/block_planner.h"
#include "controller/interpolator.h"
#include "controller/path_geometry.h"

namespace shapebench::controller {
namespace {

constexpr double kDt = 0.001;
constexpr double kFeed = 0.1;        // 6000 mm/min: 0.1 mm per period
constexpr double kBlock = 0.05e-3;   // 0.05 mm blocks

ShortBlockConfig Mode(ShortBlockMode mode) {
  ShortBlockConfig c;
  c.mode = mode;
  return c;
}

// Tests each embodiment's feed for a 0.05 mm line at 6000 mm/min, 1 ms (0.1 mm/period):
// ratio 0.5 -> 0.025 mm per period = 1500 mm/min; length -> 0.05 mm per period = 3000;
// scale 0.5 -> 3000; preset 600 -> 600; an arc with ratio_arc 0.2 -> 600 mm/min.
TEST(ShortBlockClampTest, EmbodimentFormulas) {
  auto feed = [](const ShortBlockConfig& c, bool arc = false) {
    return ClampShortBlock(c, arc, kBlock, kFeed, kDt).feed_m_s * 60000.0;
  };
  EXPECT_NEAR(feed(Mode(ShortBlockMode::kRatio)), 1500.0, 1e-9);
  EXPECT_NEAR(feed(Mode(ShortBlockMode::kRatio), true), 600.0, 1e-9);
  EXPECT_NEAR(feed(Mode(ShortBlockMode::kLength)), 3000.0, 1e-9);
  EXPECT_NEAR(feed(Mode(ShortBlockMode::kScale)), 3000.0, 1e-9);
  EXPECT_NEAR(feed(Mode(ShortBlockMode::kPreset)), 600.0, 1e-9);
  EXPECT_NEAR(feed(Mode(ShortBlockMode::kOff)), 6000.0, 1e-9);
  // A block long enough is left alone: 0.5 x 0.3 mm = 0.15 mm > 0.1 mm per period.
  EXPECT_FALSE(ClampShortBlock(Mode(ShortBlockMode::kRatio), false, 0.3e-3, kFeed, kDt).clamped);
  EXPECT_FALSE(ClampShortBlock(Mode(ShortBlockMode::kLength), false, 0.1e-3, kFeed, kDt).clamped);
}

// Tests embodiment 2: an input ratio above the minimum set for its shape is used as the
// minimum and reported as a warning naming the key.
TEST(ShortBlockClampTest, RatioAboveTheMinimumWarns) {
  ShortBlockConfig c = Mode(ShortBlockMode::kRatio);
  c.ratio_line = 0.6;
  c.min_ratio_line = 0.4;
  c.ratio_arc = 0.1;
  c.min_ratio_arc = 0.2;
  EXPECT_EQ(ShortBlockRatio(c, false), 0.4);
  EXPECT_EQ(ShortBlockRatio(c, true), 0.1);
  EXPECT_NEAR(ClampShortBlock(c, false, kBlock, kFeed, kDt).feed_m_s * 60000.0, 0.4 * 0.05 * 60000.0, 1e-9);
  const std::vector<std::string> warnings = ShortBlockWarnings(c);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("controller.short_block.ratio_line: 0.6 is above the minimum 0.4"), std::string::npos)
      << warnings[0];
}

// Tests the validation messages name the field.
TEST(ShortBlockClampTest, BadValuesNameTheField) {
  for (auto [field, set] : std::vector<std::pair<std::string, std::function<void(ShortBlockConfig&)>>>{
           {"ratio_line", [](ShortBlockConfig& c) { c.ratio_line = -0.1; }},
           {"ratio_arc", [](ShortBlockConfig& c) { c.ratio_arc = 1.5; }},
           {"scale", [](ShortBlockConfig& c) { c.scale = 0.0; }},
           {"preset_feed_mm_min", [](ShortBlockConfig& c) { c.preset_feed_mm_min = -5; }}}) {
    ShortBlockConfig c = Mode(ShortBlockMode::kRatio);
    set(c);
    try {
      c.validate();
      ADD_FAILURE() << field;
    } catch (const ValidationError& e) {
      EXPECT_EQ(e.field(), field);
    }
  }
}

// A zigzag of 0.05 mm blocks at +/-45 degrees (amplitude 0.0354 mm), no corner stops.
Program Zigzag(int blocks) {
  Program p;
  const double step = kBlock / std::sqrt(2.0);
  Eigen::Vector3d at = Eigen::Vector3d::Zero();
  for (int i = 0; i < blocks; ++i) {
    ProgramBlock b;
    b.start_m = at;
    at += Eigen::Vector3d(step, i % 2 == 0 ? step : -step, 0);
    b.end_m = at;
    b.feed_m_s = kFeed;
    p.blocks.push_back(b);
  }
  return p;
}

// The largest distance of a programmed vertex from the straight line joining the two
// interpolation points around it (what the machined shape misses).
double LargestDeviation(const ShortBlockConfig& clamp, int* clamped_blocks, double* feed_mm_min) {
  const Program program = Zigzag(400);
  const PathGeometry path(program);
  PlannerSettings s;
  s.period_s = kDt;
  s.accel_m_s2 = 2.0;
  s.default_feed_m_s = kFeed;
  s.corner_velocity_change_m_s = 1e9;  // no corner rule: the blocks overlap in a period
  s.short_block = clamp;
  const SpeedPlan plan = PlanPathSpeed(program, path, s);
  *clamped_blocks = plan.short_block_clamps;
  *feed_mm_min = plan.block_feed_m_s[0] * 60000.0;
  const InterpolatedPulses points = Interpolate(path, plan, kDt);
  double worst = 0.0;
  for (std::size_t k = 1; k < points.path_position_m.size(); ++k) {
    const Eigen::Vector3d a = path.PointAt(points.path_position_m[k - 1]);
    const Eigen::Vector3d b = path.PointAt(points.path_position_m[k]);
    for (const PathElement& e : path.elements()) {
      if (e.end_s_m() <= points.path_position_m[k - 1] || e.end_s_m() >= points.path_position_m[k]) continue;
      const Eigen::Vector3d v = e.end_m;  // a vertex passed within this period
      const Eigen::Vector3d d = b - a;
      const double t = std::clamp((v - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
      worst = std::max(worst, (v - (a + t * d)).norm());
    }
  }
  return worst;
}

// Tests the zigzag: without the clamp the points 0.1 mm apart skip whole blocks
// and miss the vertices by the zigzag's amplitude (0.0354 mm, of the order of a block);
// with the ratio clamp every block is clamped to 1500 mm/min and each vertex stays within
// the chord of ratio x block length across it: at most 0.5 x 0.025 mm (the vertex lies
// within half that chord of both its ends).
TEST(ShortBlockClampTest, ClampKeepsTheZigzag) {
  int clamped = 0;
  double feed = 0.0;
  const double unclamped = LargestDeviation(Mode(ShortBlockMode::kOff), &clamped, &feed);
  EXPECT_EQ(clamped, 0);
  EXPECT_NEAR(unclamped, kBlock / std::sqrt(2.0), 1e-9);  // whole blocks skipped
  const double with_clamp = LargestDeviation(Mode(ShortBlockMode::kRatio), &clamped, &feed);
  EXPECT_EQ(clamped, 400);
  EXPECT_NEAR(feed, 1500.0, 1e-9);
  EXPECT_LE(with_clamp, 0.5 * 0.5 * kBlock);
  // The planner applies each embodiment's formula to every block.
  for (const auto& [mode, expected] : std::vector<std::pair<ShortBlockMode, double>>{
           {ShortBlockMode::kLength, 3000.0}, {ShortBlockMode::kScale, 3000.0}, {ShortBlockMode::kPreset, 600.0}}) {
    LargestDeviation(Mode(mode), &clamped, &feed);
    EXPECT_EQ(clamped, 400);
    EXPECT_NEAR(feed, expected, 1e-9);
  }
  std::printf("zigzag vertex deviation: without clamp %.4g mm, with ratio 0.5 clamp %.4g mm\n",
              unclamped * 1e3, with_clamp * 1e3);
}

}  // namespace
}  // namespace shapebench::controller

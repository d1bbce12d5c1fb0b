#include "controller/tangential_distribution.h"

#include <gtest/gtest.h>

#include <cmath>

namespace shapebench::controller {
namespace {

constexpr double kTol = 1e-12;

void ExpectNear(const Eigen::Vector3d& actual, const Eigen::Vector3d& expected) {
  EXPECT_NEAR(actual.x(), expected.x(), kTol) << actual.transpose();
  EXPECT_NEAR(actual.y(), expected.y(), kTol) << actual.transpose();
  EXPECT_NEAR(actual.z(), expected.z(), kTol) << actual.transpose();
}

// Tests the seed's Fig. 2 walk-through by hand: three interpolated segments of an arc
// (chords (3,4), (0,5), (-4,3), each dS = 5) and acc/dec that outputs k = 20% of the
// delay ERR each cycle. Cycle 1: ERR 5, SO 1 < dS1: second output means, W = SO*K/KS =
// (0.6, 0.8). Cycle 2: ERR 4+5 = 9, SO 1.8 < 4 left: W = 1.8*(3,4)/5 = (1.08, 1.44).
// Cycle 3: ERR 7.2+5 = 12.2, SO 2.44 > 2.2 left of segment 1: first output means gives
// its rest (1.32, 1.76), then the next segment specified, 0.24 of it split: (0, 0.24).
TEST(TangentialQueueTest, FigureTwoWalkThrough) {
  TangentialQueue queue;
  const double k = 0.2;
  double err = 0.0;
  const MinuteDisplacement segments[3] = {
      {{3, 4, 0}, 5}, {{0, 5, 0}, 5}, {{-4, 3, 0}, 5}};
  const Eigen::Vector3d expected[3] = {{0.6, 0.8, 0}, {1.08, 1.44, 0}, {1.32, 2.0, 0}};
  const double expected_so[3] = {1.0, 1.8, 2.44};
  for (int cycle = 0; cycle < 3; ++cycle) {
    queue.Push(segments[cycle]);
    err += segments[cycle].tangential_m;
    const double so = k * err;
    EXPECT_NEAR(so, expected_so[cycle], kTol);
    err -= so;
    ExpectNear(queue.Release(so), expected[cycle]);
  }
  // Segment 1 is gone; 4.76 of segment 2 and all of segment 3 wait, in order.
  EXPECT_EQ(queue.size(), 2u);
  EXPECT_NEAR(queue.queued_tangential_m(), 4.76 + 5.0, kTol);
  // The next release takes segment 2 first: 4.76 of it, then 0.24 of segment 3.
  ExpectNear(queue.Release(5.0), Eigen::Vector3d(0, 4.76, 0) + 0.24 / 5.0 * Eigen::Vector3d(-4, 3, 0));
  // Nothing lost or duplicated: all outputs add up to the three segments.
  ExpectNear(queue.Flush(), (1.0 - 0.24 / 5.0) * Eigen::Vector3d(-4, 3, 0));
  EXPECT_EQ(queue.size(), 0u);
}

// Tests decision 1 and 2 of the switching means: SO = 0 outputs nothing, and an
// exhausted (dS = 0) segment hands over to the next one.
TEST(TangentialQueueTest, ZeroOutputAndEmptySegments) {
  TangentialQueue queue;
  queue.Push({{0, 0, 0}, 0.0});
  queue.Push({{0, 0, 2}, 2.0});
  ExpectNear(queue.Release(0.0), Eigen::Vector3d::Zero());
  EXPECT_EQ(queue.size(), 2u);
  ExpectNear(queue.Release(1.0), Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(queue.size(), 1u);
  // More than queued releases what there is.
  ExpectNear(queue.Release(10.0), Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(queue.size(), 0u);
}

// Tests that with a real acc/dec filter every output point lies on the interpolated
// polyline (the path is kept), the output comes in order, and it adds up exactly.
TEST(TangentialQueueTest, OutputStaysOnThePolylineAndAddsUp) {
  // A polyline with corners and uneven segments.
  std::vector<Eigen::Vector3d> pulses;
  std::vector<double> ds;
  for (int k = 0; k < 200; ++k) {
    const double angle = 0.07 * k;
    const double length = 1e-4 * (1.0 + 0.5 * std::sin(0.3 * k));
    pulses.emplace_back(length * std::cos(angle), length * std::sin(angle), 0.1 * length);
    ds.push_back(pulses.back().norm());
  }
  PulseFilter filter;
  filter.time_constant_s = 0.02;
  filter.table = {0.25, 0.25, 0.25, 0.25};
  const std::vector<Eigen::Vector3d> out = DistributeTangentially(pulses, ds, filter, 0.001);
  ASSERT_GT(out.size(), pulses.size());
  // Vertices of the input polyline.
  std::vector<Eigen::Vector3d> vertices{Eigen::Vector3d::Zero()};
  for (const auto& p : pulses) vertices.push_back(vertices.back() + p);
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  std::size_t segment = 0;  // the output may only move forward along the polyline
  for (const auto& o : out) {
    position += o;
    double best = 1e9;
    std::size_t best_segment = segment;
    for (std::size_t s = segment; s + 1 < vertices.size(); ++s) {
      const Eigen::Vector3d d = vertices[s + 1] - vertices[s];
      const double t = std::clamp((position - vertices[s]).dot(d) / d.squaredNorm(), 0.0, 1.0);
      const double dist = (position - (vertices[s] + t * d)).norm();
      if (dist < best) {
        best = dist;
        best_segment = s;
      }
      if (dist < 1e-15) break;
    }
    EXPECT_LT(best, 1e-15) << "output left the polyline";
    EXPECT_GE(best_segment, segment);
    segment = best_segment;
  }
  ExpectNear(position, vertices.back());
}

}  // namespace
}  // namespace shapebench::controller

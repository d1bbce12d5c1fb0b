// The run's max_contour_error_m against a brute-force search of the recorded trace: every
// sample's actual tool position measured against the whole path (PathGeometry::DistanceTo),
// the largest kept. bench/run/run_scenario.cc skips the search where the distance to the last
// nearest point found already bounds a sample below the largest so far; the largest must
// come out the same, bit for bit.
#include <algorithm>
#include <cstring>
#include <string>

#include <gtest/gtest.h>

#include "bench/scenario/scenario_loader.h"
#include "bench/run/run_scenario.h"
#include "controller/path_geometry.h"

namespace shapebench::bench {
namespace {

double BruteForceLargest(const RunResult& run) {
  const controller::PathGeometry path(run.program);
  double largest = 0.0;
  for (const Eigen::Vector3d& actual : run.trace.actual_m) largest = std::max(largest, path.DistanceTo(actual));
  return largest;
}

// Tests that on the shipped circles (a linear machine and one with LuGre guides: arcs, where
// the skip applies) and a pocket of lines and arcs the largest contour error equals the
// brute-force search over every recorded sample, bit for bit.
TEST(ContourGauge, LargestErrorEqualsTheSearchOverEverySample) {
  const std::string dir = std::string(SHAPEBENCH_SOURCE_DIR) + "/configs/scenarios/";
  for (const std::string name : {"circle_test", "friction_circle", "pocket_corner", "measured_frf"}) {
    const RunResult run = RunScenario(LoadScenario(dir + name + ".yaml", {}));
    ASSERT_FALSE(run.trace.actual_m.empty()) << name;
    const double expected = BruteForceLargest(run);
    EXPECT_GT(expected, 0.0) << name;
    const double got = run.metrics.max_contour_error_m;
    EXPECT_EQ(std::memcmp(&got, &expected, sizeof(double)), 0) << name << ": " << got << " vs " << expected;
  }
}

}  // namespace
}  // namespace shapebench::bench

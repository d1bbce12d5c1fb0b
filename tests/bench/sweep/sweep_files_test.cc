// The readers of a sweep's output directory (bench/sweep/sweep_files.h) on hostile files:
// manifest.json numbers that are not whole numbers, layouts the plotter cannot draw from
// the rows, grid entries of the wrong type, rows with a status GARBAGE or bytes that are
// not UTF-8. Each is refused with a std::runtime_error naming the file, or kept as it is.
// The fuzz targets fuzz_manifest and fuzz_rows search for more (fuzz/README.md).
#include <filesystem>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/bench_test_support.h"
#include "common/csv.h"
#include "bench/sweep/sweep.h"
#include "bench/sweep/sweep_files.h"

namespace shapebench::bench {
namespace {

using testing::ReadText;
using testing::ScratchDir;

const Sweep& MapSweep() {
  static const Sweep sweep =
      LoadSweep(std::string(SHAPEBENCH_SOURCE_DIR) + "/tests/bench/data/sweeps/map.yaml", {});
  return sweep;
}

// The test data's map.yaml manifest (22 points: 2 accel times x 11 frequencies), edited.
template <typename Edit>
std::string ManifestFile(const ScratchDir& dir, Edit&& edit) {
  nlohmann::ordered_json manifest = ManifestJson(MapSweep(), {}, 0, 1);
  edit(manifest);
  return dir.Write("manifest.json", manifest.dump(2) + "\n");
}

// What ReadManifest says about the file ("" when it accepts it); its message must start
// with the file's path.
std::string Refusal(const std::string& path) {
  try {
    ReadManifest(path);
    return "";
  } catch (const std::runtime_error& error) {
    const std::string what = error.what();
    EXPECT_EQ(what.rfind(path + ": ", 0), 0u) << what;
    return what;
  }
}

// Tests that a count, index or number of points written as 1e30, 1e9, -1 or 0.5 is
// refused naming the field (1e30 used to be converted to an integer: undefined), while
// 1000000000 shards is a manifest (merge then reports the missing shards).
TEST(SweepFiles, ManifestCountsAreWholeNumbers) {
  ScratchDir dir;
  EXPECT_EQ(Refusal(ManifestFile(dir, [](auto&) {})), "");
  EXPECT_NE(Refusal(ManifestFile(dir, [](auto& m) { m["points"] = 1e30; })).find("points: expected a whole number"),
            std::string::npos);
  EXPECT_NE(Refusal(ManifestFile(dir, [](auto& m) { m["shard"]["count"] = 1e9; })).find("shard.count"),
            std::string::npos);
  EXPECT_NE(Refusal(ManifestFile(dir, [](auto& m) { m["shard"]["count"] = -1; })).find("shard.count"),
            std::string::npos);
  EXPECT_NE(Refusal(ManifestFile(dir, [](auto& m) { m["shard"]["index"] = 0.5; })).find("shard.index"),
            std::string::npos);
  EXPECT_EQ(Refusal(ManifestFile(dir, [](auto& m) { m["shard"]["count"] = 1000000000; })), "");
  EXPECT_NE(Refusal(ManifestFile(dir, [](auto& m) { m["sweep"] = 7; })).find("sweep: expected a string"),
            std::string::npos);
}

// Tests that a plot layout the plotter could not draw from the merged rows is refused: an
// axis of 10^12 values in a 22-point sweep (the plotter would allocate for each), a size
// of 1e30, a heat map whose two keys share an axis, a plot of a metric not kept.
TEST(SweepFiles, ManifestLayoutFitsTheColumnsAndPoints) {
  ScratchDir dir;
  EXPECT_NE(Refusal(ManifestFile(dir, [](auto& m) { m["layout"]["axis_sizes"] = {2, 1000000000000}; }))
                .find("layout: its axes have more points than the manifest"),
            std::string::npos);
  EXPECT_NE(Refusal(ManifestFile(dir, [](auto& m) { m["layout"]["axis_sizes"] = {2, 1e30}; }))
                .find("malformed sweep layout"),
            std::string::npos);
  EXPECT_NE(Refusal(ManifestFile(dir, [](auto& m) {
              m["layout"]["plots"][1]["heatmap"] = {"controller.accel_time_s", "controller.accel_time_s"};
            })).find("two keys move together"),
            std::string::npos);
  EXPECT_NE(Refusal(ManifestFile(dir, [](auto& m) { m["layout"]["plots"][0]["metric"] = "peak_ratio"; }))
                .find("'peak_ratio', not a kept metric"),
            std::string::npos);
  EXPECT_NE(Refusal(ManifestFile(dir, [](auto& m) { m["layout"]["axis_sizes"] = {11, 2}; }))
                .find("layout: its axes are not the grid's"),
            std::string::npos);
}

// Tests that grid entries of the wrong type or shape are refused naming the key: list
// values that are numbers, a range without spacing, a log range from below zero.
TEST(SweepFiles, ManifestGridEntriesAreChecked) {
  ScratchDir dir;
  EXPECT_NE(Refusal(ManifestFile(dir, [](auto& m) { m["grid"][0][0]["list"] = {0.2, 0.3}; }))
                .find("grid: key controller.accel_time_s: expected the list's values as strings"),
            std::string::npos);
  EXPECT_NE(Refusal(ManifestFile(dir, [](auto& m) { m["grid"][1][0].erase("spacing"); })).find("spacing"),
            std::string::npos);
  EXPECT_NE(Refusal(ManifestFile(dir, [](auto& m) {
              m["grid"][1][0]["spacing"] = "log";
              m["grid"][1][0]["from"] = -5;
            })).find("log spacing needs from > 0"),
            std::string::npos);
}

// Tests that the grid merge reads back from a manifest gives every point's key values as
// the sweep itself gives them (merge checks shard rows against one, resume against the
// other).
TEST(SweepFiles, ManifestGridGivesTheSweepsKeyValues) {
  ScratchDir dir;
  const nlohmann::json manifest = ReadManifest(ManifestFile(dir, [](auto&) {}));
  bool present = false;
  const GridTexts read = GridTexts::FromManifest(manifest, &present);
  const GridTexts own = GridTexts::Of(MapSweep());
  ASSERT_TRUE(present);
  for (std::uint64_t point = 0; point < MapSweep().points; ++point) {
    EXPECT_EQ(read.Texts(point), own.Texts(point)) << "point " << point;
  }
}

// Rows of the map sweep: point, the two keys, the two metrics empty, status, error.
std::string Rows(const std::string& status, const std::string& error) {
  const GridTexts grid = GridTexts::Of(MapSweep());
  std::string rows = CsvRecord(ResultColumns(MapSweep()));
  for (std::uint64_t point = 0; point < MapSweep().points; ++point) {
    const auto keys = grid.Texts(point);
    rows += CsvRecord({std::to_string(point), keys[0], keys[1], "", "", status, error});
  }
  return rows;
}

// Tests that rows with status GARBAGE are refused by merge (naming the file and row) and
// by a sweep finding them in results.csv, and not kept from results.csv.partial; and that
// error texts that are not UTF-8 are kept byte for byte by both.
TEST(SweepFiles, ResumeAndMergeAgreeOnHostileRows) {
  ScratchDir dir;
  const nlohmann::json manifest = ReadManifest(ManifestFile(dir, [](auto&) {}));
  const auto columns = ResultColumns(MapSweep());
  const ShardPoints whole{MapSweep().points, 0, 1};
  const GridTexts grid = GridTexts::Of(MapSweep());

  const std::string garbage = dir.Write("garbage/results.csv", Rows("GARBAGE", ""));
  try {
    WriteMergedRows(dir.File("merged.csv"), {garbage}, manifest);
    ADD_FAILURE() << "merged rows with status GARBAGE";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find(garbage + ": row 1 (point 0): status 'GARBAGE'"), std::string::npos)
        << error.what();
  }
  EXPECT_THROW(KeepResumableRows(dir.File("garbage"), columns, whole, grid), std::runtime_error);
  std::filesystem::rename(garbage, dir.File("garbage/results.csv.partial"));
  EXPECT_EQ(KeepResumableRows(dir.File("garbage"), columns, whole, grid).rows, 0u);
  EXPECT_EQ(ReadText(dir.File("garbage/results.csv.partial")), CsvRecord(columns));

  const std::string bytes = Rows("error", "\xff\xfe\xc0\x80, \xed\xa0\x80");
  const std::string hostile = dir.Write("hostile/results.csv", bytes);
  WriteMergedRows(dir.File("merged.csv"), {hostile}, manifest);
  EXPECT_EQ(ReadText(dir.File("merged.csv")), bytes);
  const ResumedRows resumed = KeepResumableRows(dir.File("hostile"), columns, whole, grid);
  EXPECT_TRUE(resumed.finished);
  EXPECT_EQ(resumed.errors, MapSweep().points);
}

}  // namespace
}  // namespace shapebench::bench

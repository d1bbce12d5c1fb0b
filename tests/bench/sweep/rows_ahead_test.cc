// results.csv.ahead read back on resume (bench/sweep/rows_ahead.h): which rows a resumed
// sweep takes instead of running their points, and what it leaves in the file.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/sweep/rows_ahead.h"
#include "bench/sweep/sweep.h"
#include "common/csv.h"
#include "tests/support/bench_test_support.h"

namespace shapebench::bench {
namespace {

using testing::ReadText;
using testing::ScratchDir;

const Sweep& AheadMapSweep() {  // 22 points: 2 accel times x 11 frequencies
  static const Sweep sweep = LoadSweep(std::string(SHAPEBENCH_SOURCE_DIR) + "/tests/bench/data/sweeps/map.yaml", {});
  return sweep;
}

// Point p's row as a sweep writes it (its grid values, made-up metrics, status ok).
std::string AheadMapRow(std::uint64_t point) {
  std::vector<std::string> fields = {std::to_string(point)};
  for (const std::string& text : GridTexts::Of(AheadMapSweep()).Texts(point)) fields.push_back(text);
  fields.push_back(std::to_string(point) + ".5");
  fields.push_back("0.25");
  fields.push_back("ok");
  fields.push_back("");
  return CsvRecord(fields);
}

// Tests that the rows a resume keeps are those of the shard's points at or after the
// partial file's end, the first of a point seen twice, up to a foreign row (a key value not
// the grid's), which ends the file; that the file is then written again holding just them,
// in point order; and that a wrong header or no row to keep removes it.
TEST(RowsAhead, ResumeKeepsTheShardsRowsAfterThePartialFile) {
  ScratchDir dir;
  const Sweep& sweep = AheadMapSweep();
  const std::vector<std::string> columns = ResultColumns(sweep);
  const GridTexts grid = GridTexts::Of(sweep);
  const std::string header = CsvRecord(columns);
  std::string foreign = AheadMapRow(13);
  foreign.replace(foreign.find(",0.3,"), 5, ",0.7,");  // not the grid's accel time
  const std::string path = dir.Write("results.csv.ahead", header + AheadMapRow(3) + AheadMapRow(9) + AheadMapRow(7) +
                                                              AheadMapRow(9) + foreign + AheadMapRow(15));
  const RowsAhead ahead = RowsAhead::Resume(dir.path().string(), columns, ShardPoints{22, 0, 1}, grid, 5,
                                            Durability::kUnsynced);
  EXPECT_EQ(ahead.size(), 2u);
  ASSERT_NE(ahead.Find(9), nullptr);
  EXPECT_EQ(ahead.Find(9)->text, AheadMapRow(9));
  EXPECT_TRUE(ahead.Find(9)->ok);
  EXPECT_NE(ahead.Find(7), nullptr);
  EXPECT_EQ(ahead.Find(3), nullptr);   // before the partial file's end: already there
  EXPECT_EQ(ahead.Find(13), nullptr);  // foreign
  EXPECT_EQ(ahead.Find(15), nullptr);  // after the foreign row
  EXPECT_EQ(ReadText(path), header + AheadMapRow(7) + AheadMapRow(9));

  // Shard 1/2: point 9 is its 4th (k = 4); point 8 is not one of its points.
  dir.Write("results.csv.ahead", header + AheadMapRow(9) + AheadMapRow(8) + AheadMapRow(11));
  const RowsAhead shard = RowsAhead::Resume(dir.path().string(), columns, ShardPoints{22, 1, 2}, grid, 0,
                                            Durability::kUnsynced);
  EXPECT_EQ(shard.size(), 1u);
  ASSERT_NE(shard.Find(4), nullptr);
  EXPECT_EQ(shard.Find(4)->text, AheadMapRow(9));

  dir.Write("results.csv.ahead", "point,other\n" + AheadMapRow(9));
  EXPECT_EQ(RowsAhead::Resume(dir.path().string(), columns, ShardPoints{22, 0, 1}, grid, 0, Durability::kUnsynced).size(),
            0u);
  EXPECT_FALSE(std::filesystem::exists(path));
  dir.Write("results.csv.ahead", header + AheadMapRow(2));
  EXPECT_EQ(RowsAhead::Resume(dir.path().string(), columns, ShardPoints{22, 0, 1}, grid, 5, Durability::kUnsynced).size(),
            0u);
  EXPECT_FALSE(std::filesystem::exists(path));
}

}  // namespace
}  // namespace shapebench::bench

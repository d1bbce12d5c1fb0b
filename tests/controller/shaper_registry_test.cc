// The shaper registry (controller/shaper_registry.h): every entry well formed and its
// design a unit-gain impulse sequence, the built-ins in their listed order, unknown keys
// refused naming `method` (never an unshaped command), malformed registrations refused,
// and docs/shapers.md listing exactly the built-ins.
#include "controller/shaper_registry.h"

#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/validation_error.h"

namespace shapebench::controller {
namespace {

constexpr double kRegistryF = 25.0;

// A valid config for `entry` at 25 Hz (custom: a two-impulse sequence).
PatternConfig ConfigOf(const ShaperEntry& entry) {
  PatternConfig config;
  config.method = entry.key;
  config.frequency_hz = kRegistryF;
  if (entry.kind == ShaperKind::kCustom) config.impulses = {{0.0, 0.25}, {0.01, 0.75}};
  return config;
}

double SumOfAmplitudes(const std::vector<Impulse>& impulses) {
  double sum = 0.0;
  for (const Impulse& i : impulses) sum += i.amplitude;
  return sum;
}

// Tests that every entry has a unique key, a name and a one-line description, and that
// its design's amplitudes sum to 1 (unit gain: the move reaches its speed) with times
// ascending from 0, for one design frequency and for two convolved.
TEST(ShaperRegistry, EveryEntryIsWellFormed) {
  std::set<std::string> keys;
  for (const ShaperEntry* entry : Shapers()) {
    EXPECT_TRUE(keys.insert(entry->key).second) << "duplicate key " << entry->key;
    EXPECT_FALSE(entry->name.empty()) << entry->key;
    EXPECT_FALSE(entry->description.empty()) << entry->key;
    EXPECT_EQ(entry->description.find_first_of("|\n"), std::string::npos) << entry->key;
    PatternConfig config = ConfigOf(*entry);
    ASSERT_NO_THROW(config.validate()) << entry->key;
    for (const std::vector<double>& frequencies : {std::vector<double>{}, std::vector<double>{25.0, 41.3}}) {
      config.frequencies_hz = frequencies;
      const std::vector<Impulse> impulses = ShaperImpulses(config);
      ASSERT_FALSE(impulses.empty()) << entry->key;
      EXPECT_NEAR(SumOfAmplitudes(impulses), 1.0, 1e-12) << entry->key;
      EXPECT_EQ(impulses.front().time_s, 0.0) << entry->key;
      for (std::size_t j = 1; j < impulses.size(); ++j) {
        EXPECT_GT(impulses[j].time_s, impulses[j - 1].time_s) << entry->key;
      }
    }
  }
  EXPECT_GE(keys.size(), 15u);
}

// Tests that the built-ins keep the order every listing had before the registry (the
// YAML choices, the error messages, the pattern report), each family after its first
// member (mzv_n after mzv, the multi-hump EIs after ei).
TEST(ShaperRegistry, BuiltInsInTheirListedOrder) {
  const std::vector<std::string> expected = {"none", "1",     "2",  "3",        "4",        "zv",
                                             "zvd",  "zvdd",  "mzv", "mzv_n",    "ei",       "ei_2hump",
                                             "ei_3hump", "um_zv", "custom"};
  EXPECT_EQ(BuiltInShaperKeys(), expected);
  EXPECT_EQ(FindShaper("none").kind, ShaperKind::kNone);
  for (const char* key : {"1", "2", "3", "4"}) EXPECT_EQ(FindShaper(key).kind, ShaperKind::kPatentStep);
  for (const char* key : {"zv", "zvd", "zvdd", "mzv", "mzv_n", "ei", "ei_2hump", "ei_3hump", "um_zv"}) {
    EXPECT_EQ(FindShaper(key).kind, ShaperKind::kImpulse);
  }
  EXPECT_EQ(FindShaper("custom").kind, ShaperKind::kCustom);
}

// Tests that an unknown method is a ValidationError naming `method` and listing the keys,
// from validate() and from every function that would otherwise shape with it.
TEST(ShaperRegistry, UnknownMethodIsAnError) {
  PatternConfig config;
  config.method = "zvv";
  try {
    config.validate();
    ADD_FAILURE() << "no ValidationError";
  } catch (const ValidationError& error) {
    EXPECT_EQ(error.field(), "method");
    // Every key in registry order (BuiltInsInTheirListedOrder pins the built-ins').
    std::string keys;
    for (const std::string& key : ShaperKeys()) keys += (keys.empty() ? "" : ", ") + key;
    EXPECT_NE(error.message().find("(got 'zvv'); allowed: " + keys), std::string::npos) << error.message();
    EXPECT_NE(error.message().find("allowed: none, 1, 2, "), std::string::npos) << error.message();
  }
  EXPECT_THROW(MakeStepPattern(config), ValidationError);
  EXPECT_THROW(ShaperImpulses(config), ValidationError);
  EXPECT_THROW(ShaperGridDesign(config), ValidationError);
}

// Tests that the damping error lists the library's keys and the patent's from the registry.
TEST(ShaperRegistry, DampingMessageListsTheKinds) {
  PatternConfig config;
  config.method = "2";
  config.design_damping_ratio = 0.05;
  try {
    config.validate();
    ADD_FAILURE() << "no ValidationError";
  } catch (const ValidationError& error) {
    EXPECT_EQ(error.field(), "design_damping_ratio");
    EXPECT_NE(error.message().find("applies to the library shapers (zv, zvd, zvdd, mzv, mzv_n, ei, ei_2hump, ei_3hump, um_zv, "
                                     "custom"),
              std::string::npos)
        << error.message();
    EXPECT_NE(error.message().find("the patent's methods (1, 2, 3, 4) are designed for an undamped mode"),
              std::string::npos)
        << error.message();
  }
}

ShaperEntry Valid(const std::string& key) {
  ShaperEntry entry;
  entry.key = key;
  entry.name = key;
  entry.description = "a test shaper";
  entry.design = [](const PatternConfig&, double) { return std::vector<Impulse>{{0.0, 1.0}}; };
  return entry;
}

// Tests that malformed registrations are refused: a taken or empty key, a description
// that would break the docs table, no design, a patent step method without its steps.
TEST(ShaperRegistry, RefusesMalformedEntries) {
  EXPECT_THROW(RegisterShaper(Valid("zv")), std::invalid_argument);
  EXPECT_THROW(RegisterShaper(Valid("")), std::invalid_argument);
  ShaperEntry bar = Valid("test_bar");
  bar.description = "a | b";
  EXPECT_THROW(RegisterShaper(bar), std::invalid_argument);
  ShaperEntry no_design = Valid("test_no_design");
  no_design.design = nullptr;
  EXPECT_THROW(RegisterShaper(no_design), std::invalid_argument);
  ShaperEntry no_steps = Valid("test_no_steps");
  no_steps.kind = ShaperKind::kPatentStep;
  EXPECT_THROW(RegisterShaper(no_steps), std::invalid_argument);
  EXPECT_THROW(FindShaper("test_no_steps"), ValidationError);
}

// Tests that a registered entry is listed by its rank (here between method 2 and 3),
// whatever the order of registration, and leaves the built-ins' list alone.
TEST(ShaperRegistry, ListsByRank) {
  ShaperEntry between = Valid("test_rank_25");
  between.rank = 25;
  RegisterShaper(between);
  const std::vector<std::string> keys = ShaperKeys();
  const std::vector<std::string> head(keys.begin(), keys.begin() + 5);
  EXPECT_EQ(head, (std::vector<std::string>{"none", "1", "2", "test_rank_25", "3"}));
  EXPECT_EQ(BuiltInShaperKeys().size(), 15u);
}

// The cells of a markdown table row "| a | b | c |", trimmed, backticks removed.
std::vector<std::string> Cells(const std::string& row) {
  std::vector<std::string> cells;
  std::stringstream in(row.substr(1));
  std::string cell;
  while (std::getline(in, cell, '|')) {
    std::string text;
    for (const char c : cell) {
      if (c != '`') text += c;
    }
    const std::size_t first = text.find_first_not_of(' ');
    const std::size_t last = text.find_last_not_of(' ');
    cells.push_back(first == std::string::npos ? "" : text.substr(first, last - first + 1));
  }
  return cells;
}

// Tests that docs/shapers.md's table has one row per built-in shaper, in registry order,
// with its key, name and description; on failure it prints the rows expected.
TEST(ShaperRegistry, DocsTableListsTheBuiltIns) {
  std::ifstream file(std::string(SHAPEBENCH_SOURCE_DIR) + "/docs/shapers.md");
  ASSERT_TRUE(file) << "docs/shapers.md";
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(file, line)) {
    if (line.rfind("|", 0) != 0 || line.find("---") != std::string::npos) continue;
    rows.push_back(Cells(line));
  }
  ASSERT_FALSE(rows.empty());
  EXPECT_EQ(rows.front(), (std::vector<std::string>{"key", "name", "description"}));
  rows.erase(rows.begin());
  std::vector<std::vector<std::string>> expected;
  std::string table;
  for (const std::string& key : BuiltInShaperKeys()) {
    const ShaperEntry& entry = FindShaper(key);
    expected.push_back({entry.key, entry.name, entry.description});
    table += "| `" + entry.key + "` | " + entry.name + " | " + entry.description + " |\n";
  }
  EXPECT_EQ(rows, expected) << "docs/shapers.md's rows should read:\n" << table;
}

}  // namespace
}  // namespace shapebench::controller

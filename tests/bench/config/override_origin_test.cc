// Where a --set's values come from (ConfigDocument) and how a rule between keys is located
// among them (rule_location.h).
#include "bench/config/config_document.h"

#include <gtest/gtest.h>

#include "bench/config/rule_location.h"

namespace shapebench::bench {
namespace {

// s.yaml with `controller: {feed_mm_min: 6000}` at line 1, its value at 1:27.
ConfigDocument Document() { return ConfigDocument(YAML::Load("controller: {feed_mm_min: 6000}\n"), "dir/s.yaml"); }

// Tests that the keys a --set creates are its own (an unknown key among them is located at
// the option), and that a path it gives has no file to be relative to (the current
// directory) while one written in the file has the file's.
TEST(OverrideOrigin, CreatedKeysAndPathsBelongToTheOption) {
  ConfigDocument document = Document();
  document.ApplyOverride(Override{"controller.patern.method", "zvd"}, 1);
  EXPECT_EQ(document.OriginOf("controller.patern").override_index, 1);
  EXPECT_EQ(document.OriginOf("controller.feed_mm_min").override_index, 0);
  const ConfigError unknown = document.ErrorAtPath("controller.patern", "unknown key");
  EXPECT_EQ(unknown.file(), "--set");
  EXPECT_EQ(unknown.line(), 1);
  document.ApplyOverride(Override{"program_file", "x.nc"}, 2);
  EXPECT_EQ(document.FileOf("program_file"), "");
  EXPECT_EQ(document.FileOf("controller.feed_mm_min"), "dir/s.yaml");
}

// Tests that a rule is located at the key of the last --set among its keys, else at the
// first written, naming each other key's origin (file position, --set, or its default).
TEST(OverrideOrigin, ARuleBlamesTheKeyTheUserGave) {
  const KeyRuleError rule({{"controller.stroke_end.minute_feed_mm_min", "100 mm/min", "is above"},
                           {"controller.feed_mm_min", "6000 mm/min", "is below"}},
                          "RULE");
  const ConfigError in_file = LocateRuleError(Document(), rule);
  EXPECT_EQ(in_file.key_path(), "controller.feed_mm_min");
  EXPECT_EQ(in_file.file(), "dir/s.yaml");
  EXPECT_EQ(in_file.message(),
            "6000 mm/min is below controller.stroke_end.minute_feed_mm_min = 100 mm/min (not written, so its "
            "default): RULE");
  ConfigDocument set = Document();
  set.ApplyOverride(Override{"controller.feed_mm_min", "6000"}, 1);
  set.ApplyOverride(Override{"controller.stroke_end.minute_feed_mm_min", "100"}, 2);
  const ConfigError last = LocateRuleError(set, rule);
  EXPECT_EQ(last.file(), "--set");
  EXPECT_EQ(last.line(), 2);
  EXPECT_EQ(last.message(), "100 mm/min is above controller.feed_mm_min = 6000 mm/min (--set:1): RULE");
  ConfigDocument one = Document();
  one.ApplyOverride(Override{"controller.stroke_end.minute_feed_mm_min", "100"}, 1);
  EXPECT_EQ(LocateRuleError(one, rule).message(),
            "100 mm/min is above controller.feed_mm_min = 6000 mm/min (dir/s.yaml:1:27): RULE");
}

}  // namespace
}  // namespace shapebench::bench

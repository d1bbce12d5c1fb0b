// Key paths: the strict parser for --set and the lenient splitter for error fields.
#include "bench/config/key_path.h"

#include <gtest/gtest.h>

namespace shapebench::bench {
namespace {

// Tests that dotted keys with indices parse into keys and indices in order.
TEST(KeyPath, ParsesKeysAndIndices) {
  const auto elements = ParseKeyPath("machine.modes[0].frequency_hz");
  ASSERT_TRUE(elements.has_value());
  ASSERT_EQ(elements->size(), 4u);
  EXPECT_EQ((*elements)[0].key, "machine");
  EXPECT_EQ((*elements)[1].key, "modes");
  EXPECT_EQ(*(*elements)[2].index, 0u);
  EXPECT_EQ((*elements)[3].key, "frequency_hz");
  EXPECT_EQ(ParseKeyPath("a[1][2]")->size(), 3u);
}

// Tests that a quoted key is one element taken as written (an FMU's structured name with
// dots and brackets), and that an empty or unclosed quote is refused.
TEST(KeyPath, QuotedKeyIsOneElement) {
  const auto elements = ParseKeyPath("machine.fmu_parameters.\"machine.modes[0].frequency_hz\"");
  ASSERT_TRUE(elements.has_value());
  ASSERT_EQ(elements->size(), 3u);
  EXPECT_EQ((*elements)[2].key, "machine.modes[0].frequency_hz");
  EXPECT_FALSE((*elements)[2].index.has_value());
  EXPECT_EQ(ParseKeyPath("a.\"b.c\"[1].d")->size(), 4u);
  for (const char* bad : {"a.\"\"", "a.\"b", "a.\"b\"c", "\"a\"\"b\""}) {
    EXPECT_FALSE(ParseKeyPath(bad).has_value()) << bad;
  }
}

// Tests that malformed paths are refused.
TEST(KeyPath, RefusesMalformedPaths) {
  for (const char* bad : {"", ".", "a.", ".a", "a..b", "[0]", "a[", "a[x]", "a[]", "a b", "a[0]b"}) {
    EXPECT_FALSE(ParseKeyPath(bad).has_value()) << bad;
  }
}

// Tests that the lenient splitter keeps odd text as keys instead of failing.
TEST(KeyPath, SplitsLeniently) {
  const auto elements = SplitKeyPath("elements[2].to");
  ASSERT_EQ(elements.size(), 3u);
  EXPECT_EQ(*elements[1].index, 2u);
  EXPECT_EQ(SplitKeyPath("").size(), 0u);
  EXPECT_EQ(SplitKeyPath("a[x]").front().key, "a[x]");
}

// Tests that prefixes respect element boundaries.
TEST(KeyPath, PrefixesRespectBoundaries) {
  EXPECT_TRUE(IsPathPrefix("", "a"));
  EXPECT_TRUE(IsPathPrefix("a", "a"));
  EXPECT_TRUE(IsPathPrefix("a", "a.b"));
  EXPECT_TRUE(IsPathPrefix("a", "a[0]"));
  EXPECT_FALSE(IsPathPrefix("a", "ab"));
  EXPECT_FALSE(IsPathPrefix("a.b", "a"));
  EXPECT_EQ(ChildPath("", "a"), "a");
  EXPECT_EQ(ChildPath("a", "b"), "a.b");
  EXPECT_EQ(IndexPath("a", 3), "a[3]");
}

}  // namespace
}  // namespace shapebench::bench

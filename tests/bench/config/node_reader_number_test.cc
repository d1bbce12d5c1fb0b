// NodeReader's number and integer syntax (a hand-written matcher, docs/performance.md) against the
// regular expressions it replaces, on every string over a small alphabet up to 5
// characters and a list of edge cases.
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/config/config_document.h"
#include "bench/config/config_error.h"
#include "bench/config/node_reader.h"

namespace shapebench::bench {
namespace {

bool Accepted(const std::string& text, bool integer) {
  YAML::Node root(YAML::NodeType::Map);
  root["x"] = YAML::Node(text);  // a plain (unquoted) scalar
  const ConfigDocument document(root, "t.yaml");
  const NodeReader reader(document, root["x"], "x");
  try {
    if (integer) {
      reader.AsInteger();
    } else {
      reader.AsNumber();
    }
    return true;
  } catch (const ConfigError& error) {
    // Out of range is a syntax match too.
    return std::string(error.what()).find("out of range") != std::string::npos;
  }
}

void Enumerate(const std::string& alphabet, std::size_t length, std::string prefix,
               std::vector<std::string>* out) {
  out->push_back(prefix);
  if (prefix.size() == length) return;
  for (char c : alphabet) Enumerate(alphabet, length, prefix + c, out);
}

// Tests that AsNumber and AsInteger accept exactly the strings their documented patterns
// match, over 2e5 strings of "1.e-+ " and a few others.
TEST(NodeReaderNumbers, SameLanguageAsTheRegularExpressions) {
  const std::regex number(R"([-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?)");
  const std::regex integer(R"([-+]?\d+)");
  std::vector<std::string> texts;
  Enumerate("1.e-+E", 5, "", &texts);
  for (const char* extra : {"0x1A", ".inf", "nan", "1e309", "-1e-400", "12345678901234567890",
                            "1_000", "1,5", "١", " 1", "1 ", "+", "-", "e5", "5e", "1..2"}) {
    texts.push_back(extra);
  }
  for (const std::string& text : texts) {
    if (text.empty()) continue;  // an empty plain scalar is YAML null, not a string
    EXPECT_EQ(Accepted(text, false), std::regex_match(text, number)) << "'" << text << "'";
    EXPECT_EQ(Accepted(text, true), std::regex_match(text, integer)) << "'" << text << "'";
  }
}

}  // namespace
}  // namespace shapebench::bench

// A rule between keys that failed ("the feed must be at least the stroke end's minute
// feed"). Any of its keys may be the one to change, so the error carries them all: the
// scenario loader locates it at the key the user gave most directly (a --set, a swept or
// a band's value) and names each other key with where it came from. Seen as a plain
// ValidationError (a caller that cannot tell), it blames the first key and names the rest.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "common/validation_error.h"

namespace shapebench {

struct RuleKey {
  std::string field;     // a dotted key path, relative as ValidationError's field
  std::string value;     // as shown in the message: "24 mm/min"
  std::string relation;  // how it stands to the other keys: "is below"
};

class KeyRuleError : public ValidationError {
 public:
  // `rule` says what must hold and what is allowed ("the feed must be at least ...").
  KeyRuleError(std::vector<RuleKey> keys, std::string rule)
      : ValidationError(keys.at(0).field, Compose(keys, 0, rule, nullptr)),
        keys_(std::move(keys)),
        rule_(std::move(rule)) {}

  const std::vector<RuleKey>& keys() const { return keys_; }
  const std::string& rule() const { return rule_; }

  // The message blaming keys()[blamed]: "VALUE RELATION OTHER = VALUE (WHERE): RULE", with
  // WHERE = where(j) for each other key j (a located error says where the blamed one is).
  std::string MessageFor(std::size_t blamed, const std::function<std::string(std::size_t)>& where) const {
    return Compose(keys_, blamed, rule_, &where);
  }

  // The same error seen from one level up (ValidationError::Prefixed, for every key).
  KeyRuleError Prefixed(const std::string& prefix) const {
    if (prefix.empty()) return *this;
    std::vector<RuleKey> keys = keys_;
    for (RuleKey& key : keys) key.field = prefix + "." + key.field;
    return KeyRuleError(std::move(keys), rule_);
  }

 private:
  static std::string Compose(const std::vector<RuleKey>& keys, std::size_t blamed, const std::string& rule,
                             const std::function<std::string(std::size_t)>* where) {
    std::string others;
    for (std::size_t j = 0; j < keys.size(); ++j) {
      if (j == blamed) continue;
      if (!others.empty()) others += " and ";
      others += keys[j].field + " = " + keys[j].value;
      if (where != nullptr) others += " (" + (*where)(j) + ")";
    }
    return keys.at(blamed).value + " " + keys[blamed].relation + " " + others + ": " + rule;
  }

  std::vector<RuleKey> keys_;
  std::string rule_;
};

}  // namespace shapebench

// Locates a rule between keys that failed (common/key_rule_error.h) in a ConfigDocument:
// at the key the user gave most directly, naming every other key with where it came from.
#pragma once

#include <string>

#include "bench/config/config_document.h"
#include "common/key_rule_error.h"

namespace shapebench::bench {

// The key blamed: of the rule's keys written anywhere, the one of the last --set (a
// sweep's or a band's value is one too), else the first written in a file, else the first
// key. The others are named "(FILE:LINE:COL)", "(--set:N)" or "(not written, so its
// default)". Key paths are the document's (callers rename struct fields first).
ConfigError LocateRuleError(const ConfigDocument& document, const KeyRuleError& error);

// The text naming the N-th --set in a located rule's message: "(--set:N)". Callers that
// renumber the overrides (a sweep's points) rewrite it.
std::string OverrideMention(int index);

}  // namespace shapebench::bench

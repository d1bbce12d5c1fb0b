// "did you mean": the known name a misspelt one most likely stands for.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace shapebench {

// Damerau-Levenshtein distance (optimal string alignment): insertions, deletions,
// substitutions and swaps of two neighbouring characters each cost 1 ("patern" is 1 from
// "pattern", "zdv" 1 from "zvd").
std::size_t EditDistance(const std::string& a, const std::string& b);

// The name of `names` nearest to `name` within `max_distance` edits (the first of equals),
// or "" when none is that near; of equals, the first of the name's length, else the
// first. An exact match is not a suggestion: "" then too.
std::string ClosestName(const std::string& name, const std::vector<std::string>& names,
                        std::size_t max_distance = 2);

// "; did you mean 'NAME'?" for ClosestName, else one word's other form (settle_time_s: settling_time_s), or "".
std::string DidYouMean(const std::string& name, const std::vector<std::string>& names);

}  // namespace shapebench

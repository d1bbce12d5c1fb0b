#include "common/closest_name.h"

#include <algorithm>

namespace shapebench {

std::size_t EditDistance(const std::string& a, const std::string& b) {
  // Three rows: the swap looks two rows back.
  std::vector<std::size_t> before(b.size() + 1), previous(b.size() + 1), row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) previous[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      row[j] = std::min({previous[j] + 1, row[j - 1] + 1, previous[j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        row[j] = std::min(row[j], before[j - 2] + 1);
      }
    }
    std::swap(before, previous);
    std::swap(previous, row);
  }
  return previous[b.size()];
}

std::string ClosestName(const std::string& name, const std::vector<std::string>& names,
                        std::size_t max_distance) {
  // A 10 MB key is near nothing; skip the quadratic work.
  if (name.empty() || name.size() > 256) return "";
  std::string best;
  std::size_t best_distance = max_distance + 1;
  for (const std::string& candidate : names) {
    const std::size_t length_gap =
        name.size() > candidate.size() ? name.size() - candidate.size() : candidate.size() - name.size();
    if (length_gap > max_distance) continue;
    const std::size_t distance = EditDistance(name, candidate);
    if (distance == 0) return "";
    // Of equals, one of the same length (a swap or a slip: "zdv" is "zvd", not "zv").
    const bool same_length_tie = distance == best_distance && candidate.size() == name.size() &&
                                 best.size() != name.size();
    if (distance < best_distance || same_length_tie) {
      best = candidate;
      best_distance = distance;
    }
  }
  return best;
}

namespace {

std::vector<std::string> Words(const std::string& name) {
  std::vector<std::string> words(1);
  for (const char c : name) {
    if (c == '_') {
      words.emplace_back();
    } else {
      words.back() += c;
    }
  }
  return words;
}

// Two snake_case names alike but for one word, one form of the other: the words share
// their first four letters at least, all of the shorter but its last ("settle_time_s" and
// "settling_time_s", "freq_hz" and "frequency_hz"), which edits alone call 3 or 5 apart.
bool OtherWordForm(const std::string& a, const std::string& b) {
  const std::vector<std::string> x = Words(a);
  const std::vector<std::string> y = Words(b);
  if (x.size() != y.size() || a == b) return false;
  std::size_t differing = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (x[i] == y[i]) continue;
    if (++differing > 1) return false;
    std::size_t common = 0;
    while (common < x[i].size() && common < y[i].size() && x[i][common] == y[i][common]) ++common;
    const std::size_t shorter = std::min(x[i].size(), y[i].size());
    if (common < 4 || common + 1 < shorter) return false;
  }
  return differing == 1;
}

}  // namespace

std::string DidYouMean(const std::string& name, const std::vector<std::string>& names) {
  std::string closest = ClosestName(name, names);
  for (std::size_t i = 0; closest.empty() && name.size() <= 256 && i < names.size(); ++i) {
    if (OtherWordForm(name, names[i])) closest = names[i];
  }
  return closest.empty() ? "" : "; did you mean '" + closest + "'?";
}

}  // namespace shapebench

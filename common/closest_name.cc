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

std::string DidYouMean(const std::string& name, const std::vector<std::string>& names) {
  const std::string closest = ClosestName(name, names);
  return closest.empty() ? "" : "; did you mean '" + closest + "'?";
}

}  // namespace shapebench

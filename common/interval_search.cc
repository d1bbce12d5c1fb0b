// The searches of common/interval_search.h.
#include "common/interval_search.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace shapebench {
namespace {

// True when a is more extreme than b (a NaN is never).
bool Better(double a, double b, Extreme extreme) {
  return extreme == Extreme::kMaximum ? a > b : a < b;
}

}  // namespace

IntervalPoint GoldenSection(const std::function<double(double)>& f, double low, double high,
                            Extreme extreme, double width, int* evaluations) {
  const double kInverse = (std::sqrt(5.0) - 1.0) / 2.0;  // 1 / golden ratio
  int count = 0;
  double a = low;
  double b = high;
  double c = b - kInverse * (b - a);
  double d = a + kInverse * (b - a);
  double fc = f(c);
  double fd = f(d);
  count += 2;
  IntervalPoint best = Better(fd, fc, extreme) ? IntervalPoint{d, fd} : IntervalPoint{c, fc};
  // Each step keeps the sub-bracket on the better side: one new evaluation, the bracket
  // shrinks by the golden ratio.
  for (int i = 0; i < 200 && b - a > width && !std::isnan(fc) && !std::isnan(fd); ++i) {
    if (Better(fd, fc, extreme)) {
      a = c, c = d, fc = fd;
      d = a + kInverse * (b - a);
      fd = f(d);
      if (!Better(best.value, fd, extreme) && !std::isnan(fd)) best = {d, fd};
    } else {
      b = d, d = c, fd = fc;
      c = b - kInverse * (b - a);
      fc = f(c);
      if (!Better(best.value, fc, extreme) && !std::isnan(fc)) best = {c, fc};
    }
    ++count;
  }
  if (std::isnan(fc)) best = {c, fc};
  if (std::isnan(fd)) best = {d, fd};
  if (evaluations != nullptr) *evaluations += count;
  return best;
}

ExtremumResult FindExtremum(const std::function<double(double)>& f, double from, double to,
                            Extreme extreme, const ExtremumSearch& search) {
  ExtremumResult result;
  const int n = std::max(3, search.scan_points);
  std::vector<IntervalPoint> scan(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    // The ends exactly as given (from + (to - from) would round the last one).
    const double x = k == n - 1 ? to : from + (to - from) * static_cast<double>(k) / (n - 1);
    scan[k] = {x, f(x)};
    ++result.evaluations;
    if (std::isnan(scan[k].value)) {
      result.worst = scan[k];
      return result;
    }
  }
  // The scan's local extrema (plateaus and ends included), most extreme first.
  std::vector<int> candidates;
  for (int k = 0; k < n; ++k) {
    const bool left = k == 0 || !Better(scan[k - 1].value, scan[k].value, extreme);
    const bool right = k == n - 1 || !Better(scan[k + 1].value, scan[k].value, extreme);
    if (left && right) candidates.push_back(k);
  }
  std::stable_sort(candidates.begin(), candidates.end(), [&](int a, int b) {
    return Better(scan[a].value, scan[b].value, extreme);
  });
  candidates.resize(std::min<std::size_t>(candidates.size(), std::max(1, search.candidates)));
  result.worst = scan[candidates.front()];
  const double width = search.tolerance * (to - from);
  for (const int k : candidates) {
    const IntervalPoint refined = GoldenSection(f, scan[std::max(0, k - 1)].x,
                                                scan[std::min(n - 1, k + 1)].x, extreme, width,
                                                &result.evaluations);
    if (std::isnan(refined.value)) {
      result.worst = refined;
      return result;
    }
    if (Better(refined.value, result.worst.value, extreme)) result.worst = refined;
  }
  return result;
}

double BisectEdge(const std::function<bool(double)>& holds, double inside, double outside,
                  double width) {
  for (int i = 0; i < 200 && std::abs(outside - inside) > width; ++i) {
    const double mid = 0.5 * (inside + outside);
    (holds(mid) ? inside : outside) = mid;
  }
  return 0.5 * (inside + outside);
}

}  // namespace shapebench

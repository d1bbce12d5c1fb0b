#include "controller/profile_table.h"

#include <cmath>
#include <string>

#include "common/format.h"
#include "common/validation_error.h"
#include "controller/grid_realization.h"

namespace shapebench::controller {

std::vector<double> ProfileTableFromPattern(const StepPattern& pattern, double period_s,
                                            const GridDesign& design) {
  return ProfileTableFromImpulses(PatternImpulses(pattern), period_s, design);
}

std::vector<double> ProfileTableFromImpulses(const std::vector<Impulse>& impulses, double period_s,
                                             const GridDesign& design) {
  // Per unit acceleration, as at the start of a phase from rest: nothing before the
  // group and 1 is the largest acceleration (the table's coefficients stay in [0, 1] for
  // a positive shaper).
  const std::vector<GridImpulse> grid = RealizeOnGrid(impulses, period_s, design, 0.0, 1.0);
  std::vector<double> table;
  for (const GridImpulse& g : grid) {
    const auto tick = static_cast<std::size_t>(std::max(0L, g.tick));
    if (table.size() <= tick) table.resize(tick + 1, 0.0);
    table[tick] += g.amplitude;
  }
  while (table.size() > 1 && table.back() == 0.0) table.pop_back();
  if (table.empty()) table.push_back(1.0);
  return table;
}

std::vector<double> MovingAverageTable(double length_s, double period_s) {
  const long n = std::max(1L, std::lround(length_s / period_s));
  return std::vector<double>(static_cast<std::size_t>(n), 1.0 / static_cast<double>(n));
}

std::vector<double> ConvolveTables(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.empty()) return b;
  if (b.empty()) return a;
  std::vector<double> c(a.size() + b.size() - 1, 0.0);
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = 0; j < b.size(); ++j) c[i + j] += a[i] * b[j];
  }
  return c;
}

void ValidateProfileTable(const std::vector<double>& table, int max_length) {
  if (table.empty() || static_cast<long>(table.size()) > max_length) {
    throw ValidationError("table", "must have 1 to " + std::to_string(max_length) +
                                       " coefficients (one per period; got " +
                                       std::to_string(table.size()) + ")");
  }
  double sum = 0.0;
  for (std::size_t i = 0; i < table.size(); ++i) {
    if (!std::isfinite(table[i])) {
      throw ValidationError("table", "coefficient " + std::to_string(i) + " is not a finite number");
    }
    sum += table[i];
  }
  if (std::abs(sum - 1.0) > 1e-9) {
    throw ValidationError("table", "the jerk coefficients must sum to 1 (para. 58; got " +
                                       FormatNumber(sum) + ")");
  }
}

}  // namespace shapebench::controller

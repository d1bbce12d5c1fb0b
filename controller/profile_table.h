// The post-interpolation profile table of seed 004 (paras. 52-61): jerk coefficients
// alpha_0 .. alpha_{n-1}, one per interpolation period, summing to 1, convolved with the
// per-period move pulses. A pattern's jerk impulses on the period grid give the table
// that realises it after interpolation (para. 61: method 1 at 25 Hz and 1 ms is
// alpha_0 = alpha_20 = 0.5); a table of n equal coefficients is linear acc/dec of time
// constant n periods (a moving average).
#pragma once

#include <vector>

#include "controller/grid_realization.h"
#include "controller/vibration_suppression_pattern.h"

namespace shapebench::controller {

constexpr int kDefaultMaxTableLength = 64;  // alpha_0 .. alpha_63 (para. 58)

// The table that realises a shaper's impulse sequence (e.g. ShaperImpulses, any method)
// on the grid of `period_s`: impulses between ticks are placed by RealizeOnGrid so the
// vibration phasor at every design frequency (with the design damping) is kept.
std::vector<double> ProfileTableFromImpulses(const std::vector<Impulse>& impulses, double period_s,
                                             const GridDesign& design);

// The same for `pattern`'s shaped start (PatternImpulses): method 1-4's two steps, or a
// general pattern's impulses.
std::vector<double> ProfileTableFromPattern(const StepPattern& pattern, double period_s,
                                            const GridDesign& design);

// n = round(length_s / period_s) coefficients of 1/n (n >= 1).
std::vector<double> MovingAverageTable(double length_s, double period_s);

// The cascade of two tables (convolution); still sums to 1.
std::vector<double> ConvolveTables(const std::vector<double>& a, const std::vector<double>& b);

// Throws ValidationError("table", ...) unless 1 <= size <= max_length, every coefficient
// is finite, and they sum to 1 within 1e-9.
void ValidateProfileTable(const std::vector<double>& table, int max_length);

}  // namespace shapebench::controller

// Pattern synthesis (`shapebench design`, docs/design.md): the shortest pattern on a time
// grid, coefficients a_k >= 0 at t_k = k h summing to 1, whose residual vibration
// V(f, zeta) (impulse.h's ResidualVibration, referenced to the pattern's end D = n h) stays
// at or below a tolerance over every band of frequency and damping. On a fixed grid the
// conditions are linear in a_k; the least n is found by bisection over feasibility.
//
// - The modulus |S| <= V is a regular polygon of kPolygonSides faces circumscribing the
//   circle of radius V: Re(S e^{-i theta_j}) <= V, theta_j = 2 pi j / kPolygonSides. A
//   circle-satisfying S always passes (no design is lost to the polygon); a passing S has
//   |S| <= V / cos(pi / kPolygonSides) (0.48% of V more at 32 faces). The faces are added
//   as cutting planes (only those a solution violates), which ends at the same optimum as
//   all of them.
// - Each band is sampled so that V between samples provably stays within the tolerance
//   plus `margin`: |dS/dw| <= D and |dS/dzeta| <= w D (zeta <= 1/sqrt 2), so frequency
//   samples Delta w <= 2 margin / D apart (margin / D with a damping band, and damping
//   samples Delta zeta <= margin / (w_max D)) leave at most `margin` between them.
// - `derivatives` N: sum_k a_k t_k^m e^{(zeta w + i w_d) t_k} = 0 at each band's centre for
//   m = 1..N (ZVD, ZVDD at tolerance 0 and zero-width bands).
// - Secondary objective at the least duration: the least mean time sum a_k t_k (the delay
//   the pattern adds to the tool path, its smoothing), linear.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace shapebench::controller {

constexpr int kPolygonSides = 32;
// Guard rails: the grid points of one design and the samples of one LP (docs/reliability.md).
constexpr int kMaxDesignGridPoints = 20000;
constexpr int kMaxDesignSamples = 20000;
constexpr double kMaxDesignEntries = 2e7;  // samples x grid points (16 bytes each)

// One mode's band: frequencies [lo, hi] Hz and damping ratios [lo, hi] (equal: one value).
struct DesignBand {
  double frequency_lo_hz = 0.0;
  double frequency_hi_hz = 0.0;
  double damping_lo = 0.0;
  double damping_hi = 0.0;
};

struct DesignSpec {
  std::vector<DesignBand> bands;
  double tolerance = 0.05;  // V allowed over every band, [0, 1)
  int derivatives = 0;      // 0..4
  double grid_s = 0.001;    // the time grid (h)
  double margin = 0.01;     // the sampling margin above the tolerance between samples (> 0)
  double max_duration_s = 1.0;  // give up beyond this (DesignError)
  // Throws ValidationError naming the field ("bands[0].frequency_lo_hz", "tolerance", ...).
  void validate() const;
};

struct DesignResult {
  double duration_s = 0.0;           // n h: the last coefficient's time
  double grid_s = 0.0;
  std::vector<double> coefficients;  // a_0 .. a_n at t = k h
  std::vector<double> worst_v;       // per band: the largest V found by a dense check
  double guaranteed_v = 0.0;         // tolerance / cos(pi / sides) + margin (no margin: one-point bands)
  bool secondary_objective = true;   // the least mean time applied (see DesignPattern)
  int lp_solves = 0;
};

// The LP could not be solved or no pattern was found up to max_duration_s (exit 3).
class DesignError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The shortest pattern for `spec` (validated here); deterministic.
DesignResult DesignPattern(const DesignSpec& spec);

// Whether a pattern of n + 1 grid coefficients meets `spec` (one series of LPs, `solves`
// counting them); the coefficients when it does, of least mean time with
// `least_mean_time` (else any: a feasibility check without an objective is faster).
bool DesignFeasible(const DesignSpec& spec, int n, std::vector<double>* coefficients, int* solves,
                    bool least_mean_time = false);

// The largest V of `coefficients` (on `grid_s`) over `band`, at `frequencies` evenly spaced
// frequencies times 3 dampings (lo, middle, hi).
double WorstResidualOverBand(const std::vector<double>& coefficients, double grid_s, const DesignBand& band,
                             int frequencies = 2001);

}  // namespace shapebench::controller

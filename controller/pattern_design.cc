// Pattern synthesis; see the header and docs/design.md.
#include "controller/pattern_design.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>

#include "common/format.h"
#include "common/math_constants.h"
#include "common/validation_error.h"
#include "controller/impulse.h"
#include "controller/pattern_lp.h"

namespace shapebench::controller {
namespace {

// A point (w, zeta) of a band where the modulus is constrained.
struct DesignSample {
  double w = 0.0;
  double zeta = 0.0;
};

// Coefficients below this (CLP's round-off, negative or positive) are zero.
constexpr double kZeroCoefficient = 1e-12;
// A face is violated when Re(S e^{-i theta}) exceeds the tolerance by more than this.
constexpr double kFaceSlack = 1e-9;
constexpr int kMaxCutRounds = 1000;

void CheckFinite(const std::string& field, double value, double lo, double hi, const std::string& allowed) {
  if (!(std::isfinite(value) && value >= lo && value <= hi)) {
    throw ValidationError(field, "must be " + allowed + " (got " + FormatNumber(value) + ")");
  }
}

// The samples of `band` for a pattern of duration `duration_s` (header: the spacing).
std::vector<DesignSample> BandSamples(const DesignBand& band, double duration_s, double margin) {
  const double w_lo = 2.0 * kPi * band.frequency_lo_hz;
  const double w_hi = 2.0 * kPi * band.frequency_hi_hz;
  const bool damping_band = band.damping_hi > band.damping_lo;
  const double dw = (damping_band ? margin : 2.0 * margin) / duration_s;
  const long nw = w_hi > w_lo ? static_cast<long>(std::ceil((w_hi - w_lo) / dw)) + 1 : 1;
  long nz = 1;
  if (damping_band) {
    const double dz = margin / (w_hi * duration_s);
    nz = static_cast<long>(std::ceil((band.damping_hi - band.damping_lo) / dz)) + 1;
  }
  if (nw * nz > kMaxDesignSamples) {
    throw DesignError("a band needs " + std::to_string(nw * nz) + " samples for a " + FormatNumber(duration_s) +
                      " s pattern, more than " + std::to_string(kMaxDesignSamples) +
                      ": narrow the band or raise the margin");
  }
  std::vector<DesignSample> samples;
  for (long i = 0; i < nw; ++i) {
    const double w = nw == 1 ? w_lo : w_lo + (w_hi - w_lo) * static_cast<double>(i) / static_cast<double>(nw - 1);
    for (long j = 0; j < nz; ++j) {
      const double z = nz == 1 ? band.damping_lo
                               : band.damping_lo + (band.damping_hi - band.damping_lo) * static_cast<double>(j) /
                                                       static_cast<double>(nz - 1);
      samples.push_back({w, z});
    }
  }
  return samples;
}

// c_k = e^{-zeta w (D - t_k)} e^{i w_d t_k}: S = sum a_k c_k, V = |S| (sum a_k = 1).
std::vector<std::complex<double>> DesignPhasors(const DesignSample& s, int n, double h) {
  const double wd = s.w * std::sqrt(1.0 - s.zeta * s.zeta);
  const double d = n * h;
  std::vector<std::complex<double>> c(n + 1);
  for (int k = 0; k <= n; ++k) {
    const double t = k * h;
    c[k] = std::exp(-s.zeta * s.w * (d - t)) * std::complex<double>(std::cos(wd * t), std::sin(wd * t));
  }
  return c;
}

// Re(c e^{-i theta}) per coefficient: one face of one sample's polygon.
std::vector<double> FaceRow(const std::vector<std::complex<double>>& c, int face) {
  const double theta = 2.0 * kPi * face / kPolygonSides;
  std::vector<double> row(c.size());
  for (std::size_t k = 0; k < c.size(); ++k) row[k] = c[k].real() * std::cos(theta) + c[k].imag() * std::sin(theta);
  return row;
}

// m-th derivative conditions at each band's centre: Re and Im of sum a_k (t_k/D)^m c_k = 0.
void AddDerivativeRows(const DesignSpec& spec, int n, DenseLp* lp) {
  for (const DesignBand& band : spec.bands) {
    const DesignSample centre{kPi * (band.frequency_lo_hz + band.frequency_hi_hz),
                              0.5 * (band.damping_lo + band.damping_hi)};
    const std::vector<std::complex<double>> c = DesignPhasors(centre, n, spec.grid_s);
    for (int m = 1; m <= spec.derivatives; ++m) {
      std::vector<double> re(n + 1), im(n + 1);
      for (int k = 0; k <= n; ++k) {
        const double scale = std::pow(static_cast<double>(k) / std::max(n, 1), m);
        re[k] = scale * c[k].real();
        im[k] = scale * c[k].imag();
      }
      lp->AddRow(re, 0.0, 0.0);
      lp->AddRow(im, 0.0, 0.0);
    }
  }
}

std::vector<double> Cleaned(std::vector<double> a) {
  double total = 0.0;
  for (double& x : a) {
    if (x < kZeroCoefficient) x = 0.0;
    total += x;
  }
  for (double& x : a) x /= total;
  return a;
}

}  // namespace

void DesignSpec::validate() const {
  if (bands.empty()) throw ValidationError("bands", "at least one band is needed");
  for (std::size_t i = 0; i < bands.size(); ++i) {
    const DesignBand& b = bands[i];
    const std::string at = "bands[" + std::to_string(i) + "].";
    CheckFinite(at + "frequency_lo_hz", b.frequency_lo_hz, 1e-9, 1e9, "> 0 Hz");
    CheckFinite(at + "frequency_hi_hz", b.frequency_hi_hz, b.frequency_lo_hz, 1e9,
                "at least frequency_lo_hz (" + FormatNumber(b.frequency_lo_hz) + " Hz)");
    CheckFinite(at + "damping_lo", b.damping_lo, 0.0, 0.7, "in [0, 0.7]");
    CheckFinite(at + "damping_hi", b.damping_hi, b.damping_lo, 0.7,
                "in [damping_lo, 0.7] (damping_lo " + FormatNumber(b.damping_lo) + ")");
  }
  CheckFinite("tolerance", tolerance, 0.0, 0.999999, "in [0, 1)");
  if (derivatives < 0 || derivatives > 4) {
    throw ValidationError("derivatives", "must be 0 to 4 (got " + std::to_string(derivatives) + ")");
  }
  CheckFinite("grid_s", grid_s, 1e-7, 1.0, "in [1e-7, 1] s");
  CheckFinite("margin", margin, 1e-6, 1.0, "in [1e-6, 1]");
  CheckFinite("max_duration_s", max_duration_s, grid_s, 1e3, "in [grid_s, 1000] s");
}

bool DesignFeasible(const DesignSpec& spec, int n, std::vector<double>* coefficients, int* solves,
                    bool least_mean_time) {
  const double h = spec.grid_s;
  const double duration = std::max(n, 1) * h;  // n = 0: one impulse, V = 1 everywhere
  std::vector<double> objective(n + 1);
  if (least_mean_time) {
    for (int k = 0; k <= n; ++k) objective[k] = static_cast<double>(k) / std::max(n, 1);  // mean time / D
  }
  DenseLp lp(objective, 1.0);
  lp.AddRow(std::vector<double>(n + 1, 1.0), 1.0, 1.0);
  AddDerivativeRows(spec, n, &lp);
  std::vector<std::vector<std::complex<double>>> phasors;
  for (const DesignBand& band : spec.bands) {
    for (const DesignSample& s : BandSamples(band, duration, spec.margin)) {
      if (static_cast<double>(phasors.size() + 1) * (n + 1) > kMaxDesignEntries ||
          phasors.size() >= static_cast<std::size_t>(kMaxDesignSamples)) {
        throw DesignError("a " + FormatNumber(n * h) + " s pattern on the bands needs more than " +
                          std::to_string(kMaxDesignSamples) + " samples or " + FormatNumber(kMaxDesignEntries) +
                          " samples x grid points: narrow the bands, coarsen the grid or raise the margin");
      }
      phasors.push_back(DesignPhasors(s, n, h));
    }
  }
  std::vector<std::vector<char>> has_face(phasors.size(), std::vector<char>(kPolygonSides, 0));
  for (std::size_t s = 0; s < phasors.size(); ++s) {  // every solution starts near S = 1
    lp.AddRow(FaceRow(phasors[s], 0), -1e30, spec.tolerance);
    has_face[s][0] = 1;
  }
  for (int round = 0; round < kMaxCutRounds; ++round) {
    const DenseLp::Outcome outcome = lp.Solve();
    ++*solves;
    if (outcome == DenseLp::Outcome::kInfeasible) return false;
    if (outcome == DenseLp::Outcome::kFailed) {
      throw DesignError("the LP solver (CLP) stopped without an answer for a " + FormatNumber(n * h) + " s pattern");
    }
    const std::vector<double> a = lp.Solution();
    int added = 0;
    for (std::size_t s = 0; s < phasors.size(); ++s) {
      std::complex<double> sum = 0.0;
      for (int k = 0; k <= n; ++k) sum += a[k] * phasors[s][k];
      const double step = 2.0 * kPi / kPolygonSides;
      int face = static_cast<int>(std::lround(std::arg(sum) / step)) % kPolygonSides;
      if (face < 0) face += kPolygonSides;
      const double value = sum.real() * std::cos(face * step) + sum.imag() * std::sin(face * step);
      if (value > spec.tolerance + kFaceSlack && !has_face[s][face]) {
        lp.AddRow(FaceRow(phasors[s], face), -1e30, spec.tolerance);
        has_face[s][face] = 1;
        ++added;
      }
    }
    if (added == 0) {
      *coefficients = Cleaned(a);
      return true;
    }
  }
  throw DesignError("the cutting planes did not settle in " + std::to_string(kMaxCutRounds) + " rounds");
}

namespace {

// The least n in (lo, hi] that `feasible` accepts, given that it accepts hi and not lo
// (feasibility is monotone in n: a pattern padded with a zero coefficient still passes).
int BisectFeasible(const std::function<bool(int)>& feasible, int lo, int hi) {
  while (hi - lo > 1) {
    const int mid = lo + (hi - lo) / 2;
    (feasible(mid) ? hi : lo) = mid;
  }
  return hi;
}

// The least feasible n <= n_max of `feasible`: from `start`, doubling until feasible, then
// bisecting. Throws DesignError (saying `what`) when n_max is not feasible.
int LeastFeasible(const std::function<bool(int)>& feasible, int start, int n_max, const std::string& what) {
  int lo = 0;  // one impulse leaves V = 1 > tolerance
  int hi = std::clamp(start, 1, std::max(n_max, 1));
  while (!feasible(hi)) {
    lo = hi;
    if (hi >= n_max) {
      throw DesignError("no pattern of at most " + what +
                        " meets the tolerance over the bands: widen the tolerance, narrow the bands or allow a "
                        "longer pattern");
    }
    hi = std::min(2 * hi, n_max);
  }
  return BisectFeasible(feasible, lo, hi);
}

}  // namespace

DesignResult DesignPattern(const DesignSpec& spec) {
  spec.validate();
  const double h = spec.grid_s;
  const int n_max = std::min(kMaxDesignGridPoints - 1, static_cast<int>(std::floor(spec.max_duration_s / h + 1e-9)));
  const std::string what = FormatNumber(n_max * h) + " s (" + std::to_string(n_max + 1) + " grid points of " +
                           FormatNumber(h) + " s)";
  double f_top = 0.0;
  for (const DesignBand& band : spec.bands) f_top = std::max(f_top, band.frequency_hi_hz);
  DesignResult result;
  result.grid_s = h;
  // The search starts near ZV's length for the highest frequency. On a fine grid it runs
  // first on a grid `coarse` times coarser (about 10 points per ZV length): its least
  // duration bounds the fine one from above (its patterns are fine-grid patterns), and the
  // fine search then looks below it only.
  const int zv_points = static_cast<int>(std::lround(0.5 / f_top / h));
  const int coarse = std::max(1, zv_points / 10);
  DesignSpec coarse_spec = spec;
  coarse_spec.grid_s = coarse * h;
  // Every search below only lowers the feasible bound, so the last feasible check's pattern
  // (on the fine grid) is the one of the current least duration.
  std::vector<double> found;
  const auto check = [&](const DesignSpec& on, int scale, int n) {
    std::vector<double> a;
    if (!DesignFeasible(on, n, &a, &result.lp_solves)) return false;
    found.assign(static_cast<std::size_t>(n * scale + 1), 0.0);
    for (int k = 0; k <= n; ++k) found[static_cast<std::size_t>(k * scale)] = a[k];
    return true;
  };
  const auto fine = [&](int n) { return check(spec, 1, n); };
  int hi = coarse * LeastFeasible([&](int n) { return check(coarse_spec, coarse, n); }, zv_points / coarse,
                                  n_max / coarse, what);
  if (coarse > 1) {
    int lo = hi - coarse;  // galloping down from the coarse answer
    for (int step = coarse; lo > 0 && fine(lo); step *= 2) {
      hi = lo;
      lo = std::max(0, hi - 2 * step);
    }
    hi = BisectFeasible(fine, std::max(lo, 0), hi);
  }
  // The secondary objective at the least duration: the least mean time. A duration CLP
  // finds only marginally feasible (its tolerances, 1e-7) may fail with the objective, or
  // on the fine grid where the coarse grid passed: then the check's own pattern stands
  // (secondary_objective false).
  result.secondary_objective = DesignFeasible(spec, hi, &result.coefficients, &result.lp_solves, true);
  if (!result.secondary_objective) result.coefficients = found;
  result.duration_s = hi * h;
  for (const DesignBand& band : spec.bands) {
    result.worst_v.push_back(WorstResidualOverBand(result.coefficients, h, band));
  }
  // The margin covers the points between samples; a band of one frequency and one damping
  // is its one sample.
  bool between_samples = false;
  for (const DesignBand& band : spec.bands) {
    between_samples = between_samples || band.frequency_hi_hz > band.frequency_lo_hz || band.damping_hi > band.damping_lo;
  }
  result.guaranteed_v = spec.tolerance / std::cos(kPi / kPolygonSides) + (between_samples ? spec.margin : 0.0);
  return result;
}

double WorstResidualOverBand(const std::vector<double>& coefficients, double grid_s, const DesignBand& band,
                             int frequencies) {
  const std::vector<Impulse> impulses = TableImpulses(coefficients, grid_s);
  std::vector<double> dampings{band.damping_lo};
  if (band.damping_hi > band.damping_lo) {
    dampings.push_back(0.5 * (band.damping_lo + band.damping_hi));
    dampings.push_back(band.damping_hi);
  }
  double worst = 0.0;
  const int count = band.frequency_hi_hz > band.frequency_lo_hz ? std::max(frequencies, 2) : 1;
  for (int i = 0; i < count; ++i) {
    const double f = count == 1 ? band.frequency_lo_hz
                                : band.frequency_lo_hz + (band.frequency_hi_hz - band.frequency_lo_hz) * i / (count - 1);
    for (double z : dampings) worst = std::max(worst, ResidualVibration(impulses, f, z));
  }
  return worst;
}

}  // namespace shapebench::controller

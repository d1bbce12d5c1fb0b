#include "model/band_crossing.h"

#include <algorithm>
#include <cmath>

#include "common/math_constants.h"

namespace shapebench::model {
namespace {

// The terms' sizes, once (std::abs of a complex is a hypot).
struct Sizes {
  std::vector<double> q;       // |q_k|
  std::vector<double> rate;    // |q_k| |lambda_k|
  std::vector<double> sigma;   // Re lambda_k
  double Envelope(double t) const {
    double sum = 0.0;
    for (std::size_t k = 0; k < q.size(); ++k) sum += q[k] * std::exp(sigma[k] * t);
    return sum;
  }
  // sum |q_k| |lambda_k| e^{sigma_k a}: |y'| on [a, ...] (every sigma_k < 0).
  double RateBound(double a) const {
    double bound = 0.0;
    for (std::size_t k = 0; k < q.size(); ++k) bound += rate[k] * std::exp(sigma[k] * a);
    return bound;
  }
};

// The largest t in [a, b] with |y(t)| >= band, or -1; g = band - |y| at the ends.
double LastIn(const FreeTerms& y, const Sizes& sizes, double band, double a, double b, double g_a, double g_b,
              double resolution) {
  if (g_b <= 0.0) return b;
  if (g_a + g_b > sizes.RateBound(a) * (b - a)) return -1.0;  // cleared
  if (b - a <= resolution) return g_a <= 0.0 ? a : -1.0;
  const double mid = 0.5 * (a + b);
  const double g_mid = band - std::abs(y.At(mid));
  const double later = LastIn(y, sizes, band, mid, b, g_mid, g_b, resolution);
  return later >= 0.0 ? later : LastIn(y, sizes, band, a, mid, g_a, g_mid, resolution);
}

}  // namespace

double FreeTerms::At(double t) const {
  double sum = 0.0;
  for (std::size_t k = 0; k < q.size(); ++k) sum += (q[k] * std::exp(lambda[k] * t)).real();
  return sum;
}

double FreeTerms::Envelope(double t) const {
  double sum = 0.0;
  for (std::size_t k = 0; k < q.size(); ++k) sum += std::abs(q[k]) * std::exp(lambda[k].real() * t);
  return sum;
}

double LastBandCrossing(const FreeTerms& y, double band) {
  if (!(band > 0.0)) return NAN;
  double fastest = 0.0;
  double end = 0.0;  // every term below band / n from here on: E(end) <= band
  const double n = static_cast<double>(y.q.size());
  Sizes sizes;
  for (std::size_t k = 0; k < y.q.size(); ++k) {
    const double size = std::abs(y.q[k]);
    if (size == 0.0) continue;
    const double sigma = y.lambda[k].real();
    if (!(sigma < 0.0) || !std::isfinite(size)) return NAN;
    fastest = std::max(fastest, std::abs(y.lambda[k]));
    end = std::max(end, std::log(n * size / band) / -sigma);
    sizes.q.push_back(size);
    sizes.rate.push_back(size * std::abs(y.lambda[k]));
    sizes.sigma.push_back(sigma);
  }
  if (!(sizes.Envelope(0.0) >= band)) return -1.0;
  // The envelope's crossing: E decreases, E(0) >= band >= E(end).
  double lo = 0.0;
  double hi = end;
  for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (sizes.Envelope(mid) >= band ? lo : hi) = mid;
  }
  const double step = 0.5 * kPi / fastest;
  const double resolution = 1e-13 * 2.0 * kPi / fastest;
  double b = hi;
  double g_b = band - std::abs(y.At(b));
  while (b > 0.0) {
    const double a = std::max(0.0, b - step);
    const double g_a = band - std::abs(y.At(a));
    const double last = LastIn(y, sizes, band, a, b, g_a, g_b, resolution);
    if (last >= 0.0) return last;
    b = a;
    g_b = g_a;
  }
  return -1.0;
}

}  // namespace shapebench::model

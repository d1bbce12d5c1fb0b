// The last band crossing of a decaying free response (model/band_crossing.h) against the
// closed form of one damped mode, y = A e^{-zeta w t} cos(w_d t + phi): its |y| peaks
// where tan(w_d t + phi) = -zeta w / w_d, the last peak at or above the band is found by
// walking those peaks, and past it |y| falls monotonically to the next zero of the cosine,
// where the crossing is bisected. Tolerance 1e-12 s: the search resolves the crossing to
// 1e-13 of the period (40 ms here), the oracle's bisection to 1e-16 s.
#include "common/math_constants.h"
#include "model/band_crossing.h"

#include <cmath>
#include <complex>

#include <gtest/gtest.h>

namespace shapebench::model {
namespace {


struct DampedCosine {
  double amplitude, zeta, w, phi;
  double wd() const { return w * std::sqrt(1.0 - zeta * zeta); }
  double At(double t) const { return amplitude * std::exp(-zeta * w * t) * std::cos(wd() * t + phi); }
  FreeTerms Terms() const {
    // A e^{-sigma t} cos(w_d t + phi) = Re(A e^{i phi} e^{lambda t}), lambda = -sigma + i w_d.
    return {{std::polar(amplitude, phi)}, {std::complex<double>(-zeta * w, wd())}};
  }
};

double OracleLastCrossing(const DampedCosine& y, double band) {
  const double shift = -std::atan(y.zeta * y.w / y.wd());  // w_d t + phi at a peak of |y|, mod pi
  double last_peak = -1.0;
  for (int n = -2; n < 100000; ++n) {
    const double t = (shift + n * kPi - y.phi) / y.wd();
    if (t < 0.0) continue;
    if (std::abs(y.At(t)) >= band) last_peak = t;
    if (y.amplitude * std::exp(-y.zeta * y.w * t) < band) break;
  }
  if (std::abs(y.At(0.0)) >= band && last_peak < 0.0) last_peak = 0.0;
  if (last_peak < 0.0) return -1.0;
  // The next zero of the cosine after the peak: |y| decreases on [peak, zero].
  double zero = (kPi / 2 - y.phi) / y.wd();
  while (zero <= last_peak) zero += kPi / y.wd();
  double lo = last_peak;
  double hi = zero;
  while (hi - lo > 1e-16) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    (std::abs(y.At(mid)) >= band ? lo : hi) = mid;
  }
  return lo;
}

class OneModeCrossing : public ::testing::TestWithParam<double> {};

// Tests that the last crossing of one damped mode is the closed form's, for several phases
// and damping ratios, bands from just under the amplitude to far below it.
TEST_P(OneModeCrossing, MatchesClosedForm) {
  for (double zeta : {0.005, 0.02, 0.1, 0.5}) {
    for (double band : {0.9, 0.3, 0.05, 0.001}) {
      const DampedCosine y{1.0, zeta, 2.0 * kPi * 25.0, GetParam()};
      const double expected = OracleLastCrossing(y, band);
      EXPECT_NEAR(LastBandCrossing(y.Terms(), band), expected, 1e-12)
          << "zeta " << zeta << " band " << band << " phi " << GetParam();
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Phases, OneModeCrossing, ::testing::Values(0.0, 0.7, 1.5707, 2.9, -1.2));

// Tests the edge cases: inside the band from the start (-1), and no decay to bound the
// tail (NaN: the caller simulates it).
TEST(BandCrossing, InsideFromTheStartAndUndamped) {
  const DampedCosine small{0.01, 0.02, 150.0, 0.3};
  EXPECT_EQ(LastBandCrossing(small.Terms(), 0.05), -1.0);
  const DampedCosine undamped{1.0, 0.0, 150.0, 0.3};
  EXPECT_TRUE(std::isnan(LastBandCrossing(undamped.Terms(), 0.05)));
  EXPECT_TRUE(std::isnan(LastBandCrossing(small.Terms(), 0.0)));
}

// Tests two modes (a beat: the envelope sum is far from tight) against a dense scan of the
// sum backwards from the envelope's bound, 1e-7 s apart, then bisected.
TEST(BandCrossing, TwoModesMatchDenseScan) {
  const DampedCosine a{1.0, 0.02, 2.0 * kPi * 25.0, 0.4};
  const DampedCosine b{0.8, 0.015, 2.0 * kPi * 27.0, -1.0};
  FreeTerms terms = a.Terms();
  terms.q.push_back(b.Terms().q[0]);
  terms.lambda.push_back(b.Terms().lambda[0]);
  const double band = 0.05;
  const auto y = [&](double t) { return std::abs(a.At(t) + b.At(t)); };
  double t = std::log(1.8 / band) / (0.015 * 2.0 * kPi * 25.0);  // beyond the envelope's crossing
  while (t > 0.0 && y(t) < band) t -= 1e-7;
  double lo = t;
  double hi = t + 1e-7;
  while (hi - lo > 1e-16 && 0.5 * (lo + hi) != lo) (y(0.5 * (lo + hi)) >= band ? lo : hi) = 0.5 * (lo + hi);
  EXPECT_NEAR(LastBandCrossing(terms, band), lo, 1e-12);
}

}  // namespace
}  // namespace shapebench::model

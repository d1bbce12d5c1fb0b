// When a decaying free response leaves a band for good: the last t >= 0 with |y(t)| >=
// band, y(t) = sum_k Re(q_k e^{lambda_k t}) (a pole pair by its upper member with q
// doubled, a real pole as it is: model/free_response.h's modal split). Without simulating
// the decay:
// - the envelope E(t) = sum |q_k| e^{sigma_k t} bounds |y| and decreases; where it meets the
//   band (bisection) bounds the last crossing from above;
// - from there back, a quarter of the fastest pole's period at a time, an interval [a, b]
//   is cleared when (band - |y(a)|) + (band - |y(b)|) > M1 (b - a), M1 = sum |q_k|
//   |lambda_k| e^{sigma_k a} (a bound of |y'| on it), else halved: the first interval that
//   is not cleared holds the last crossing, found to 1e-13 of the fastest period
//   (a point closer to the band than M1 times that may be missed).
#pragma once

#include <complex>
#include <vector>

namespace shapebench::model {

struct FreeTerms {
  std::vector<std::complex<double>> q;
  std::vector<std::complex<double>> lambda;

  double At(double t) const;
  double Envelope(double t) const;
};

// The last t >= 0 with |y(t)| >= band; -1 when |y| < band from t = 0 on. NaN when that is
// not decided by a decay: band <= 0, or a term with q != 0 whose pole does not decay.
double LastBandCrossing(const FreeTerms& y, double band);

}  // namespace shapebench::model

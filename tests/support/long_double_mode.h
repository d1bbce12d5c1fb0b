// One structural mode (gain 1) in extended precision (long double: 64-bit mantissa), the
// single-mode tests' oracle: q'' + 2 zeta w q' + w^2 q = -a, a held, from the closed form
// of the exponential; the extremum inside a period by bisection on q' (not the kernel's
// atan2 formula).
#pragma once

#include <cmath>

#include "model/machine.h"

namespace shapebench::bench::testing {

class LongDoubleMode {
 public:
  using Real = long double;

  explicit LongDoubleMode(const model::ModalMode& mode) {
    const Real pi = 3.141592653589793238462643383279502884L;
    w_ = 2 * pi * static_cast<Real>(mode.frequency_hz);
    sigma_ = static_cast<Real>(mode.damping_ratio) * w_;
    wd_ = w_ * std::sqrt(1 - static_cast<Real>(mode.damping_ratio) * mode.damping_ratio);
  }
  // The state t after (q0, v0) under a.
  void Step(Real q0, Real v0, Real a, Real t, Real* q, Real* v) const {
    const Real q_eq = -a / (w_ * w_);
    const Real x0 = q0 - q_eq;
    const Real e = std::exp(-sigma_ * t);
    const Real c = std::cos(wd_ * t);
    const Real sn = std::sin(wd_ * t);
    *q = q_eq + e * (x0 * (c + sigma_ / wd_ * sn) + v0 * sn / wd_);
    *v = e * (v0 * (c - sigma_ / wd_ * sn) - x0 * w_ * w_ / wd_ * sn);
  }
  // The largest |q| inside [0, h] where q' changes sign: bisection on q' (not the
  // kernel's atan2 formula); 0 without a sign change.
  Real Inside(Real q0, Real v0, Real a, Real h) const {
    Real q1 = 0;
    Real v1 = 0;
    Step(q0, v0, a, h, &q1, &v1);
    if (!((v0 < 0) != (v1 < 0) && v0 != 0 && v1 != 0)) return 0;
    Real lo = 0;
    Real hi = h;
    for (int i = 0; i < 100; ++i) {
      const Real mid = 0.5L * (lo + hi);
      Real qm = 0;
      Real vm = 0;
      Step(q0, v0, a, mid, &qm, &vm);
      ((vm < 0) == (v0 < 0) ? lo : hi) = mid;
    }
    Real qm = 0;
    Real vm = 0;
    Step(q0, v0, a, 0.5L * (lo + hi), &qm, &vm);
    return std::abs(qm);
  }
  Real Amplitude(Real q, Real v) const { return std::hypot(q, (v + sigma_ * q) / wd_); }
  Real w() const { return w_; }
  Real wd() const { return wd_; }

 private:
  Real w_ = 0, sigma_ = 0, wd_ = 0;
};

}  // namespace shapebench::bench::testing

#include "model/tick_extremum.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include "common/math_constants.h"

namespace shapebench::model {
namespace {

// The multi-pole search (model/tick_extremum.h): an interval not cleared is halved no
// further once the extremum it can hide is at most kHiddenTolerance of the output's scale,
// or at kMaxDepth halvings of a grid step. kRoundingSlack widens the Taylor bounds by the
// rounding of y', y'' and y''' (sums of n terms, each within a few ulps of its magnitude:
// 1e-13 of the sum of magnitudes leaves room for ~1000 ulps).
constexpr int kMaxDepth = 15;
constexpr double kHiddenTolerance = 3e-10;
constexpr double kRoundingSlack = 1e-13;
constexpr double kTimeTolerance = 1e-15;  // of the period

using Complex = std::complex<double>;

}  // namespace

std::unique_ptr<TickExtremum> TickExtremum::Make(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b,
                                                 const Eigen::RowVectorXd& c, double h) {
  const Eigen::Index n = a.rows();
  if (n == 0 || !(h > 0.0) || !a.allFinite() || !b.allFinite() || !c.allFinite()) return nullptr;
  Eigen::EigenSolver<Eigen::MatrixXd> solver(a);
  if (solver.info() != Eigen::Success) return nullptr;
  const Eigen::VectorXcd lambda = solver.eigenvalues();
  const Eigen::MatrixXcd v = solver.eigenvectors();
  const double largest = lambda.cwiseAbs().maxCoeff();
  // A pole at 0 (a drive velocity among the states) has no equilibrium: keep the samples.
  if (!(largest > 0.0) || lambda.cwiseAbs().minCoeff() <= 1e-9 * largest) return nullptr;
  const Eigen::MatrixXcd v_inv = v.inverse();
  const Eigen::MatrixXcd identity = Eigen::MatrixXcd::Identity(n, n);
  // A defective a (a critically damped pair) has no trustworthy split
  // (ModalDecomposition::kMaxInverseError in model/free_response.h).
  if (!v_inv.allFinite() || !((v * v_inv - identity).norm() <= 1e-6)) return nullptr;
  const Eigen::RowVectorXcd cv = c.cast<Complex>() * v;
  const Eigen::MatrixXcd z_eq = -(lambda.cwiseInverse().asDiagonal() * (v_inv * b.cast<Complex>()));
  // The poles the output sees, a conjugate pair by its upper member (doubled in the sums).
  const double seen = 1e-12 * cv.cwiseAbs().maxCoeff();
  std::vector<Eigen::Index> kept;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (std::abs(cv(i)) > seen && lambda(i).imag() >= 0.0) kept.push_back(i);
  }
  auto e = std::unique_ptr<TickExtremum>(new TickExtremum());
  e->n_ = static_cast<int>(kept.size());
  e->m_ = static_cast<int>(b.cols());
  e->h_ = h;
  e->c_a_ = c * a;
  e->c_b_ = c * b;
  e->c_eq_ = -(c * a.partialPivLu().solve(b));
  e->lambda_.resize(e->n_);
  e->v_inv_.resize(e->n_, n);
  e->cv_.resize(e->n_);
  e->z_eq_.resize(e->n_, b.cols());
  e->weight_.resize(e->n_);
  double fastest = 0.0;
  for (int k = 0; k < e->n_; ++k) {
    const Eigen::Index i = kept[static_cast<std::size_t>(k)];
    e->lambda_(k) = lambda(i);
    e->v_inv_.row(k) = v_inv.row(i);
    e->cv_(k) = cv(i);
    e->z_eq_.row(k) = z_eq.row(i);
    e->weight_(k) = lambda(i).imag() > 0.0 ? 2.0 : 1.0;
    fastest = std::max(fastest, std::abs(lambda(i)));
  }
  e->q_.resize(e->n_);
  e->single_pole_ = e->n_ == 1 && lambda(kept.front()).imag() > 0.0;
  // One pair: roots of y' pi / w_d apart, the grid's step at most half that. Several poles:
  // a quarter of the fastest one's period (the bound test does the rest).
  const double step = e->single_pole_ ? 0.5 * kPi / e->lambda_(0).imag() : 0.5 * kPi / std::max(fastest, 1e-300);
  e->grid_ = static_cast<int>(std::min(1e6, std::max(1.0, std::ceil(h / step))));
  return e;
}

void TickExtremum::SetUpPeriod(const double* z0, const double* u) {
  const Eigen::Index n = v_inv_.cols();
  for (int k = 0; k < n_; ++k) {
    Complex z = 0.0;
    for (Eigen::Index j = 0; j < n; ++j) z += v_inv_(k, j) * z0[j];
    for (int i = 0; i < m_; ++i) z -= z_eq_(k, i) * u[i];
    q_(k) = weight_(k) * cv_(k) * z;
  }
  double y_eq = 0.0;
  for (int i = 0; i < m_; ++i) y_eq += c_eq_(i) * u[i];
  y_eq_ = y_eq;
}

double TickExtremum::OutputAt(double t) const {
  ++work_;
  double y = y_eq_;
  for (int k = 0; k < n_; ++k) y += (q_(k) * std::exp(lambda_(k) * t)).real();
  return y;
}

void TickExtremum::RateAndCurvature(double t, double* rate, double* curvature) const {
  ++work_;
  double r = 0.0;
  double d = 0.0;
  for (int k = 0; k < n_; ++k) {
    const Complex term = q_(k) * lambda_(k) * std::exp(lambda_(k) * t);
    r += term.real();
    d += (term * lambda_(k)).real();
  }
  *rate = r;
  *curvature = d;
}

double TickExtremum::Rate(double t) const {
  double r = 0.0;
  double d = 0.0;
  RateAndCurvature(t, &r, &d);
  return r;
}

// sum |q_i| |lambda_i|^power e^{sigma_i t} at its largest on [lo, hi]: a bound of
// |y^(power)| there.
double TickExtremum::DerivativeBound(double lo, double hi, int power) const {
  ++work_;
  double bound = 0.0;
  for (int k = 0; k < n_; ++k) {
    const double sigma = lambda_(k).real();
    bound += std::abs(q_(k)) * std::pow(std::abs(lambda_(k)), power) * std::exp(std::max(sigma * lo, sigma * hi));
  }
  return bound;
}

// Safeguarded Newton on y' in [lo, hi], y'(lo) = rate_lo and y'(hi) of the other sign.
double TickExtremum::Refine(double lo, double hi, double rate_lo) const {
  double t = 0.5 * (lo + hi);
  for (int iteration = 0; iteration < 200; ++iteration) {
    double r = 0.0;
    double d = 0.0;
    RateAndCurvature(t, &r, &d);
    if (r == 0.0) return t;
    if ((r < 0.0) == (rate_lo < 0.0)) {
      lo = t;
    } else {
      hi = t;
    }
    double next = t - r / d;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - t) <= kTimeTolerance * h_ || hi - lo <= kTimeTolerance * h_) return next;
    t = next;
  }
  return t;
}

void TickExtremum::Search(double lo, double hi, double rate_lo, double rate_hi, int depth, double* best) const {
  const bool change = (rate_lo < 0.0) != (rate_hi < 0.0) && rate_lo != 0.0 && rate_hi != 0.0;
  if (!single_pole_) {
    // Several poles: a sign change with y'' of one sign holds exactly one root; no sign
    // change and |y'| kept off 0 by the bound of y'' holds none. Else halve, or stop.
    double r = 0.0;
    double d = 0.0;
    RateAndCurvature(lo, &r, &d);
    const bool settled = change ? std::abs(d) > DerivativeBound(lo, hi, 3) * (hi - lo)
                                : std::abs(rate_lo) + std::abs(rate_hi) > DerivativeBound(lo, hi, 2) * (hi - lo);
    if (!settled) {
      const TaylorBounds taylor = Taylor(lo, hi);
      const double w = hi - lo;
      // No sign change and y' kept off 0 by its Taylor polynomial from lo: no root (what
      // the halving would have found too, sooner where the modes cancel).
      if (!change && std::abs(rate_lo) - kRoundingSlack * taylor.rate_bound >
                         taylor.curvature * w + 0.5 * taylor.jerk_bound * w * w) {
        return;
      }
      if (depth >= kMaxDepth || taylor.curvature_bound * w * w / 8.0 <= kHiddenTolerance * scale_) {
        CountEnds(lo, hi, best);
        return;
      }
      const double mid = 0.5 * (lo + hi);
      const double rate_mid = Rate(mid);
      if (rate_mid == 0.0) *best = std::max(*best, std::abs(OutputAt(mid)));
      Search(lo, mid, rate_lo, rate_mid, depth + 1, best);
      Search(mid, hi, rate_mid, rate_hi, depth + 1, best);
      return;
    }
  }
  if (change) *best = std::max(*best, std::abs(OutputAt(Refine(lo, hi, rate_lo))));
}

// One pass over the poles: M1..M4 on [lo, hi] (sum |q_i| |lambda_i|^k e^{sigma_i t} at its
// largest), y'' and y''' at lo, and from them bounds of |y''| and |y'''| on [lo, hi], the
// smaller of M_k and the Taylor bound from lo, which sees the modes' cancellation (each
// value at lo widened by its rounding, kRoundingSlack of its M).
TickExtremum::TaylorBounds TickExtremum::Taylor(double lo, double hi) const {
  ++work_;
  double m[5] = {0.0, 0.0, 0.0, 0.0, 0.0};
  double curvature = 0.0;
  double jerk = 0.0;
  for (int k = 0; k < n_; ++k) {
    const double sigma = lambda_(k).real();
    const double magnitude = std::abs(lambda_(k));
    double term = std::abs(q_(k)) * std::exp(std::max(sigma * lo, sigma * hi));
    for (int power = 1; power <= 4; ++power) {
      term *= magnitude;
      m[power] += term;
    }
    const Complex second = q_(k) * lambda_(k) * lambda_(k) * std::exp(lambda_(k) * lo);
    curvature += second.real();
    jerk += (second * lambda_(k)).real();
  }
  const double w = hi - lo;
  TaylorBounds out;
  out.rate_bound = m[1];
  out.curvature = std::abs(curvature) + kRoundingSlack * m[2];
  out.jerk_bound = std::min(m[3], std::abs(jerk) + kRoundingSlack * m[3] + m[4] * w);
  out.curvature_bound = std::min(m[2], out.curvature + out.jerk_bound * w);
  return out;
}

// The ends of an interval the search stopped halving: values y takes inside the period
// (the period's own ends are the caller's samples).
void TickExtremum::CountEnds(double lo, double hi, double* best) const {
  ++stopped_;
  if (lo > 0.0) *best = std::max(*best, std::abs(OutputAt(lo)));
  if (hi < h_) *best = std::max(*best, std::abs(OutputAt(hi)));
}

double TickExtremum::Inside(const double* z0, const double* u, double d0, double d1) {
  work_ = 0;
  stopped_ = 0;
  if (n_ == 0) return 0.0;
  SetUpPeriod(z0, u);
  if (!single_pole_) {
    double scale = std::abs(y_eq_);
    for (int k = 0; k < n_; ++k) scale += std::abs(q_(k)) * std::exp(std::max(0.0, lambda_(k).real() * h_));
    scale_ = scale;
  }
  if (single_pole_ && grid_ == 1) {
    // Closed form: y' = |q lambda| e^{sigma t} cos(w_d t + arg(q lambda)) vanishes where
    // w_d t + arg(q lambda) = pi / 2 (mod pi), once in the period (the sign change).
    const double wd = lambda_(0).imag();
    const double half = kPi / wd;
    double t = std::fmod(0.5 * kPi - std::arg(q_(0) * lambda_(0)), kPi) / wd;
    if (t < 0.0) t += half;
    if (!(t > 0.0 && t < h_)) t = Refine(0.0, h_, d0);  // rounding at an end of the period
    return std::abs(OutputAt(t));
  }
  double best = 0.0;
  const double step = h_ / grid_;
  double lo = 0.0;
  double rate_lo = d0;
  for (int g = 1; g <= grid_; ++g) {
    const double hi = g == grid_ ? h_ : step * g;
    const double rate_hi = g == grid_ ? d1 : Rate(hi);
    if (g < grid_ && rate_hi == 0.0) best = std::max(best, std::abs(OutputAt(hi)));
    Search(lo, hi, rate_lo, rate_hi, 0, &best);
    lo = hi;
    rate_lo = rate_hi;
  }
  return best;
}

}  // namespace shapebench::model

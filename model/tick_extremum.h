// The extrema of one output of a linear plant inside an interpolation period, exactly,
// instead of from output substeps. With the input u held over the period the output is
// y(t) = y_eq + sum_i q_i e^{lambda_i t} (A = V diag(lambda) V^{-1}, q_i = (c V)_i
// (z_i(0) - z_eq,i), z = V^{-1} x): a sum of damped sinusoids plus a constant, whose
// extrema lie where y'(t) = sum_i q_i lambda_i e^{lambda_i t} changes sign.
//
// How the roots of y' are found (and why none is missed):
// - y' at a grid of points over the period (the ends from the states, c A x + c B u,
//   without the modal split), a sign change brackets a root, refined by safeguarded Newton
//   (bisection where a Newton step leaves the bracket) to 1e-15 of the period in time.
// - One oscillatory pole pair seen by the output (a single mode): y' =
//   2 |q lambda| e^{sigma t} cos(w_d t + phi), whose roots are simple and pi / w_d apart;
//   the grid is finer than half that, so no interval holds two roots: every root is found.
//   With the period itself that short, the root is the closed form w_d t + arg(q lambda)
//   = pi / 2 (mod pi), no iteration.
// - Several poles: an interval without a sign change is cleared only if
//   |y'(a)| + |y'(b)| > M2 (b - a), M2 = sum |q_i| |lambda_i|^2 e^{sigma_i t} (a bound of
//   |y''| on it), which rules out any root; one with a sign change is left to Newton only
//   if |y''(a)| > M3 (b - a) (y'' of one sign: one root). Otherwise it is halved.
// - The work is bounded. M2 ignores cancellation between the modes (two modes of opposite
//   gains at one frequency, or at 25 and 25.01 Hz, give a y' far below M2 (b - a) on every
//   interval: the halving ran to 2^30 intervals a tick and a run never ended). So an
//   interval without a sign change is also cleared when y' is kept off 0 by its Taylor
//   polynomial from a, |y'(a)| > |y''(a)| w + B3 w^2 / 2 (w = b - a; B3 a bound of |y'''|,
//   the smaller of M3 and |y'''(a)| + M4 w, each value at a widened by its rounding), which
//   sees the cancellation. And an interval still not cleared is halved no further once
//   the extremum it can hide, B2 w^2 / 8 (B2 the smaller of M2 and |y''(a)| + B3 w), is at
//   most 3e-10 of the output's scale S = |y_eq| + sum |q_i| e^{max(0, sigma_i h)} (a
//   bound of |y| over the period), or at 2^-15 of the grid step (kMaxDepth); its ends,
//   values y takes inside the period, are counted instead of a root. On such an interval
//   max |y| <= max(|y(a)|, |y(b)|) + B2 w^2 / 8 (y less its chord bends at most B2), and
//   at 2^-15 of a step no longer than a quarter of the fastest pole's period M2 w^2 / 8 <=
//   (pi^2 / 32) 4^-15 S < 3e-10 S too. So the in-tick extremum is never above the true
//   one (to rounding) and at most 3e-10 S below it; exact (its time to 1e-15 of the
//   period) where every interval is cleared, as on ordinary plants (on the shipped
//   scenarios one interval is stopped: at the start of a gantry_zvd period where y'(0) is
//   exactly 0, a root at the end, which the halving cannot clear; no output moved). At
//   most 2^16 - 1 intervals a grid step; in practice a few dozen passes over the poles,
//   and at most ~2600 where the output is rounding only (modes that cancel exactly, a
//   grid step of a quarter period). The grid itself is at most 1e6 steps, beyond which
//   (a pole above ~2.5e5 cycles a period) the step exceeds a quarter period and the
//   2^-15 bound is M2 w^2 / 8 as it stands. last_work() counts the passes over the poles (y, y' and y'',
//   or the bounds, at one time) of the last call: tests/model/tick_extremum_test.cc holds
//   random mode sets, coincident, cancelling and nearly coincident ones among them, to a
//   dense closed-form oracle within 3e-10 S and to 4000 passes a grid step.
#pragma once

#include <memory>

#include <Eigen/Dense>

namespace shapebench::model {

class TickExtremum {
 public:
  // z' = a z + b u over a period of h; the watched output y = c z. Null when a does not
  // split into modes well (a defective or singular a, e.g. a drive velocity state, or a
  // pole at 0): the caller keeps its samples.
  static std::unique_ptr<TickExtremum> Make(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b,
                                            const Eigen::RowVectorXd& c, double h);

  // The largest |y| at a stationary point strictly inside (0, h) of the period from state
  // z0 to z1 under input u (arrays of the sizes of a and b); 0 when there is none (the
  // ends are the caller's samples). No allocation.
  double LargestInside(const double* z0, const double* z1, const double* u) {
    const Eigen::Index n = c_a_.size();
    double d0 = 0.0;
    double d1 = 0.0;
    for (Eigen::Index j = 0; j < n; ++j) {
      d0 += c_a_(j) * z0[j];
      d1 += c_a_(j) * z1[j];
    }
    double forced = 0.0;
    for (int i = 0; i < m_; ++i) forced += c_b_(i) * u[i];
    d0 += forced;
    d1 += forced;
    // The common case (one mode, a period shorter than half its period): no sign change
    // of y' over the period, no extremum inside it, nothing more to compute (inline).
    if (single_pole_ && grid_ == 1 && !(d0 * d1 < 0.0)) return Nothing();
    return Inside(z0, u, d0, d1);
  }

  // LargestInside with y'(0) and y'(h) given: sums over rate_row() (c a) of z0 and z1, in
  // index order, each plus ForcedRate(u), as LargestInside computes them (the same bits).
  double LargestInsideWithRates(const double* z0, const double* u, double d0, double d1) {
    if (single_pole_ && grid_ == 1 && !(d0 * d1 < 0.0)) return Nothing();
    return Inside(z0, u, d0, d1);
  }
  const Eigen::RowVectorXd& rate_row() const { return c_a_; }
  double ForcedRate(const double* u) const {
    double forced = 0.0;
    for (int i = 0; i < m_; ++i) forced += c_b_(i) * u[i];
    return forced;
  }

  // y at time t of the current period (after LargestInside set it up; 0 when it had
  // nothing to set up).
  double OutputAt(double t) const;

  bool single_pole() const { return single_pole_; }
  // The last LargestInside*'s work: passes over the poles (y, y' and y'', or a derivative
  // bound, at one time), and intervals it stopped halving at the tolerance or the depth cap
  // (0 when every interval was cleared: the extremum exact).
  long last_work() const { return work_; }
  long last_stopped_intervals() const { return stopped_; }
  int grid_intervals() const { return grid_; }

 private:
  TickExtremum() = default;
  double Nothing() {
    work_ = 0;
    stopped_ = 0;
    return 0.0;
  }
  double Inside(const double* z0, const double* u, double d0, double d1);  // y'(0), y'(h)
  void SetUpPeriod(const double* z0, const double* u);
  double Rate(double t) const;  // y'(t)
  void RateAndCurvature(double t, double* rate, double* curvature) const;  // y', y''
  double DerivativeBound(double lo, double hi, int power) const;
  double Refine(double lo, double hi, double rate_lo) const;
  void Search(double lo, double hi, double rate_lo, double rate_hi, int depth, double* best) const;
  struct TaylorBounds {
    double rate_bound;       // M1 on [lo, hi]: the scale of y' (its rounding)
    double curvature;        // |y''(lo)| with its rounding
    double jerk_bound;       // of |y'''| on [lo, hi]
    double curvature_bound;  // of |y''| on [lo, hi]
  };
  TaylorBounds Taylor(double lo, double hi) const;
  void CountEnds(double lo, double hi, double* best) const;

  int n_ = 0;
  int m_ = 0;
  double h_ = 0.0;
  int grid_ = 1;
  bool single_pole_ = false;
  Eigen::RowVectorXd c_a_;        // c a: y' = c a z + c b u
  Eigen::RowVectorXd c_b_;
  Eigen::RowVectorXd c_eq_;       // y_eq = c_eq u (= -c a^{-1} b u)
  Eigen::VectorXcd lambda_;
  Eigen::MatrixXcd v_inv_;
  Eigen::RowVectorXcd cv_;        // c V
  Eigen::MatrixXcd z_eq_;         // modal equilibrium per input: -diag(1/lambda) V^{-1} b
  Eigen::VectorXd weight_;        // 2 for a pair's upper member, 1 for a real pole
  // The current period's: q_i and y_eq.
  Eigen::VectorXcd q_;
  double y_eq_ = 0.0;
  double scale_ = 0.0;  // |y_eq| + sum |q_i| e^{max(0, sigma_i h)} (the multi-pole search's)
  mutable long work_ = 0;
  mutable long stopped_ = 0;
};

}  // namespace shapebench::model

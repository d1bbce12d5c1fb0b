// Newton's method on a shaper's vibration conditions; see the header.
#include "controller/vibration_conditions.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>

#include <Eigen/Dense>

namespace shapebench::controller {
namespace {

using Complex = std::complex<double>;

Complex Pole(double zeta) { return {zeta, std::sqrt(1.0 - zeta * zeta)}; }

// R, dR/dr and d2R/dr2 at one ratio, and each impulse's e^{r c p_j}.
struct Phasors {
  Complex r0, r1, r2;
  std::vector<Complex> e;
};

Phasors Evaluate(const ConditionedShaper& s, double ratio, Complex c) {
  Phasors p;
  for (std::size_t j = 0; j < s.amplitudes.size(); ++j) {
    const double a = s.amplitudes[j];
    const double t = s.phases[j];
    const Complex e = std::exp(ratio * c * t);
    p.e.push_back(e);
    p.r0 += a * e;
    p.r1 += a * c * t * e;
    p.r2 += a * c * c * t * t * e;
  }
  return p;
}

// How R and dR/dr at one condition move with one unknown, and the decay terms of a hump's
// two equations (zeta r p_n in its value, zeta p_n in its slope).
struct Partial {
  Complex d0, d1;
  double d_value_decay = 0.0;
  double d_slope_decay = 0.0;
};

// Writes condition `k`'s two rows of the residual F and of the Jacobian J.
void AssembleCondition(const ConditionedShaper& s, std::size_t k, int free_column, double zeta,
                       double tolerance, Eigen::VectorXd& f, Eigen::MatrixXd& jacobian) {
  const VibrationCondition& condition = s.conditions[k];
  const std::size_t n = s.amplitudes.size();
  const Complex c = Pole(zeta);
  const double r = condition.ratio;
  const double last = s.phases.back();
  const Phasors p = Evaluate(s, r, c);
  const Eigen::Index row = 1 + 2 * static_cast<Eigen::Index>(k);
  const double q = std::norm(p.r0);
  const double g = (std::conj(p.r0) * p.r1).real();
  const bool hump = condition.kind == ConditionKind::kHump;
  if (hump) {
    f(row) = 0.5 * std::log(q) - zeta * r * last - std::log(tolerance);
    f(row + 1) = g / q - zeta * last;
  } else {
    f(row) = p.r0.real();
    f(row + 1) = p.r0.imag();
  }
  const auto write = [&](Eigen::Index column, const Partial& d) {
    if (hump) {
      const double dq = 2.0 * (std::conj(p.r0) * d.d0).real();
      const double dg = (std::conj(d.d0) * p.r1 + std::conj(p.r0) * d.d1).real();
      jacobian(row, column) = 0.5 * dq / q - d.d_value_decay;
      jacobian(row + 1, column) = (dg * q - g * dq) / (q * q) - d.d_slope_decay;
    } else {
      jacobian(row, column) = d.d0.real();
      jacobian(row + 1, column) = d.d0.imag();
    }
  };
  for (std::size_t j = 0; j < n; ++j) {
    write(static_cast<Eigen::Index>(j), {p.e[j], c * s.phases[j] * p.e[j]});
  }
  for (std::size_t j = 1; j < n; ++j) {
    const double a = s.amplitudes[j];
    Partial d{a * r * c * p.e[j], a * c * p.e[j] * (1.0 + r * c * s.phases[j])};
    if (j == n - 1) {
      d.d_value_decay = zeta * r;
      d.d_slope_decay = zeta;
    }
    write(static_cast<Eigen::Index>(n + j - 1), d);
  }
  if (free_column >= 0) write(free_column, {p.r1, p.r2, zeta * last, 0.0});
}

// The unknowns as one vector (amplitudes, phases 2..n, free ratios) and back.
Eigen::VectorXd Unknowns(const ConditionedShaper& s) {
  std::vector<double> x = s.amplitudes;
  x.insert(x.end(), s.phases.begin() + 1, s.phases.end());
  for (const VibrationCondition& c : s.conditions) {
    if (!c.fixed) x.push_back(c.ratio);
  }
  return Eigen::Map<Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(x.size()));
}

void SetUnknowns(const Eigen::VectorXd& x, ConditionedShaper* s) {
  const std::size_t n = s->amplitudes.size();
  Eigen::Index i = 0;
  for (std::size_t j = 0; j < n; ++j) s->amplitudes[j] = x(i++);
  for (std::size_t j = 1; j < n; ++j) s->phases[j] = x(i++);
  for (VibrationCondition& c : s->conditions) {
    if (!c.fixed) c.ratio = x(i++);
  }
}

// Newton's method at one damping ratio, from `s`; true once converged to rounding.
bool Newton(double zeta, double tolerance, ConditionedShaper* s) {
  const Eigen::Index size = Unknowns(*s).size();
  bool polishing = false;
  for (int iteration = 0; iteration < 50; ++iteration) {
    Eigen::VectorXd f = Eigen::VectorXd::Zero(size);
    Eigen::MatrixXd jacobian = Eigen::MatrixXd::Zero(size, size);
    double sum = -1.0;
    for (std::size_t j = 0; j < s->amplitudes.size(); ++j) {
      sum += s->amplitudes[j];
      jacobian(0, static_cast<Eigen::Index>(j)) = 1.0;
    }
    f(0) = sum;
    int free_column = static_cast<int>(2 * s->amplitudes.size() - 1);
    for (std::size_t k = 0; k < s->conditions.size(); ++k) {
      const int column = s->conditions[k].fixed ? -1 : free_column++;
      AssembleCondition(*s, k, column, zeta, tolerance, f, jacobian);
    }
    if (!f.allFinite() || !jacobian.allFinite()) return false;
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(jacobian);
    if (!lu.isInvertible()) return false;
    const Eigen::VectorXd step = lu.solve(-f);
    SetUnknowns(Unknowns(*s) + step, s);
    // Quadratic convergence: after a step this small the error is below rounding; one more
    // step polishes the last digits.
    if (polishing) return true;
    polishing = step.cwiseAbs().maxCoeff() < 1e-9;
  }
  return false;
}

// The solved design still on the undamped one's branch (see the header).
bool OnBranch(const ConditionedShaper& s) {
  for (std::size_t j = 0; j < s.amplitudes.size(); ++j) {
    if (!(s.amplitudes[j] > 0.0)) return false;
    if (j > 0 && !(s.phases[j] > s.phases[j - 1])) return false;
  }
  for (std::size_t k = 0; k < s.conditions.size(); ++k) {
    if (!(s.conditions[k].ratio > 0.0)) return false;
    if (k > 0 && !(s.conditions[k].ratio > s.conditions[k - 1].ratio)) return false;
  }
  return true;
}

}  // namespace

double ConditionedResidual(const ConditionedShaper& shaper, double ratio, double zeta) {
  const Phasors p = Evaluate(shaper, ratio, Pole(zeta));
  return std::exp(-zeta * ratio * shaper.phases.back()) * std::abs(p.r0);
}

std::optional<ConditionedShaper> SolveForDamping(const ConditionedShaper& undamped, double zeta,
                                                 double tolerance) {
  ConditionedShaper s = undamped;
  if (Unknowns(s).size() != 1 + 2 * static_cast<Eigen::Index>(s.conditions.size()) ||
      s.phases.size() != s.amplitudes.size() || s.phases.front() != 0.0) {
    throw std::invalid_argument("SolveForDamping: as many unknowns as equations needed, phases from 0");
  }
  if (!OnBranch(s)) return std::nullopt;
  const int stages = std::max(1, static_cast<int>(std::ceil(zeta / 0.02)));
  for (int stage = 1; stage <= stages; ++stage) {
    if (!Newton(zeta * stage / stages, tolerance, &s) || !OnBranch(s)) return std::nullopt;
  }
  return s;
}

}  // namespace shapebench::controller

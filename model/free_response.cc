#include "model/free_response.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "common/math_constants.h"

namespace shapebench::model {
namespace {

// Poles closer than this share of the largest |lambda| are one (the same mode of two axes:
// rounding separates them by ~1e-15 of it); distinct modes of a model differ far more.
constexpr double kSamePole = 1e-9;

// The poles of `lambda`: pairs by their upper member, equal ones together, ascending
// frequency. A pole whose imaginary part is within rounding of 0 is real.
std::vector<FreePole> GroupPoles(const Eigen::VectorXcd& lambda) {
  double scale = 0.0;
  for (Eigen::Index i = 0; i < lambda.size(); ++i) scale = std::max(scale, std::abs(lambda(i)));
  const double same = kSamePole * scale;
  std::vector<FreePole> poles;
  for (Eigen::Index i = 0; i < lambda.size(); ++i) {
    const std::complex<double> l = lambda(i);
    const bool oscillatory = std::abs(l.imag()) > same;
    if (oscillatory && l.imag() < 0.0) continue;  // the pair's lower member
    auto found = std::find_if(poles.begin(), poles.end(), [&](const FreePole& p) {
      return p.oscillatory == oscillatory && std::abs(lambda(p.members.front()) - l) <= same;
    });
    if (found == poles.end()) {
      FreePole pole;
      const double magnitude = std::abs(l);
      pole.frequency_hz = magnitude / kTwoPi;
      pole.damping_ratio = magnitude > 0.0 ? (0.0 - l.real()) / magnitude : 0.0;  // never -0
      pole.oscillatory = oscillatory;
      poles.push_back(pole);
      found = poles.end() - 1;
    }
    found->members.push_back(static_cast<int>(i));
  }
  std::stable_sort(poles.begin(), poles.end(),
                   [](const FreePole& a, const FreePole& b) { return a.frequency_hz < b.frequency_hz; });
  return poles;
}

// A pair's envelope `envelope` = |p| capped (CappedResidual) at sqrt(n) ResidualCap(zeta)
// times the largest PairPeak of the n rows of p that are not 0, y_r(t) = Re(p_r e^{lambda t}):
// y_r(0) = Re(p_r), y_r'(0) = Re(lambda p_r).
double CappedPairAmplitude(double envelope, const Eigen::VectorXcd& p, std::complex<double> lambda, double zeta,
                           bool* capped) {
  double peak = 0.0;
  int rows = 0;
  for (Eigen::Index r = 0; r < p.size(); ++r) {
    if (p(r) == 0.0) continue;
    ++rows;
    peak = std::max(peak, PairPeak(p(r).real(), (lambda * p(r)).real(), -lambda.real(), lambda.imag()));
  }
  const double amplitude = CappedResidual(envelope, peak, std::sqrt(static_cast<double>(rows)) * ResidualCap(zeta));
  *capped = amplitude != envelope && !std::isnan(envelope);
  return amplitude;
}

}  // namespace

double PairPeak(double y0, double y0dot, double sigma, double wd) {
  // y' = e^{-sigma t} (y0' cos(w_d t) - (sigma y0' + w^2 y0) sin(w_d t) / w_d), w^2 = sigma^2 + w_d^2.
  const double w2 = sigma * sigma + wd * wd;
  double theta = std::atan2(wd * y0dot, sigma * y0dot + w2 * y0);
  if (theta < 0.0) theta += kPi;
  if (theta >= kPi) theta -= kPi;
  const double t = theta / wd;
  const double at = std::exp(-sigma * t) * (y0 * std::cos(theta) + (y0dot + sigma * y0) * (std::sin(theta) / wd));
  return std::max(std::abs(y0), std::abs(at));
}

double ResidualCap(double damping_ratio) {
  const double z = std::clamp(std::min(damping_ratio, 1.0 - damping_ratio), 0.0, 0.5);
  return std::exp(kPi * z / std::sqrt(1.0 - z * z)) * (1.0 + 1e-9);
}

ModalDecomposition::ModalDecomposition(const Eigen::MatrixXd& a) {
  const Eigen::EigenSolver<Eigen::MatrixXd> solver(a, true);
  lambda_ = solver.eigenvalues();
  v_ = solver.eigenvectors();
  const Eigen::FullPivLU<Eigen::MatrixXcd> lu(v_);
  v_inv_ = lu.inverse();
  // A defective A has (numerically) parallel eigenvectors: V^{-1} is then no inverse.
  const Eigen::Index n = v_.rows();
  const double inverse_error = (v_ * v_inv_ - Eigen::MatrixXcd::Identity(n, n)).cwiseAbs().maxCoeff();
  invertible_ = lu.isInvertible() && std::isfinite(inverse_error) && inverse_error <= kMaxInverseError;
  poles_ = GroupPoles(lambda_);
  BuildRealBasis(a);
}

void ModalDecomposition::BuildRealBasis(const Eigen::MatrixXd& a) {
  const Eigen::Index n = v_.rows();
  basis_ = Eigen::MatrixXd::Zero(n, n);
  Eigen::Index column = 0;
  for (const FreePole& pole : poles_) {
    std::vector<Eigen::Index> columns;
    for (int i : pole.members) {
      Eigen::VectorXcd v = v_.col(i);
      const std::complex<double> vtv = v.transpose() * v;
      v *= std::polar(1.0, -0.5 * std::arg(vtv));
      if (column + (pole.oscillatory ? 2 : 1) > n) return;  // not a basis: the fallback stays off
      columns.push_back(column);
      basis_.col(column++) = v.real().normalized();
      if (pole.oscillatory) {
        columns.push_back(column);
        basis_.col(column++) = v.imag().normalized();
      }
    }
    pole_columns_.push_back(columns);
  }
  if (column != n) return;
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(basis_);
  basis_inv_ = lu.inverse();
  const double inverse_error = (basis_ * basis_inv_ - Eigen::MatrixXd::Identity(n, n)).cwiseAbs().maxCoeff();
  real_invertible_ = lu.isInvertible() && std::isfinite(inverse_error) && inverse_error <= kMaxInverseError;
  a_basis_ = a * basis_;
}

std::vector<PoleAmplitude> ModalDecomposition::AmplitudesOfState(const Eigen::MatrixXd& c,
                                                                 const Eigen::VectorXd& x) const {
  std::vector<PoleAmplitude> amplitudes;
  amplitudes.reserve(poles_.size());
  Eigen::VectorXd alpha = Eigen::VectorXd::Zero(x.size());
  bool reliable = real_invertible_;
  if (reliable) {
    alpha = basis_inv_ * x;
    const double parts = alpha.cwiseAbs().sum();  // the columns have norm 1
    reliable = std::isfinite(parts) && parts <= kMaxCancellation * (basis_ * alpha).norm() + 1e-300;
  }
  for (std::size_t p = 0; p < poles_.size(); ++p) {
    const FreePole& pole = poles_[p];
    if (!reliable) {
      amplitudes.push_back({pole.frequency_hz, pole.damping_ratio, NAN});
      continue;
    }
    // The pole's part of the output and of its rate at t = 0.
    Eigen::VectorXd y0 = Eigen::VectorXd::Zero(c.rows());
    Eigen::VectorXd y0dot = Eigen::VectorXd::Zero(c.rows());
    for (const Eigen::Index k : pole_columns_[p]) {
      y0 += c * basis_.col(k) * alpha(k);
      y0dot += c * a_basis_.col(k) * alpha(k);
    }
    double amplitude = y0.norm();
    bool capped = false;
    if (pole.oscillatory) {
      // y(t) = Re(p e^{lambda t}): Re p = y0, y'(0) = Re(lambda p) = -sigma y0 - w_d Im p.
      const std::complex<double> lambda = lambda_(pole.members.front());
      const Eigen::VectorXcd pair =
          y0.cast<std::complex<double>>() -
          std::complex<double>(0.0, 1.0) * ((y0dot - lambda.real() * y0) / lambda.imag()).cast<std::complex<double>>();
      amplitude = CappedPairAmplitude(pair.norm(), pair, lambda, pole.damping_ratio, &capped);
    }
    amplitudes.push_back({pole.frequency_hz, pole.damping_ratio, amplitude, capped});
  }
  return amplitudes;
}

bool ModalDecomposition::WellSplit(const Eigen::VectorXcd& z) const {
  if (!invertible_) return false;
  double parts = 0.0;
  for (Eigen::Index i = 0; i < z.size(); ++i) parts += std::abs(z(i)) * v_.col(i).norm();
  const double whole = (v_ * z).norm();
  return std::isfinite(parts) && parts <= kMaxCancellation * whole + 1e-300;
}

std::vector<PoleAmplitude> ModalDecomposition::Amplitudes(const Eigen::MatrixXcd& cv,
                                                          const Eigen::VectorXcd& z) const {
  const bool reliable = WellSplit(z);
  std::vector<PoleAmplitude> amplitudes;
  amplitudes.reserve(poles_.size());
  for (const FreePole& pole : poles_) {
    Eigen::VectorXcd part = Eigen::VectorXcd::Zero(cv.rows());
    for (int i : pole.members) part += cv.col(i) * z(i);
    double amplitude = (pole.oscillatory ? 2.0 : 1.0) * part.norm();
    bool capped = false;
    if (pole.oscillatory) {
      amplitude =
          CappedPairAmplitude(amplitude, 2.0 * part, lambda_(pole.members.front()), pole.damping_ratio, &capped);
    }
    amplitudes.push_back({pole.frequency_hz, pole.damping_ratio, reliable ? amplitude : NAN, capped});
  }
  return amplitudes;
}

std::shared_ptr<const ModalDecomposition> DecomposeModes(const Eigen::MatrixXd& a) {
  struct Entry {
    Eigen::MatrixXd a;
    std::shared_ptr<const ModalDecomposition> result;
  };
  constexpr std::size_t kKept = 8;
  thread_local std::vector<Entry> cache;  // most recent first
  for (std::size_t i = 0; i < cache.size(); ++i) {
    if (cache[i].a.rows() == a.rows() && cache[i].a.cols() == a.cols() && cache[i].a == a) {
      std::rotate(cache.begin(), cache.begin() + static_cast<std::ptrdiff_t>(i),
                  cache.begin() + static_cast<std::ptrdiff_t>(i) + 1);
      return cache.front().result;
    }
  }
  auto result = std::make_shared<const ModalDecomposition>(a);
  cache.insert(cache.begin(), Entry{a, result});
  if (cache.size() > kKept) cache.pop_back();
  return result;
}

}  // namespace shapebench::model

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

}  // namespace

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
    const double amplitude = (pole.oscillatory ? 2.0 : 1.0) * part.norm();
    amplitudes.push_back({pole.frequency_hz, pole.damping_ratio, reliable ? amplitude : NAN});
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

#include "bench/run/damped_tail.h"

namespace shapebench::bench {

DampedTail::DampedTail(const model::LinearPlant& plant, const OutputView& view)
    : modes_(model::DecomposeModes(plant.A)),
      cv_(plant.C.cast<std::complex<double>>() * modes_->eigenvectors()),
      view_row_(model::kDeflectionRow + view.axis) {}

bool DampedTail::Split(const Eigen::VectorXd& x) {
  const Eigen::VectorXcd z = modes_->Coordinates(x);
  if (!modes_->WellSplit(z)) return false;
  const Eigen::VectorXcd& lambda = modes_->eigenvalues();
  for (int r = 0; r < model::kNumOutputRows; ++r) {
    model::FreeTerms& terms = rows_[r];
    terms.q.clear();
    terms.lambda.clear();
    for (Eigen::Index i = 0; i < z.size(); ++i) {
      // A pair by its upper member, doubled (the lower one is its conjugate).
      if (lambda(i).imag() < 0.0) continue;
      const std::complex<double> q = (lambda(i).imag() > 0.0 ? 2.0 : 1.0) * cv_(r, i) * z(i);
      if (q == 0.0) continue;
      terms.q.push_back(q);
      terms.lambda.push_back(lambda(i));
    }
  }
  return true;
}

}  // namespace shapebench::bench

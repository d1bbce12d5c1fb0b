#include "bench/run/residual_vibration.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "model/multi_axis_machine.h"

namespace shapebench::bench {

ResidualVibration::ResidualVibration(const model::LinearPlant& plant, const OutputView& view)
    : modes_(model::DecomposeModes(plant.A)) {
  // The magnitude view bounds the norm of the deflection vector: every deflection row.
  const int first = view.axis >= 0 ? model::kDeflectionRow + view.axis : model::kDeflectionRow;
  const int rows = view.axis >= 0 ? 1 : model::kNumAxes;
  c_ = plant.C.middleRows(first, rows);
  cv_ = c_.cast<std::complex<double>>() * modes_->eigenvectors();
  for (const model::FreePole& pole : modes_->poles()) {
    bool seen = false;
    for (int i : pole.members) seen = seen || cv_.col(i).cwiseAbs().maxCoeff() > 0.0;
    visible_.push_back(seen ? 1 : 0);
  }
  loads_velocity_ = plant.B_vel.cwiseAbs().maxCoeff() > 0.0;
  if (loads_velocity_) {
    // At constant velocity and no acceleration, A x_eq + B_vel v = 0: per mode
    // z_eq = -(V^{-1} B_vel v) / lambda.
    z_per_velocity_ = -(modes_->eigenvalues().cwiseInverse().asDiagonal() * modes_->Coordinates(plant.B_vel));
    x_per_velocity_ = -plant.A.fullPivLu().solve(plant.B_vel);
  }
}

std::vector<model::PoleAmplitude> ResidualVibration::Amplitudes(const Eigen::VectorXd& x,
                                                                const Eigen::Vector3d& v) const {
  Eigen::VectorXcd z = modes_->Coordinates(x);
  if (loads_velocity_) z -= z_per_velocity_ * v.head(z_per_velocity_.cols()).cast<std::complex<double>>();
  std::vector<model::PoleAmplitude> all = modes_->Amplitudes(cv_, z);
  // A pair near critical damping: the real basis (its cap acted, or V^{-1} cancelled).
  const bool near_critical = std::any_of(all.begin(), all.end(), [](const model::PoleAmplitude& a) {
    return a.capped || std::isnan(a.amplitude);
  });
  if (near_critical) {
    Eigen::VectorXd free = x;
    if (loads_velocity_) free -= x_per_velocity_ * v.head(x_per_velocity_.cols());
    std::vector<model::PoleAmplitude> real = modes_->AmplitudesOfState(c_, free);
    if (real.empty() || !std::isnan(real.front().amplitude)) all = std::move(real);
  }
  std::vector<model::PoleAmplitude> seen;
  for (std::size_t p = 0; p < all.size(); ++p) {
    if (visible_[p]) seen.push_back(all[p]);
  }
  return seen;
}

double ResidualVibration::Total(const std::vector<model::PoleAmplitude>& amplitudes) {
  double total = 0.0;
  for (const model::PoleAmplitude& a : amplitudes) total += a.amplitude;
  return total;
}

}  // namespace shapebench::bench

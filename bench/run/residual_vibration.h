// The residual vibration of a run as the input-shaping literature means it: the amplitude of
// the free vibration the plant's state holds at an instant (the end of motion, a point of a
// cruise), about the equilibrium of the drive velocity then held (acceleration 0), in the
// run's output view. The complex-mode split of the plant (model/free_response.h) is made
// once per plant; an amplitude costs a matrix-vector product, asked for a few times a run.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Dense>

#include "bench/run/output_view.h"
#include "model/free_response.h"
#include "model/linear_plant.h"

namespace shapebench::bench {

class ResidualVibration {
 public:
  // `plant`: the machine plant (MachinePlant::plant, states > 0), outputs in its row layout.
  ResidualVibration(const model::LinearPlant& plant, const OutputView& view);

  // Per pole of the plant the view can see (ascending frequency; a pole of another axis,
  // whose modes never reach the view's rows, is left out): the amplitude (m) in the view of
  // the free vibration from state x about the equilibrium under drive velocity v (per
  // axis, m/s). Where V^{-1} does not split the state (a pair near critical damping:
  // ModalDecomposition::WellSplit), through the real basis (AmplitudesOfState).
  std::vector<model::PoleAmplitude> Amplitudes(const Eigen::VectorXd& x, const Eigen::Vector3d& v) const;

  // Their sum: a bound of the view's free vibration for all later t (the amplitude the
  // metrics report); NaN when the split failed (ModalDecomposition::WellSplit).
  static double Total(const std::vector<model::PoleAmplitude>& amplitudes);

 private:
  std::shared_ptr<const model::ModalDecomposition> modes_;
  Eigen::MatrixXcd cv_;                 // the view's deflection rows of C, times V
  Eigen::MatrixXd c_;                   // the view's deflection rows of C
  Eigen::MatrixXd x_per_velocity_;      // the equilibrium state per drive velocity, -A^{-1} B_vel
  Eigen::MatrixXcd z_per_velocity_;     // modal coordinates of the equilibrium per drive velocity
  bool loads_velocity_ = false;         // B_vel is not 0
  std::vector<char> visible_;           // per pole: some member's column of cv_ is not 0
};

}  // namespace shapebench::bench

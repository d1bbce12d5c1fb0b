// The exact discretisation of a linear plant over a communication step of any length (the
// FMU's doStep): z+ = phi(h) z + gamma(h) a with the acceleration a held (Van Loan's
// exponential, model/exact_integrator.h's DiscretizeExactly), and each output's largest
// magnitude inside the step found exactly (model/tick_extremum.h), so that a peak between
// two communication points survives as an output.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Dense>

#include "model/exact_integrator.h"
#include "model/linear_plant.h"
#include "model/tick_extremum.h"

namespace shapebench::bench::fmu {

class ExactStepper {
 public:
  explicit ExactStepper(const model::LinearPlant& plant);
  // Holds `accel` (num_inputs values) over a step of h seconds.
  void Step(const double* accel, double h);
  double Output(int row) const { return y_(row); }
  // The largest |output| over the last step, its ends and inside (0 before any step).
  double Peak(int row) const { return peak_[static_cast<std::size_t>(row)]; }
  // The plant's states x (without the drive velocities).
  Eigen::VectorXd State() const { return z_.head(n_); }
  int num_outputs() const { return static_cast<int>(plant_.C.rows()); }

 private:
  struct Grid {
    double h = 0.0;
    std::shared_ptr<const model::ExactDiscretization> discretization;
    std::vector<std::unique_ptr<model::TickExtremum>> extremum;  // per output row, or null
  };
  Grid& GridFor(double h);

  model::LinearPlant plant_;
  int n_ = 0;
  int m_ = 0;
  Eigen::MatrixXd a_z_, b_z_;
  std::vector<std::vector<int>> kept_;  // per output row: the augmented states it reads
  std::vector<Grid> grids_;             // the step sizes seen, most recent first
  Eigen::VectorXd z_, z_next_, y_, y_next_;
  std::vector<double> peak_;
  std::vector<double> z0_kept_, z1_kept_;
};

}  // namespace shapebench::bench::fmu

// The exact discretisation of a linear plant over a communication step of any length (the
// FMU's doStep): z+ = phi(h) z + gamma(h) a with the acceleration a held (Van Loan's
// exponential, model/exact_integrator.h's DiscretizeExactly), and each output's largest
// magnitude inside the step, so that a peak between two communication points survives as an
// output: found exactly where the output's states split into modes (model/tick_extremum.h),
// else at the run's output substeps (an output that reads a drive velocity, e.g. a lumped
// machine's dampers loaded from the drive: the native run samples it there too).
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
  // `substeps` output samples per `period_s` (the run's: RunPlan::substeps) where no exact
  // search is possible; a step of h takes ceil(substeps h / period_s) of them.
  ExactStepper(const model::LinearPlant& plant, double period_s, int substeps);
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
    bool sampled = false;  // some row has states but no exact search: sample it
    int inner = 1;         // the samples a step then takes
    std::shared_ptr<const model::ExactDiscretization> inner_discretization;  // over h / inner
  };
  void SampleInside(const Grid& grid, const double* accel);
  Grid& GridFor(double h);

  model::LinearPlant plant_;
  int n_ = 0;
  int m_ = 0;
  double period_s_ = 0.0;
  int substeps_ = 1;
  Eigen::MatrixXd a_z_, b_z_;
  std::vector<std::vector<int>> kept_;  // per output row: the augmented states it reads
  std::vector<Grid> grids_;             // the step sizes seen, most recent first
  Eigen::VectorXd z_, z_next_, y_, y_next_;
  std::vector<double> peak_;
  std::vector<double> z0_kept_, z1_kept_;
};

}  // namespace shapebench::bench::fmu

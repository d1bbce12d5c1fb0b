// The oracle integrator: exact discretisation of the linear plant under an acceleration
// held over each substep (zero-order hold on a, so the drive velocity v is a ramp).
#pragma once

#include <Eigen/Dense>

#include "model/integrator.h"

namespace shapebench::model {

class ExactIntegrator final : public PlantIntegrator {
 public:
  ExactIntegrator(const LinearPlant& plant, double period_s, int substeps);

  void Reset(const Eigen::VectorXd& drive_velocity) override;
  void SetInput(const Eigen::VectorXd& drive_accel) override;
  void Step() override;
  Eigen::VectorXd Output() const override;
  double Time() const override;
  IntegratorStats Stats() const override;

 private:
  int num_states_;
  int num_inputs_;
  double period_s_;
  int substeps_;
  Eigen::MatrixXd C_;
  // Augmented state z = [x; v] over one substep: z+ = phi_ z + gamma_ a.
  Eigen::MatrixXd phi_;
  Eigen::MatrixXd gamma_;
  Eigen::VectorXd z_;
  Eigen::VectorXd accel_;
  long count_ = 0;
};

}  // namespace shapebench::model

// A plant FMU behind the co-simulation master's integrator interface
// (model::PlantIntegrator), so that the run core steps it as it steps its own plants: per
// tick t_k = k period (time from the integer step count), for each output substep set the
// inputs (the held base acceleration per mapped axis), fmiDoStep to the next communication
// point, read the outputs into the six rows of model::MachinePlant (deflection x, y, z,
// tool error x, y, z; an unmapped axis reads 0, an unmapped tool error its deflection).
// A mapped deflection_peak output is offered as the period's extremum (period_extremum), so the
// in-step peaks the FMU saw survive; nothing else is offered.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include <Eigen/Dense>

#include "bench/fmi/fmu_instance.h"
#include "bench/fmi/fmu_machine.h"
#include "model/integrator.h"

namespace shapebench::bench {

class FmuPlant final : public model::PlantIntegrator {
 public:
  // Instantiates and initialises the FMU for a run of at most `stop_time_s`.
  FmuPlant(const FmuMachine& machine, double period_s, int substeps, double stop_time_s);

  void Reset(const Eigen::VectorXd& drive_velocity) override;  // only at t = 0 (a fresh instance)
  void SetInput(const Eigen::VectorXd& drive_accel) override;
  void Step() override;
  Eigen::VectorXd Output() const override;
  // The state[i] outputs of shapebench's own machine FMU (FmuMachine::states); else empty.
  Eigen::VectorXd PlantState() const override;
  double Time() const override;
  int num_inputs() const override { return 3; }
  int num_outputs() const override;
  int substeps() const override { return substeps_; }
  void AdvancePeriod(const double* drive_accel, long same_input_periods, double* outputs) override;
  model::IntegratorCapabilities Capabilities() const override;
  bool WatchExtremum(int row) override;
  double PeriodExtremum() const override { return period_peak_; }

  // Deflection per held m/s^2 along each axis (the static_compliance outputs, read once
  // after initialisation; negative where the tool lags), on the diagonal; false when the
  // FMU maps none.
  bool StaticGain(Eigen::Matrix3d* gain) const;
  // The residual_amplitude output of `axis` (-1: the sum over the mapped axes) now; NaN when
  // not mapped.
  double ResidualAmplitude(int axis);

 private:
  void ReadOutputs();

  const FmuMachine& machine_;
  std::unique_ptr<FmuInstance> instance_;
  const double period_s_;
  const int substeps_;
  long count_ = 0;  // communication steps done
  std::vector<unsigned> input_refs_;
  std::vector<int> input_axes_;
  std::vector<unsigned> output_refs_;  // deflection, tool error, step peak (those mapped)
  std::vector<int> output_rows_;       // their rows (6 + axis: the step peak of axis)
  std::vector<double> inputs_, read_;
  std::array<double, 9> rows_{};       // the six output rows, then the step peaks
  int watched_ = -1;                   // the step peak row PeriodExtremum reports
  double period_peak_ = 0.0;
  Eigen::Matrix3d static_gain_ = Eigen::Matrix3d::Zero();
  bool has_static_ = false;
};

}  // namespace shapebench::bench

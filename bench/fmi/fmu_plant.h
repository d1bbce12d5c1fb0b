// A plant FMU behind the co-simulation master's integrator interface
// (model::PlantIntegrator), so that the run core steps it as it steps its own plants: per
// tick t_k = k period (time from the integer step count), for each output substep set the
// inputs (the held base acceleration per mapped axis), fmiDoStep to the next communication
// point, read the outputs into the six rows of model::MachinePlant (deflection x, y, z,
// tool error x, y, z; an unmapped axis reads 0, an unmapped tool error its deflection).
// A mapped deflection_peak output is offered as the period's extremum (period_extremum), so the
// in-step peaks the FMU saw survive; nothing else is offered.
// With FmuMachine::master_servo the servo's loops run here, on the master: before each
// communication step the drive acceleration of each driven axis is computed from the
// drive_position / drive_velocity outputs of the last communication point (the one-step
// delay: the feedback is held over the step) and the command there, then held over the step
// (docs/fmi.md#the-servo-drive).
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
  // Under the master's servo: the number of the FMU's states (state[i]) per axis, so that
  // PlantState() gives the native servo plant's layout (per axis its structure's states, then
  // e, e', z). False (PlantState stays the FMU's states) when they do not add up.
  bool LayOutServoStates(const std::array<int, 3>& structure_states);

 private:
  void ReadOutputs();
  void ServoInputs(double h);       // the held drive accelerations of the step [t, t + h]
  void AdvanceCommand(double h);    // the command's position and velocity, to t + h

  // One axis of the master's servo (servo_drive.h's notation): the command u, v (the held
  // command acceleration integrated exactly), the PI's integral state z.
  struct ServoAxis {
    double u = 0.0, v = 0.0, z = 0.0;
  };

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
  // The six output rows, then the step peaks, the drive positions and velocities per axis.
  std::array<double, 15> rows_{};
  std::array<double, 3> command_accel_{};  // held over the period (SetInput, AdvancePeriod)
  std::array<ServoAxis, 3> servo_{};
  std::array<int, 3> structure_states_{};
  bool servo_state_layout_ = false;
  int watched_ = -1;                   // the step peak row PeriodExtremum reports
  double period_peak_ = 0.0;
  Eigen::Matrix3d static_gain_ = Eigen::Matrix3d::Zero();
  bool has_static_ = false;
};

}  // namespace shapebench::bench

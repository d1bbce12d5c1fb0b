#include "bench/fmi/fmu_plant.h"

#include <algorithm>
#include <cmath>

#include "common/math_constants.h"
#include "model/multi_axis_machine.h"

namespace shapebench::bench {
namespace {

constexpr int kPeakRow = model::kNumOutputRows;  // rows_ 6..8: the step peaks per axis
constexpr int kDrivePositionRow = kPeakRow + 3;   // rows_ 9..11 (master's servo)
constexpr int kDriveVelocityRow = kPeakRow + 6;   // rows_ 12..14

std::vector<std::pair<unsigned, double>> Parameters(const FmuMachine& machine) {
  std::vector<std::pair<unsigned, double>> parameters;
  for (const auto& [signal, value] : machine.parameters) parameters.emplace_back(signal.value_reference, value);
  return parameters;
}

}  // namespace

FmuPlant::FmuPlant(const FmuMachine& machine, double period_s, int substeps, double stop_time_s)
    : machine_(machine),
      instance_(std::make_unique<FmuInstance>(machine.fmu, Parameters(machine), stop_time_s)),
      period_s_(period_s),
      substeps_(substeps) {
  for (int axis = 0; axis < 3; ++axis) {
    if (const auto& in = machine.base_acceleration[axis]) {
      input_refs_.push_back(in->value_reference);
      input_axes_.push_back(axis);
    }
    const auto add_output = [&](const std::optional<FmuSignal>& signal, int row) {
      if (!signal) return;
      output_refs_.push_back(signal->value_reference);
      output_rows_.push_back(row);
    };
    add_output(machine.deflection[axis], model::kDeflectionRow + axis);
    add_output(machine.tool_error[axis], model::kToolErrorRow + axis);
    add_output(machine.deflection_peak[axis], kPeakRow + axis);
    if (machine.master_servo && machine.base_acceleration[axis]) {
      add_output(machine.drive_position[axis], kDrivePositionRow + axis);
      add_output(machine.drive_velocity[axis], kDriveVelocityRow + axis);
    }
  }
  inputs_.assign(input_refs_.size(), 0.0);
  read_.assign(output_refs_.size(), 0.0);
  // The static compliances: constant outputs (or calculated parameters) of the model.
  std::vector<unsigned> refs;
  std::vector<int> axes;
  for (int axis = 0; axis < 3; ++axis) {
    if (const auto& c = machine.static_compliance[axis]) {
      refs.push_back(c->value_reference);
      axes.push_back(axis);
    }
  }
  if (!refs.empty()) {
    std::vector<double> values(refs.size());
    instance_->GetReal(refs, values.data());
    for (std::size_t i = 0; i < refs.size(); ++i) static_gain_(axes[i], axes[i]) = values[i];
    has_static_ = true;
  }
  ReadOutputs();  // the outputs at t = 0
}

void FmuPlant::Reset(const Eigen::VectorXd& /*drive_velocity*/) {
  // The instance was initialised at rest at t = 0; a run resets it only before its first step.
}

void FmuPlant::SetInput(const Eigen::VectorXd& drive_accel) {
  for (int axis = 0; axis < 3; ++axis) command_accel_[static_cast<std::size_t>(axis)] = drive_accel(axis);
}

double FmuPlant::Time() const { return period_s_ * static_cast<double>(count_) / substeps_; }

void FmuPlant::Step() {
  const double t = Time();
  // The step ends on the grid point t_(count+1) (an integer count, never accumulated).
  const double h = period_s_ * static_cast<double>(count_ + 1) / substeps_ - t;
  if (machine_.master_servo) {
    ServoInputs(h);
  } else {
    for (std::size_t i = 0; i < input_axes_.size(); ++i) inputs_[i] = command_accel_[static_cast<std::size_t>(input_axes_[i])];
  }
  if (!input_refs_.empty()) instance_->SetReal(input_refs_, inputs_.data());
  ++count_;
  instance_->DoStep(t, h);
  if (machine_.master_servo) AdvanceCommand(h);
  ReadOutputs();
}

// servo_drive.h's finite velocity loop with the motor an acceleration source (the FMU's
// input): v_ref = -Kp e + FF v, s'' = w_v (v_ref - s') + (w_v^2 / 4) z, z' = v_ref - s',
// i.e. F_m / m_m with Kv = m_m w_v, Ki = Kv w_v / 4 (the native modal form exactly, whose
// structure neither loads nor pushes the motor). Sampled: s, s' the FMU's outputs at t, u,
// v the command there; the PI's integral summed by the rectangle at t.
void FmuPlant::ServoInputs(double h) {
  const model::ServoConfig& servo = *machine_.master_servo;
  const double kp = servo.position_gain_1_s;
  const double w_v = 2.0 * kPi * servo.velocity_loop_hz;
  for (std::size_t i = 0; i < input_axes_.size(); ++i) {
    const int axis = input_axes_[i];
    ServoAxis& a = servo_[static_cast<std::size_t>(axis)];
    const double s = rows_[static_cast<std::size_t>(kDrivePositionRow + axis)];
    const double s_dot = rows_[static_cast<std::size_t>(kDriveVelocityRow + axis)];
    const double velocity_error = -kp * (s - a.u) + servo.velocity_feedforward * a.v - s_dot;
    inputs_[i] = w_v * velocity_error + 0.25 * w_v * w_v * a.z;
    a.z += h * velocity_error;
  }
}

void FmuPlant::AdvanceCommand(double h) {
  for (std::size_t axis = 0; axis < 3; ++axis) {
    ServoAxis& a = servo_[axis];
    a.u += a.v * h + 0.5 * command_accel_[axis] * h * h;
    a.v += command_accel_[axis] * h;
  }
}

void FmuPlant::ReadOutputs() {
  if (!output_refs_.empty()) instance_->GetReal(output_refs_, read_.data());
  rows_.fill(0.0);
  for (std::size_t i = 0; i < read_.size(); ++i) rows_[static_cast<std::size_t>(output_rows_[i])] = read_[i];
  for (int axis = 0; axis < 3; ++axis) {
    if (!machine_.tool_error[axis]) rows_[model::kToolErrorRow + axis] = rows_[model::kDeflectionRow + axis];
    // The tool error measured from the command: the FMU's (from its driven point) plus the
    // following error e = s - u (servo_drive.h's row 1 for a tool that moves with the drive).
    if (machine_.master_servo && machine_.base_acceleration[axis]) {
      rows_[model::kToolErrorRow + axis] +=
          rows_[kDrivePositionRow + axis] - servo_[static_cast<std::size_t>(axis)].u;
    }
  }
}

int FmuPlant::num_outputs() const { return model::kNumOutputRows; }

Eigen::VectorXd FmuPlant::Output() const {
  Eigen::VectorXd out(model::kNumOutputRows);
  for (int r = 0; r < model::kNumOutputRows; ++r) out(r) = rows_[static_cast<std::size_t>(r)];
  return out;
}

void FmuPlant::AdvancePeriod(const double* drive_accel, long /*same_input_periods*/, double* outputs) {
  for (std::size_t axis = 0; axis < 3; ++axis) command_accel_[axis] = drive_accel[axis];
  period_peak_ = 0.0;
  const int width = output_width();
  for (int j = 0; j < substeps_; ++j) {
    Step();
    if (watched_ >= 0) period_peak_ = std::max(period_peak_, std::abs(rows_[static_cast<std::size_t>(watched_)]));
    WriteSelected(rows_.data(), outputs + static_cast<std::ptrdiff_t>(j) * width);
  }
}

model::IntegratorCapabilities FmuPlant::Capabilities() const {
  model::IntegratorCapabilities caps;
  for (const auto& peak : machine_.deflection_peak) caps.period_extremum = caps.period_extremum || peak.has_value();
  return caps;
}

bool FmuPlant::WatchExtremum(int row) {
  const int axis = row - model::kDeflectionRow;
  if (axis < 0 || axis >= 3 || !machine_.deflection_peak[axis]) return false;
  watched_ = kPeakRow + axis;
  return true;
}

Eigen::VectorXd FmuPlant::PlantState() const {
  Eigen::VectorXd x(static_cast<Eigen::Index>(machine_.states.size()));
  if (!machine_.states.empty()) instance_->GetReal(machine_.states, x.data());
  if (!servo_state_layout_) return x;
  // The native servo plant's layout: per axis the structure's states, then e, e', z.
  Eigen::VectorXd servo_x(x.size() + 9);
  Eigen::Index from = 0, to = 0;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    const int n = structure_states_[axis];
    servo_x.segment(to, n) = x.segment(from, n);
    from += n;
    to += n;
    const ServoAxis& a = servo_[axis];
    const bool driven = machine_.base_acceleration[axis].has_value();
    servo_x(to++) = driven ? rows_[kDrivePositionRow + axis] - a.u : 0.0;
    servo_x(to++) = driven ? rows_[kDriveVelocityRow + axis] - a.v : 0.0;
    servo_x(to++) = a.z;
  }
  return servo_x;
}

bool FmuPlant::LayOutServoStates(const std::array<int, 3>& structure_states) {
  int total = 0;
  for (int n : structure_states) total += n;
  servo_state_layout_ = machine_.master_servo && static_cast<std::size_t>(total) == machine_.states.size();
  if (servo_state_layout_) structure_states_ = structure_states;
  return servo_state_layout_;
}

bool FmuPlant::StaticGain(Eigen::Matrix3d* gain) const {
  *gain = static_gain_;
  return has_static_;
}

double FmuPlant::ResidualAmplitude(int axis) {
  std::vector<unsigned> refs;
  for (int a = 0; a < 3; ++a) {
    if ((axis < 0 || a == axis) && machine_.residual_amplitude[a]) {
      refs.push_back(machine_.residual_amplitude[a]->value_reference);
    }
  }
  if (refs.empty()) return NAN;
  std::vector<double> values(refs.size());
  instance_->GetReal(refs, values.data());
  double total = 0.0;
  for (double v : values) total += std::abs(v);
  return total;
}

}  // namespace shapebench::bench

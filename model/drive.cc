// validate() of the drive configs: every invalid value is rejected with its YAML key
// (drive.position_gain, ...), which the scenario loader turns into FILE:LINE:COL.
#include "model/drive.h"

#include <cmath>
#include <string>

#include "common/format.h"
#include "common/validation_error.h"

namespace shapebench::model {
namespace {

std::string Got(double value) { return " (got " + FormatNumber(value) + ")"; }

}  // namespace

void ServoConfig::validate() const {
  if (!(position_gain_1_s > 0.0) || !std::isfinite(position_gain_1_s)) {
    throw ValidationError("position_gain",
                          "must be finite and > 0 (1/s; Kp = 1 / T2)" + Got(position_gain_1_s));
  }
  if (!(velocity_feedforward >= 0.0 && velocity_feedforward <= 1.0)) {
    throw ValidationError("velocity_feedforward",
                          "must be in [0, 1] (0 = none, 1 = full)" + Got(velocity_feedforward));
  }
  if (!(velocity_loop_hz >= 0.0) || !std::isfinite(velocity_loop_hz)) {
    throw ValidationError("velocity_loop_hz",
                          "must be finite and >= 0 (0 = ideal inner loops)" +
                              Got(velocity_loop_hz));
  }
  if (!(motor_mass_kg > 0.0) || !std::isfinite(motor_mass_kg)) {
    throw ValidationError("motor_mass_kg", "must be finite and > 0" + Got(motor_mass_kg));
  }
}

void DriveConfig::validate() const {
  if (type == DriveType::kServo) servo.validate();
}

}  // namespace shapebench::model

// validate() of the drive configs: every invalid value is rejected with its YAML key
// (drive.position_gain, ...), which the scenario loader turns into FILE:LINE:COL.
#include "model/drive.h"

#include <cmath>
#include <string>

#include "common/format.h"
#include "common/validation_error.h"

namespace shapebench::model {

void ServoConfig::validate() const {
  if (!(position_gain_1_s > 0.0) || !std::isfinite(position_gain_1_s)) {
    throw ValidationError("position_gain",
                          "must be finite and > 0 (1/s; Kp = 1 / T2)" + FormatGot(position_gain_1_s));
  }
  if (!(velocity_feedforward >= 0.0 && velocity_feedforward <= 1.0)) {
    throw ValidationError("velocity_feedforward",
                          "must be in [0, 1] (0 = none, 1 = full)" + FormatGot(velocity_feedforward));
  }
  if (!(velocity_loop_hz >= 0.0) || !std::isfinite(velocity_loop_hz)) {
    throw ValidationError("velocity_loop_hz",
                          "must be finite and >= 0 (0 = ideal inner loops)" +
                              FormatGot(velocity_loop_hz));
  }
  if (!(motor_mass_kg > 0.0) || !std::isfinite(motor_mass_kg)) {
    throw ValidationError("motor_mass_kg", "must be finite and > 0" + FormatGot(motor_mass_kg));
  }
  try {
    friction.validate();
  } catch (const ValidationError& error) {
    throw error.Prefixed("friction");
  }
  if (!(force_limit_n >= 0.0) || !std::isfinite(force_limit_n)) {
    throw ValidationError("force_limit_n",
                          "must be finite and >= 0 (N, the motor force's limit; 0 = none)" + FormatGot(force_limit_n));
  }
  // An ideal velocity loop makes the motor a velocity source: no force would slow it.
  if (velocity_loop_hz == 0.0 && (friction.present() || force_limit_n > 0.0)) {
    throw ValidationError(friction.present() ? "friction" : "force_limit_n",
                          "needs a velocity loop (velocity_loop_hz > 0): under ideal inner loops "
                          "(velocity_loop_hz: 0) the motor is a velocity source that no force slows");
  }
}

void DriveConfig::validate() const {
  if (type == DriveType::kServo) servo.validate();
}

}  // namespace shapebench::model

// The drive between command and plant, one per axis.
#pragma once

#include "common/field_list.h"
#include "model/friction.h"

namespace shapebench::model {

enum class DriveType { kKinematic, kServo };

// Per axis: a position loop (gain Kp) with velocity feedforward, a velocity loop (PI)
// and the motor, whose position is the "driven" point of the structure (it acts through
// the structure's elements attached to "driven": ball screw and nut). Continuous-time.
//   v_ref = Kp (x_cmd - x_motor) + velocity_feedforward * v_cmd
//   F_motor = Kv (v_ref - v_motor) + Ki * integral(v_ref - v_motor)
struct ServoConfig {
  double position_gain_1_s = 30.0;    // Kp; T2 = 1 / Kp
  double velocity_feedforward = 0.0;  // 0..1
  // Velocity-loop bandwidth; 0 = ideal inner loops (v_motor = v_ref exactly, the motor is
  // a velocity source and the axis a first-order lag of time constant 1/Kp).
  double velocity_loop_hz = 200.0;
  double motor_mass_kg = 40.0;  // rotor and screw inertia reflected to the axis
  // Friction on the driven point's motion relative to what the drive is mounted on (the
  // table's guideways, the screw's bearings: docs/nonlinear.md), in the motor's force
  // balance; and the motor force's saturation, |F_m| <= force_limit_n (0: no limit). Both
  // need a velocity loop (velocity_loop_hz > 0): an ideal loop is a velocity source.
  FrictionConfig friction{};
  double force_limit_n = 0.0;
  void validate() const;        // throws ValidationError naming the field

  // The servo's keys sit beside `type` in the `drive:` mapping.
  template <typename Archive>
  void Serialize(Archive* a) {  // the field list (common/field_list.h)
    a->Visit("position_gain", &position_gain_1_s);
    a->Visit("velocity_feedforward", &velocity_feedforward);
    a->Visit("velocity_loop_hz", &velocity_loop_hz);
    a->Visit("motor_mass_kg", &motor_mass_kg);
    a->Visit("friction", &friction);
    a->Visit("force_limit_n", &force_limit_n);
  }
  bool nonlinear() const { return friction.present() || force_limit_n > 0.0; }
};

// kinematic: the driven point follows the command exactly, the command's acceleration
// held over each interpolation period (JP2551868B2, seed 004: the excitation the patent analyses).
struct DriveConfig {
  DriveType type = DriveType::kKinematic;
  ServoConfig servo;  // used when type is kServo
  void validate() const;

  static Choices<DriveType> TypeChoices() {
    return {{"kinematic", DriveType::kKinematic}, {"servo", DriveType::kServo}};
  }
};

}  // namespace shapebench::model

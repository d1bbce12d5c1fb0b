// The servo drive of one axis (DriveType::kServo) as a LinearPlant, with the axis' structure
// (modal, lumped, or none: a rigid axis) hanging off the motor.
//
// Notation: u, v = u', a = u'' the command (a held over each interpolation period, v
// continuous and piecewise linear); s the motor position = the "driven" point of the
// structure (relative to the body the drive is mounted on); e = s - u the following error;
// Kp = position_gain, FF = velocity_feedforward. Position loop with feedforward:
//   v_ref = -Kp e + FF v.
//
// Ideal inner loops (velocity_loop_hz = 0): the motor is a velocity source, s' = v_ref:
//   e'  = -Kp e - (1 - FF) v
//   s'  = FF v - Kp e,      s'' = FF a - Kp e' = FF a + Kp^2 e + Kp (1 - FF) v.
// Without structure this is the first-order lag s = u through 1 / (1 + s/Kp) (plus FF).
//
// Finite velocity loop (w_v = 2 pi velocity_loop_hz): PI on the velocity error with the
// integral state z, the motor a mass m_m (motor_mass_kg) that feels the reaction of the
// structure's elements attached to "driven" (ball screw and nut):
//   z'  = v_ref - s' = -Kp e - e' - (1 - FF) v
//   F_m = Kv (v_ref - s') + Ki z,   Kv = (m_m + m_load) w_v,   Ki = Kv w_v / 4
//   m_m s'' = F_m - F_r,   e'' = s'' - a.
// (Kv, Ki place the rigid loop's velocity poles at a double pole -w_v/2 per unit mass.)
// m_load = g^T M g is the rigid mass the drive moves (lumped form); the modal form does not
// load the motor (m_load = 0, F_r = 0).
//
// The structure rides on the motor: its deflection coordinates are taken relative to the
// motor, y = q - g s (lumped; the kinematic drive's y = q - g u with u replaced by s), so
//   lumped:  M y'' + C y' + K y = f s'' - (C g + C_u) s',   f = -M g
//   modal:   q_i'' + 2 zeta_i w_i q_i' + w_i^2 q_i = -s''
// i.e. the kinematic plant (BuildPlant) driven by the motor's acceleration and velocity
// instead of the command's. In absolute coordinates the lumped structure equation is
// M q'' + C q' + K q = -K_u (u + e) - C_u (u' + e'): the driven endpoint sits at u + e.
// The reaction on the motor follows from the potential 0.5 sum k (D q + d s)^2 and the
// dissipation 0.5 sum c (D q' + d s')^2 differentiated by s:
//   F_r = sum k d (D q + d s) + sum c d (D q' + d s') = K_u^T y + C_u^T y'
// provided the rigid motion stretches no element (D g + d = 0 for every element: the
// structure follows the driven point freely, as a carriage on its guides does). Otherwise
// F_r would depend on the absolute motor position and the axis could not be simulated in
// relative coordinates (nor would it be a feed axis): BuildServoAxisPlant then throws a
// ValidationError naming the element. Under the ideal inner loops the motor needs no force
// balance and any structure is accepted.
//
// Outputs: row 0 the structural deflection c^T y (tool relative to the workpiece, less the
// motion of the driven point: what the kinematic drive's plant outputs); row 1 the tool
// relative to the workpiece less the command, c^T y + (c^T g) e (the following error plus
// the deflection; c^T g = 1 for a tool that moves with the driven point, and for modal
// and rigid axes). Held acceleration, at rest: e = e' = 0, s'' = a, so the static
// deflection is the kinematic drive's.
#pragma once

#include "model/drive.h"
#include "model/linear_plant.h"
#include "model/machine.h"
#include "model/nonlinear_plant.h"

namespace shapebench::model {

// One servo axis: inputs (1 column each) the axis' commanded acceleration and velocity;
// outputs row 0 = deflection, row 1 = tool relative to the command. `structure` null: a
// rigid axis (servo states only, deflection row 0). States: the structure's (as in
// BuildPlant), then e, and for a finite velocity loop e' and z. Tolerance groups: the
// structure's states, the servo's states.
// Throws ValidationError: the structure's own (its field names), "elements[i]" when a
// finite velocity loop meets an element the rigid motion stretches.
LinearPlant BuildServoAxisPlant(const MachineConfig* structure, const ServoConfig& servo);

// The same plant with its nonlinear elements (docs/nonlinear.md): the structure's
// (BuildStructureElements, moved onto the servo's states: their velocity input is the
// motor's s' = v + e', and with a velocity loop the motor feels the force of an element
// attached to "driven"), then the drive's own: `friction` on s' in the motor's force
// balance (m_m s'' = F_m - F_r - F_friction) and the force limit (F_m clamped).
NonlinearPlant BuildServoAxis(const MachineConfig* structure, const ServoConfig& servo);

}  // namespace shapebench::model

// A plant with nonlinear elements (docs/nonlinear.md): the LinearPlant of everything linear
// plus elements each of which adds one scalar force, a function of one linear combination
// of the state, along one direction of the state's derivative. Over the augmented state
// z = [x; v] (LinearPlant::AugmentedA: the plant's states, then the drive velocity per
// input):
//   z' = A_z z + B_z a + sum_e column_e F_e(row_e z, internal state of e)
// Friction: row z is the relative velocity w of the element's two ends, F its friction
// force opposing w. Backlash: row z is the stretch d, F the difference between the contact
// law and the linear spring the LinearPlant already holds (k (|d| - b/2) sign(d) - k d
// outside the gap, -k d inside). Saturation: row z is the motor force F_m, F the clamped
// force less F_m.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "model/linear_plant.h"
#include "model/machine.h"
#include "model/nonlinear_element.h"

namespace shapebench::model {

struct NonlinearElement {
  NonlinearLaw law;  // friction, backlash or the force limit (model/nonlinear_element.h)
  // How messages name it: "machine.axes.y.elements[1] (y_guides_friction)", "drive.friction".
  std::string name;
  // row z = row_x . x + row_v . v;  the force enters x' along column_x (v' = a has none).
  Eigen::VectorXd row_x;
  Eigen::VectorXd row_v;
  Eigen::VectorXd column_x;
  // The share of the element's force that acts on the driven point (d of its stretch
  // D q + d s): what the motor of a servo with a velocity loop feels of it.
  double driven_share = 0.0;
};

struct NonlinearPlant {
  LinearPlant linear;  // backlash springs included as linear springs, friction left out
  std::vector<NonlinearElement> elements;
  // Per state of `linear`: the input (axis) whose command the state is taken relative to
  // (a servo's following error e = s - u, and its rate e' = s' - v, a velocity state:
  // servo_drive.h), -1 for the others; empty: none. The nonlinear integrator integrates
  // the motor's position e + u and velocity e' + v in their place: a motor held by friction
  // or a force limit then keeps states of exactly 0, where e = -u, e' = -v would carry
  // CVODE's relative error rtol |u| into the tool's position.
  std::vector<int> following_error_axis;
  bool IsLinear() const { return elements.empty(); }
};

// The elements of the lumped form's `elements:` that are nonlinear, over the state of
// BuildPlant(machine) (one input: the driven point's velocity). Throws ValidationError
// "elements[i]" for a backlash element the rigid motion stretches (its stretch would depend
// on the driven point's absolute position, which the relative coordinates do not hold).
// `machine` must have passed validate(). A modal form has none.
std::vector<NonlinearElement> BuildStructureElements(const MachineConfig& machine);

}  // namespace shapebench::model

// BuildServoAxisPlant: the equations are in servo_drive.h.
#include "model/servo_drive.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <type_traits>
#include <variant>

#include "common/format.h"
#include "common/math_constants.h"
#include "common/validation_error.h"
#include "model/lumped_matrices.h"
#include "model/nonlinear_plant.h"

namespace shapebench::model {
namespace {

// What the servo needs of the structure besides its kinematic plant.
struct StructureCoupling {
  LinearPlant plant;          // BuildPlant: driven by the driven point's a and v
  Eigen::RowVectorXd reaction;  // F_r = reaction * x_structure (needs free following)
  double load_mass_kg = 0.0;  // g^T M g
  double tool_per_driven = 1.0;  // c^T g
};

// A modal structure has no drive reaction or load model: the coupling's defaults.
void CoupleForm(const ModalMachineConfig&, bool, StructureCoupling*) {}

void CoupleForm(const LumpedMachineConfig& lumped, bool needs_free_following,
                StructureCoupling* coupling) {
  const LumpedMatrices m = AssembleLumped(lumped);
  const int nb = static_cast<int>(m.mass_kg.size());
  if (needs_free_following) {
    for (int i = 0; i < m.rigid_stretch.size(); ++i) {
      // A friction element has no spring or dashpot: its force depends on the relative
      // velocity alone, which the servo's states hold (nonlinear_plant.h).
      if (lumped.elements[i].friction.present()) continue;
      // g entries are O(1) (rigid motion per unit driven motion), so is the stretch.
      if (std::abs(m.rigid_stretch(i)) > 1e-9) {
        const LumpedElement& e = lumped.elements[i];
        throw ValidationError(
            "elements[" + std::to_string(i) + "]",
            "element \"" + e.name + "\" (" + e.from + " - " + e.to + ") stretches by " +
                FormatNumber(m.rigid_stretch(i)) +
                " per unit of driven motion when the structure follows the driven point "
                "rigidly; a servo drive with a velocity loop (velocity_loop_hz > 0) needs a "
                "structure that follows the driven point freely (no spring or damper from "
                "the moving bodies to what stays put), or use velocity_loop_hz: 0 (ideal "
                "inner loops)");
      }
    }
  }
  coupling->reaction.head(nb) = m.K_u.transpose();
  coupling->reaction.segment(nb, nb) = m.C_u.transpose();
  coupling->load_mass_kg = m.g.dot(m.mass_kg.cwiseProduct(m.g));
  coupling->tool_per_driven = m.output.dot(m.g);
}

StructureCoupling Couple(const MachineConfig& structure, bool needs_free_following) {
  StructureCoupling coupling;
  coupling.plant = BuildPlant(structure);  // validates
  coupling.reaction = Eigen::RowVectorXd::Zero(coupling.plant.num_states());
  std::visit([&](const auto& form) { CoupleForm(form, needs_free_following, &coupling); },
             structure.form);
  return coupling;
}

// What the servo's nonlinear elements need beside its plant (servo_drive.h's notation).
struct ServoCoupling {
  Eigen::RowVectorXd sd_x;     // s' = sd_x x + sd_v v
  double sd_v = 0.0;
  Eigen::VectorXd motor_column;  // x' per unit force on the motor (0: ideal inner loops)
  Eigen::RowVectorXd force_x;    // F_m = force_x x + force_v v (finite loop)
  double force_v = 0.0;
};

// The coupling of a servo axis' structure; without one, an empty plant of one input and
// one output.
StructureCoupling CoupleStructure(const MachineConfig* structure, bool ideal) {
  StructureCoupling coupling;
  coupling.plant.A = Eigen::MatrixXd::Zero(0, 0);
  coupling.plant.B_accel = Eigen::MatrixXd::Zero(0, 1);
  coupling.plant.B_vel = Eigen::MatrixXd::Zero(0, 1);
  coupling.plant.C = Eigen::MatrixXd::Zero(1, 0);
  coupling.reaction = Eigen::RowVectorXd::Zero(0);
  if (structure != nullptr) coupling = Couple(*structure, !ideal);
  return coupling;
}

// Where the servo's states sit: after the structure's ns states.
struct ServoStates {
  int ns;   // the structure's states
  int n;    // all states
  int ie;   // e
  int ied;  // e' (finite loop)
  int iz;   // z  (finite loop)
};

// s' and s'' as rows over the states plus input coefficients, and the servo states'
// frequency for CVODE's velocity tolerances (LinearPlant tolerance groups): e' changes at
// the rate of the fastest loop.
struct DrivenPointMotion {
  Eigen::RowVectorXd sd_x;
  Eigen::RowVectorXd sdd_x;
  double sd_v = 0.0;
  double sdd_a = 0.0;
  double sdd_v = 0.0;
  double velocity_frequency = 0.0;
};

DrivenPointMotion IdealInnerLoops(const ServoConfig& servo, const ServoStates& at, LinearPlant* plant) {
  const double kp = servo.position_gain_1_s;
  const double ff = servo.velocity_feedforward;
  DrivenPointMotion m;
  m.sd_x = Eigen::RowVectorXd::Zero(at.n);
  m.sdd_x = Eigen::RowVectorXd::Zero(at.n);
  m.velocity_frequency = kp;
  // e' = -Kp e - (1 - FF) v;  s' = FF v - Kp e;  s'' = FF a + Kp^2 e + Kp (1 - FF) v.
  plant->A(at.ie, at.ie) = -kp;
  plant->B_vel(at.ie, 0) = -(1.0 - ff);
  m.sd_x(at.ie) = -kp;
  m.sd_v = ff;
  m.sdd_x(at.ie) = kp * kp;
  m.sdd_a = ff;
  m.sdd_v = kp * (1.0 - ff);
  return m;
}

DrivenPointMotion FiniteVelocityLoop(const ServoConfig& servo, const StructureCoupling& coupling,
                                     const ServoStates& at, LinearPlant* plant, ServoCoupling* out) {
  const double kp = servo.position_gain_1_s;
  const double ff = servo.velocity_feedforward;
  const int ie = at.ie;
  const int ied = at.ied;
  const int iz = at.iz;
  const double w_v = kTwoPi * servo.velocity_loop_hz;
  const double m_m = servo.motor_mass_kg;
  const double kv = (m_m + coupling.load_mass_kg) * w_v;
  const double ki = kv * w_v / 4.0;
  DrivenPointMotion m;
  m.sd_x = Eigen::RowVectorXd::Zero(at.n);
  m.sdd_x = Eigen::RowVectorXd::Zero(at.n);
  m.velocity_frequency = std::max(kp, w_v);
  // m_m s'' = Kv (-Kp e - e' - (1 - FF) v) + Ki z - reaction x_structure
  m.sdd_x.head(at.ns) = -coupling.reaction / m_m;
  m.sdd_x(ie) = -kv * kp / m_m;
  m.sdd_x(ied) = -kv / m_m;
  m.sdd_x(iz) = ki / m_m;
  m.sdd_v = -kv * (1.0 - ff) / m_m;
  out->motor_column = Eigen::VectorXd::Zero(at.n);
  out->motor_column.head(at.ns) = coupling.plant.B_accel.col(0) / m_m;
  out->motor_column(ied) = 1.0 / m_m;
  out->force_x = Eigen::RowVectorXd::Zero(at.n);
  out->force_x(ie) = -kv * kp;
  out->force_x(ied) = -kv;
  out->force_x(iz) = ki;
  out->force_v = -kv * (1.0 - ff);
  // s' = v + e'
  m.sd_x(ied) = 1.0;
  m.sd_v = 1.0;
  // (e)' = e';  (e')' = s'' - a;  z' = -Kp e - e' - (1 - FF) v
  plant->A(ie, ied) = 1.0;
  plant->A.row(ied) = m.sdd_x;
  plant->B_accel(ied, 0) = m.sdd_a - 1.0;
  plant->B_vel(ied, 0) = m.sdd_v;
  plant->A(iz, ie) = -kp;
  plant->A(iz, ied) = -1.0;
  plant->B_vel(iz, 0) = -(1.0 - ff);
  return m;
}

// The outputs (the structure's deflection; the tool's following error besides), the state
// kinds and the tolerance groups (the structure's, the servo's).
void SetOutputsAndGroups(const StructureCoupling& coupling, const ServoStates& at, bool ideal,
                         double velocity_frequency, LinearPlant* plant) {
  const LinearPlant& s = coupling.plant;
  const int ns = at.ns;
  plant->C.block(0, 0, 1, ns) = s.C;
  plant->C.block(1, 0, 1, ns) = s.C;
  plant->C(1, at.ie) = coupling.tool_per_driven;

  plant->state_kinds = s.state_kinds;
  plant->state_kinds.push_back(StateKind::kPosition);  // e
  if (!ideal) {
    plant->state_kinds.push_back(StateKind::kVelocity);  // e'
    plant->state_kinds.push_back(StateKind::kPosition);  // z: integral of a velocity error
  }
  plant->max_frequency_rad_s = std::max(s.max_frequency_rad_s, velocity_frequency);
  const int structure_groups = ns > 0 ? 1 : 0;
  plant->tolerance_group.assign(ns, 0);
  plant->tolerance_group.resize(at.n, structure_groups);
  if (structure_groups > 0) plant->group_frequency_rad_s.push_back(s.max_frequency_rad_s);
  plant->group_frequency_rad_s.push_back(velocity_frequency);
}

LinearPlant BuildServoAxisModel(const MachineConfig* structure, const ServoConfig& servo,
                                ServoCoupling* out) {
  servo.validate();
  const bool ideal = servo.velocity_loop_hz == 0.0;
  const StructureCoupling coupling = CoupleStructure(structure, ideal);
  const LinearPlant& s = coupling.plant;
  const int ns = s.num_states();
  const int n = ns + (ideal ? 1 : 3);
  const ServoStates at{ns, n, ns, ns + 1, ns + 2};

  LinearPlant plant;
  plant.A = Eigen::MatrixXd::Zero(n, n);
  plant.B_accel = Eigen::MatrixXd::Zero(n, 1);
  plant.B_vel = Eigen::MatrixXd::Zero(n, 1);
  plant.C = Eigen::MatrixXd::Zero(2, n);
  plant.A.topLeftCorner(ns, ns) = s.A;
  const DrivenPointMotion m = ideal ? IdealInnerLoops(servo, at, &plant)
                                    : FiniteVelocityLoop(servo, coupling, at, &plant, out);
  // The structure driven by the motor: x_s' = A_s x_s + b_a s'' + b_v s'.
  const Eigen::VectorXd b_a = s.B_accel.col(0);  // structure per unit s''
  const Eigen::VectorXd b_v = s.B_vel.col(0);    // structure per unit s'
  plant.A.topRows(ns) += b_a * m.sdd_x + b_v * m.sd_x;
  plant.B_accel.topRows(ns) += b_a * m.sdd_a;
  plant.B_vel.topRows(ns) += b_a * m.sdd_v + b_v * m.sd_v;
  SetOutputsAndGroups(coupling, at, ideal, m.velocity_frequency, &plant);
  out->sd_x = m.sd_x;
  out->sd_v = m.sd_v;
  if (ideal) out->motor_column = Eigen::VectorXd::Zero(n);
  return plant;
}

// A structure element (BuildStructureElements: over the structure's states, its velocity
// input the driven point's) moved onto the servo axis' states: the driven point moves at
// s' = sd_x x + sd_v v, and with a velocity loop the motor feels the element's force times
// its share of the driven point.
NonlinearElement OnServoAxis(NonlinearElement e, const ServoCoupling& c) {
  const int ns = static_cast<int>(e.row_x.size());
  const double r_v = e.row_v(0);
  Eigen::VectorXd row_x = r_v * c.sd_x.transpose();
  row_x.head(ns) += e.row_x;
  Eigen::VectorXd column_x = -e.driven_share * c.motor_column;
  column_x.head(ns) += e.column_x;
  e.row_x = row_x;
  e.row_v(0) = r_v * c.sd_v;
  e.column_x = column_x;
  return e;
}

}  // namespace

LinearPlant BuildServoAxisPlant(const MachineConfig* structure, const ServoConfig& servo) {
  ServoCoupling coupling;
  return BuildServoAxisModel(structure, servo, &coupling);
}

NonlinearPlant BuildServoAxis(const MachineConfig* structure, const ServoConfig& servo) {
  ServoCoupling c;
  NonlinearPlant axis;
  axis.linear = BuildServoAxisModel(structure, servo, &c);
  // e (the first servo state, after the structure's) lags the command: see nonlinear_plant.h.
  const int num_states = axis.linear.num_states();
  const int num_servo = servo.velocity_loop_hz == 0.0 ? 1 : 3;
  axis.following_error_axis.assign(num_states, -1);
  axis.following_error_axis[num_states - num_servo] = 0;
  if (num_servo == 3) axis.following_error_axis[num_states - 2] = 0;  // e', a velocity
  if (structure != nullptr) {
    for (NonlinearElement& e : BuildStructureElements(*structure)) {
      axis.elements.push_back(OnServoAxis(std::move(e), c));
    }
  }
  if (servo.friction.present()) {
    NonlinearElement friction;
    friction.law = FrictionElement{servo.friction};
    friction.name = "drive.friction";
    friction.row_x = c.sd_x.transpose();
    friction.row_v = Eigen::VectorXd::Constant(1, c.sd_v);
    friction.column_x = -c.motor_column;
    axis.elements.push_back(std::move(friction));
  }
  if (servo.force_limit_n > 0.0) {
    NonlinearElement limit;
    limit.law = SaturationElement{servo.force_limit_n};
    limit.name = "drive.force_limit_n";
    limit.row_x = c.force_x.transpose();
    limit.row_v = Eigen::VectorXd::Constant(1, c.force_v);
    limit.column_x = c.motor_column;
    axis.elements.push_back(std::move(limit));
  }
  return axis;
}

}  // namespace shapebench::model

// Machine models: the modal form and the lumped mass-spring-damper form (docs/scenario-reference.md),
// both turned into a LinearPlant; modal analysis of either.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "model/friction.h"
#include "model/linear_plant.h"

namespace shapebench::model {

// Components along the machine axes x, y, z.
struct AxisVector {
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("x", &x);
    a->Visit("y", &y);
    a->Visit("z", &z);
  }
};

// One axis (the gain shorthand):
//   q_i'' + 2 zeta_i w_i q_i' + w_i^2 q_i = -a_base;  deflection = sum(gain_i * q_i)
// Coupled (participation and shape instead of gain; model/coupled_modes.h):
//   q_i'' + 2 zeta_i w_i q_i' + w_i^2 q_i = -sum_a participation_a a_a;
//   deflection_b = sum_i shape_b q_i
// gain is the coupled form with participation e_axis and shape gain e_axis (axis: the
// machine's). The scale of q is free: only shape_b participation_a matters (dimensionless;
// an FE export's mass-normalised phi and Gamma = phi^T M r give it directly).
struct ModalMode {
  double frequency_hz = 25.0;
  double damping_ratio = 0.0;
  double gain = 1.0;  // unused (left at 1) by a coupled mode
  std::optional<AxisVector> participation{};  // how each axis' acceleration excites the mode
  std::optional<AxisVector> shape{};          // tool deflection per unit modal coordinate

  bool coupled() const { return participation.has_value() || shape.has_value(); }

  template <typename Archive>
  void Serialize(Archive* a) {  // the field list (common/field_list.h)
    a->Visit("frequency_hz", &frequency_hz);
    a->Visit("damping_ratio", &damping_ratio);
    a->Visit("gain", &gain);
    a->Visit("participation", &participation);
    a->Visit("shape", &shape);
  }
};

// A model's entries per axis are bounded: the modal analysis and the exact integrator's
// matrix exponential grow with the cube of the states (400 bodies: 17 s a run).
constexpr std::size_t kMaxModelEntries = 100;

struct ModalMachineConfig {
  // The YAML key of an FE modal export (bench/measured/modal_file_reader.h), beside no `modes`.
  static constexpr const char* kModalFileKey = "modal_file";

  std::vector<ModalMode> modes = std::vector<ModalMode>(1);  // one default mode
  // The file the modes were read from (`modal_file:`, resolved); empty for YAML modes.
  std::string modal_file{};

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("modes", &modes, kMaxModelEntries);
  }
  // True when a mode gives participation or shape: the form then models all three axes
  // (only as a single form; MultiAxisMachineConfig).
  bool coupled() const;
  // Throws ValidationError naming e.g. "modes[0].frequency_hz", or "modes[1].shape" for a
  // mode with participation but no shape.
  void validate() const;
};

struct LumpedBody {
  std::string name;
  double mass_kg = 0.0;

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("name", &name);
    a->Visit("mass_kg", &mass_kg);
  }
};

// A spring and/or a parallel viscous damper between two endpoints. An endpoint is a body
// name, "ground" (the floor) or "driven" (the point the drive moves: the ball-screw nut).
// Two nonlinear kinds (docs/nonlinear.md), acting on the relative motion of the two ends:
// a friction element (`friction:`, nothing else) and a spring with backlash (backlash_m > 0:
// no force while the stretch d lies within the gap, |d| <= backlash_m / 2, contact with
// stiffness_n_m outside it, force k (|d| - b/2) sign(d)).
struct LumpedElement {
  std::string name;
  std::string from;
  std::string to;
  double stiffness_n_m = 0.0;
  double damping_n_s_m = 0.0;
  double backlash_m = 0.0;  // the whole play b; 0: a plain spring
  FrictionConfig friction{};  // model none: no friction

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("name", &name);
    a->Visit("from", &from);
    a->Visit("to", &to);
    a->Visit("stiffness_n_m", &stiffness_n_m);
    a->Visit("damping_n_s_m", &damping_n_s_m);
    a->Visit("backlash_m", &backlash_m);
    a->Visit("friction", &friction);
  }
  bool nonlinear() const { return friction.present() || backlash_m > 0.0; }
};

// C = alpha M + beta K: zeta_i = alpha / (2 w_i) + beta w_i / 2 at each undamped mode w_i.
struct RayleighDamping {
  double alpha = 0.0;  // 1/s, the mass-proportional part
  double beta = 0.0;   // s, the stiffness-proportional part

  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("alpha", &alpha);
    a->Visit("beta", &beta);
  }
};

// Where a lumped axis' damping comes from: its elements' dashpots (damping_n_s_m), or a
// `damping:` block that sets it per undamped mode instead (then every damping_n_s_m is 0).
enum class LumpedDampingKind { kElements, kModal, kRayleigh };

// The `damping:` block of a lumped axis. Its C acts on the deflection y = q - g u, not on
// the rigid motion the command imposes (lumped_matrices.h): like a dashpot across the
// guides, it does not brake a carriage moving at constant speed.
struct LumpedDamping {
  // The YAML keys (the reader, messages and the sweep's fast path spell them from here).
  static constexpr const char* kKey = "damping";
  static constexpr const char* kModalKey = "modal";
  static constexpr const char* kRayleighKey = "rayleigh";

  LumpedDampingKind kind = LumpedDampingKind::kElements;
  // kModal: zeta of the undamped modes in ascending frequency; a list shorter than the
  // modes repeats its last entry for the higher ones (`modal: [0.03]`: 3 % on every mode).
  // C = M Phi diag(2 zeta_i w_i) Phi^T M with Phi^T M Phi = I.
  std::vector<double> modal;
  RayleighDamping rayleigh;  // kRayleigh
};

struct LumpedMachineConfig {
  std::vector<LumpedBody> bodies;
  std::vector<LumpedElement> elements;
  // What the drive is mounted on: "ground", or a body (the bed) that then takes the
  // drive's reaction. The "driven" endpoint sits at that body's position plus the command.
  std::string driven_relative_to = "ground";
  // Deflection = displacement of `output_body` relative to `output_relative_to` (a body or
  // "ground"), less the relative motion the command itself imposes.
  std::string output_body;
  std::string output_relative_to = "ground";
  LumpedDamping damping;
  void validate() const;

  // `output: {body, relative_to}` and `damping: {modal: [...]}` | `{rayleigh: {alpha,
  // beta}}` are nested mappings the machine reader reads itself.
  template <typename Archive>
  void Serialize(Archive* a) {
    a->Visit("bodies", &bodies, kMaxModelEntries);
    a->Visit("elements", &elements, 2 * kMaxModelEntries);
    a->Visit("driven_relative_to", &driven_relative_to);
  }
};

struct MachineConfig {
  using Form = std::variant<ModalMachineConfig, LumpedMachineConfig>;
  Form form = ModalMachineConfig{};
  void validate() const;
};

// Calls f(form) with a default-constructed instance of every plant form, in the variant's
// order: key lists that cover "any form" (the sweep's plant-only keys, structure numbers)
// take a new form in with no edit.
template <typename F, std::size_t... I>
void ForEachMachineForm(F&& f, std::index_sequence<I...>) {
  (f(std::variant_alternative_t<I, MachineConfig::Form>{}), ...);
}
template <typename F>
void ForEachMachineForm(F&& f) {
  ForEachMachineForm(f, std::make_index_sequence<std::variant_size_v<MachineConfig::Form>>{});
}

// One axis' structure (input: that axis' acceleration, output: its deflection). A coupled
// modal form spans three axes and is built by BuildMachinePlant (multi_axis_machine.h):
// here it is a std::logic_error, as in AnalyzeModes.
LinearPlant BuildPlant(const MachineConfig& machine);

struct ModeInfo {
  double frequency_hz = 0.0;
  double damping_ratio = 0.0;
  // Share of this mode in the static deflection per unit acceleration; sums to 1.
  double participation = 0.0;
};

struct ModalAnalysis {
  std::vector<ModeInfo> modes;  // ascending frequency
  // |deflection| in m per 1 m/s^2 of acceleration along the driven axis, held constant.
  double static_deflection_per_accel_s2 = 0.0;
};

ModalAnalysis AnalyzeModes(const MachineConfig& machine);

// True when the structure has no damping at all (every modal damping_ratio, every lumped
// element's damping_n_s_m, every entry of a lumped `damping:` block exactly 0): the vibration a motion leaves in it stays for ever.
bool ConservesEnergy(const MachineConfig& machine);

}  // namespace shapebench::model

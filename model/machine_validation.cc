// validate() of the machine configs: every physically invalid value is rejected with the
// field that holds it, so the scenario loader can point at the offending YAML line.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <unordered_map>
#include <variant>
#include <vector>

#include "common/field_list.h"
#include "common/format.h"
#include "common/validation_error.h"
#include "model/machine.h"

namespace shapebench::model {
namespace {

// "LIST[i].FIELD" as the field lists name them (common/field_list.h), "LIST[i]" for the
// whole entry.
template <typename Form, typename Entry>
std::string Indexed(std::vector<Entry> Form::*list, size_t i) {
  return FieldName(list) + "[" + std::to_string(i) + "]";
}
template <typename Form, typename Entry, typename T>
std::string Indexed(std::vector<Entry> Form::*list, size_t i, T Entry::*field) {
  return Indexed(list, i) + "." + FieldName(field);
}
constexpr auto kBodies = &LumpedMachineConfig::bodies;
constexpr auto kElements = &LumpedMachineConfig::elements;
constexpr auto kModes = &ModalMachineConfig::modes;

bool IsReserved(const std::string& name) { return name == "ground" || name == "driven"; }

// The graph of springs (k > 0) between bodies and ground, "driven" standing for the node it
// is mounted on. K is positive definite exactly when every body reaches ground through it.
std::vector<bool> RestrainedBodies(const LumpedMachineConfig& config,
                                   const std::unordered_map<std::string, int>& index) {
  const int n = static_cast<int>(config.bodies.size());
  const int ground = n;
  auto node = [&](const std::string& name) {
    const std::string& resolved = name == "driven" ? config.driven_relative_to : name;
    return resolved == "ground" ? ground : index.at(resolved);
  };
  std::vector<std::vector<int>> neighbours(n + 1);
  for (const LumpedElement& e : config.elements) {
    if (!(e.stiffness_n_m > 0.0)) continue;
    const int a = node(e.from);
    const int b = node(e.to);
    if (a == b) continue;
    neighbours[a].push_back(b);
    neighbours[b].push_back(a);
  }
  std::vector<bool> reached(n + 1, false);
  std::vector<int> stack{ground};
  reached[ground] = true;
  while (!stack.empty()) {
    const int at = stack.back();
    stack.pop_back();
    for (int next : neighbours[at]) {
      if (!reached[next]) {
        reached[next] = true;
        stack.push_back(next);
      }
    }
  }
  reached.pop_back();
  return reached;
}

void ValidateBodies(const LumpedMachineConfig& config,
                    std::unordered_map<std::string, int>& index) {
  if (config.bodies.empty()) {
    throw ValidationError("bodies", "must list at least one body");
  }
  for (size_t i = 0; i < config.bodies.size(); ++i) {
    const LumpedBody& body = config.bodies[i];
    if (body.name.empty()) {
      throw ValidationError(Indexed(kBodies, i, &LumpedBody::name), "must not be empty");
    }
    if (IsReserved(body.name)) {
      throw ValidationError(Indexed(kBodies, i, &LumpedBody::name),
                            "\"" + body.name +
                                "\" is reserved for an element endpoint; "
                                "choose another body name");
    }
    if (!index.emplace(body.name, static_cast<int>(i)).second) {
      throw ValidationError(Indexed(kBodies, i, &LumpedBody::name),
                            "duplicate body name \"" + body.name + "\"");
    }
    if (!(body.mass_kg > 0.0) || !std::isfinite(body.mass_kg)) {
      throw ValidationError(Indexed(kBodies, i, &LumpedBody::mass_kg),
                            "must be finite and > 0" + FormatGot(body.mass_kg));
    }
  }
}

// A friction element is friction alone; a backlash element a contact spring alone
// (docs/nonlinear.md): a dashpot beside either would act inside the gap or add to the
// friction law, so it goes into an element of its own.
void ValidateNonlinearElement(const LumpedElement& e, size_t i) {
  if (e.friction.present()) {
    for (double LumpedElement::*field :
         {&LumpedElement::stiffness_n_m, &LumpedElement::damping_n_s_m, &LumpedElement::backlash_m}) {
      if (e.*field != 0.0) {
        throw ValidationError(Indexed(kElements, i, field),
                              "must be 0 in a friction element (\"" + e.name +
                                  "\" has friction:); put a spring or damper in an element of its own" +
                                  FormatGot(e.*field));
      }
    }
  }
  try {
    e.friction.validate();
  } catch (const ValidationError& error) {
    throw error.Prefixed(Indexed(kElements, i, &LumpedElement::friction));
  }
  if (e.backlash_m > 0.0) {
    if (!(e.stiffness_n_m > 0.0)) {
      throw ValidationError(Indexed(kElements, i, &LumpedElement::stiffness_n_m),
                            "must be > 0 in an element with backlash_m (the contact stiffness "
                            "outside the gap)" + FormatGot(e.stiffness_n_m));
    }
    if (e.damping_n_s_m != 0.0) {
      throw ValidationError(Indexed(kElements, i, &LumpedElement::damping_n_s_m),
                            "must be 0 in an element with backlash_m (a dashpot would act inside "
                            "the gap); put it in an element of its own" + FormatGot(e.damping_n_s_m));
    }
  }
}

void ValidateElements(const LumpedMachineConfig& config,
                      const std::unordered_map<std::string, int>& index) {
  auto check_endpoint = [&](size_t i, std::string LumpedElement::*field) {
    const std::string& name = config.elements[i].*field;
    if (name != "ground" && name != "driven" && index.count(name) == 0) {
      throw ValidationError(
          Indexed(kElements, i, field),
          "unknown endpoint \"" + name + "\"; allowed: a body name, \"ground\" or \"driven\"");
    }
  };
  auto check_coefficient = [&](size_t i, double LumpedElement::*field) {
    const double value = config.elements[i].*field;
    if (!(value >= 0.0) || !std::isfinite(value)) {
      throw ValidationError(Indexed(kElements, i, field), "must be finite and >= 0" + FormatGot(value));
    }
  };
  bool touches_driven = false;
  for (size_t i = 0; i < config.elements.size(); ++i) {
    const LumpedElement& e = config.elements[i];
    check_endpoint(i, &LumpedElement::from);
    check_endpoint(i, &LumpedElement::to);
    if (e.from == e.to) {
      throw ValidationError(Indexed(kElements, i, &LumpedElement::to),
                            "must differ from \"from\" (both are \"" + e.to + "\")");
    }
    check_coefficient(i, &LumpedElement::stiffness_n_m);
    check_coefficient(i, &LumpedElement::damping_n_s_m);
    check_coefficient(i, &LumpedElement::backlash_m);
    ValidateNonlinearElement(e, i);
    if (e.stiffness_n_m == 0.0 && e.damping_n_s_m == 0.0 && !e.friction.present()) {
      throw ValidationError(Indexed(kElements, i),
                            "stiffness_n_m and damping_n_s_m are both 0; give at least one "
                            "a positive value (or a friction: {model: ...})");
    }
    touches_driven = touches_driven || e.from == "driven" || e.to == "driven";
  }
  if (!touches_driven) {
    throw ValidationError("elements",
                          "no element has the endpoint \"driven\"; the drive would not move "
                          "the machine");
  }
}

void ValidateReferences(const LumpedMachineConfig& config,
                        const std::unordered_map<std::string, int>& index) {
  if (config.driven_relative_to != "ground" && index.count(config.driven_relative_to) == 0) {
    throw ValidationError("driven_relative_to", "unknown \"" + config.driven_relative_to +
                                                    "\"; allowed: \"ground\" or a body name");
  }
  if (index.count(config.output_body) == 0) {
    throw ValidationError("output.body",
                          "unknown body \"" + config.output_body + "\"; allowed: a body name");
  }
  if (config.output_relative_to != "ground" && index.count(config.output_relative_to) == 0) {
    throw ValidationError("output.relative_to", "unknown \"" + config.output_relative_to +
                                                    "\"; allowed: \"ground\" or a body name");
  }
  if (config.output_relative_to == config.output_body) {
    throw ValidationError("output.relative_to",
                          "must differ from output.body (both are \"" + config.output_body + "\")");
  }
}

// "damping.modal" | "damping.rayleigh": the block as the YAML spells it.
std::string DampingBlockName(LumpedDampingKind kind) {
  return std::string(LumpedDamping::kKey) + "." +
         (kind == LumpedDampingKind::kModal ? LumpedDamping::kModalKey : LumpedDamping::kRayleighKey);
}

// The `damping:` block: its numbers, and no dashpot beside it (one source of damping).
void ValidateDamping(const LumpedMachineConfig& config) {
  const LumpedDamping& damping = config.damping;
  if (damping.kind == LumpedDampingKind::kElements) return;
  const std::string block = DampingBlockName(damping.kind);
  for (size_t i = 0; i < config.elements.size(); ++i) {
    const LumpedElement& e = config.elements[i];
    if (e.damping_n_s_m == 0.0) continue;
    throw ValidationError(Indexed(kElements, i, &LumpedElement::damping_n_s_m),
                          "element \"" + e.name + "\" has a dashpot" + FormatGot(e.damping_n_s_m) +
                              " and the axis has '" + block +
                              "': damp the axis one way, set every damping_n_s_m to 0 or "
                              "remove '" + std::string(LumpedDamping::kKey) + "'");
  }
  if (damping.kind == LumpedDampingKind::kRayleigh) {
      for (double RayleighDamping::*field : {&RayleighDamping::alpha, &RayleighDamping::beta}) {
      const double value = damping.rayleigh.*field;
      if (!(value >= 0.0) || !std::isfinite(value)) {
        throw ValidationError(block + "." + FieldName(field), "must be finite and >= 0" + FormatGot(value));
      }
    }
    return;
  }
  if (damping.modal.empty()) throw ValidationError(block, "must list at least one damping ratio");
  if (damping.modal.size() > config.bodies.size()) {
    throw ValidationError(block, "lists " + std::to_string(damping.modal.size()) +
                                     " damping ratios; the axis has " +
                                     std::to_string(config.bodies.size()) +
                                     " modes (one per body)");
  }
  for (size_t i = 0; i < damping.modal.size(); ++i) {
    const double zeta = damping.modal[i];
    if (!(zeta >= 0.0 && zeta < 1.0)) {
      throw ValidationError(block + "[" + std::to_string(i) + "]",
                            "must be in [0, 1) (underdamped)" + FormatGot(zeta));
    }
  }
}

// A coupled mode (machine.h, ModalMode): participation and shape together, instead of
// gain (which stays at its default 1), every component finite.
void ValidateCoupling(const ModalMode& mode, size_t i) {
  const std::string gain = Indexed(kModes, i, &ModalMode::gain);
  const std::string participation = Indexed(kModes, i, &ModalMode::participation);
  const std::string shape = Indexed(kModes, i, &ModalMode::shape);
  if (!mode.participation || !mode.shape) {
    const bool has_shape = mode.shape.has_value();
    throw ValidationError(has_shape ? participation : shape,
                          std::string("missing: a mode with ") + (has_shape ? "shape" : "participation") +
                              " needs " + (has_shape ? "participation" : "shape") +
                              " too ({x, y, z} each), or neither and a gain");
  }
  if (mode.gain != 1.0) {
    throw ValidationError(gain, "is the one-axis shorthand of participation and shape (gain = "
                                "shape_a x participation_a); give gain, or participation and "
                                "shape" + FormatGot(mode.gain));
  }
  for (const auto& [name, vector] : {std::pair{participation, *mode.participation}, std::pair{shape, *mode.shape}}) {
    for (double AxisVector::*component : {&AxisVector::x, &AxisVector::y, &AxisVector::z}) {
      if (!std::isfinite(vector.*component)) {
        throw ValidationError(name + "." + FieldName(component), "must be finite" + FormatGot(vector.*component));
      }
    }
  }
}

}  // namespace

void ModalMachineConfig::validate() const {
  if (modes.empty()) throw ValidationError("modes", "must list at least one mode");
  for (size_t i = 0; i < modes.size(); ++i) {
    const ModalMode& mode = modes[i];
    if (!(mode.frequency_hz > 0.0) || !std::isfinite(mode.frequency_hz)) {
      throw ValidationError(Indexed(kModes, i, &ModalMode::frequency_hz),
                            "must be finite and > 0" + FormatGot(mode.frequency_hz));
    }
    if (!(mode.damping_ratio >= 0.0 && mode.damping_ratio < 1.0)) {
      throw ValidationError(Indexed(kModes, i, &ModalMode::damping_ratio),
                            "must be in [0, 1) (underdamped)" + FormatGot(mode.damping_ratio));
    }
    if (!std::isfinite(mode.gain)) {
      throw ValidationError(Indexed(kModes, i, &ModalMode::gain), "must be finite" + FormatGot(mode.gain));
    }
    if (mode.coupled()) ValidateCoupling(mode, i);
  }
}

bool ModalMachineConfig::coupled() const {
  return std::any_of(modes.begin(), modes.end(), [](const ModalMode& mode) { return mode.coupled(); });
}

void LumpedMachineConfig::validate() const {
  std::unordered_map<std::string, int> index;
  ValidateBodies(*this, index);
  ValidateElements(*this, index);
  ValidateDamping(*this);
  ValidateReferences(*this, index);
  const std::vector<bool> restrained = RestrainedBodies(*this, index);
  for (size_t i = 0; i < bodies.size(); ++i) {
    if (!restrained[i]) {
      throw ValidationError(Indexed(kBodies, i, &LumpedBody::name),
                            "body \"" + bodies[i].name +
                                "\" is not restrained: no chain of springs (stiffness_n_m > 0) "
                                "ties it to \"ground\" or \"driven\", so it has no rest position");
    }
  }
}

void MachineConfig::validate() const {
  std::visit([](const auto& config) { config.validate(); }, form);
}

}  // namespace shapebench::model

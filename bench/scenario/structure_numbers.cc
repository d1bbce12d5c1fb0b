#include "bench/scenario/structure_numbers.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <system_error>
#include <variant>

#include "common/field_list.h"

#include "bench/config/key_path.h"
#include "bench/config/node_reader.h"
#include "bench/scenario/scenario_loader.h"

namespace shapebench::bench {
namespace {

// Where a structure number lives: the axis' form (-1: the single form's axis), the list,
// the entry and the field; or a number of a lumped axis' `damping:` block (block set).
struct StructureKey {
  int axis = -1;
  std::string list;   // "modes", "bodies", "elements"
  std::size_t index = 0;
  std::string field;  // "frequency_hz", ...
  // kModal: damping.modal[index]; kRayleigh: damping.rayleigh.FIELD.
  std::optional<model::LumpedDampingKind> block;
  // A component (x, y, z) of a coupled mode's participation or shape (`field`).
  std::string component;
  // `modes[i].frequency_hz`, `damping_ratio` or `gain`: the member ListNumberField finds in
  // a modal form, named once here (a sweep point sets it without walking the field list).
  double model::ModalMode::*modal_number = nullptr;
};

// `modes[i].participation.x` (or shape; x, y, z) of the single form from `path[1]` on.
std::optional<StructureKey> ParseCouplingKey(const std::vector<PathElement>& path) {
  model::AxisVector vector;
  const PathElement& list = path[1];
  const PathElement& entry = path[2];
  const PathElement& field = path[3];
  const PathElement& component = path[4];
  if (list.key != FieldName(&model::ModalMachineConfig::modes) || list.index || !entry.index ||
      !entry.key.empty() || field.index || component.index || NumberField(&vector, component.key) == nullptr ||
      (field.key != FieldName(&model::ModalMode::participation) && field.key != FieldName(&model::ModalMode::shape))) {
    return std::nullopt;
  }
  StructureKey key;
  key.list = list.key;
  key.index = *entry.index;
  key.field = field.key;
  key.component = component.key;
  return key;
}

// `damping.modal[i]` or `damping.rayleigh.alpha|beta` (machine.h, LumpedDamping) from
// `path[at]` on (three elements); nullopt for anything else.
std::optional<StructureKey> ParseDampingKey(const std::vector<PathElement>& path, std::size_t at,
                                            StructureKey key) {
  using model::LumpedDamping;
  const PathElement& block = path[at + 1];
  const PathElement& last = path[at + 2];
  if (path[at].key != LumpedDamping::kKey || path[at].index || block.index) return std::nullopt;
  if (block.key == LumpedDamping::kModalKey && last.index && last.key.empty()) {
    key.block = model::LumpedDampingKind::kModal;
    key.index = *last.index;
    return key;
  }
  model::RayleighDamping rayleigh;
  if (block.key == LumpedDamping::kRayleighKey && !last.index && NumberField(&rayleigh, last.key)) {
    key.block = model::LumpedDampingKind::kRayleigh;
    key.field = last.key;
    return key;
  }
  return std::nullopt;
}

bool IsField(const std::string& list, const std::string& field) {
  // A number field of an entry of one of the forms' lists (their field lists say which).
  bool found = false;
  model::ForEachMachineForm([&](const auto& form) {
    found = found || ListHasNumberField<std::decay_t<decltype(form)>>(list, field);
  });
  return found;
}

std::optional<StructureKey> ParseStructureKey(const std::string& key_path) {
  const auto path = ParseKeyPath(key_path);
  if (!path || path->empty() || (*path)[0].key != "machine" || (*path)[0].index) return std::nullopt;
  if (path->size() == 5) return ParseCouplingKey(*path);  // coupled modes: single form only
  StructureKey key;
  std::size_t at = 1;
  if (path->size() == 6 && (*path)[1].key == "axes" && !(*path)[1].index) {
    const std::string& name = (*path)[2].key;
    if ((*path)[2].index) return std::nullopt;
    key.axis = name == "x" ? 0 : name == "y" ? 1 : name == "z" ? 2 : -2;
    if (key.axis < 0) return std::nullopt;
    at = 3;
  } else if (path->size() != 4) {
    return std::nullopt;
  }
  // LIST, then [i] (ParseKeyPath gives the index as its own element), then FIELD.
  if (auto damping = ParseDampingKey(*path, at, key)) return damping;
  const PathElement& list = (*path)[at];
  const PathElement& entry = (*path)[at + 1];
  const PathElement& field = (*path)[at + 2];
  if (list.index || !entry.index || !entry.key.empty() || field.index) return std::nullopt;
  if (!IsField(list.key, field.key)) return std::nullopt;
  key.list = list.key;
  key.index = *entry.index;
  key.field = field.key;
  if (key.list == FieldName(&model::ModalMachineConfig::modes)) {
    for (double model::ModalMode::*number :
         {&model::ModalMode::frequency_hz, &model::ModalMode::damping_ratio, &model::ModalMode::gain}) {
      if (key.field == FieldName(number)) key.modal_number = number;
    }
  }
  return key;
}

// The number as NodeReader::AsNumber reads it; nullopt where it would refuse it.
std::optional<double> PlainNumber(const std::string& text) {
  if (!IsNumberText(text)) return std::nullopt;
  // from_chars first: the same correctly rounded value as strtod, at a fraction of its cost
  // (a sweep point parses its values here); strtod for what it leaves (a '+', an underflow).
  const char* first = text.data();
  const char* last = first + text.size();
  double parsed = 0.0;
  if (const auto [end, ec] = std::from_chars(first, last, parsed); ec == std::errc() && end == last) return parsed;
  errno = 0;
  const double value = std::strtod(text.c_str(), nullptr);
  if (errno == ERANGE && std::isinf(value)) return std::nullopt;
  return value;
}

// A number of the axis' `damping:` block; nullptr unless the axis is lumped and has that
// very block (a point that adds, removes or switches a block is loaded from its sources,
// which also locates a dashpot beside it).
double* DampingFieldOf(model::MachineConfig& machine, const StructureKey& key) {
  auto* lumped = std::get_if<model::LumpedMachineConfig>(&machine.form);
  if (lumped == nullptr || lumped->damping.kind != *key.block) return nullptr;
  if (*key.block == model::LumpedDampingKind::kRayleigh) {
    return NumberField(&lumped->damping.rayleigh, key.field);
  }
  std::vector<double>& modal = lumped->damping.modal;
  return key.index < modal.size() ? &modal[key.index] : nullptr;
}

// A coupled mode's participation or shape component; nullptr unless the mode has it. A
// gain of a coupled mode does not fit either: loaded from its sources, it is the error
// that names gain beside participation and shape. Modes read from a modal_file have no
// keys in the YAML to set.
double* ModalFieldOf(model::ModalMachineConfig& modal, const StructureKey& key) {
  if (!modal.modal_file.empty() || key.index >= modal.modes.size()) return nullptr;
  model::ModalMode& mode = modal.modes[key.index];
  if (key.component.empty()) {
    if (key.modal_number != nullptr) {
      return mode.coupled() && key.modal_number == &model::ModalMode::gain ? nullptr : &(mode.*key.modal_number);
    }
    return ListNumberField(&modal, key.list, key.index, key.field);
  }
  std::optional<model::AxisVector>& vector =
      key.field == FieldName(&model::ModalMode::participation) ? mode.participation : mode.shape;
  return vector ? NumberField(&*vector, key.component) : nullptr;
}

// The field, whichever form the axis has; nullptr when the key does not fit it.
double* FieldOf(model::MachineConfig& machine, const StructureKey& key) {
  if (key.block) return DampingFieldOf(machine, key);
  if (auto* modal = std::get_if<model::ModalMachineConfig>(&machine.form)) return ModalFieldOf(*modal, key);
  if (!key.component.empty()) return nullptr;
  return std::visit([&](auto& form) { return ListNumberField(&form, key.list, key.index, key.field); },
                    machine.form);
}


// ParseStructureKey of the keys this thread parsed last: a sweep asks for the same one or
// two keys at every point (a function of the text alone, so the same answer).
const std::optional<StructureKey>& ParsedStructureKey(const std::string& key_path) {
  struct Parsed {
    std::string text;
    std::optional<StructureKey> key;
  };
  constexpr std::size_t kKept = 8;
  thread_local std::vector<Parsed> parsed;
  for (const Parsed& p : parsed) {
    if (p.text == key_path) return p.key;
  }
  if (parsed.size() == kKept) parsed.erase(parsed.begin());
  parsed.push_back({key_path, ParseStructureKey(key_path)});
  return parsed.back().key;
}

}  // namespace

bool IsStructureNumberKey(const std::string& key_path) {
  return ParsedStructureKey(key_path).has_value();
}

bool SetStructureNumbers(Scenario* scenario, const std::vector<Override>& values, std::optional<double> motion_s) {
  model::MultiAxisMachineConfig& machine = scenario->machine;
  for (const Override& value : values) {
    const std::optional<StructureKey>& key = ParsedStructureKey(value.key_path);
    const std::optional<double> number = PlainNumber(value.value_yaml);
    if (!key || !number) return false;
    // The single form's keys have no axis; the axes form's name theirs.
    if ((key->axis < 0) != machine.single_form) return false;
    const int axis = key->axis < 0 ? machine.driven_axis : key->axis;
    if (!machine.axes[axis]) return false;
    double* field = FieldOf(*machine.axes[axis], *key);
    if (field == nullptr) return false;
    *field = *number;
  }
  return MachineChecksPass(*scenario, motion_s);
}

}  // namespace shapebench::bench

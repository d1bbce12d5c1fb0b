#include "bench/scenario/machine_reader.h"

#include "bench/config/field_reader.h"
#include "bench/scenario/frf_machine_reader.h"
#include "bench/measured/modal_file_reader.h"

#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace shapebench::bench {
namespace {

// The lumped form's keys: its field list and the nested `output` and `damping` mappings.
std::vector<std::string> LumpedKeys() {
  std::vector<std::string> keys = FieldNames<model::LumpedMachineConfig>();
  keys.push_back("output");
  keys.push_back(model::LumpedDamping::kKey);
  return keys;
}

const Choices<int>& AxisChoices() {
  static const Choices<int> kChoices = {{"x", 0}, {"y", 1}, {"z", 2}};
  return kChoices;
}

// "FILE:LINE:COL" of a node, for a message located elsewhere that names it.
std::string Where(const NodeReader& node) {
  const ConfigError at = node.Error("");
  return at.file() + ":" + std::to_string(at.line()) + ":" + std::to_string(at.column());
}

// A coupled mode's keys as written: participation and shape together, without gain (its
// one-axis shorthand). Under `axes:` (`coupling_allowed` false) neither.
void CheckModeCoupling(const NodeReader& mode, bool coupling_allowed) {
  const char* kParticipation = "participation";
  const char* kShape = "shape";
  const auto participation = mode.Child(kParticipation);
  const auto shape = mode.Child(kShape);
  if (!participation && !shape) return;
  const NodeReader& given = participation ? *participation : *shape;
  if (!coupling_allowed) {
    throw given.Error("coupled modes (participation, shape) belong to the single `modes:` form, which "
                      "then models all three axes; under `axes:` each axis has its own independent "
                      "model: use gain");
  }
  if (auto gain = mode.Child("gain")) {
    throw gain->Error("'gain' is the one-axis shorthand of participation and shape (gain = shape_a x "
                      "participation_a, a the machine's axis); this mode gives " +
                      std::string(participation ? kParticipation : kShape) + " (at " + Where(given) +
                      "): give gain, or participation and shape");
  }
  if (!participation || !shape) {
    throw given.Error(std::string("a mode with ") + (participation ? kParticipation : kShape) + " needs " +
                      (participation ? kShape : kParticipation) + " too ({x, y, z} each), or neither and a gain");
  }
}

model::ModalMachineConfig ReadModal(const NodeReader& machine, bool coupling_allowed) {
  model::ModalMachineConfig modal;
  FieldReader reader(machine);
  modal.Serialize(&reader);
  if (auto modes = machine.Child("modes")) {
    for (const NodeReader& mode : modes->Elements()) CheckModeCoupling(mode, coupling_allowed);
  }
  return modal;
}

// `damping: {modal: [zeta, ...]}` or `damping: {rayleigh: {alpha, beta}}` (machine.h,
// LumpedDamping); numbers are checked by validate(), a dashpot beside it here, where both
// places are known.
void ReadDamping(const NodeReader& machine, model::LumpedMachineConfig* lumped) {
  using model::LumpedDamping;
  const auto damping = machine.Child(LumpedDamping::kKey);
  if (!damping) return;
  damping->ExpectMap({LumpedDamping::kModalKey, LumpedDamping::kRayleighKey});
  const auto modal = damping->Child(LumpedDamping::kModalKey);
  const auto rayleigh = damping->Child(LumpedDamping::kRayleighKey);
  if (modal && rayleigh) {
    throw rayleigh->Error("'rayleigh' and 'modal' (at " + Where(*modal) +
                          ") both set this axis' damping; keep one");
  }
  if (modal) {
    const std::vector<NodeReader> ratios = modal->Elements();
    if (ratios.empty()) throw modal->Error("expected a list of damping ratios, one per mode");
    if (ratios.size() > model::kMaxModelEntries) {
      throw modal->Error("at most " + std::to_string(model::kMaxModelEntries) +
                         " damping ratios per axis (got " + std::to_string(ratios.size()) + ")");
    }
    lumped->damping.kind = model::LumpedDampingKind::kModal;
    for (const NodeReader& ratio : ratios) lumped->damping.modal.push_back(ratio.AsNumber());
  } else if (rayleigh) {
    lumped->damping.kind = model::LumpedDampingKind::kRayleigh;
    ReadFields(*rayleigh, &lumped->damping.rayleigh);
  } else {
    throw damping->Error("expected 'modal: [zeta, ...]' or 'rayleigh: {alpha, beta}'");
  }
  const std::string block = std::string(LumpedDamping::kKey) + "." +
                            (modal ? LumpedDamping::kModalKey : LumpedDamping::kRayleighKey);
  for (std::size_t i = 0; i < lumped->elements.size(); ++i) {
    if (lumped->elements[i].damping_n_s_m == 0.0) continue;
    const NodeReader element =
        machine.Child(FieldName(&model::LumpedMachineConfig::elements))->Elements()[i];
    throw element.Child(FieldName(&model::LumpedElement::damping_n_s_m))
        ->Error("element \"" + lumped->elements[i].name + "\" has a dashpot and the axis has '" +
                block + "' (at " + Where(modal ? *modal : *rayleigh) +
                "): damp the axis one way, set every damping_n_s_m to 0 or remove '" +
                LumpedDamping::kKey + "'");
  }
}

model::LumpedMachineConfig ReadLumped(const NodeReader& machine) {
  model::LumpedMachineConfig lumped;
  FieldReader reader(machine);
  lumped.Serialize(&reader);
  if (auto output = machine.Child("output")) {
    output->ExpectMap({"body", "relative_to"});
    output->Read("body", &lumped.output_body);
    output->Read("relative_to", &lumped.output_relative_to);
  }
  ReadDamping(machine, &lumped);
  return lumped;
}

// The measured form (`frf_file`, bench/scenario/frf_machine_reader.h): its keys alone.
model::MachineConfig ReadMeasuredForm(const NodeReader& machine, int axis) {
  std::vector<std::string> others = LumpedKeys();
  others.push_back("modes");
  for (const auto& key : others) {
    if (auto child = machine.Child(key)) {
      throw child->Error("'" + key + "' and 'frf_file' both give this axis' model; the measured form's modes "
                         "come from the file: use one form");
    }
  }
  model::MachineConfig config;
  config.form = ReadFrfMachine(machine, axis);
  return config;
}

// One axis' model (`axis` 0, 1, 2): `modes`, `bodies` (+ elements, ...) or `frf_file`;
// `extra_keys` are allowed beside them and read by the caller.
model::MachineConfig ReadForm(const NodeReader& machine,
                              const std::vector<std::string>& extra_keys, int axis) {
  const std::vector<std::string> lumped_keys = LumpedKeys();
  std::vector<std::string> allowed = FieldNames<model::ModalMachineConfig>();
  allowed.insert(allowed.end(), lumped_keys.begin(), lumped_keys.end());
  allowed.insert(allowed.end(), FrfFormKeys().begin(), FrfFormKeys().end());
  allowed.insert(allowed.end(), extra_keys.begin(), extra_keys.end());
  machine.ExpectMap(allowed);

  if (machine.Has("frf_file")) return ReadMeasuredForm(machine, axis);
  for (const auto& key : FrfFormKeys()) {
    if (auto child = machine.Child(key)) {
      throw child->Error("'" + key + "' belongs to the measured form: give 'frf_file' (a UFF 58 file of FRFs) "
                         "beside it");
    }
  }
  model::MachineConfig config;
  const bool top_level = !extra_keys.empty();  // the single form, where 'axes' could stand
  const char* modal_file_key = model::ModalMachineConfig::kModalFileKey;
  if (auto file = machine.Child(modal_file_key); file && machine.Has("modes")) {
    throw file->Error(std::string("'") + modal_file_key + "' and 'modes' (at " + Where(*machine.Child("modes")) +
                      ") both give the modes; keep one");
  }
  if (machine.Has("modes") || machine.Has(modal_file_key)) {
    const std::string form_key = machine.Has("modes") ? "modes" : modal_file_key;
    for (const auto& key : lumped_keys) {
      if (auto child = machine.Child(key)) {
        throw child->Error("'" + key +
                           "' belongs to the lumped form (bodies, elements, ...); this "
                           "machine is modal (it has '" + form_key + "'): use one form");
      }
    }
    if (auto file = machine.Child(modal_file_key)) {
      config.form = ReadModalFile(*file);
    } else {
      config.form = ReadModal(machine, top_level);
    }
  } else if (machine.Has("bodies")) {
    config.form = ReadLumped(machine);
  } else {
    throw machine.Error(
        std::string("expected 'modes' (modal form) or 'bodies' (lumped mass-spring-damper "
                    "form)") +
        (top_level ? ", or 'axes' (one of those per axis x, y, z)" : "") +
        "; or 'frf_file' (modes identified from measured FRFs)" +
        (top_level ? "; or 'modal_file' (an FE modal export)" : ""));
  }
  return config;
}

// `stroke: {x: [min, max], ...}` in mm (EP0646852's stroke ends).
void ReadStroke(const NodeReader& machine, model::MultiAxisMachineConfig* config) {
  const auto stroke = machine.Child("stroke");
  if (!stroke) return;
  stroke->ExpectMap({"x", "y", "z"});
  for (const auto& [name, axis] : AxisChoices()) {
    const auto limits = stroke->Child(name);
    if (!limits) continue;
    const std::vector<NodeReader> ends = limits->Elements();
    if (ends.size() != 2) throw limits->Error("expected [min, max] in mm");
    config->stroke_m[axis] = std::array<double, 2>{ends[0].AsNumber() * 1e-3, ends[1].AsNumber() * 1e-3};
  }
}

// `rigid: [x, z]`: axes without a model that a program may still move. An axis with a
// model cannot be rigid.
void ReadRigid(const NodeReader& machine, model::MultiAxisMachineConfig* config) {
  const auto rigid = machine.Child("rigid");
  if (!rigid) return;
  for (const NodeReader& entry : rigid->Elements()) {
    const int axis = entry.AsChoice(AxisChoices());
    if (config->Models(axis)) {
      throw entry.Error(std::string("axis ") + model::AxisName(axis) + " has a model in this machine" +
                        (config->axes[axis] ? "" : " (its coupled modes model every axis)") +
                        "; only an axis without one can be rigid");
    }
    config->rigid[axis] = true;
  }
}

model::MultiAxisMachineConfig ReadAxesForm(const NodeReader& machine) {
  std::vector<std::string> single_keys = {"modes", "axis", model::ModalMachineConfig::kModalFileKey};
  const std::vector<std::string> lumped_keys = LumpedKeys();
  single_keys.insert(single_keys.end(), lumped_keys.begin(), lumped_keys.end());
  single_keys.insert(single_keys.end(), FrfFormKeys().begin(), FrfFormKeys().end());
  for (const auto& key : single_keys) {
    if (auto child = machine.Child(key)) {
      throw child->Error("'" + key +
                         "' belongs to the single-axis form; this machine lists 'axes': put "
                         "each axis' model under axes.x, axes.y or axes.z");
    }
  }
  machine.ExpectMap({"axes", "driven_axis", "stroke", "rigid", "reference_mm"});
  model::MultiAxisMachineConfig config;
  config.axes = {};
  config.single_form = false;
  const NodeReader axes = *machine.Child("axes");
  axes.ExpectMap({"x", "y", "z"});
  for (const auto& [name, axis] : AxisChoices()) {
    if (auto form = axes.Child(name)) {
      if (auto misplaced = form->Child(model::ModalMachineConfig::kModalFileKey)) {
        throw misplaced->Error(std::string("'") + model::ModalMachineConfig::kModalFileKey +
                               "' belongs to the single form: an FE export's modes couple the axes, "
                               "and under 'axes' each axis has its own independent model");
      }
      if (auto misplaced = form->Child("axis")) {
        throw misplaced->Error("'axis' belongs to the single-axis form; under 'axes' the key (" +
                               name + ") names the axis");
      }
      config.axes[axis] = ReadForm(*form, {}, axis);
    }
  }
  machine.Read<int>("driven_axis", AxisChoices(), &config.driven_axis);
  ReadStroke(machine, &config);
  ReadRigid(machine, &config);
  return config;
}

// The single form's driven axis: `axis`, or for a coupled modal form (which models every
// axis) `driven_axis` as well, one of the two.
void ReadSingleFormAxis(const NodeReader& machine, const model::MachineConfig& form,
                        model::MultiAxisMachineConfig* config) {
  const auto* modal = std::get_if<model::ModalMachineConfig>(&form.form);
  if (auto driven = machine.Child("driven_axis")) {
    if (modal == nullptr || !modal->coupled()) {
      throw driven->Error(
          "'driven_axis' belongs to the multi-axis form (axes:); a single-form machine is "
          "driven along its 'axis' (default y); a coupled modal machine (participation and "
          "shape, or a modal_file) may name either");
    }
    if (auto axis = machine.Child("axis")) {
      throw driven->Error("'driven_axis' and 'axis' (at " + Where(*axis) +
                          ") both name the driven axis; keep one");
    }
    machine.Read<int>("driven_axis", AxisChoices(), &config->driven_axis);
  }
  machine.Read<int>("axis", AxisChoices(), &config->driven_axis);
}

}  // namespace

model::MultiAxisMachineConfig ReadMachineAxes(const NodeReader& machine) {
  if (machine.IsMap() && machine.Has("axes")) return ReadAxesForm(machine);
  if (!machine.IsMap() || !(machine.Has("modes") || machine.Has(model::ModalMachineConfig::kModalFileKey))) {
    if (auto driven = machine.Child("driven_axis")) {
      throw driven->Error(
          "'driven_axis' belongs to the multi-axis form (axes:); a single-form machine is "
          "driven along its 'axis' (default y)");
    }
  }
  model::MultiAxisMachineConfig config;
  config.axes = {};
  config.single_form = true;
  // The measured form reads its FRF records along the axis, so it is known before the form.
  if (machine.IsMap()) machine.Read<int>("axis", AxisChoices(), &config.driven_axis);
  const model::MachineConfig form = ReadForm(
      machine, {"axis", "driven_axis", "stroke", "rigid", "reference_mm",
                model::ModalMachineConfig::kModalFileKey},
      config.driven_axis);
  ReadSingleFormAxis(machine, form, &config);
  ReadStroke(machine, &config);
  config.axes[config.driven_axis] = form;
  ReadRigid(machine, &config);
  return config;
}

model::MachineConfig ReadMachine(const NodeReader& machine) {
  const model::MultiAxisMachineConfig config = ReadMachineAxes(machine);
  if (config.CoupledModes() != nullptr) {
    throw machine.Error("the machine's coupled modes span three axes; the single-axis view drops their "
                        "cross terms (read it with ReadMachineAxes)");
  }
  const auto& driven = config.axes[config.driven_axis];
  if (!driven) {
    const auto at = machine.Child("driven_axis");
    throw (at ? *at : machine)
        .Error(std::string("the driven axis ") + model::AxisName(config.driven_axis) +
               " has no model under 'axes'");
  }
  return *driven;
}

}  // namespace shapebench::bench

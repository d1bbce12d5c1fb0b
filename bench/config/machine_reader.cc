#include "bench/config/machine_reader.h"

#include <string>
#include <utility>
#include <vector>

namespace shapebench::bench {
namespace {

const std::vector<std::string> kLumpedKeys = {"bodies", "elements", "driven_relative_to",
                                              "output"};

const std::vector<std::pair<std::string, int>>& AxisChoices() {
  static const std::vector<std::pair<std::string, int>> kChoices = {{"x", 0}, {"y", 1}, {"z", 2}};
  return kChoices;
}

// Guard rail (issue 7): a model's states per axis. The modal analysis and the exact
// integrator's matrix exponential grow with their cube (400 bodies: 17 s a run).
constexpr std::size_t kMaxModelEntries = 100;

void CheckModelSize(const NodeReader& list, const char* what, std::size_t max = kMaxModelEntries) {
  if (list.node().IsSequence() && list.node().size() > max) {
    throw list.Error("at most " + std::to_string(max) + " " + what + " per axis (got " +
                     std::to_string(list.node().size()) + ")");
  }
}

model::ModalMachineConfig ReadModal(const NodeReader& machine) {
  model::ModalMachineConfig modal;
  modal.modes.clear();
  CheckModelSize(*machine.Child("modes"), "modes");
  for (const NodeReader& entry : machine.Child("modes")->Elements()) {
    entry.ExpectMap({"frequency_hz", "damping_ratio", "gain"});
    model::ModalMode mode;
    entry.Read("frequency_hz", &mode.frequency_hz);
    entry.Read("damping_ratio", &mode.damping_ratio);
    entry.Read("gain", &mode.gain);
    modal.modes.push_back(mode);
  }
  return modal;
}

model::LumpedMachineConfig ReadLumped(const NodeReader& machine) {
  model::LumpedMachineConfig lumped;
  if (auto bodies = machine.Child("bodies")) {
    CheckModelSize(*bodies, "bodies");
    for (const NodeReader& entry : bodies->Elements()) {
      entry.ExpectMap({"name", "mass_kg"});
      model::LumpedBody body;
      entry.Read("name", &body.name);
      entry.Read("mass_kg", &body.mass_kg);
      lumped.bodies.push_back(body);
    }
  }
  if (auto elements = machine.Child("elements")) {
    CheckModelSize(*elements, "elements", 2 * kMaxModelEntries);
    for (const NodeReader& entry : elements->Elements()) {
      entry.ExpectMap({"name", "from", "to", "stiffness_n_m", "damping_n_s_m"});
      model::LumpedElement element;
      entry.Read("name", &element.name);
      entry.Read("from", &element.from);
      entry.Read("to", &element.to);
      entry.Read("stiffness_n_m", &element.stiffness_n_m);
      entry.Read("damping_n_s_m", &element.damping_n_s_m);
      lumped.elements.push_back(element);
    }
  }
  machine.Read("driven_relative_to", &lumped.driven_relative_to);
  if (auto output = machine.Child("output")) {
    output->ExpectMap({"body", "relative_to"});
    output->Read("body", &lumped.output_body);
    output->Read("relative_to", &lumped.output_relative_to);
  }
  return lumped;
}

// One axis' model: `modes` or `bodies` (+ elements, ...); `extra_keys` are allowed beside
// them and read by the caller.
model::MachineConfig ReadForm(const NodeReader& machine,
                              const std::vector<std::string>& extra_keys) {
  std::vector<std::string> allowed = {"modes"};
  allowed.insert(allowed.end(), kLumpedKeys.begin(), kLumpedKeys.end());
  allowed.insert(allowed.end(), extra_keys.begin(), extra_keys.end());
  machine.ExpectMap(allowed);

  model::MachineConfig config;
  if (machine.Has("modes")) {
    for (const auto& key : kLumpedKeys) {
      if (auto child = machine.Child(key)) {
        throw child->Error("'" + key +
                           "' belongs to the lumped form (bodies, elements, ...); this "
                           "machine is modal (it has 'modes'): use one form");
      }
    }
    config.form = ReadModal(machine);
  } else if (machine.Has("bodies")) {
    config.form = ReadLumped(machine);
  } else {
    const bool top_level = !extra_keys.empty();  // the single form, where 'axes' could stand
    throw machine.Error(
        std::string("expected 'modes' (modal form) or 'bodies' (lumped mass-spring-damper "
                    "form)") +
        (top_level ? ", or 'axes' (one of those per axis x, y, z)" : ""));
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

model::MultiAxisMachineConfig ReadAxesForm(const NodeReader& machine) {
  std::vector<std::string> single_keys = {"modes", "axis"};
  single_keys.insert(single_keys.end(), kLumpedKeys.begin(), kLumpedKeys.end());
  for (const auto& key : single_keys) {
    if (auto child = machine.Child(key)) {
      throw child->Error("'" + key +
                         "' belongs to the single-axis form; this machine lists 'axes': put "
                         "each axis' model under axes.x, axes.y or axes.z");
    }
  }
  machine.ExpectMap({"axes", "driven_axis", "stroke"});
  model::MultiAxisMachineConfig config;
  config.axes = {};
  config.single_form = false;
  const NodeReader axes = *machine.Child("axes");
  axes.ExpectMap({"x", "y", "z"});
  for (const auto& [name, axis] : AxisChoices()) {
    if (auto form = axes.Child(name)) {
      if (auto misplaced = form->Child("axis")) {
        throw misplaced->Error("'axis' belongs to the single-axis form; under 'axes' the key (" +
                               name + ") names the axis");
      }
      config.axes[axis] = ReadForm(*form, {});
    }
  }
  machine.Read<int>("driven_axis", AxisChoices(), &config.driven_axis);
  ReadStroke(machine, &config);
  return config;
}

}  // namespace

model::MultiAxisMachineConfig ReadMachineAxes(const NodeReader& machine) {
  if (machine.IsMap() && machine.Has("axes")) return ReadAxesForm(machine);
  if (auto driven = machine.Child("driven_axis")) {
    throw driven->Error(
        "'driven_axis' belongs to the multi-axis form (axes:); a single-form machine is "
        "driven along its 'axis' (default y)");
  }
  model::MultiAxisMachineConfig config;
  config.axes = {};
  config.single_form = true;
  const model::MachineConfig form = ReadForm(machine, {"axis", "stroke"});
  machine.Read<int>("axis", AxisChoices(), &config.driven_axis);
  ReadStroke(machine, &config);
  config.axes[config.driven_axis] = form;
  return config;
}

model::MachineConfig ReadMachine(const NodeReader& machine) {
  const model::MultiAxisMachineConfig config = ReadMachineAxes(machine);
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

#include "bench/machine_reader.h"

#include <string>
#include <vector>

namespace shapebench::bench {
namespace {

const std::vector<std::string> kLumpedKeys = {"bodies", "elements", "driven_relative_to",
                                              "output"};

model::ModalMachineConfig ReadModal(const NodeReader& machine) {
  model::ModalMachineConfig modal;
  modal.modes.clear();
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
    for (const NodeReader& entry : bodies->Elements()) {
      entry.ExpectMap({"name", "mass_kg"});
      model::LumpedBody body;
      entry.Read("name", &body.name);
      entry.Read("mass_kg", &body.mass_kg);
      lumped.bodies.push_back(body);
    }
  }
  if (auto elements = machine.Child("elements")) {
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

}  // namespace

model::MachineConfig ReadMachine(const NodeReader& machine) {
  std::vector<std::string> allowed = {"modes"};
  allowed.insert(allowed.end(), kLumpedKeys.begin(), kLumpedKeys.end());
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
    throw machine.Error(
        "expected 'modes' (modal form) or 'bodies' (lumped mass-spring-damper form)");
  }
  return config;
}

}  // namespace shapebench::bench

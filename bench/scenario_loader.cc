#include "bench/scenario_loader.h"

#include <cmath>
#include <filesystem>
#include <optional>

#include "bench/config_document.h"
#include "bench/controller_reader.h"
#include "bench/key_path.h"
#include "bench/machine_reader.h"
#include "bench/metrics.h"
#include "bench/node_reader.h"
#include "bench/program_reader.h"
#include "controller/controller.h"

namespace shapebench::bench {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kScenarioKeys = {
    "name", "machine", "drive", "controller", "move", "program", "program_file", "output",
    "integrator", "checks"};

bool HasKey(const YAML::Node& map, const std::string& key) {
  if (!map.IsMap()) return false;
  for (const auto& entry : map) {
    if (entry.first.IsScalar() && entry.first.Scalar() == key) return true;
  }
  return false;
}

// Struct field names that are spelled differently in YAML.
std::string YamlKeyPath(const std::string& field) {
  static const std::vector<std::pair<std::string, std::string>> kRenamed = {
      {"output_body", "output.body"}, {"output_relative_to", "output.relative_to"}};
  for (const auto& [from, to] : kRenamed) {
    const std::size_t at = field.rfind(from);
    if (at != std::string::npos && at + from.size() == field.size() &&
        (at == 0 || field[at - 1] == '.')) {
      return field.substr(0, at) + to;
    }
  }
  return field;
}

ConfigError Located(const ConfigDocument& document, const ValidationError& error) {
  const std::string path = YamlKeyPath(error.field());
  return document.ErrorAtPath(path, error.message());
}

// Runs a validate()-style check; its ValidationError is prefixed and located.
template <typename Check>
void Validated(const ConfigDocument& document, const std::string& prefix, Check&& check) {
  try {
    check();
  } catch (const ValidationError& error) {
    throw Located(document, error.Prefixed(prefix));
  }
}

// `machine: path/to/machine.yaml` -> the file's content in place, its origin recorded.
void ResolveMachineFile(ConfigDocument& document, const fs::path& base_dir) {
  NodeReader top(document, document.root(), "");
  const auto machine = top.Child("machine");
  if (!machine || !machine->IsScalar()) return;
  const std::string reference = machine->AsString();
  const fs::path resolved =
      fs::path(reference).is_absolute() ? fs::path(reference) : base_dir / reference;
  const std::string file = resolved.lexically_normal().string();
  YAML::Node content;
  try {
    content = ConfigDocument::ParseFile(file);
  } catch (const ConfigError& error) {
    if (error.line() > 0) throw;  // malformed YAML: located in the machine file itself
    const std::string shown = file == reference ? "'" + reference + "'"
                                                : "'" + reference + "' (" + file + ")";
    throw machine->Error("machine file " + shown + ": " + error.message());
  }
  document.SpliceTopLevel("machine", content, file);
}

// The scenario file with its machine file spliced in and the overrides applied.
ConfigDocument BuildScenarioDocument(const std::string& path,
                                     const std::vector<Override>& overrides) {
  ConfigDocument document(ConfigDocument::ParseFile(path), path);
  if (!document.root().IsMap()) {
    throw NodeReader(document, document.root(), "")
        .Error("expected a mapping of scenario keys (" + JoinNames(kScenarioKeys, ", ") +
               ")");
  }
  const fs::path base_dir = fs::path(path).parent_path();
  ResolveMachineFile(document, base_dir);
  for (std::size_t i = 0; i < overrides.size(); ++i) {
    document.ApplyOverride(overrides[i], static_cast<int>(i) + 1);
    ResolveMachineFile(document, base_dir);  // --set machine=other.yaml
  }
  return document;
}

const std::vector<std::string> kServoKeys = {"position_gain", "velocity_feedforward",
                                             "velocity_loop_hz", "motor_mass_kg"};

model::DriveConfig ReadDrive(const NodeReader& drive) {
  std::vector<std::string> allowed = {"type"};
  allowed.insert(allowed.end(), kServoKeys.begin(), kServoKeys.end());
  drive.ExpectMap(allowed);
  model::DriveConfig config;
  drive.Read<model::DriveType>(
      "type", {{"kinematic", model::DriveType::kKinematic}, {"servo", model::DriveType::kServo}},
      &config.type);
  if (config.type != model::DriveType::kServo) {
    for (const auto& key : kServoKeys) {
      if (auto child = drive.Child(key)) {
        throw child->Error("'" + key +
                           "' is a servo setting; it needs type: servo (the kinematic drive "
                           "follows the command exactly)");
      }
    }
    return config;
  }
  model::ServoConfig& servo = config.servo;
  drive.Read("position_gain", &servo.position_gain_1_s);
  drive.Read("velocity_feedforward", &servo.velocity_feedforward);
  drive.Read("velocity_loop_hz", &servo.velocity_loop_hz);
  drive.Read("motor_mass_kg", &servo.motor_mass_kg);
  try {
    config.validate();
  } catch (const ValidationError& error) {
    // Its field is the YAML key (a default is always valid, so the key is there).
    const auto child = drive.Child(error.field());
    throw (child ? *child : drive).Error(error.message());
  }
  return config;
}

model::IntegratorConfig ReadIntegrator(const NodeReader& integrator) {
  integrator.ExpectMap(
      {"method", "rtol", "atol_scale", "lmm", "max_num_steps", "output_substeps"});
  model::IntegratorConfig config;
  integrator.Read<model::IntegratorMethod>(
      "method",
      {{"cvode", model::IntegratorMethod::kCvode}, {"exact", model::IntegratorMethod::kExact}},
      &config.method);
  integrator.Read("rtol", &config.rtol);
  integrator.Read("atol_scale", &config.atol_scale);
  integrator.Read<model::CvodeLmm>(
      "lmm", {{"adams", model::CvodeLmm::kAdams}, {"bdf", model::CvodeLmm::kBdf}}, &config.lmm);
  integrator.Read("max_num_steps", &config.max_num_steps);
  integrator.Read("output_substeps", &config.output_substeps);
  return config;
}

std::vector<Check> ReadChecksEntry(const NodeReader& checks) {
  std::vector<std::string> metric_names;
  for (const auto& named : Metrics{}.Named()) metric_names.push_back(named.first);
  checks.ExpectMap(metric_names);
  std::vector<Check> result;
  for (const auto& [metric, bounds] : checks.Entries()) {
    bounds.ExpectMap({"min", "max"});
    Check check;
    check.metric = metric;
    if (auto min = bounds.Child("min")) check.min = min->AsNumber();
    if (auto max = bounds.Child("max")) check.max = max->AsNumber();
    if (!check.min && !check.max) throw bounds.Error("expected min and/or max");
    if (check.min && check.max && *check.min > *check.max) {
      throw bounds.Error("min " + std::to_string(*check.min) + " is above max " +
                         std::to_string(*check.max));
    }
    result.push_back(check);
  }
  return result;
}

Scenario ReadScenario(const ConfigDocument& document, const std::string& path,
                      const LoadOptions& options) {
  NodeReader top(document, document.root(), "");
  top.ExpectMap(kScenarioKeys);

  Scenario scenario;
  scenario.source_file = path;
  scenario.name = fs::path(path).stem().string();
  top.Read("name", &scenario.name);
  if (auto machine = top.Child("machine")) scenario.machine = ReadMachineAxesEntry(*machine);
  if (auto drive = top.Child("drive")) scenario.drive = ReadDrive(*drive);
  if (auto controller = top.Child("controller")) scenario.controller = ReadController(*controller);
  // One of move (the one-block shorthand), program and program_file says what runs.
  std::optional<NodeReader> what_runs;
  for (const char* key : {"move", "program", "program_file"}) {
    auto child = top.Child(key);
    if (!child) continue;
    if (what_runs) {
      throw child->Error("give only one of move, program and program_file (" + what_runs->path() +
                         " is given already)");
    }
    what_runs = child;
  }
  if (auto move = top.Child("move")) scenario.move = ReadMove(*move);
  if (auto program = top.Child("program")) scenario.program = ReadProgramList(*program);
  if (auto program_file = top.Child("program_file")) {
    scenario.program = ReadProgramFile(*program_file, fs::path(path).parent_path().string());
  }
  if (auto output = top.Child("output")) {
    output->ExpectMap({"direction"});
    output->Read<OutputDirection>("direction",
                                  {{"auto", OutputDirection::kAuto},
                                   {"magnitude", OutputDirection::kMagnitude},
                                   {"x", OutputDirection::kX},
                                   {"y", OutputDirection::kY},
                                   {"z", OutputDirection::kZ}},
                                  &scenario.output.direction);
  }
  if (auto integrator = top.Child("integrator")) scenario.integrator = ReadIntegrator(*integrator);
  if (auto checks = top.Child("checks")) scenario.checks = ReadChecksEntry(*checks);

  Validated(document, "machine", [&] { scenario.machine.validate(); });
  Validated(document, "controller", [&] { scenario.controller.validate(); });
  Validated(document, "move", [&] { scenario.move.validate(); });
  Validated(document, "integrator", [&] { scenario.integrator.validate(); });
  if (options.plan_move && !scenario.program) {
    // Its fields are scenario-root paths already ("move.distance_mm").
    Validated(document, "", [&] {
      controller::CheckShapedMove(scenario.controller, std::abs(scenario.move.distance_mm) * 1e-3);
    });
  }
  return scenario;
}

}  // namespace

std::vector<Check> ReadChecks(const NodeReader& checks) { return ReadChecksEntry(checks); }

YAML::Node BuildScenarioTree(const std::string& path, const std::vector<Override>& overrides) {
  return BuildScenarioDocument(path, overrides).root();
}

model::MultiAxisMachineConfig ReadMachineAxesEntry(const NodeReader& machine) {
  if (!machine.IsMap()) {
    throw machine.Error(
        "expected a mapping (modes:, bodies: or axes:) or the path of a machine file");
  }
  return ReadMachineAxes(machine);
}

Scenario LoadScenario(const std::string& path, const std::vector<Override>& overrides,
                      const LoadOptions& options) {
  const ConfigDocument document = BuildScenarioDocument(path, overrides);
  return ReadScenario(document, path, options);
}

model::MultiAxisMachineConfig LoadMachineAxes(const std::string& path,
                                              const std::vector<Override>& overrides) {
  YAML::Node root = ConfigDocument::ParseFile(path);
  const bool machine_file =
      HasKey(root, "modes") || HasKey(root, "bodies") || HasKey(root, "axes");
  if (!machine_file) {
    const ConfigDocument document = BuildScenarioDocument(path, overrides);
    NodeReader top(document, document.root(), "");
    top.ExpectMap(kScenarioKeys);
    model::MultiAxisMachineConfig machine;  // without `machine:`: the default machine
    if (auto entry = top.Child("machine")) machine = ReadMachineAxesEntry(*entry);
    Validated(document, "machine", [&] { machine.validate(); });
    return machine;
  }
  // A machine file is read as the `machine:` of a scenario, so paths match scenarios'.
  YAML::Node top(YAML::NodeType::Map);
  top["machine"] = root;
  ConfigDocument document(top, path);
  for (std::size_t i = 0; i < overrides.size(); ++i) {
    Override scoped = overrides[i];
    if (!IsPathPrefix("machine", scoped.key_path)) {
      scoped.key_path = ChildPath("machine", scoped.key_path);
    }
    document.ApplyOverride(scoped, static_cast<int>(i) + 1);
  }
  NodeReader machine_node(document, document.root(), "");
  machine_node.ExpectMap({"machine"});
  model::MultiAxisMachineConfig machine = ReadMachineAxesEntry(*machine_node.Child("machine"));
  Validated(document, "machine", [&] { machine.validate(); });
  return machine;
}

model::MachineConfig LoadMachine(const std::string& path,
                                 const std::vector<Override>& overrides) {
  const model::MultiAxisMachineConfig machine = LoadMachineAxes(path, overrides);
  const auto& driven = machine.axes[machine.driven_axis];
  if (!driven) {
    throw ConfigError(path, 0, 0, "machine",
                      std::string("the driven axis ") + model::AxisName(machine.driven_axis) +
                          " is rigid (no model); the single-axis view needs its model");
  }
  return *driven;
}

ConfigError LocateValidationError(const std::string& path,
                                  const std::vector<Override>& overrides,
                                  const ValidationError& error) {
  try {
    return Located(BuildScenarioDocument(path, overrides), error);
  } catch (const ConfigError& config_error) {
    return config_error;
  }
}

}  // namespace shapebench::bench

#include "bench/scenario/scenario_loader.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <variant>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>

#include "common/format.h"
#include "common/shown_text.h"
#include "bench/config/config_document.h"
#include "bench/scenario/controller_reader.h"
#include "bench/config/field_reader.h"
#include "bench/config/input_path.h"
#include "bench/config/key_path.h"
#include "bench/config/rule_location.h"
#include "bench/scenario/fmu_machine_reader.h"
#include "bench/scenario/machine_reader.h"
#include "bench/scenario/pattern_defaults.h"
#include "bench/scenario/metrics.h"
#include "bench/scenario/run_memory.h"
#include "bench/config/node_reader.h"
#include "bench/scenario/program_reader.h"
#include "bench/scenario/scenario_guards.h"
#include "controller/controller.h"
#include "controller/path_geometry.h"
#include "controller/shaper_registry.h"
#include "controller/vibration_suppression_pattern.h"
#include "model/nonlinear_integrator.h"

namespace shapebench::bench {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kScenarioKeys = {
    "name", "machine", "drive", "controller", "move", "program", "program_file", "program_strict",
    "program_dialect", "program_arc_tolerance", "program_max_iterations", "output",
    "integrator", "checks", "limits"};

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

// A rule between keys is located at the key the user gave (rule_location.h).
ConfigError Located(const ConfigDocument& document, const ValidationError& error, const std::string& prefix = "") {
  if (const auto* rule = dynamic_cast<const KeyRuleError*>(&error)) {
    std::vector<RuleKey> keys = rule->Prefixed(prefix).keys();
    for (RuleKey& key : keys) key.field = YamlKeyPath(key.field);
    return LocateRuleError(document, KeyRuleError(std::move(keys), rule->rule()));
  }
  const std::string path = YamlKeyPath(error.Prefixed(prefix).field());
  return document.ErrorAtPath(path, error.message());
}

// Runs a validate()-style check; its ValidationError is prefixed and located.
template <typename Check>
void Validated(const ConfigDocument& document, const std::string& prefix, Check&& check) {
  try {
    check();
  } catch (const ValidationError& error) {
    throw Located(document, error, prefix);
  }
}

// `machine: path/to/machine.yaml` -> the file's content in place, its origin recorded.
void ResolveMachineFile(ConfigDocument& document) {
  NodeReader top(document, document.root(), "");
  const auto machine = top.Child("machine");
  if (!machine || !machine->IsScalar()) return;
  const std::string reference = machine->AsString();
  const std::string file = ResolvedInputPath(*machine);
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

// The first key of `key_path` the tree lacks ("machine.mode" of "machine.mode[0].gain"),
// when an index follows it (the override cannot be applied); "" otherwise.
std::string MissingIndexedKey(const YAML::Node& root, const std::string& key_path) {
  const auto elements = ParseKeyPath(key_path);
  if (!elements) return "";
  YAML::Node node;
  node.reset(root);
  std::string path;
  for (std::size_t i = 0; i < elements->size(); ++i) {
    const PathElement& element = (*elements)[i];
    const YAML::Node& parent = node;
    YAML::Node child;
    if (element.index) {
      if (!parent.IsSequence() || *element.index >= parent.size()) return "";
      child.reset(parent[static_cast<int>(*element.index)]);
      path = IndexPath(path, *element.index);
    } else if (!HasKey(parent, element.key)) {
      const bool indexed = std::any_of(elements->begin() + static_cast<std::ptrdiff_t>(i), elements->end(),
                                       [](const PathElement& e) { return e.index.has_value(); });
      return indexed ? ChildPath(path, element.key) : "";
    } else {
      child.reset(parent[element.key]);
      path = ChildPath(path, element.key);
    }
    node.reset(child);
  }
  return "";
}

// An override that indexes a missing key may have misspelt it: loaded with that key set to
// {} instead, the scenario's reader says whether it is unknown (with its "did you mean"),
// which is the better error, located at the same --set.
ConfigError MisspeltIndexedKey(const std::string& path, std::vector<Override> overrides, std::size_t failed,
                               const ConfigError& error) {
  // The tree as it was before the failed override (which may have created keys).
  const std::vector<Override> before(overrides.begin(), overrides.begin() + static_cast<std::ptrdiff_t>(failed));
  const std::string missing = MissingIndexedKey(BuildScenarioTree(path, before), overrides[failed].key_path);
  if (missing.empty()) return error;
  overrides.resize(failed + 1);
  overrides[failed] = Override{missing, "{}"};
  try {
    LoadScenario(path, overrides);
  } catch (const ConfigError& unknown) {
    if (unknown.key_path() == missing && unknown.message().rfind("unknown key", 0) == 0) return unknown;
  } catch (const std::exception&) {
  }
  return error;
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
  ResolveMachineFile(document);
  for (std::size_t i = 0; i < overrides.size(); ++i) {
    try {
      document.ApplyOverride(overrides[i], static_cast<int>(i) + 1);
    } catch (const ConfigError& error) {
      throw MisspeltIndexedKey(path, overrides, i, error);
    }
    ResolveMachineFile(document);  // --set machine=other.yaml, from the current directory
  }
  return document;
}

model::DriveConfig ReadDrive(const NodeReader& drive) {
  const std::vector<std::string> servo_keys = FieldNames<model::ServoConfig>();
  drive.ExpectMap([&] {
    std::vector<std::string> allowed = {"type"};
    allowed.insert(allowed.end(), servo_keys.begin(), servo_keys.end());
    return allowed;
  }());
  model::DriveConfig config;
  drive.Read<model::DriveType>("type", model::DriveConfig::TypeChoices(), &config.type);
  if (config.type != model::DriveType::kServo) {
    for (const auto& key : servo_keys) {
      if (auto child = drive.Child(key)) {
        throw child->Error("'" + key +
                           "' is a servo setting; it needs type: servo (the kinematic drive "
                           "follows the command exactly)");
      }
    }
    return config;
  }
  FieldReader servo(drive);
  config.servo.Serialize(&servo);
  try {
    config.validate();
  } catch (const ValidationError& error) {
    // Its field is the YAML key path (a default is always valid, so the key is there; a
    // nested one, friction.coulomb_n, as deep as it is given).
    NodeReader at = drive;
    std::string field = error.field();
    for (std::size_t dot; !field.empty(); field = dot == std::string::npos ? "" : field.substr(dot + 1)) {
      dot = field.find('.');
      const auto child = at.Child(field.substr(0, dot));
      if (!child) break;
      at = *child;
    }
    throw at.Error(error.message());
  }
  return config;
}

model::IntegratorConfig ReadIntegrator(const NodeReader& integrator) {
  model::IntegratorConfig config;
  ReadFields(integrator, &config);
  config.rtol_given = integrator.Has("rtol");
  return config;
}

// The node at a dotted key path of `root`, or an undefined node when absent.
// Handles alias the tree: reset() moves one, operator= would overwrite the data.
YAML::Node NodeAtPath(const YAML::Node& root, const std::vector<PathElement>& path) {
  YAML::Node node;
  node.reset(root);
  for (const PathElement& step : path) {
    const YAML::Node& parent = node;
    YAML::Node child;
    if (step.index) {
      if (!parent.IsSequence() || *step.index >= parent.size()) return YAML::Node(YAML::NodeType::Undefined);
      child.reset(parent[static_cast<int>(*step.index)]);
    } else {
      if (!parent.IsMap() || !HasKey(parent, step.key)) return YAML::Node(YAML::NodeType::Undefined);
      child.reset(parent[step.key]);
    }
    node.reset(child);
  }
  return node;
}

// band: {key, from, to} of a check. The key must be a key path whose value, where the
// scenario writes one, is a plain number; whether the scenario takes the band's values
// is tried when `check` loads it (bench/sweep/band_check.h).
CheckBand ReadCheckBand(const NodeReader& band, const YAML::Node& root) {
  band.ExpectMap({"key", "from", "to"});
  CheckBand result;
  const auto key = band.Child("key");
  if (!key) throw band.Error("missing 'key': the dotted key path of a number, e.g. machine.modes[0].frequency_hz");
  result.key = key->AsString();
  const ConfigError where = key->Error("");
  result.file = where.file();
  result.line = where.line();
  result.column = where.column();
  result.path = key->path();
  const auto path = ParseKeyPath(result.key);
  if (!path || path->empty()) throw key->Error("not a key path like machine.modes[0].frequency_hz");
  const YAML::Node value = NodeAtPath(root, *path);
  if (value.IsDefined() && !(value.IsScalar() && IsNumberText(value.Scalar()))) {
    throw key->Error(result.key + " is not a number in this scenario, so it cannot span a band");
  }
  for (const char* end : {"from", "to"}) {
    const auto node = band.Child(end);
    if (!node) throw band.Error(std::string("missing '") + end + "'");
    (std::string(end) == "from" ? result.from : result.to) = node->AsNumber();
  }
  if (!(result.from < result.to)) {
    throw band.Child("to")->Error("must be above from (" + FormatNumber(result.from) + "; got " +
                                  FormatNumber(result.to) + ")");
  }
  return result;
}

// `root` is the scenario's whole tree (a band's key is looked up there); null for a
// sweep's checks, which take no band.
std::vector<Check> ReadChecksEntry(const NodeReader& checks, const YAML::Node* root) {
  checks.ExpectMap(AllMetricNames());
  std::vector<Check> result;
  for (const auto& [metric, bounds] : checks.Entries()) {
    if (root == nullptr) {
      bounds.ExpectMap({"min", "max"});
    } else {
      bounds.ExpectMap({"min", "max", "band"});
    }
    Check check;
    check.metric = metric;
    if (auto min = bounds.Child("min")) check.min = min->AsNumber();
    if (auto max = bounds.Child("max")) check.max = max->AsNumber();
    if (auto band = bounds.Child("band")) check.band = ReadCheckBand(*band, *root);
    if (!check.min && !check.max) throw bounds.Error("expected min and/or max");
    if (check.min && check.max && *check.min > *check.max) {
      throw bounds.Error("min " + std::to_string(*check.min) + " is above max " +
                         std::to_string(*check.max));
    }
    result.push_back(check);
  }
  return result;
}

RunLimits ReadLimits(const NodeReader& limits) {
  RunLimits config;
  ReadFields(limits, &config);
  if (!(config.max_simulated_s > 0.0)) {
    throw limits.Child("max_simulated_s")->Error("must be > 0 s");
  }
  if (config.max_ticks < 1) throw limits.Child("max_ticks")->Error("must be >= 1");
  if (config.max_trace_rows < 2) throw limits.Child("max_trace_rows")->Error("must be >= 2");
  if (config.max_memory_mb < 1) throw limits.Child("max_memory_mb")->Error("must be >= 1");
  if (config.max_work < 1) throw limits.Child("max_work")->Error("must be >= 1");
  if (!(config.max_wall_s >= 0.0) || !std::isfinite(config.max_wall_s)) {
    throw limits.Child("max_wall_s")->Error("must be >= 0 s (0: no wall-clock limit)");
  }
  return config;
}

// The pattern's values left to the machine (pattern_defaults.h), before it is validated.
void ResolveDesignDefaults(const ConfigDocument& document, const LoadOptions& options,
                           Scenario* scenario) {
  controller::PatternConfig& pattern = scenario->controller.pattern;
  if (!pattern.frequency_from_machine && !pattern.frequencies_from_machine && !pattern.damping_from_machine) {
    return;
  }
  DesignModes modes;
  if (options.design_modes) {
    modes = *options.design_modes;
  } else {
    try {
      modes = FindDesignModes(scenario->machine, scenario->RunProgram());
    } catch (const ValidationError&) {
      return;  // a move that makes no program: its own validation below says why
    }
    for (const model::ModeInfo& mode : modes.modes) {
      // A degenerate model (CheckPlantFinite below says so) designs for nothing.
      if (!std::isfinite(mode.frequency_hz) || !std::isfinite(mode.damping_ratio)) return;
    }
  }
  Validated(document, "controller.pattern", [&] { ResolvePatternDefaults(modes, &pattern); });
}

// The axes the program moves: a line's changed coordinates, an arc's plane (a full
// circle ends where it starts) and its changed normal coordinate.
std::array<bool, model::kNumAxes> MovedAxes(const controller::Program& program) {
  std::array<bool, model::kNumAxes> moved{};
  Eigen::Vector3d at = program.start_m;
  for (const controller::ProgramBlock& block : program.blocks) {
    using controller::MotionKind;
    if (block.kind == MotionKind::kDwell) continue;
    for (int a = 0; a < model::kNumAxes; ++a) moved[a] = moved[a] || block.end_m(a) != at(a);
    if (block.kind == MotionKind::kArcCw || block.kind == MotionKind::kArcCcw) {
      const int normal = block.plane == controller::Plane::kXY ? 2 : block.plane == controller::Plane::kZX ? 1 : 0;
      for (int a = 0; a < model::kNumAxes; ++a) moved[a] = moved[a] || a != normal;
    }
    at = block.end_m;
  }
  return moved;
}

// A machine that models some axes and not one the program moves would run that axis as
// rigid without a word (every ratio n/a): an error unless the machine lists it in
// `rigid:`. A machine with no model at all (`axes: {}`) is rigid throughout, as it says.
void CheckMovedAxesModelled(const NodeReader& machine, const Scenario& scenario) {
  const model::MultiAxisMachineConfig& config = scenario.machine;
  bool any_model = false;
  std::string modelled;
  for (int a = 0; a < model::kNumAxes; ++a) {
    if (!config.Models(a)) continue;
    any_model = true;
    modelled += std::string(modelled.empty() ? "" : ", ") + model::AxisName(a);
  }
  if (!any_model) return;
  const std::array<bool, model::kNumAxes> moved = MovedAxes(scenario.RunProgram());
  for (int a = 0; a < model::kNumAxes; ++a) {
    if (!moved[a] || config.Models(a) || config.rigid[a]) continue;
    const std::string name = model::AxisName(a);
    const ConfigError at = machine.Error("");
    throw machine.Error("the program moves axis " + name + ", which the machine (" + at.file() +
                        ") does not model (it models " + modelled + "): model it, or say it is rigid with " +
                        "rigid: [" + name + "]");
  }
}

// `machine:` (any form, a plant FMU too) and `drive:`.
void ReadMachineAndDrive(const NodeReader& top, Scenario* scenario) {
  if (auto machine = top.Child("machine")) {
    if (IsFmuMachine(*machine)) {
      const auto load_packed = [](const std::string& path, const std::vector<Override>& overrides) {
        return LoadScenario(path, overrides, LoadOptions{false, std::nullopt});
      };
      scenario->fmu = ReadFmuMachine(*machine, &scenario->machine, load_packed);
    } else {
      scenario->machine = ReadMachineAxesEntry(*machine);
    }
  }
  if (auto drive = top.Child("drive")) scenario->drive = ReadDrive(*drive);
  if (scenario->fmu && scenario->drive.type == model::DriveType::kServo) {
    // The servo's loops on the master, closed across the FMU boundary with the one-step
    // delay (docs/fmi.md#the-servo-drive); the run keeps the servo drive as its own.
    scenario->fmu = WithMasterServo(*scenario->fmu, scenario->drive.servo, *top.Child("drive"));
  } else if (scenario->fmu && scenario->fmu->drive) {
    scenario->drive = *scenario->fmu->drive;  // shapebench's FMU's own
  }
}

Scenario ReadScenario(const ConfigDocument& document, const std::string& path,
                      const LoadOptions& options) {
  NodeReader top(document, document.root(), "");
  top.ExpectMap(kScenarioKeys);

  Scenario scenario;
  scenario.source_file = path;
  scenario.name = fs::path(path).stem().string();
  top.Read("name", &scenario.name);
  ReadMachineAndDrive(top, &scenario);
  if (auto controller = top.Child("controller")) scenario.controller = ReadController(*controller);
  // Before the program: a G-code file is read under them.
  if (auto limits = top.Child("limits")) scenario.limits = ReadLimits(*limits);
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
  const controller::GcodeOptions gcode_options = ReadProgramOptions(top);
  if (auto program = top.Child("program")) {
    scenario.program = ReadProgramList(*program, Eigen::Vector3d::Zero(), gcode_options.program);
  }
  if (auto program_file = top.Child("program_file")) {
    // Limits from a validated period only (an invalid one is reported below, as before).
    const bool period_ok = scenario.controller.period_s > 0.0 && std::isfinite(scenario.controller.period_s);
    scenario.program = ReadProgramFile(*program_file,
                                       Eigen::Vector3d::Zero(),
                                       period_ok ? ParseLimits(scenario) : controller::GcodeLimits{},
                                       gcode_options);
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
  scenario.integrator.rtol_given = false;  // the default, which CVODE's cross-check may tighten
  if (auto integrator = top.Child("integrator")) scenario.integrator = ReadIntegrator(*integrator);
  if (auto checks = top.Child("checks")) scenario.checks = ReadChecksEntry(*checks, &document.root());

  Validated(document, "machine", [&] { scenario.machine.validate(); });
  ResolveDesignDefaults(document, options, &scenario);
  Validated(document, "controller", [&] { scenario.controller.validate(); });
  Validated(document, "move", [&] { scenario.move.validate(); });
  Validated(document, "integrator", [&] { scenario.integrator.validate(); });
  // A degenerate model (a frequency or stiffness so large that its matrices overflow)
  // would make the integrators loop or return NaN: refused here, at the machine.
  Validated(document, "", [&] { CheckPlantFinite(scenario); });
  if (options.plan_move && !scenario.program) {
    // Its fields are scenario-root paths already ("move.distance_mm").
    Validated(document, "", [&] {
      controller::CheckShapedMove(scenario.controller, std::abs(scenario.move.distance_mm) * 1e-3);
    });
  }
  if (auto machine = top.Child("machine")) CheckMovedAxesModelled(*machine, scenario);
  CheckRunLength(document, scenario);
  return scenario;
}

}  // namespace

std::vector<Check> ReadChecks(const NodeReader& checks) { return ReadChecksEntry(checks, nullptr); }

YAML::Node BuildScenarioTree(const std::string& path, const std::vector<Override>& overrides) {
  return BuildScenarioDocument(path, overrides).root();
}

model::MultiAxisMachineConfig ReadMachineAxesEntry(const NodeReader& machine) {
  if (IsFmuMachine(machine)) {
    throw machine.Child("fmu")->Error("a plant FMU is a black box: this reads the machine's own model (modes, "
                                      "bodies, axes); run, check and sweep drive an FMU");
  }
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
      HasKey(root, "modes") || HasKey(root, "bodies") || HasKey(root, "axes") || HasKey(root, "frf_file") ||
      HasKey(root, model::ModalMachineConfig::kModalFileKey);
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
  if (machine.CoupledModes() != nullptr) {
    throw ConfigError(path, 0, 0, "machine",
                      "the machine's coupled modes span three axes; the single-axis view drops their "
                      "cross terms (load it with LoadMachineAxes)");
  }
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

#include "bench/sweep/sweep_point_run.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <optional>
#include <regex>
#include <type_traits>
#include <utility>

#include "bench/config/key_path.h"
#include "bench/run/cross_check_family.h"
#include "bench/run/located_run.h"
#include "bench/scenario/scenario_loader.h"
#include "bench/scenario/structure_numbers.h"
#include "bench/run/run_scenario.h"
#include "bench/sweep/shared_command.h"
#include "common/field_list.h"
#include "common/validation_error.h"
#include "model/cvode_cross_check.h"
#include "model/integrator.h"

namespace shapebench::bench {
namespace {

// Keys the command (controller::GenerateProgramCommand: controller, program, move, the
// machine's stroke and driven axis) does not read: the structure (the machine forms' lists,
// as their field lists name them, a lumped axis' `damping:` block, a modal form's
// `modal_file`), the drive, the integrator, the output view, the checks.
bool PlantOnlyKey(const std::string& key) {
  for (const char* prefix : {"drive", "integrator", "output", "checks"}) {
    if (IsPathPrefix(prefix, key)) return true;
  }
  static const std::vector<std::string> lists = [] {
    std::vector<std::string> names;
    model::ForEachMachineForm([&](const auto& form) {
      for (std::string& list : ListNames<std::decay_t<decltype(form)>>()) names.push_back(std::move(list));
    });
    names.emplace_back(model::LumpedDamping::kKey);
    names.emplace_back(model::ModalMachineConfig::kModalFileKey);
    return names;
  }();
  for (const std::string& list : lists) {
    if (IsPathPrefix("machine." + list, key)) return true;
    for (const char* axis : {"x", "y", "z"}) {
      if (IsPathPrefix(std::string("machine.axes.") + axis + "." + list, key)) return true;
    }
  }
  return false;
}

// PlantOnlyKey of the keys this thread met: a sweep asks about the same few keys every
// point (the answer builds strings for every list of every machine form).
bool PlantOnlyKeyCached(const std::string& key) {
  thread_local std::vector<std::pair<std::string, bool>> known;
  for (const auto& [name, plant_only] : known) {
    if (name == key) return plant_only;
  }
  const bool plant_only = PlantOnlyKey(key);
  if (known.size() < 64) known.emplace_back(key, plant_only);
  return plant_only;
}

std::string CommandKey(const SweepPoint& point) {
  std::string key;
  for (std::size_t i = 0; i < point.overrides.size(); ++i) {
    const Override& o = point.overrides[i];
    // The --set options (after the point's values) and the swept keys the controller reads.
    if (i >= point.keys.size() || !PlantOnlyKeyCached(o.key_path)) {
      key.append(o.key_path).append(1, '=').append(o.value_yaml).append(1, '\n');
    }
  }
  return key;
}

// The scenario a point of a sweep loaded on this thread, with what it depends on besides
// the point's own values: the sweep and the --set options.
struct LoadedScenario {
  std::uint64_t sweep_id = 0;
  std::string sets_key;
  Scenario scenario;
  double motion_s = 0.0;  // MinimumMotionSeconds(scenario): the same for every such point
};

std::string SetsKey(const SweepPoint& point) {
  return OverridesKey(point.overrides.begin() + static_cast<std::ptrdiff_t>(point.keys.size()),
                      point.overrides.end());
}

// A point that ran with a warning (integrator.cross_check: warn) says so in its row's
// error column; its status stays ok.
std::string WarningText(const std::vector<std::string>& warnings) {
  std::string text;
  for (const std::string& warning : warnings) text += (text.empty() ? "warning: " : "; warning: ") + warning;
  return text;
}

// The scenario of a point. A point that changes only numbers of the structure takes the
// scenario the last point loaded on this thread and sets them (structure_numbers.h).
// Otherwise the base (and its machine file) is parsed once per thread (ParseCacheScope); a
// point whose scenario does not load is loaded again without, which locates its error.
// `loaded_here` holds a scenario loaded for this point alone (made only then: a point set
// in place builds and frees no Scenario).
const Scenario& PointScenario(const Sweep& sweep, const SweepPoint& point, std::optional<Scenario>* loaded_here) {
  thread_local LoadedScenario loaded;
  const bool structure_only =
      std::all_of(point.keys.begin(), point.keys.end(), IsStructureNumberKey);
  const std::string sets_key = SetsKey(point);
  if (structure_only && sweep.id != 0 && !(loaded.sweep_id == sweep.id && loaded.sets_key == sets_key) &&
      sweep.base_scenario != nullptr && sweep.base_sets_key == sets_key) {
    loaded = {sweep.id, sets_key, *sweep.base_scenario, MinimumMotionSeconds(*sweep.base_scenario)};
  }
  if (structure_only && loaded.sweep_id == sweep.id && sweep.id != 0 && loaded.sets_key == sets_key) {
    // Set in place: every such point sets every swept number, so what the last one set
    // is overwritten (no copy of the scenario a point). A refused value may have left some
    // set: the cache is dropped then.
    // The point's own values: its overrides, unless --set options follow them (a copy then).
    const bool sets_follow = point.overrides.size() != point.keys.size();
    std::vector<Override> copied;
    if (sets_follow) {
      copied.assign(point.overrides.begin(), point.overrides.begin() + static_cast<std::ptrdiff_t>(point.keys.size()));
    }
    const std::vector<Override>& values = sets_follow ? copied : point.overrides;
    if (SetStructureNumbers(&loaded.scenario, values, loaded.motion_s)) return loaded.scenario;
    loaded = LoadedScenario{};
  }
  LoadOptions options;
  options.design_modes = sweep.design_modes;  // the base's: the pattern stays fixed
  try {
    const ParseCacheScope parse_once;
    loaded_here->emplace(LoadScenario(sweep.base, point.overrides, options));
  } catch (const std::exception&) {
    loaded_here->emplace(LoadScenario(sweep.base, point.overrides, options));
  }
  const Scenario& here = **loaded_here;
  if (structure_only) loaded = {sweep.id, sets_key, here, MinimumMotionSeconds(here)};
  return here;
}

// Points that differ only in keys the controller does not read (the natural-period
// sweep: the plant's frequency) share one command and its samples, generated once for
// all threads (shared_command.h): the same inputs, the same command, so the same
// metrics bit for bit (tests/bench/sweep_test.cc checks the rows against independent
// runs, tests/bench/shared_command_test.cc against a sweep without sharing).
void UseSharedCommand(const Sweep& sweep, const SweepPoint& point, const Scenario& scenario,
                      RunOptions* options) {
  if (sweep.id == 0 || !SharedCommandCache::Enabled()) return;
  // The command this thread used last, when the point's is the same one: no lock and
  // no count of its owners a point (the threads of a sweep would take turns at the
  // cache's lock and at the shared count's cache line; the thread's copy keeps it).
  thread_local struct {
    std::uint64_t sweep_id = 0;
    std::string key;
    std::shared_ptr<const SharedCommand> command;
  } last;
  std::string key = CommandKey(point);
  if (last.command == nullptr || last.sweep_id != sweep.id || last.key != key) {
    std::shared_ptr<const SharedCommand> got =
        SharedCommandCache::Instance().Get(sweep.id, key, [&](controller::Program* program) {
          *program = scenario.RunProgram();
          return GenerateScenarioCommand(scenario, *program);
        });
    last = {sweep.id, std::move(key), std::move(got)};
  }
  options->command = &last.command->command;
  options->samples = &last.command->samples;
  options->program = &last.command->program;
  options->path = &*last.command->path;
}

// The swept key whose values make a family for CVODE's cross-check (cross_check_family.h):
// the first one that is a mode's frequency_hz or damping_ratio, alone on its axis, with a
// band (a range, or a list of plain numbers) of enough values that a dozen checks are
// worth it, and not set again by --set. SHAPEBENCH_CROSS_CHECK_FAMILY=0: none (every point
// checks itself, as before).
struct FamilyKey {
  std::uint64_t sweep_id = 0;
  std::size_t index = 0;  // among Sweep::Keys() and a point's overrides
  CrossCheckFamilyBand band;
  bool found = false;
};

bool ListBand(const SweepValues& values, double* lo, double* hi) {
  for (std::uint64_t i = 0; i < values.size(); ++i) {
    const std::string text = values.Yaml(i);
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || !std::isfinite(v)) return false;
    *lo = i == 0 ? v : std::min(*lo, v);
    *hi = i == 0 ? v : std::max(*hi, v);
  }
  return values.size() > 0;
}

FamilyKey FindFamilyKey(const Sweep& sweep, const SweepPoint& point) {
  FamilyKey family;
  family.sweep_id = sweep.id;
  const char* env = std::getenv("SHAPEBENCH_CROSS_CHECK_FAMILY");
  if (sweep.id == 0 || (env != nullptr && std::strcmp(env, "0") == 0)) return family;
  static const std::regex mode_number(R"(machine(\.axes\.[xyz])?\.modes\[\d+\]\.(frequency_hz|damping_ratio))");
  constexpr std::uint64_t kMinValues = 2 * (model::kFamilyInterior + 4);  // half the checks at most
  std::size_t index = 0;
  for (const SweepAxis& axis : sweep.axes) {
    for (const SweepValues& values : axis.keys) {
      const std::size_t here = index++;
      if (family.found || axis.keys.size() != 1 || values.size() < kMinValues ||
          !std::regex_match(values.key, mode_number) || !IsStructureNumberKey(values.key)) {
        continue;
      }
      double lo = std::min(values.from, values.to);
      double hi = std::max(values.from, values.to);
      if (values.kind == SweepValues::Kind::kSampled) continue;
      if (values.kind == SweepValues::Kind::kList && !ListBand(values, &lo, &hi)) continue;
      const bool set_again = std::any_of(point.overrides.begin() + static_cast<std::ptrdiff_t>(point.keys.size()),
                                         point.overrides.end(),
                                         [&](const Override& o) { return o.key_path == values.key; });
      if (set_again) continue;
      family.found = true;
      family.index = here;
      family.band = {values.key, lo, hi, ""};
    }
  }
  return family;
}

// The point's family band, or null; the key found once per sweep and thread.
const CrossCheckFamilyBand* PointFamily(const Sweep& sweep, const SweepPoint& point) {
  thread_local FamilyKey key;
  if (key.sweep_id != sweep.id || sweep.id == 0) key = FindFamilyKey(sweep, point);
  if (!key.found) return nullptr;
  // Built in place (its capacity kept from the last point: no allocation a point).
  std::string& identity = key.band.identity;
  char id[24];
  identity.assign(id, std::to_chars(id, id + sizeof id, sweep.id).ptr);
  identity += '\n';
  for (std::size_t i = 0; i < point.overrides.size(); ++i) {
    if (i == key.index) continue;
    identity.append(point.overrides[i].key_path).append(1, '=').append(point.overrides[i].value_yaml).append(1, '\n');
  }
  return &key.band;
}

}  // namespace

PointOutcome RunPoint(const Sweep& sweep, const std::vector<Override>& sets, std::uint64_t index) {
  return RunPoint(sweep, MakePoint(sweep, index, sets));  // (MakePoint reads the grid: no input error)
}

PointOutcome RunPoint(const Sweep& sweep, const SweepPoint& point) {
  PointOutcome outcome;
  outcome.index = point.index;
  try {
    std::optional<Scenario> loaded_here;
    const Scenario& scenario = PointScenario(sweep, point, &loaded_here);
    try {
      RunOptions options{false};  // no trace needed
      UseSharedCommand(sweep, point, scenario, &options);
      const CrossCheckFamilyScope family(PointFamily(sweep, point));
      const RunResult result = RunScenario(scenario, options);
      outcome.metrics = result.metrics;
      outcome.error = WarningText(result.warnings);
    } catch (const ValidationError& error) {
      throw LocateValidationError(sweep.base, point.overrides, error);
    }
  } catch (const ConfigError& error) {
    outcome.status = PointOutcome::Status::kBadInput;
    outcome.error = RelocatePointError(sweep, point, error).what();
  } catch (const model::SolverError& error) {
    outcome.status = PointOutcome::Status::kSolverFailed;
    outcome.error = SolverFailureText(error);
  } catch (const std::bad_alloc&) {
    throw;  // the machine's, not the point's: no row, the sweep stops and resumes later
  } catch (const std::exception& error) {
    outcome.status = PointOutcome::Status::kFailed;
    outcome.error = error.what();
  }
  if (!outcome.ok()) outcome.metrics = Metrics{};
  return outcome;
}

}  // namespace shapebench::bench

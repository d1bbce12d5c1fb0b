// The bodies of the libFuzzer targets (fuzz/fuzz_*.cc), shared with the regression test
// (tests/bench/fuzz_regressions_test.cc) that runs every file of fuzz/regressions/TARGET/
// through them. Each takes the input's bytes and returns normally when the bench accepts
// the input or refuses it with its documented, located error. Anything else is a finding:
// a Violation thrown (an invariant broken), another exception escaping, a crash, a
// sanitizer report or a hang.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "bench/config/config_error.h"
#include "bench/config/override.h"
#include "bench/sim/scenario.h"
#include "bench/config/scenario_loader.h"
#include "bench/config/structure_numbers.h"
#include "bench/sweep/sweep.h"
#include "bench/sweep/sweep_runner.h"
#include "common/validation_error.h"
#include "controller/controller.h"
#include "controller/gcode_parser.h"
#include "model/multi_axis_machine.h"
#include "fuzz/fuzz_support.h"

namespace shapebench::fuzz {

// An invariant the input broke (not derived from std::exception: nothing catches it).
struct Violation {
  std::string what;
};

// The small limits every target loads with (after the input's own options, so they
// hold): the loader refuses longer runs before planning, so each input stays quick.
inline std::vector<bench::Override> SmallLimits() {
  return {{"limits.max_simulated_s", "20"}, {"limits.max_ticks", "50000"}};
}

// G-code parser (controller/gcode_parser.h): any bytes are a program or a ProgramError
// at a line and column; a parsed program is finite, and one short enough (64 blocks,
// 5 s) goes through the whole controller (planner, interpolation, filters) on the
// default settings.
inline void GcodeTarget(const std::string& text) {
  controller::Program program;
  try {
    program = controller::ParseGcode(text);
  } catch (const controller::ProgramError& error) {
    if (error.line() < 1 || error.column() < 0) throw Violation{"unlocated: " + std::string(error.what())};
    return;
  }
  for (const controller::ProgramBlock& block : program.blocks) {
    if (!block.start_m.allFinite() || !block.end_m.allFinite() || !block.center_m.allFinite() ||
        !std::isfinite(block.dwell_s)) {
      throw Violation{"a parsed program with a non-finite block"};
    }
  }
  // Long programs only slow the search down (the parser is the target; the scenario
  // target plans programs too).
  if (program.blocks.size() > 64) return;
  bench::Scenario scenario;
  scenario.program = program;
  scenario.machine.axes = {};  // rigid: the residual window is short
  scenario.limits.max_simulated_s = 5.0;
  scenario.limits.max_ticks = 5000;
  try {
    const double seconds = bench::MinimumRunSeconds(scenario);
    if (seconds > scenario.limits.max_simulated_s ||
        seconds / scenario.controller.period_s > static_cast<double>(scenario.limits.max_ticks)) {
      return;  // the loader refuses these (limits:)
    }
    controller::GenerateProgramCommand(scenario.controller, program);
  } catch (const ValidationError& error) {
    if (error.field().empty()) throw Violation{"a ValidationError without a key: " + std::string(error.what())};
  }
}

// Scenario loader (bench/config/scenario_loader.h): any bytes as a scenario file are a Scenario
// or a ConfigError at FILE:LINE:COL; a loaded scenario's command is generated, or refused
// with a ValidationError naming a scenario key.
inline void ScenarioTarget(const std::string& bytes) {
  ConfigsCopy();
  const std::string path = WriteInput("scenarios/input.yaml", bytes);
  bench::Scenario scenario;
  try {
    scenario = bench::LoadScenario(path, SmallLimits());
  } catch (const bench::ConfigError& error) {
    if (error.file().empty()) throw Violation{"unlocated: " + std::string(error.what())};
    return;
  }
  try {
    controller::ControllerConfig config = scenario.controller;
    config.stroke_limits = scenario.machine.stroke_m;
    controller::GenerateProgramCommand(config, scenario.RunProgram());
  } catch (const ValidationError& error) {
    if (error.field().empty()) throw Violation{"a ValidationError without a key: " + std::string(error.what())};
  }
}

// Sweep points' structure numbers (bench/config/structure_numbers.h), differentially: the
// overrides that are structure numbers, set on the loaded base, must give what the loader
// reads with them, bit for bit (or not be set at all: the loader then decides).
inline void StructureNumbersAgree(const std::string& path, const std::vector<bench::Override>& overrides) {
  std::vector<bench::Override> numbers;
  for (const bench::Override& o : overrides) {
    if (bench::IsStructureNumberKey(o.key_path)) numbers.push_back(o);
  }
  if (numbers.empty()) return;
  bench::Scenario set = bench::LoadScenario(path, SmallLimits());  // a shipped scenario: loads
  if (!bench::SetStructureNumbers(&set, numbers)) return;
  std::vector<bench::Override> with_limits = numbers;
  for (const bench::Override& limit : SmallLimits()) with_limits.push_back(limit);
  bench::Scenario loaded;
  try {
    loaded = bench::LoadScenario(path, with_limits);
  } catch (const bench::ConfigError& error) {
    throw Violation{"structure numbers set where the loader refuses them: " + std::string(error.what())};
  }
  const model::MachinePlant a = model::BuildMachinePlant(set.machine, set.drive);
  const model::MachinePlant b = model::BuildMachinePlant(loaded.machine, loaded.drive);
  if (!(a.plant.A == b.plant.A) || !(a.plant.B_accel == b.plant.B_accel) ||
      !(a.plant.B_vel == b.plant.B_vel) || !(a.plant.C == b.plant.C) || !(a.static_gain == b.static_gain)) {
    throw Violation{"structure numbers set give another plant than the loader reads"};
  }
}

// --set parser (bench/config/override.h, ConfigDocument::ApplyOverride): the first byte picks a
// shipped file, every following line is one --set KEY=VALUE; parsed, applied and loaded
// (a machine file as `modes` reads it); the structure numbers among them, differentially
// (StructureNumbersAgree).
inline void SetTarget(const std::string& bytes) {
  static const char* const kBases[] = {"demo.yaml",
                                       "scenarios/method2.yaml",
                                       "scenarios/pocket_corner.yaml",
                                       "scenarios/pocket_gcode.yaml",
                                       "scenarios/circle_test.yaml",
                                       "scenarios/um_zv.yaml",
                                       "scenarios/stroke_end.yaml",
                                       "machines/moving_column.yaml"};
  if (bytes.empty()) return;
  const std::filesystem::path root = ConfigsCopy();
  const std::string base =
      kBases[static_cast<unsigned char>(bytes[0]) % (sizeof kBases / sizeof kBases[0])];
  std::vector<std::string> texts;
  std::string line;
  for (std::size_t i = 1; i < bytes.size(); ++i) {
    if (bytes[i] == '\n') {
      texts.push_back(line);
      line.clear();
    } else {
      line += bytes[i];
    }
  }
  if (!line.empty()) texts.push_back(line);
  try {
    std::vector<bench::Override> overrides = bench::ParseOverrides(texts);
    const std::string path = (root / base).string();
    if (base.rfind("machines/", 0) == 0) {
      bench::LoadMachineAxes(path, overrides);
    } else {
      StructureNumbersAgree(path, overrides);
      for (const bench::Override& limit : SmallLimits()) overrides.push_back(limit);
      bench::LoadScenario(path, overrides);
    }
  } catch (const bench::ConfigError& error) {
    if (error.file().empty()) throw Violation{"unlocated: " + std::string(error.what())};
  }
}

// Sweep loader (bench/sweep/sweep.h): any bytes as a sweep file (in sweeps/, beside copies of
// the shipped scenarios) are a Sweep or a located ConfigError; a loaded sweep's columns,
// hash and first, middle and last points are computed (points are not run).
inline void SweepTarget(const std::string& bytes) {
  ConfigsCopy();
  const std::string path = WriteInput("sweeps/input.yaml", bytes);
  bench::IsSweepFile(path);
  try {
    const bench::Sweep sweep = bench::LoadSweep(path, {});
    if (sweep.points == 0) throw Violation{"a sweep without points"};
    bench::ResultColumns(sweep);
    bench::SweepHash(sweep, {});
    for (const std::uint64_t point : {std::uint64_t{0}, sweep.points / 2, sweep.points - 1}) {
      bench::MakePoint(sweep, point, {}).Label();
    }
  } catch (const bench::ConfigError& error) {
    if (error.file().empty()) throw Violation{"unlocated: " + std::string(error.what())};
  }
}

}  // namespace shapebench::fuzz

// A scenario: everything one run needs (docs/scenario-reference.md), already validated.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "controller/controller.h"
#include "controller/program.h"
#include "model/drive.h"
#include "model/integrator.h"
#include "model/multi_axis_machine.h"

namespace shapebench::bench {

struct FmuMachine;  // bench/fmi/fmu_machine.h

// A band check's range: the metric's worst value over `key` in [from, to]
// (bench/sweep/band_check.h), e.g. band: {key: "machine.modes[0].frequency_hz", from: 24, to: 26}.
struct CheckBand {
  std::string key;  // a dotted key path of a number, as in --set
  double from = 0.0;
  double to = 0.0;
  // Where `key` is written: an error of the band's points (a key the scenario does not
  // have, a value it refuses) is located there.
  std::string file;
  int line = 0;
  int column = 0;
  std::string path;  // "checks.residual_ratio.band.key"
};

// A bound on one metric (MetricTable() names), e.g. peak_ratio: {max: 1.01}; with a band,
// on its worst value over the band.
struct Check {
  std::string metric;
  std::optional<double> min;
  std::optional<double> max;
  std::optional<CheckBand> band = std::nullopt;
};

// Which scalar the deflection metrics (peak, residual, ...) and the plot use:
// `magnitude` |d| of the tool-tip deflection vector; `x`, `y`, `z` one signed component;
// `auto` the signed component along the only axis that moves when one axis does
// (`move:`), else the magnitude. The peak metrics are the same either way for a
// single-axis move; only the sign shown in trace and plot differs.
enum class OutputDirection { kAuto, kMagnitude, kX, kY, kZ };

struct OutputConfig {
  OutputDirection direction = OutputDirection::kAuto;
};

// limits.max_work's default (docs/reliability.md#limits: how it was chosen, from the costliest
// shipped scenario's count and a 2-hour program at a 1 ms period).
constexpr long kDefaultMaxWork = 2'000'000'000;

// Guard rails (docs/reliability.md), `limits:` in a scenario. A run whose simulated time (motion and
// the residual window) would exceed max_simulated_s, or whose command would exceed
// max_ticks interpolation periods, is refused (exit 2) before anything is generated, from
// a lower bound of its length (MinimumRunSeconds), and again on the generated command.
// trace.csv and the plots keep at most max_trace_rows samples (evenly decimated, noted in
// trace.csv's first line and on stderr); the metrics always use every sample.
// max_memory_mb bounds the memory one run needs for its command, per-tick samples and
// trace (bench/scenario/run_memory.h), estimated from the same lower bound of its length; a
// sweep's peak is about --jobs times it.
// max_work bounds the work a run does, counted, never timed (bench/run/run_work.h: output
// samples, CVODE's steps and right-hand-side evaluations, the exact path's extremum
// passes): beyond it the run stops with exit 3 (WORK_LIMIT), or is refused before it
// starts where its lower bound already exceeds it. The verdict is the count's, whatever
// the host or --jobs. max_wall_s (0: off, the default) stops a run after that many seconds
// of wall-clock time, looked at where max_work is (exit 3, WALL_LIMIT): the host's verdict.
struct RunLimits {
  double max_simulated_s = 14400.0;  // 4 h: real jobs run 15-50 min; max_work bounds the cost
  long max_ticks = 10'000'000;
  long max_trace_rows = 1'000'000;
  long max_memory_mb = 1024;
  long max_work = kDefaultMaxWork;
  double max_wall_s = 0.0;

  template <typename Archive>
  void Serialize(Archive* a) {  // the field list (common/field_list.h)
    a->Visit("max_simulated_s", &max_simulated_s);
    a->Visit("max_ticks", &max_ticks);
    a->Visit("max_trace_rows", &max_trace_rows);
    a->Visit("max_memory_mb", &max_memory_mb);
    a->Visit("max_work", &max_work);
    a->Visit("max_wall_s", &max_wall_s);
  }
};

struct Scenario {
  model::MultiAxisMachineConfig machine;
  // `machine: {fmu: ...}` (bench/scenario/fmu_machine_reader.h): the plant FMU the run steps;
  // `machine` is then rigid throughout (the FMU is the structure). Null for every other form.
  std::shared_ptr<const FmuMachine> fmu;
  model::DriveConfig drive;
  controller::ControllerConfig controller;
  // `move:` (the one-block shorthand) runs unless a program is given.
  controller::MoveConfig move;
  std::optional<controller::Program> program;
  OutputConfig output;
  model::IntegratorConfig integrator;
  std::vector<Check> checks;
  RunLimits limits;
  std::string name;         // the file's stem, for reports
  std::string source_file;  // as given on the command line

  // The axis `move:` runs along.
  int move_axis() const { return move.axis >= 0 ? move.axis : machine.driven_axis; }
  // The program that runs: `program`, or the one block of `move:`.
  controller::Program RunProgram() const {
    return program ? *program : controller::MoveProgram(move, move_axis());
  }
};

}  // namespace shapebench::bench

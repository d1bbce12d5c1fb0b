// `make bench`: full runs of the G-code corpus's longest programs (tests/data/gcode/, issues
// 35 and 36). The corpus test (tests/controller/gcode_corpus_test.cc) reads and plans every program
// to its end; this runs the longest ones through the whole simulation as `shapebench run`
// would: configs/scenarios/face_mill.yaml (the three-axis moving column, method 1, exact
// integrator) with the program swapped in, in its controller's dialect.
//
// Three keys of the base scenario are raised so each program runs to its end, and why:
//   limits.max_simulated_s -> 20000: flower_mold.nc, heart.ngc, cutout.ngc and slant_test.nc
//     take more than the 600 s default this was written under (4 hours since issue 36).
//   limits.max_memory_mb -> 2048: flower_mold.nc's 3.08 million periods are more than the
//     1024 MB default allows at the guard's 360 bytes a period (it measures about 116).
//   machine.stroke x/y [-1000, 1000] mm, z [-400, 400] mm: the programs are in their part's
//     coordinates, not the machine's: heart.ngc, cutout.ngc and g17-g18-g19.gcode go below
//     the column's X end (-5 mm), and with the shipped stroke the run ends at the first
//     stroke alarm (35 s, 16 s and 0.09 s in).
// A run that still ends early (a stroke alarm) or is refused is reported as an error of the
// benchmark (SkipWithError), never dropped silently.
//
// Counters: sim_s (simulated seconds, motion and residual tail), wall_s (one run's wall
// time), real_time_factor (sim_s / wall_s), cpu_s and real_time_factor_cpu (the same with
// the process's CPU time, the figure to read on a shared machine), blocks (the program's
// planned blocks).
// Left out: the corpus's other 27 programs, each shorter (the next: modal_state_test.ngc
// 127 s simulated, scorpion.nc 96 s; the rest under 60 s; circle_test.nc, which needs
// machine.reference_mm for its G28, timed only with `shapebench run`: 0.3 s of wall time);
// the corpus test plans them all. linuxcnc/spiral.ngc is refused for its '@' polar
// coordinates (kept refused, not run).
#include <benchmark/benchmark.h>

#include <time.h>

#include <chrono>
#include <cmath>
#include <exception>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "bench/run/run_scenario.h"
#include "bench/scenario/scenario_loader.h"

namespace {

using namespace shapebench;
using namespace shapebench::bench;

// The process's CPU time, s: on a shared machine the figure to read (wall time grows with
// the other jobs' load).
double ProcessCpuS() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

// The benchmark's iterations of one untraced run: the last run's result, *wall_s and *cpu_s
// its wall and CPU time.
RunResult TimedRuns(benchmark::State& state, const Scenario& scenario, double* wall_s, double* cpu_s = nullptr) {
  RunResult last;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const double cpu_start = ProcessCpuS();
    last = RunScenario(scenario, RunOptions{false});
    *wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (cpu_s != nullptr) *cpu_s = ProcessCpuS() - cpu_start;
    benchmark::ClobberMemory();
  }
  return last;
}

struct CorpusProgram {
  const char* file;     // under tests/data/gcode/
  const char* dialect;  // the corpus test's DialectOf: its controller's
};

// The six longest in simulated time (longest first), in the dialect the corpus test reads
// each in. flower_mold.nc is the 30-minute real job of issue 36's must-show 1 (about 49
// minutes at its own feeds).
const CorpusProgram kPrograms[] = {
    {"camotics/flower_mold.nc", "linuxcnc"},
    {"camotics/heart.ngc", "linuxcnc"},
    {"camotics/cutout.ngc", "linuxcnc"},
    {"camotics/slant_test.nc", "linuxcnc"},
    {"ugs/g17-g18-g19.gcode", "grbl"},
    {"camotics/buildbotics.gcode", "linuxcnc"},
};

void BM_CorpusProgram(benchmark::State& state) {
  const CorpusProgram& program = kPrograms[state.range(0)];
  const std::string source = SHAPEBENCH_SOURCE_DIR;
  state.SetLabel(program.file);
  Scenario scenario;
  try {
    scenario = LoadScenario(source + "/configs/scenarios/face_mill.yaml",
                            {{"program_file", source + "/tests/data/gcode/" + program.file},
                             {"program_dialect", program.dialect},
                             {"limits.max_simulated_s", "20000"},
                             {"limits.max_memory_mb", "2048"},
                             {"machine.stroke", "{x: [-1000, 1000], y: [-1000, 1000], z: [-400, 400]}"}});
  } catch (const std::exception& error) {
    state.SkipWithError((std::string("refused: ") + error.what()).c_str());
    return;
  }
  double wall_s = 0.0, cpu_s = 0.0;
  RunResult last;
  try {
    last = TimedRuns(state, scenario, &wall_s, &cpu_s);
  } catch (const std::exception& error) {
    state.SkipWithError((std::string("refused: ") + error.what()).c_str());
    return;
  }
  if (last.metrics.stroke_alarm == 1.0) {
    state.SkipWithError("stroke alarm: the run ended before the program did");
    return;
  }
  state.counters["sim_s"] = last.simulated_s;
  state.counters["wall_s"] = wall_s;
  state.counters["real_time_factor"] = last.simulated_s / wall_s;
  state.counters["cpu_s"] = cpu_s;
  state.counters["real_time_factor_cpu"] = last.simulated_s / cpu_s;
  state.counters["blocks"] = static_cast<double>(last.program.blocks.size());
  state.counters["peak_ratio"] = last.metrics.peak_ratio;
}

void CorpusArgs(benchmark::internal::Benchmark* b) {
  for (std::size_t k = 0; k < std::size(kPrograms); ++k) b->Arg(static_cast<int>(k));
}

}  // namespace

// One run each: flower_mold.nc alone takes tens of seconds.
BENCHMARK(BM_CorpusProgram)->Apply(CorpusArgs)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

namespace {

// One repetition of a generated job: 40 passes of 60 mm along X, 1 mm apart, joined by
// 0.5 mm arcs (160 blocks, about 50 s at 3000 mm/min), then a rapid back to the start.
std::string RepeatedJob(int repetitions) {
  std::ostringstream gcode;
  gcode << "G21 G90 G17 F3000\nG0 X0 Y0\n";
  for (int r = 0; r < repetitions; ++r) {
    for (int i = 0; i < 20; ++i) {
      const int y = 2 * i;
      gcode << "G1 X60 Y" << y << "\nG3 X60 Y" << y + 1 << " R0.5\nG1 X0\nG2 X0 Y" << y + 2 << " R0.5\n";
    }
    gcode << "G0 X0 Y0\n";
  }
  gcode << "M30\n";
  return gcode.str();
}

// Must-show 1 of issue 36: the job repeated 1, 2, 4 and 8 times on the moving column of
// face_mill.yaml (exact integrator, no trace). wall_per_rep_s is the wall time over the
// repetitions: it stays flat when the cost is linear in the program (it grew with the
// repetitions while the contour error searched the whole path at every sample).
void BM_ProgramRepeated(benchmark::State& state) {
  const int repetitions = static_cast<int>(state.range(0));
  const std::string source = SHAPEBENCH_SOURCE_DIR;
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("shapebench_repeated_" + std::to_string(repetitions) + ".nc");
  std::ofstream(file) << RepeatedJob(repetitions);
  const Scenario scenario = LoadScenario(source + "/configs/scenarios/face_mill.yaml",
                                         {{"program_file", file.string()},
                                          {"program_dialect", "linuxcnc"},
                                          {"machine.stroke", "{x: [-1000, 1000], y: [-1000, 1000], z: [-400, 400]}"}});
  double wall_s = 0.0;
  const RunResult last = TimedRuns(state, scenario, &wall_s);
  std::filesystem::remove(file);
  state.counters["repetitions"] = repetitions;
  state.counters["sim_s"] = last.simulated_s;
  state.counters["wall_s"] = wall_s;
  state.counters["wall_per_rep_s"] = wall_s / repetitions;
  state.counters["real_time_factor"] = last.simulated_s / wall_s;
  state.counters["blocks"] = static_cast<double>(last.program.blocks.size());
}

}  // namespace

BENCHMARK(BM_ProgramRepeated)->Arg(1)->Arg(2)->Arg(4)->Arg(8)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

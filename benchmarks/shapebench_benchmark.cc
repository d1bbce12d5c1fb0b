#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>

#include "bench/cosim.h"
#include "bench/scenario_loader.h"
#include "bench/sweep.h"
#include "bench/sweep_runner.h"

namespace {
using namespace shapebench;
using namespace shapebench::bench;
const std::string kSource = SHAPEBENCH_SOURCE_DIR;

Scenario Case1(const std::string& method) {
  return LoadScenario(kSource + "/benchmarks/cases/case1.yaml", {{"integrator.method", method}});
}
Scenario Case2(const std::string& method) {
  return LoadScenario(kSource + "/configs/scenarios/pocket_corner.yaml",
                      {{"drive.type", "servo"}, {"integrator.method", method}});
}

void RunCase(benchmark::State& state, const Scenario& scenario) {
  RunResult last;
  for (auto _ : state) {
    last = RunScenario(scenario);
    benchmark::DoNotOptimize(last.metrics.peak_ratio);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["peak_ratio"] = last.metrics.peak_ratio;
  const double simulated = last.trace.time_s.empty() ? 0 : last.trace.time_s.back();
  state.counters["steps_per_sim_s"] = last.stats.steps / simulated;
  state.counters["rhs_per_sim_s"] = last.stats.rhs_evals / simulated;
}

void BM_Case1_Exact(benchmark::State& s) { RunCase(s, Case1("exact")); }
void BM_Case1_Cvode(benchmark::State& s) { RunCase(s, Case1("cvode")); }
void BM_Case2_Exact(benchmark::State& s) { RunCase(s, Case2("exact")); }
void BM_Case2_Cvode(benchmark::State& s) { RunCase(s, Case2("cvode")); }

void Case3(benchmark::State& state, const std::string& method) {
  const std::vector<Override> sets = {{"integrator.method", method}};
  const Sweep sweep = LoadSweep(kSource + "/benchmarks/cases/case3_sweep.yaml", sets);
  const std::string dir = std::filesystem::temp_directory_path() / "shapebench_bench_sweep";
  for (auto _ : state) {
    std::filesystem::remove_all(dir);
    SweepRunOptions options;
    options.out_dir = dir;
    options.jobs = static_cast<int>(state.range(0));
    RunSweep(sweep, sets, options);
  }
  std::filesystem::remove_all(dir);
  state.SetItemsProcessed(state.iterations() * sweep.points);
}
void BM_Case3_Exact(benchmark::State& s) { Case3(s, "exact"); }
void BM_Case3_Cvode(benchmark::State& s) { Case3(s, "cvode"); }

}  // namespace

BENCHMARK(BM_Case1_Exact)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Case1_Cvode)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Case2_Exact)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Case2_Cvode)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Case3_Exact)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Case3_Cvode)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
namespace {
void BM_Case1_CommandOnly(benchmark::State& state) {
  const Scenario s = Case1("exact");
  for (auto _ : state) {
    auto program = s.RunProgram();
    controller::ControllerConfig c = s.controller;
    auto cmd = controller::GenerateProgramCommand(c, program);
    benchmark::DoNotOptimize(cmd.num_ticks());
  }
}
}
BENCHMARK(BM_Case1_CommandOnly)->Unit(benchmark::kMicrosecond);

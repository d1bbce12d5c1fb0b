// `make bench`: Google Benchmark over the fixed cases of benchmarks/cases/.
//
//   case 1  one undamped 25 Hz mode, 100 mm at 6000 mm/min, method 1, 1 ms (case1.yaml)
//   case 2  the moving-column machine (X, Y, Z), servo drive, the pocket corner
//           (configs/scenarios/pocket_corner.yaml with drive.type servo)
//   case 3  a 1000-point natural-period sweep of case 1 (case3_sweep.yaml), 1 and 2 jobs
//   case 4  the moving column with LuGre friction on its X and Y guides on a 10 s circle
//           (case4_lugre_circle.yaml): a plant with nonlinear elements, CVODE with events
//   case 4d case 3 on a 2% damped mode with every metric (case4_damped_sweep.yaml): the
//           sweep users run, with the settling tail; exact and CVODE, 1 and 2 jobs
//   case 41 case 1's 5000-point sweep, 1 job, and the same with a 1000 mm move
//           (case41_sweep_5k*.yaml): a closed-form point's cost, whatever the cruise
//   floor   the bare exact zero-order hold of case 1's mode over case 1's ticks with the
//           exact extremum inside each tick, the command built once (BM_Floor): what a
//           sweep point cannot beat; the table gives every sweep figure as a ratio to it
//
// Each reports the time per run, runs per second (items_per_second) and, for CVODE, its
// internal steps and right-hand-side evaluations per simulated second. BM_CvodeTuning
// measures each CVODE choice of model/integrator.h (CvodeTuning) at equal accuracy: for
// each variant the loosest rtol whose metrics stay within kTargetError of the exact path's
// (case 3: every point's within kCase3TargetError).
// Extra options (before Google Benchmark's own):
//   --export_case1=FILE   writes case 1's command and plant for scripts/baseline.py, exits
//   --export_case4=FILE   the same for case 4 (plant, elements, command, shapebench's answer)
#include <benchmark/benchmark.h>

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bench/run/command_samples.h"
#include "bench/run/run_scenario.h"
#include "bench/scenario/scenario_loader.h"
#include "bench/sweep/sweep.h"
#include "bench/sweep/sweep_runner.h"
#include "model/cvode_cross_check.h"
#include "model/multi_axis_machine.h"
#include "model/cvode_integrator.h"

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

// The ratio metrics' largest difference between two runs.
double MetricError(const Metrics& a, const Metrics& b) {
  double error = 0.0;
  for (auto [x, y] : {std::pair{a.peak_ratio, b.peak_ratio},
                      std::pair{a.residual_ratio, b.residual_ratio},
                      std::pair{a.cruise_residual_ratio, b.cruise_residual_ratio}}) {
    if (std::isfinite(x) && std::isfinite(y)) error = std::max(error, std::abs(x - y));
  }
  return error;
}

void RunCase(benchmark::State& state, const Scenario& scenario, const Metrics* exact) {
  RunResult last;
  for (auto _ : state) {
    last = RunScenario(scenario, RunOptions{false});
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["peak_ratio"] = last.metrics.peak_ratio;
  state.counters["sim_s"] = last.simulated_s;
  state.counters["steps_per_sim_s"] = last.stats.steps / last.simulated_s;
  state.counters["rhs_per_sim_s"] = last.stats.rhs_evals / last.simulated_s;
  if (exact != nullptr) state.counters["error_vs_exact"] = MetricError(last.metrics, *exact);
}

const Metrics& ExactMetrics(int which) {
  static const Metrics case1 = RunScenario(Case1("exact"), RunOptions{false}).metrics;
  static const Metrics case2 = RunScenario(Case2("exact"), RunOptions{false}).metrics;
  return which == 1 ? case1 : case2;
}

void BM_Case1_Exact(benchmark::State& state) { RunCase(state, Case1("exact"), nullptr); }
void BM_Case1_Cvode(benchmark::State& state) { RunCase(state, Case1("cvode"), &ExactMetrics(1)); }
void BM_Case2_Exact(benchmark::State& state) { RunCase(state, Case2("exact"), nullptr); }
void BM_Case2_Cvode(benchmark::State& state) { RunCase(state, Case2("cvode"), &ExactMetrics(2)); }

// Case 1 with the trace recorded (what `run --out` pays for trace.csv and the plots).
void BM_Case1_Exact_WithTrace(benchmark::State& state) {
  const Scenario scenario = Case1("exact");
  for (auto _ : state) benchmark::DoNotOptimize(RunScenario(scenario).trace.time_s.size());
  state.SetItemsProcessed(state.iterations());
}

// Case 1's command alone (the controller's share of a run).
void BM_Case1_CommandOnly(benchmark::State& state) {
  const Scenario scenario = Case1("exact");
  for (auto _ : state) {
    controller::ControllerConfig c = scenario.controller;
    c.stroke_limits = scenario.machine.stroke_m;
    benchmark::DoNotOptimize(controller::GenerateProgramCommand(c, scenario.RunProgram()).num_ticks());
  }
  state.SetItemsProcessed(state.iterations());
}

// Case 3 (and 4d): the sweep as `shapebench sweep` runs it (results.csv written, no plots).
void Case3(benchmark::State& state, const std::string& method,
           const std::string& file = "case3_sweep.yaml", Durability durability = Durability::kSynced,
           bool write_mat = false, const std::vector<Override>& more = {}) {
  std::vector<Override> sets = {{"integrator.method", method}};
  sets.insert(sets.end(), more.begin(), more.end());
  const Sweep sweep = LoadSweep(kSource + "/benchmarks/cases/" + file, sets);
  const std::string dir = (std::filesystem::temp_directory_path() /
                           ("shapebench_bench_sweep_" + std::to_string(getpid())))
                              .string();
  // The process's CPU time (every thread's): on a shared machine the wall time per point
  // depends on what else runs; the CPU time per point does not, and 1 / (CPU per point) per
  // core is what the sweep reaches on cores of its own.
  double cpu_s = 0.0;
  auto process_cpu_s = [] {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
           1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  };
  for (auto _ : state) {
    state.PauseTiming();  // the last run's files: not this run's work
    std::filesystem::remove_all(dir);
    state.ResumeTiming();
    SweepRunOptions options;
    options.out_dir = dir;
    options.jobs = static_cast<int>(state.range(0));
    options.durability = durability;
    options.write_mat = write_mat;
    const double before = process_cpu_s();
    benchmark::DoNotOptimize(RunSweep(sweep, sets, options).ok);
    cpu_s += process_cpu_s() - before;
  }
  std::filesystem::remove_all(dir);
  // The integrator's work per simulated second over the sweep's points (run again, once,
  // outside the timing: RunSweep keeps only the metrics).
  // Once per sweep file (repetitions reuse it).
  static std::map<std::string, benchmark::UserCounters> accuracy;
  if (method == "cvode" && state.range(0) == 1 && accuracy.count(file) != 0) {
    for (const auto& [name, value] : accuracy[file]) state.counters[name] = value;
  } else if (method == "cvode" && state.range(0) == 1) {
    long steps = 0;
    long rhs_evals = 0;
    double simulated_s = 0.0;
    double error = 0.0;  // the ratio metrics' largest difference from the exact path's
    double settling_error_s = 0.0;  // settling_time_s's
    for (std::uint64_t p = 0; p < sweep.points; ++p) {
      Scenario scenario = LoadScenario(sweep.base, MakePoint(sweep, p, sets).overrides);
      const RunResult run = RunScenario(scenario, RunOptions{false});
      scenario.integrator.method = model::IntegratorMethod::kExact;
      const Metrics exact = RunScenario(scenario, RunOptions{false}).metrics;
      error = std::max(error, MetricError(run.metrics, exact));
      if (std::isfinite(exact.settling_time_s) && std::isfinite(run.metrics.settling_time_s)) {
        settling_error_s = std::max(settling_error_s, std::abs(exact.settling_time_s - run.metrics.settling_time_s));
      }
      steps += run.stats.steps;
      rhs_evals += run.stats.rhs_evals;
      simulated_s += run.simulated_s;
    }
    state.counters["error_vs_exact"] = error;
    state.counters["settling_error_s"] = settling_error_s;
    state.counters["steps_per_point"] = static_cast<double>(steps) / static_cast<double>(sweep.points);
    state.counters["rhs_per_point"] = static_cast<double>(rhs_evals) / static_cast<double>(sweep.points);
    state.counters["steps_per_sim_s"] = static_cast<double>(steps) / simulated_s;
    state.counters["rhs_per_sim_s"] = static_cast<double>(rhs_evals) / simulated_s;
    state.counters["sim_s"] = simulated_s / static_cast<double>(sweep.points);
    accuracy[file] = state.counters;
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(sweep.points));
  state.counters["points"] = static_cast<double>(sweep.points);
  state.counters["cpu_s_per_point"] =
      cpu_s / static_cast<double>(state.iterations() * static_cast<std::int64_t>(sweep.points));
}
void BM_Case3_Exact(benchmark::State& state) { Case3(state, "exact"); }
void BM_Case3_Cvode(benchmark::State& state) { Case3(state, "cvode"); }
// Case 3 with results.mat (issue 38), as `shapebench sweep` writes it; the other sweep
// cases leave it out, as the versions bench-compare compares with did.
void BM_Case3_ExactWithMat(benchmark::State& state) {
  Case3(state, "exact", "case3_sweep.yaml", Durability::kSynced, true);
}
void BM_Case3_Exact10k(benchmark::State& state) { Case3(state, "exact", "case3_sweep_10k.yaml"); }
void BM_Case4Damped_Exact(benchmark::State& state) { Case3(state, "exact", "case4_damped_sweep.yaml"); }
// Issue 41: case 1's 5000-point sweep, and the same with a move ten times longer.
void BM_Case41_Exact5k(benchmark::State& state) { Case3(state, "exact", "case41_sweep_5k.yaml"); }
void BM_Case41_Exact5kLong(benchmark::State& state) { Case3(state, "exact", "case41_sweep_5k_long.yaml"); }
void BM_Case4Damped_Cvode(benchmark::State& state) { Case3(state, "cvode", "case4_damped_sweep.yaml"); }
// Issue 41: the same without CVODE's cross-check, what the check costs a sweep (one
// family check for the 1000 points: docs/performance.md).
void BM_Case4Damped_CvodeNoCheck(benchmark::State& state) {
  Case3(state, "cvode", "case4_damped_sweep.yaml", Durability::kSynced, false, {{"integrator.cross_check", "off"}});
}
// `sweep --no-sync`: the same sweeps without their three syncs of the disk (about half a
// millisecond a sweep here), what the sweep's own work gives from 1 to 2 jobs.
void BM_Case3_ExactNoSync(benchmark::State& state) {
  Case3(state, "exact", "case3_sweep.yaml", Durability::kUnsynced);
}
void BM_Case4Damped_ExactNoSync(benchmark::State& state) {
  Case3(state, "exact", "case4_damped_sweep.yaml", Durability::kUnsynced);
}

// ---- The floor: the bare exact zero-order hold of case 1's mode ----

// Case 1's mode (q'' + 2 zeta w q' + w^2 q = -a, deflection = gain q, scripts/baseline.py),
// its command's accelerations built once, the number of ticks case 1's run simulates.
struct FloorCase {
  double w = 0.0, zeta = 0.0, gain = 0.0, dt = 0.0;
  std::vector<double> accel;  // per tick 1..ticks (index k - 1); 0 after the command
  double static_m = 0.0;
  double run_peak_ratio = 0.0;  // what the exact path's run reports (sampled peak)
};

FloorCase MakeFloor(const std::vector<Override>& sets) {
  {
    const Scenario scenario = LoadScenario(kSource + "/benchmarks/cases/case1.yaml", sets);
    const RunResult run = RunScenario(scenario, RunOptions{false});
    const auto& mode = std::get<model::ModalMachineConfig>(scenario.machine.axes[scenario.move_axis()]->form).modes.at(0);
    FloorCase f;
    f.w = 2.0 * M_PI * mode.frequency_hz;
    f.zeta = mode.damping_ratio;
    f.gain = mode.gain;
    f.dt = run.command.period_s;
    const std::size_t ticks = static_cast<std::size_t>(std::lround(run.simulated_s / f.dt));
    f.accel.assign(ticks, 0.0);
    const auto& axis = run.command.axes[scenario.move_axis()];
    for (std::size_t k = 1; k <= std::min(ticks, run.command.num_ticks()); ++k) f.accel[k - 1] = axis.accel_m_s2(k);
    f.static_m = run.metrics.static_displacement_m;
    f.run_peak_ratio = run.metrics.peak_ratio;
    return f;
  }
}

const FloorCase& Floor() {
  static const FloorCase floor = MakeFloor({});
  return floor;
}

// The largest |deflection| of the run: per tick the exact transition of (q, q') under the
// held acceleration, and where q' changes sign inside the tick the extremum there (one
// root at most: w dt < pi), in closed form: undamped, the free oscillation's amplitude
// about the static deflection; damped, at w_d t = atan2(v0, (s v0 + w^2 x0) / w_d).
double FloorPeak(const FloorCase& f) {
  const double s = f.zeta * f.w;
  const double wd = f.w * std::sqrt(1.0 - f.zeta * f.zeta);
  const double e = std::exp(-s * f.dt), c = std::cos(wd * f.dt), sn = std::sin(wd * f.dt);
  const double p11 = e * (c + s / wd * sn), p12 = e * sn / wd, p21 = -e * f.w * f.w / wd * sn,
               p22 = e * (c - s / wd * sn);
  const double w2 = f.w * f.w;
  const double g1 = -(1.0 - p11) / w2, g2 = p21 / w2;  // the response to a held a = 1
  double q = 0.0, v = 0.0, peak = 0.0;
  for (const double a : f.accel) {
    const double q1 = p11 * q + p12 * v + g1 * a;
    const double v1 = p21 * q + p22 * v + g2 * a;
    if ((v > 0.0 && v1 < 0.0) || (v < 0.0 && v1 > 0.0)) {
      const double x0 = q + a / w2;  // about the static deflection -a / w^2
      double x;
      if (f.zeta == 0.0) {
        x = std::copysign(std::sqrt(x0 * x0 + v * v / w2), v);  // v > 0: a maximum
      } else {
        double theta = std::atan2(v, (s * v + w2 * x0) / wd);
        if (theta <= 0.0) theta += M_PI;
        const double t = theta / wd;
        x = std::exp(-s * t) * (x0 * std::cos(theta) + (v + s * x0) / wd * std::sin(theta));
      }
      peak = std::max(peak, std::abs(x - a / w2));
    }
    peak = std::max(peak, std::abs(q1));
    q = q1;
    v = v1;
  }
  return std::abs(f.gain) * peak;
}

// The floor of a batch: kLanes modes of different frequencies (undamped, as case 1's)
// advanced together through the same command, one lane per frequency, the lanes' loops
// left to the compiler's vectoriser; the in-tick extremum only in a tick where some lane's
// velocity changes sign, for those lanes. Each lane's peak is the scalar
// FloorPeak's of its frequency bit for bit (the same operations; max is exact).
constexpr int kLanes = 4;

std::array<double, kLanes> FloorPeakLanes(const FloorCase& f, const std::array<double, kLanes>& w) {
  std::array<double, kLanes> p11, p12, p21, p22, g1, g2, w2, q{}, v{}, peak{};
  for (int l = 0; l < kLanes; ++l) {
    const double c = std::cos(w[l] * f.dt), sn = std::sin(w[l] * f.dt);
    w2[l] = w[l] * w[l];
    p11[l] = 1.0 * (c + 0.0 / w[l] * sn);
    p12[l] = 1.0 * sn / w[l];
    p21[l] = -1.0 * w[l] * w[l] / w[l] * sn;
    p22[l] = 1.0 * (c - 0.0 / w[l] * sn);
    g1[l] = -(1.0 - p11[l]) / w2[l];
    g2[l] = p21[l] / w2[l];
  }
  std::array<double, kLanes> q1, v1;
  for (const double a : f.accel) {
    // The state update of every lane (vectorised), then the rare turns lane by lane.
    int turns = 0;
    for (int l = 0; l < kLanes; ++l) {
      q1[l] = p11[l] * q[l] + p12[l] * v[l] + g1[l] * a;
      v1[l] = p21[l] * q[l] + p22[l] * v[l] + g2[l] * a;
      turns |= (v[l] > 0.0 && v1[l] < 0.0) || (v[l] < 0.0 && v1[l] > 0.0);
    }
    if (turns) {
      for (int l = 0; l < kLanes; ++l) {
        if ((v[l] > 0.0 && v1[l] < 0.0) || (v[l] < 0.0 && v1[l] > 0.0)) {
          const double x0 = q[l] + a / w2[l];
          const double x = std::copysign(std::sqrt(x0 * x0 + v[l] * v[l] / w2[l]), v[l]);
          peak[l] = std::max(peak[l], std::abs(x - a / w2[l]));
        }
      }
    }
    for (int l = 0; l < kLanes; ++l) {
      peak[l] = std::max(peak[l], std::abs(q1[l]));
      q[l] = q1[l];
      v[l] = v1[l];
    }
  }
  for (int l = 0; l < kLanes; ++l) peak[l] *= std::abs(f.gain);
  return peak;
}

// Per point (lane): the batch floor's time over kLanes.
void BM_FloorBatch(benchmark::State& state) {
  FloorCase f = Floor();
  const std::array<double, kLanes> w = {2.0 * M_PI * 21.0, 2.0 * M_PI * 24.5, 2.0 * M_PI * 27.25, 2.0 * M_PI * 33.0};
  std::array<double, kLanes> peaks{};
  for (auto _ : state) {
    peaks = FloorPeakLanes(f, w);
    benchmark::DoNotOptimize(peaks.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * kLanes);
  bool same = true;
  for (int l = 0; l < kLanes; ++l) {
    f.w = w[l];
    const double scalar = FloorPeak(f);
    same = same && std::memcmp(&scalar, &peaks[l], sizeof scalar) == 0;
  }
  state.counters["lanes"] = kLanes;
  state.counters["lanes_equal_scalar_bits"] = same ? 1.0 : 0.0;
}

void BM_Floor(benchmark::State& state) {
  const FloorCase& f = Floor();
  double peak = 0.0;
  for (auto _ : state) {
    peak = FloorPeak(f);
    benchmark::DoNotOptimize(&peak);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["ticks"] = static_cast<double>(f.accel.size());
  state.counters["peak_ratio"] = peak / f.static_m;
  // The run's sampled peak is below the exact extremum (200 samples a period: by at most
  // 1.2e-4 of it).
  state.counters["run_peak_ratio"] = f.run_peak_ratio;
  // Off the design frequency, undamped and damped: the floor's exact extremum against the
  // run's sampled peak (the floor's at least as large, by at most 1.2e-4 of it).
  for (const char* damping : {"0", "0.02"}) {
    const FloorCase off = MakeFloor({{"machine.modes[0].frequency_hz", "31.3"},
                                     {"machine.modes[0].damping_ratio", damping}});
    const std::string name = std::string("peak_ratio_31hz_zeta") + damping;
    state.counters[name] = FloorPeak(off) / off.static_m;
    state.counters["run_" + name] = off.run_peak_ratio;
  }
}

// ---- Case 4: a plant with nonlinear elements ----

Scenario Case4() { return LoadScenario(kSource + "/benchmarks/cases/case4_lugre_circle.yaml", {}); }

// Case 4 as a run: time per run, the points (output samples) per second and how much faster
// than real time (simulated seconds per CPU second), CVODE's work per simulated second.
void BM_Case4_LugreCircle(benchmark::State& state) {
  const Scenario scenario = Case4();
  RunResult last;
  for (auto _ : state) {
    last = RunScenario(scenario, RunOptions{false});
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations());
  const double points = last.simulated_s / scenario.controller.period_s * last.substeps;
  state.counters["sim_s"] = last.simulated_s;
  state.counters["points"] = points;
  state.counters["points_per_s"] =
      benchmark::Counter(points * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["real_time_factor"] =
      benchmark::Counter(last.simulated_s * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["steps_per_sim_s"] = last.stats.steps / last.simulated_s;
  state.counters["rhs_per_sim_s"] = last.stats.rhs_evals / last.simulated_s;
  state.counters["events"] = static_cast<double>(last.stats.events);
  state.counters["peak_ratio"] = last.metrics.peak_ratio;
}

// ---- The CVODE cross-check (model/cvode_cross_check.h) ----

// One check, not cached, of case 1's plant (arg 1) or case 2's servo-driven moving column
// (arg 2), with the settings and scales a run of that case passes: what a sweep pays once
// per distinct plant, and a single run once. The deviation is reported beside the time.
void BM_CvodeCrossCheck(benchmark::State& state) {
  const Scenario scenario = state.range(0) == 1 ? Case1("cvode") : Case2("cvode");
  const model::MachinePlant machine = model::BuildMachinePlant(scenario.machine, scenario.drive);
  const RunResult run = RunScenario(scenario, RunOptions{false});
  model::CrossCheckResult check;
  for (auto _ : state) {
    check = model::CrossCheckCvode(machine.plant, scenario.integrator, scenario.controller.period_s,
                                   run.substeps, 1.0, 0.3);
    // Through memory: DoNotOptimize on a double ("+r,m") can corrupt it with this GCC.
    benchmark::DoNotOptimize(&check);
    benchmark::ClobberMemory();
  }
  state.counters["deviation"] = check.deviation;
  state.counters["sample_ticks"] = static_cast<double>(check.sample_ticks);
}

// ---- CVODE tuning, each choice at equal accuracy (case 1) ----

// The accuracy every variant must reach: the ratio metrics within this of the exact path.
constexpr double kTargetError = 3e-7;

struct Variant {
  const char* name;
  std::function<void(model::IntegratorConfig&)> apply;
};

const std::vector<Variant>& Variants() {
  using model::CvodeInputMode;
  static const std::vector<Variant> variants = {
      {"default", [](model::IntegratorConfig&) {}},
      {"bdf", [](model::IntegratorConfig& c) { c.lmm = model::CvodeLmm::kBdf; }},
      {"stop_every_tick",
       [](model::IntegratorConfig& c) { c.tuning.input_mode = CvodeInputMode::kStopEveryTick; }},
      {"restart_every_tick",
       [](model::IntegratorConfig& c) { c.tuning.input_mode = CvodeInputMode::kRestartEveryTick; }},
      {"scalar_atol", [](model::IntegratorConfig& c) { c.tuning.per_state_atol = false; }},
      {"no_memory_reuse", [](model::IntegratorConfig& c) { c.tuning.reuse_memory = false; }},
      {"dq_jacobian", [](model::IntegratorConfig& c) { c.tuning.jacobian = false; }},
      {"fixed_point", [](model::IntegratorConfig& c) { c.tuning.fixed_point = true; }},
      {"adams_max_order_5", [](model::IntegratorConfig& c) { c.tuning.max_order = 5; }},
      {"cvode_interpolation",
       [](model::IntegratorConfig& c) { c.tuning.output = model::CvodeOutput::kCvodeInterpolation; }},
      {"eta_fixed_step_1.5", [](model::IntegratorConfig& c) { c.tuning.eta_max_fixed_step = 1.5; }},
      {"packaged_vector_ops",
       [](model::IntegratorConfig& c) { c.tuning.optimized_vector_ops = false; }},
  };
  return variants;
}

// The loosest rtol (of a fixed ladder) at which the variant meets kTargetError.
double RtolAtTarget(const Scenario& base, const Metrics& exact, const Variant& variant) {
  Scenario scenario = base;
  for (double rtol : {1e-6, 3e-7, 1e-7, 3e-8, 1e-8, 3e-9, 1e-9, 3e-10, 1e-10, 3e-11, 1e-11, 3e-12,
                      1e-12}) {
    scenario.integrator.rtol = rtol;
    variant.apply(scenario.integrator);
    // The variants are measured against the exact path here; the cross-check is timed apart
    // (BM_CvodeCrossCheck).
    scenario.integrator.cross_check = model::CrossCheckPolicy::kOff;
    try {
      if (MetricError(RunScenario(scenario, RunOptions{false}).metrics, exact) <= kTargetError) {
        return rtol;
      }
    } catch (const model::SolverError&) {
    }
  }
  return NAN;
}

// Case 3's points (CVODE) and their exact metrics, loaded and run once.
struct Case3Point {
  Scenario scenario;
  Metrics exact;
};
const std::vector<Case3Point>& Case3Points() {
  static const std::vector<Case3Point> points = [] {
    const std::vector<Override> sets = {{"integrator.method", "cvode"}};
    const Sweep sweep = LoadSweep(kSource + "/benchmarks/cases/case3_sweep.yaml", sets);
    std::vector<Case3Point> result;
    for (std::uint64_t p = 0; p < sweep.points; ++p) {
      Scenario scenario = LoadScenario(sweep.base, MakePoint(sweep, p, sets).overrides);
      Scenario exact = scenario;
      exact.integrator.method = model::IntegratorMethod::kExact;
      // CVODE's peak is the largest of its output samples (200 a period), up to 1.2e-4
      // below the exact path's in-tick extremum; the tuning asks how well CVODE
      // integrates, so its peak is held to the exact path's samples on the same grid.
      RunResult traced = RunScenario(exact, RunOptions{true});
      double sampled_m = 0.0;
      for (const double y : traced.trace.deflection_m) sampled_m = std::max(sampled_m, std::abs(y));
      traced.metrics.peak_ratio = sampled_m / traced.metrics.static_displacement_m;
      result.push_back({scenario, traced.metrics});
    }
    return result;
  }();
  return points;
}

// Case 3's accuracy for the tuning: the ratio metrics of every point within this of the
// exact path's (its peak sampled as CVODE's is), what CVODE's own settings (fixed-step
// bound 1.5) reach at rtol 1e-8. A sweep's error is its worst point's, and grows with the
// steps an undamped mode takes, so the ladder is finer than case 1's: the choices differ
// by tens of percent here.
constexpr double kCase3TargetError = 2e-5;

// One job, each point run as the sweep runs it (RunScenario on the loaded point); the
// loosest rtol of the ladder at which the worst point meets kCase3TargetError.
void Case3Tuning(benchmark::State& state, const Variant& variant) {
  const std::vector<Case3Point>& points = Case3Points();
  auto configured = [&](const Case3Point& point, double rtol) {
    Scenario scenario = point.scenario;
    scenario.integrator.rtol = rtol;
    variant.apply(scenario.integrator);
    scenario.integrator.cross_check = model::CrossCheckPolicy::kOff;
    return scenario;
  };
  auto worst_error = [&](double rtol, model::IntegratorStats* stats, double* simulated_s) {
    double error = 0.0;
    for (const Case3Point& point : points) {
      const RunResult run = RunScenario(configured(point, rtol), RunOptions{false});
      error = std::max(error, MetricError(run.metrics, point.exact));
      stats->steps += run.stats.steps;
      stats->rhs_evals += run.stats.rhs_evals;
      *simulated_s += run.simulated_s;
    }
    return error;
  };
  double rtol = NAN;
  double error = NAN;
  model::IntegratorStats stats;
  double simulated_s = 0.0;
  for (double candidate : {1e-8, 7e-9, 5e-9, 3.5e-9, 2.5e-9, 1.7e-9, 1.2e-9, 1e-9}) {
    stats = {};
    simulated_s = 0.0;
    error = worst_error(candidate, &stats, &simulated_s);
    if (error <= kCase3TargetError) {
      rtol = candidate;
      break;
    }
  }
  if (!std::isfinite(rtol)) {
    state.SkipWithError("no rtol of the ladder reaches the target accuracy");
    return;
  }
  for (auto _ : state) {
    for (const Case3Point& point : points) {
      benchmark::DoNotOptimize(RunScenario(configured(point, rtol), RunOptions{false}).metrics.peak_ratio);
    }
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(points.size()));
  state.counters["points"] = static_cast<double>(points.size());
  state.counters["rtol"] = rtol;
  state.counters["error_vs_exact"] = error;
  state.counters["steps_per_sim_s"] = static_cast<double>(stats.steps) / simulated_s;
  state.counters["rhs_per_sim_s"] = static_cast<double>(stats.rhs_evals) / simulated_s;
}

// Args: the case (1, 2 or 3), the variant.
void BM_CvodeTuning(benchmark::State& state) {
  const int which = static_cast<int>(state.range(0));
  const Variant& variant = Variants()[static_cast<std::size_t>(state.range(1))];
  state.SetLabel(variant.name);
  if (which == 3) {
    Case3Tuning(state, variant);
    return;
  }
  const Scenario base = which == 1 ? Case1("cvode") : Case2("cvode");
  const double rtol = RtolAtTarget(base, ExactMetrics(which), variant);
  if (!std::isfinite(rtol)) {
    state.SkipWithError("no rtol of the ladder reaches the target accuracy");
    return;
  }
  Scenario scenario = base;
  scenario.integrator.rtol = rtol;
  variant.apply(scenario.integrator);
  RunCase(state, scenario, &ExactMetrics(which));
  state.counters["rtol"] = rtol;
}

void TuningArgs(benchmark::internal::Benchmark* b) {
  for (std::size_t i = 0; i < Variants().size(); ++i) b->Args({1, static_cast<int>(i)});
  // Case 2 (servo, three axes): the choices whose answer could differ on a stiffer plant.
  auto add = [&](int which, const char* name) {
    for (std::size_t i = 0; i < Variants().size(); ++i) {
      if (std::string(Variants()[i].name) == name) b->Args({which, static_cast<int>(i)});
    }
  };
  for (const char* name : {"default", "bdf", "fixed_point", "scalar_atol", "eta_fixed_step_1.5"}) {
    add(2, name);
  }
  // Case 3 (the sweep, one job): the choices made for it.
  for (const char* name : {"default", "eta_fixed_step_1.5", "cvode_interpolation", "packaged_vector_ops"}) {
    add(3, name);
  }
}

// ---- the command and plant of case 1 for scripts/baseline.py ----

int ExportCase1(const std::string& path) {
  const Scenario scenario = Case1("exact");
  const RunResult exact = RunScenario(scenario, RunOptions{false});
  const RunResult cvode = RunScenario(Case1("cvode"), RunOptions{false});
  const controller::MultiAxisCommand& command = exact.command;
  const int axis = scenario.move_axis();
  const auto& mode = std::get<model::ModalMachineConfig>(scenario.machine.axes[axis]->form).modes.at(0);
  std::ofstream out(path);
  out.precision(17);
  out << "{\n  \"frequency_hz\": " << mode.frequency_hz << ",\n  \"damping_ratio\": "
      << mode.damping_ratio << ",\n  \"gain\": " << mode.gain << ",\n  \"period_s\": "
      << command.period_s << ",\n  \"substeps\": " << exact.substeps
      << ",\n  \"simulated_ticks\": " << std::lround(exact.simulated_s / command.period_s)
      << ",\n  \"rtol\": " << scenario.integrator.rtol
      << ",\n  \"static_displacement_m\": " << exact.metrics.static_displacement_m
      << ",\n  \"shapebench_peak_ratio_exact\": " << exact.metrics.peak_ratio
      << ",\n  \"shapebench_peak_ratio_cvode\": " << cvode.metrics.peak_ratio
      << ",\n  \"accel_m_s2\": [";
  for (std::size_t k = 1; k <= command.num_ticks(); ++k) {
    out << (k > 1 ? ", " : "") << command.axes[axis].accel_m_s2(k);
  }
  out << "]\n}\n";
  return out ? 0 : 1;
}

// Case 4 for scripts/baseline.py: the plant the run integrates (its Z axis, which the
// circle never moves, left out: it stays at rest, plant_sampler.cc's IdleAxesRigid), its LuGre
// elements, CVODE's tolerances, the command's acceleration per tick and axis, and
// shapebench's X and Y deflection at every tick's end.
void WriteMatrix(std::ostream& out, const char* name, const Eigen::MatrixXd& m) {
  out << "  \"" << name << "\": [";
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    out << (r > 0 ? ", " : "") << "[";
    for (Eigen::Index c = 0; c < m.cols(); ++c) out << (c > 0 ? ", " : "") << m(r, c);
    out << "]";
  }
  out << "],\n";
}

int ExportCase4(const std::string& path) {
  const Scenario scenario = Case4();
  const RunResult run = RunScenario(scenario);
  model::MultiAxisMachineConfig machine = scenario.machine;
  machine.axes[2].reset();
  const model::MachinePlant plant = model::BuildMachinePlant(machine, scenario.drive);
  const CommandSamples samples = SampleCommand(run.command);
  // As the run's: the scales of CoSimulation::SetUpPlant (the bristles' atol is the script's).
  const Eigen::VectorXd atol = model::CvodeAbsoluteTolerances(
      plant.plant, scenario.integrator, std::max(samples.max_accel_m_s2, 1e-12), samples.max_speed_m_s);
  std::ofstream out(path);
  out.precision(17);
  out << "{\n  \"period_s\": " << run.command.period_s << ",\n  \"substeps\": " << run.substeps
      << ",\n  \"simulated_ticks\": " << std::lround(run.simulated_s / run.command.period_s)
      << ",\n  \"rtol\": " << scenario.integrator.rtol << ",\n";
  WriteMatrix(out, "A", plant.plant.A);
  WriteMatrix(out, "B_accel", plant.plant.B_accel);
  WriteMatrix(out, "B_vel", plant.plant.B_vel);
  WriteMatrix(out, "C_deflection", plant.plant.C.topRows(2));  // X and Y deflection rows
  WriteMatrix(out, "atol", atol.transpose());  // x, then the 3 drive velocities
  out << "  \"atol_scale\": " << scenario.integrator.atol_scale << ",\n";
  out << "  \"elements\": [";
  for (std::size_t i = 0; i < plant.nonlinear.size(); ++i) {
    const model::NonlinearElement& e = plant.nonlinear[i];
    const model::FrictionConfig& f = std::get<model::FrictionElement>(e.law).friction;
    out << (i > 0 ? ", " : "") << "{\"coulomb_n\": " << f.coulomb_n << ", \"static_n\": " << f.StaticN()
        << ", \"stribeck_velocity_m_s\": " << f.stribeck_velocity_m_s << ", \"viscous_n_s_m\": " << f.viscous_n_s_m
        << ", \"sigma0_n_m\": " << f.sigma0_n_m << ", \"sigma1_n_s_m\": " << f.sigma1_n_s_m << ", \"row_x\": [";
    for (Eigen::Index k = 0; k < e.row_x.size(); ++k) out << (k > 0 ? ", " : "") << e.row_x(k);
    out << "], \"row_v\": [" << e.row_v(0) << ", " << e.row_v(1) << ", " << e.row_v(2) << "], \"column_x\": [";
    for (Eigen::Index k = 0; k < e.column_x.size(); ++k) out << (k > 0 ? ", " : "") << e.column_x(k);
    out << "]}";
  }
  out << "],\n  \"accel_m_s2\": [";
  for (std::size_t k = 1; k <= run.command.num_ticks(); ++k) {
    out << (k > 1 ? ", " : "") << "[" << run.command.axes[0].accel_m_s2(k) << ", " << run.command.axes[1].accel_m_s2(k) << "]";
  }
  out << "],\n  \"shapebench_deflection_m\": [";
  for (std::size_t i = static_cast<std::size_t>(run.substeps), k = 0; i < run.trace.time_s.size();
       i += static_cast<std::size_t>(run.substeps), ++k) {
    const Eigen::Vector3d& d = run.trace.deflection_axes_m[i];
    out << (k > 0 ? ", " : "") << "[" << d(0) << ", " << d(1) << "]";
  }
  out << "]\n}\n";
  return out ? 0 : 1;
}

}  // namespace

// Case 1's two targets: the median of five repetitions (one run of a few seconds can
// catch a busy moment of a shared machine).
BENCHMARK(BM_Case1_Exact)->Unit(benchmark::kMicrosecond)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_Case1_Cvode)->Unit(benchmark::kMicrosecond)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_Case1_Exact_WithTrace)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Case1_CommandOnly)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Case2_Exact)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Case2_Cvode)->Unit(benchmark::kMillisecond);
// Case 3 exact, the floor and case 4d: medians of five (the must-show ratios compare them).
BENCHMARK(BM_Case3_Exact)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(1)
    ->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_Case3_ExactWithMat)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(1)
    ->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_Case3_ExactNoSync)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(1)
    ->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_Case3_Exact10k)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3)
    ->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_Case41_Exact5k)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3)
    ->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_Case41_Exact5kLong)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3)
    ->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_Case3_Cvode)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2);
BENCHMARK(BM_Floor)->Unit(benchmark::kMicrosecond)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_FloorBatch)->Unit(benchmark::kMicrosecond)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_Case4Damped_Exact)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()
    ->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_Case4Damped_ExactNoSync)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()
    ->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_Case4Damped_Cvode)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()
    ->Iterations(1)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_Case4Damped_CvodeNoCheck)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()
    ->Iterations(1)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_CvodeCrossCheck)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CvodeTuning)->Apply(TuningArgs)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Case4_LugreCircle)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);

int main(int argc, char** argv) {
  std::vector<char*> rest;
  for (int i = 0; i < argc; ++i) {
    const std::string arg = argv[i];
    const std::string flag = "--export_case1=";
    if (arg.compare(0, flag.size(), flag) == 0) return ExportCase1(arg.substr(flag.size()));
    const std::string flag4 = "--export_case4=";
    if (arg.compare(0, flag4.size(), flag4) == 0) return ExportCase4(arg.substr(flag4.size()));
    rest.push_back(argv[i]);
  }
  int count = static_cast<int>(rest.size());
  benchmark::Initialize(&count, rest.data());
  if (benchmark::ReportUnrecognizedArguments(count, rest.data())) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

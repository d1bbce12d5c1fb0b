#include "bench/run/run_work.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "common/format.h"
#include "model/integrator.h"

namespace shapebench::bench {
namespace {

// The largest value limits.max_work takes (a long).
constexpr double kLargestMaxWork = 9e18;

// A count as digits (up to 1e15), else in exponent form.
std::string Count(double count) {
  return count < 1e15 ? std::to_string(static_cast<long long>(count)) : FormatNumber(count, 3);
}

// A power of ten at least `work`: the suggested limit.
std::string Suggestion(double work) {
  const double power = std::pow(10.0, std::ceil(std::log10(std::max(work, 1.0))));
  if (!(power <= kLargestMaxWork)) return "9000000000000000000, the largest it takes";
  return Count(power);
}

std::string Prefix(const RunPlan& plan) { return "scenario '" + plan.scenario.name + "' "; }

}  // namespace

double RunWork(const RunPlan& plan, std::size_t tick, long integrator_work) {
  return static_cast<double>(tick) * plan.substeps + static_cast<double>(integrator_work);
}

void CheckEstimatedWork(const RunPlan& plan, long period_work) {
  const double periods = static_cast<double>(plan.window.window_end());
  const double least = periods * (static_cast<double>(plan.substeps) + static_cast<double>(period_work));
  const long limit = plan.scenario.limits.max_work;
  if (!(least > static_cast<double>(limit))) return;
  std::string each = std::to_string(plan.substeps) + " output samples";
  if (period_work > 0) {
    each += " + " + Count(static_cast<double>(period_work)) +
            " passes of the exact path's in-tick extremum search (its grid: a quarter of the fastest pole's "
            "period a step)";
  }
  throw model::SolverError(
      "WORK_LIMIT", Prefix(plan) + "would do at least " + Count(least) + " units of work, more than limits.max_work (" +
                        Count(static_cast<double>(limit)) + "): " + Count(periods) +
                        " periods (the motion and its residual window) x (" + each +
                        ") a period; nothing was run: raise limits.max_work (e.g. --set limits.max_work=" +
                        Suggestion(10.0 * least) + ") to run it");
}

// limits.max_wall_s, off at 0: the host's verdict, never the default.
void CheckWallClock(const RunPlan& plan, std::size_t tick) {
  const double limit_s = plan.scenario.limits.max_wall_s;
  if (!(limit_s > 0.0)) return;
  const double elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - plan.started).count();
  if (!(elapsed_s > limit_s)) return;
  throw model::SolverError(
      "WALL_LIMIT", Prefix(plan) + "stopped at t = " + FormatNumber(plan.dt_s * static_cast<double>(tick), 6) +
                        " s (period " + std::to_string(tick) + " of at least " +
                        std::to_string(plan.window.window_end()) + ") after " + FormatNumber(elapsed_s, 3) +
                        " s of wall-clock time, more than limits.max_wall_s (" + FormatNumber(limit_s) +
                        " s): this host's speed and load decided it (limits.max_work is the same everywhere); "
                        "raise limits.max_wall_s, or set it to 0 (no limit), to run it on");
}

void CheckWork(const RunPlan& plan, std::size_t tick, long integrator_work, std::string_view what) {
  CheckWallClock(plan, tick);
  const long limit = plan.scenario.limits.max_work;
  const double work = RunWork(plan, tick, integrator_work);
  if (!(work > static_cast<double>(limit))) return;
  const double samples = static_cast<double>(tick) * plan.substeps;
  std::string done = Count(samples) + " output samples";
  if (integrator_work > 0) {
    done += " + " + Count(static_cast<double>(integrator_work)) + " " + std::string(what);
  }
  throw model::SolverError(
      "WORK_LIMIT", Prefix(plan) + "stopped at t = " + FormatNumber(plan.dt_s * static_cast<double>(tick), 6) +
                        " s (period " + std::to_string(tick) + " of at least " +
                        std::to_string(plan.window.window_end()) + ") after " + Count(work) +
                        " units of work, more than limits.max_work (" + Count(static_cast<double>(limit)) +
                        "): " + done + "; raise limits.max_work (e.g. --set limits.max_work=" +
                        Suggestion(10.0 * static_cast<double>(limit)) + ") to run it on");
}

}  // namespace shapebench::bench

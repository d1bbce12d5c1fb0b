#include "model/cvode_cross_check.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <mutex>
#include <new>
#include <stdexcept>
#include <vector>

#include <Eigen/Eigenvalues>

#include "common/format.h"
#include "common/math_constants.h"
#include "model/nonlinear_integrator.h"

namespace shapebench::model {
namespace {

constexpr long kMaxHalfPulseTicks = 500;  // a 1 Hz mode at 1 ms: the sample stays < 2,000 ticks

// Ticks in half a period of the plant's slowest pole (oscillatory or real), at least 1.
long HalfPulseTicks(const Eigen::VectorXcd& poles, double period_s) {
  double slowest = 0.0;
  for (Eigen::Index i = 0; i < poles.size(); ++i) {
    const double magnitude = std::abs(poles(i));
    if (magnitude > 0.0 && (slowest == 0.0 || magnitude < slowest)) slowest = magnitude;
  }
  if (!(slowest > 0.0)) return 1;
  const double ticks = std::min(kPi / slowest / period_s, static_cast<double>(kMaxHalfPulseTicks));
  return std::max(std::lround(ticks), 1L);  // bounded first: lround of a huge value is undefined
}

// Drives `integrator` with the pulse and returns its outputs, substep after substep: a
// sine of acceleration over one period (velocity out and back to rest), changing every
// tick as shaped and filtered commands do (each change restarts CVODE, whose first steps
// after a restart are its least accurate), then free.
std::vector<double> RunSample(PlantIntegrator* integrator, int num_inputs, double accel_m_s2,
                              long half_ticks) {
  const long ticks = 4 * half_ticks;
  const int width = integrator->num_outputs();
  const int substeps = integrator->substeps();
  std::vector<double> outputs(static_cast<std::size_t>(ticks) * substeps * width);
  std::vector<double> input(num_inputs);
  integrator->Reset(Eigen::VectorXd::Zero(num_inputs));
  for (long k = 0; k < ticks; ++k) {
    const double a =
        k < 2 * half_ticks
            ? accel_m_s2 * std::sin(kPi * (static_cast<double>(k) + 0.5) / static_cast<double>(half_ticks))
            : 0.0;
    std::fill(input.begin(), input.end(), a);
    const long held = k < 2 * half_ticks ? 1 : ticks - k;
    integrator->AdvancePeriod(input.data(), held,
                              outputs.data() + static_cast<std::size_t>(k) * substeps * width);
  }
  return outputs;
}

// The key of a distinct check: every number CrossCheckCvode reads, as bytes.
std::string CacheKey(const LinearPlant& plant, const IntegratorConfig& config, double period_s,
                     int substeps, double scale_accel_m_s2, double scale_velocity_m_s) {
  std::string key;
  auto add = [&key](const void* data, std::size_t bytes) {
    key.append(static_cast<const char*>(data), bytes);
  };
  auto add_matrix = [&](const Eigen::MatrixXd& m) {
    const Eigen::Index shape[2] = {m.rows(), m.cols()};
    add(shape, sizeof shape);
    add(m.data(), sizeof(double) * static_cast<std::size_t>(m.size()));
  };
  add_matrix(plant.A);
  add_matrix(plant.B_accel);
  add_matrix(plant.B_vel);
  add_matrix(plant.C);
  for (int i = 0; i < plant.num_states(); ++i) {
    const int kind_group[2] = {static_cast<int>(plant.state_kinds[i]), plant.ToleranceGroup(i)};
    add(kind_group, sizeof kind_group);
  }
  for (int g = 0; g < plant.NumToleranceGroups(); ++g) {
    const double f = plant.GroupFrequency(g);
    add(&f, sizeof f);
  }
  const double numbers[5] = {config.rtol, config.atol_scale, period_s, scale_accel_m_s2,
                             scale_velocity_m_s};
  add(numbers, sizeof numbers);
  const long counts[3] = {config.max_num_steps, substeps, static_cast<long>(config.lmm)};
  add(counts, sizeof counts);
  // The tuning changes CVODE's steps; it is compared whole (a plain struct of numbers).
  const CvodeTuning& t = config.tuning;
  const double tuning[9] = {static_cast<double>(t.input_mode), double(t.jacobian),
                            double(t.per_state_atol), double(t.reuse_memory),
                            double(t.fixed_point), double(t.max_order),
                            static_cast<double>(t.output), t.eta_max_fixed_step,
                            double(t.optimized_vector_ops)};
  add(tuning, sizeof tuning);
  return key;
}

// The pulse's length and the plant's memory (CrossCheckResult's), no deviation yet.
CrossCheckResult PulseScales(const Eigen::VectorXcd& poles, double period_s) {
  CrossCheckResult result;
  result.sample_ticks = 4 * HalfPulseTicks(poles, period_s);
  result.sample_s = static_cast<double>(result.sample_ticks) * period_s;
  for (Eigen::Index i = 0; i < poles.size(); ++i) {
    const double decay = -poles(i).real();
    result.memory_s = std::max(result.memory_s, decay > 0.0 ? 1.0 / decay : HUGE_VAL);
  }
  return result;
}

}  // namespace

CrossCheckResult CrossCheckCvode(const LinearPlant& plant, const IntegratorConfig& config,
                                 double period_s, int substeps, double scale_accel_m_s2,
                                 double scale_velocity_m_s, CheckedIntegrator which) {
  IntegratorConfig cvode = config;
  cvode.method = IntegratorMethod::kCvode;
  IntegratorConfig exact = config;
  exact.method = IntegratorMethod::kExact;
  const Eigen::VectorXcd poles = plant.A.eigenvalues();
  const long half_ticks = HalfPulseTicks(poles, period_s);
  auto run = [&](const IntegratorConfig& c) {
    std::unique_ptr<PlantIntegrator> integrator;
    if (which == CheckedIntegrator::kNonlinear && c.method == IntegratorMethod::kCvode) {
      // The whole state through CVODE, not the split (CvodeTuning::split_linear_part),
      // which would integrate the linear part exactly and leave nothing to check: whether
      // BDF at this rtol resolves the plant's modes under a forcing pulse, as it must the
      // elements' forces, which the split leaves to it.
      IntegratorConfig whole = c;
      whole.tuning.split_linear_part = false;
      integrator = std::make_unique<NonlinearCvodeIntegrator>(NonlinearPlant{plant, {}, {}}, whole, period_s, substeps,
                                                              scale_accel_m_s2, scale_velocity_m_s);
    } else {
      integrator = MakeIntegrator(plant, c, period_s, substeps, scale_accel_m_s2, scale_velocity_m_s);
    }
    return RunSample(integrator.get(), plant.num_inputs(), scale_accel_m_s2, half_ticks);
  };
  const std::vector<double> reference = run(exact);
  CrossCheckResult result = PulseScales(poles, period_s);
  std::vector<double> checked;
  try {
    checked = run(cvode);
  } catch (const SolverError& error) {
    result.solver_failure = error.flag_name() + ": " + error.what();
    return result;
  }
  const int width = plant.num_outputs();
  std::vector<double> scale(width, 0.0);
  std::vector<double> error(width, 0.0);
  for (std::size_t i = 0; i < reference.size(); ++i) {
    const int row = static_cast<int>(i % width);
    scale[row] = std::max(scale[row], std::abs(reference[i]));
    error[row] = std::max(error[row], std::abs(checked[i] - reference[i]));
  }
  for (int row = 0; row < width; ++row) {
    if (scale[row] > 0.0) {
      result.deviation = std::max(result.deviation, error[row] / scale[row]);
    } else if (error[row] > 0.0 || std::isnan(error[row])) {
      result.deviation = HUGE_VAL;  // CVODE moves an output the exact solution keeps at rest
    }
  }
  if (std::any_of(checked.begin(), checked.end(), [](double y) { return !std::isfinite(y); })) {
    result.deviation = HUGE_VAL;
  }
  return result;
}

CrossCheckResult CachedCrossCheckCvode(const LinearPlant& plant, const IntegratorConfig& config,
                                       double period_s, int substeps, double scale_accel_m_s2,
                                       double scale_velocity_m_s, CheckedIntegrator checked) {
  static std::mutex mutex;
  static std::map<std::string, CrossCheckResult> cache;
  constexpr std::size_t kMaxEntries = 4096;  // a sweep over the plant: bounded memory
  // A linear plant's response and the tolerances (CvodeIntegrator::AbsoluteTolerances) both
  // scale with the acceleration: the check at unit acceleration (and the run's ratio of
  // speed to acceleration) stands for every run of this plant, up to rounding.
  const double velocity_per_accel =
      scale_accel_m_s2 > 0.0 ? scale_velocity_m_s / scale_accel_m_s2 : scale_velocity_m_s;
  std::string key = CacheKey(plant, config, period_s, substeps, 1.0, velocity_per_accel);
  if (checked == CheckedIntegrator::kNonlinear) key += "nonlinear";
  {
    std::lock_guard<std::mutex> lock(mutex);
    const auto found = cache.find(key);
    if (found != cache.end()) return found->second;
  }
  // Computed outside the lock: two threads may both compute one key, with equal results.
  const CrossCheckResult result =
      CrossCheckCvode(plant, config, period_s, substeps, 1.0, velocity_per_accel, checked);
  std::lock_guard<std::mutex> lock(mutex);
  if (cache.size() >= kMaxEntries) cache.clear();
  cache.emplace(key, result);
  return result;
}

CrossCheckFamily CrossCheckCvodeFamily(double lo, double hi,
                                       const std::function<std::optional<FamilyMember>(double)>& member,
                                       const IntegratorConfig& config, double period_s,
                                       double velocity_per_accel_s, CheckedIntegrator checked) {
  CrossCheckFamily family;
  family.usable = lo <= hi;
  auto check = [&](double value) {
    if (!family.usable) return;
    // A member that cannot be built or checked says nothing of the point being run (which
    // may be valid): no verdict, each member checks itself.
    CrossCheckResult r;
    try {
      const std::optional<FamilyMember> m = member(value);
      if (!m) {
        family.usable = false;
        return;
      }
      r = CrossCheckCvode(m->plant, config, period_s, m->substeps, 1.0, velocity_per_accel_s, checked);
    } catch (const std::bad_alloc&) {
      throw;
    } catch (const std::exception&) {
      family.usable = false;
      return;
    }
    family.values.push_back(value);
    if (!r.solver_failure.empty() || !std::isfinite(r.deviation)) {
      family.usable = false;  // no verdict: each member checks itself
    } else if (r.deviation >= family.deviation) {
      family.deviation = r.deviation;
      family.worst_value = value;
    }
  };
  const double step = (hi - lo) / (kFamilyInterior + 1);
  for (int i = 0; i <= kFamilyInterior + 1; ++i) check(i == kFamilyInterior + 1 ? hi : lo + step * i);
  // Beside the largest: half a step either way, inside the band.
  const double worst = family.worst_value;
  if (worst - 0.5 * step > lo) check(worst - 0.5 * step);
  if (worst + 0.5 * step < hi) check(worst + 0.5 * step);
  return family;
}

CrossCheckFamily CachedCrossCheckCvodeFamily(const std::string& identity, double lo, double hi,
                                             const std::function<std::optional<FamilyMember>(double)>& member,
                                             const IntegratorConfig& config, double period_s,
                                             double velocity_per_accel_s, CheckedIntegrator checked) {
  static std::mutex mutex;
  static std::map<std::string, CrossCheckFamily> cache;
  constexpr std::size_t kMaxEntries = 256;
  std::string key = identity;
  const double band[2] = {lo, hi};
  key.append(reinterpret_cast<const char*>(band), sizeof band);
  key += checked == CheckedIntegrator::kNonlinear ? "nonlinear" : "linear";
  // Computed under the lock: the threads of a sweep need the same family at its start, and
  // one computation (a dozen checks) is cheaper than one per thread.
  std::lock_guard<std::mutex> lock(mutex);
  const auto found = cache.find(key);
  if (found != cache.end()) return found->second;
  CrossCheckFamily family = CrossCheckCvodeFamily(lo, hi, member, config, period_s, velocity_per_accel_s, checked);
  if (cache.size() >= kMaxEntries) cache.clear();
  cache.emplace(std::move(key), family);
  return family;
}

bool FamilyCovers(const CrossCheckFamily& family, const LinearPlant& plant, double period_s, double run_s) {
  if (!family.usable) return false;
  CrossCheckResult own = PulseScales(plant.A.eigenvalues(), period_s);
  own.deviation = kFamilyMargin * family.deviation;
  return own.Passed(run_s);
}

std::string CrossCheckMessage(const CrossCheckResult& result, const IntegratorConfig& config,
                              double run_s, CheckedIntegrator checked) {
  const double predicted = result.Predicted(run_s);
  const bool nonlinear = checked == CheckedIntegrator::kNonlinear;
  const bool adams = config.lmm == CvodeLmm::kAdams && !nonlinear;
  if (!result.solver_failure.empty()) {
    return "CVODE failed on the cross-check pulse (" + result.solver_failure +
           "), so its accuracy on this plant is unknown (docs/accuracy.md); use "
           "integrator.method: exact (or auto), or integrator.cross_check: warn";
  }
  std::string text = "CVODE (integrator.rtol " + FormatNumber(config.rtol) + ", lmm " +
                     (adams ? "adams" : "bdf") + ") disagrees with the exact discretisation of "
                     "this linear plant: ";
  if (nonlinear) {
    text = "CVODE (integrator.rtol " + FormatNumber(config.rtol) + ", BDF as for nonlinear elements) "
           "disagrees with the exact discretisation of this plant's linear part (its nonlinear "
           "elements left out; docs/nonlinear.md): ";
  }
  if (!std::isfinite(predicted)) {
    text += "non-finite values on the check pulse";
  } else {
    text += FormatNumber(result.deviation, 3) + " of the response on a " +
            std::to_string(result.sample_ticks) + "-tick check pulse, " +
            FormatNumber(predicted, 3) + " over this run";
  }
  text += " (allowed " + FormatNumber(kCrossCheckLimit) + ", which keeps ratio metrics within " +
          FormatNumber(kCvodeMetricAccuracy) + " of the exact path; docs/accuracy.md). "
          "Tighten integrator.rtol";
  if (adams) text += ", use integrator.lmm: bdf if a mode is stiff";
  text += nonlinear ? "; integrator.cross_check: warn runs anyway"
                    : ", or use integrator.method: exact (or auto); integrator.cross_check: warn runs anyway";
  return text;
}

}  // namespace shapebench::model

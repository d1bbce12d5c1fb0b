// The family a sweep's point belongs to for CVODE's cross-check (model/cvode_cross_check.h,
// CrossCheckCvodeFamily): the points that differ only in one mode's frequency_hz or
// damping_ratio over the sweep's band share one check instead of one each. The sweep sets
// the band around a point's run (CrossCheckFamilyScope, thread-local like ParseCacheScope);
// the sampler's cross-check asks FamilyCoversRun before checking the point alone.
#pragma once

#include <string>

#include "bench/scenario/scenario.h"
#include "model/integrator.h"
#include "model/linear_plant.h"

namespace shapebench::bench {

struct CrossCheckFamilyBand {
  std::string key_path;  // machine[.axes.AXIS].modes[i].frequency_hz | damping_ratio
  double lo = 0.0;       // the band the sweep gives that key
  double hi = 0.0;
  // Everything else that makes the point's plant, command and settings: the sweep's load
  // and the point's other values and --set options.
  std::string identity;
};

// The band of the runs on this thread while it lives (null: none).
class CrossCheckFamilyScope {
 public:
  explicit CrossCheckFamilyScope(const CrossCheckFamilyBand* band);
  ~CrossCheckFamilyScope();
  CrossCheckFamilyScope(const CrossCheckFamilyScope&) = delete;
  CrossCheckFamilyScope& operator=(const CrossCheckFamilyScope&) = delete;

 private:
  const CrossCheckFamilyBand* previous_;
};

// Whether the check of the current band's family (computed once per family) covers this
// run of `scenario` (a member: its plant `plant`) over `run_s`: false without a band, when
// a member cannot be built or its check gave no verdict; the run then checks itself.
bool FamilyCoversRun(const Scenario& scenario, const model::LinearPlant& plant,
                     const model::IntegratorConfig& config, double period_s,
                     double velocity_per_accel_s, double run_s);

}  // namespace shapebench::bench

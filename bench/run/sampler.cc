#include "bench/run/sampler.h"

#include "bench/run/closed_form_sampler.h"
#include "bench/run/plant_sampler.h"

namespace shapebench::bench {

std::unique_ptr<Sampler> MakeSampler(const RunPlan& plan, SamplerKind fastest, RunResult* result) {
  if (fastest == SamplerKind::kClosedForm && plan.single_mode.mode != nullptr) {
    return MakeClosedFormSampler(plan, result);
  }
  return std::make_unique<PlantSampler>(plan, fastest, result);
}

}  // namespace shapebench::bench

#include "bench/run/cross_check_family.h"

#include <cstdio>
#include <optional>
#include <vector>

#include "bench/run/run_window.h"
#include "bench/scenario/structure_numbers.h"
#include "model/cvode_cross_check.h"
#include "model/multi_axis_machine.h"

namespace shapebench::bench {
namespace {

thread_local const CrossCheckFamilyBand* current_band = nullptr;

}  // namespace

CrossCheckFamilyScope::CrossCheckFamilyScope(const CrossCheckFamilyBand* band) : previous_(current_band) {
  current_band = band;
}

CrossCheckFamilyScope::~CrossCheckFamilyScope() { current_band = previous_; }

bool FamilyCoversRun(const Scenario& scenario, const model::LinearPlant& plant,
                     const model::IntegratorConfig& config, double period_s,
                     double velocity_per_accel_s, double run_s) {
  const CrossCheckFamilyBand* band = current_band;
  if (band == nullptr) return false;
  // A member: the point's scenario with the family's number set, built as the run builds
  // its plant and substeps (PlantSampler, RunPlan).
  auto member = [&](double value) -> std::optional<model::FamilyMember> {
    Scenario copy = scenario;  // (a throw here: no verdict, CrossCheckCvodeFamily)
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", value);  // round-trips
    if (!SetStructureNumbers(&copy, {Override{band->key_path, text}})) return std::nullopt;
    model::FamilyMember m;
    m.plant = model::BuildMachinePlant(copy.machine, copy.drive).plant;
    m.substeps = copy.integrator.output_substeps > 0 ? copy.integrator.output_substeps
                                                     : AutoSubsteps(model::AnalyzeMachine(copy.machine), period_s);
    return m;
  };
  const model::CrossCheckFamily family = model::CachedCrossCheckCvodeFamily(
      band->identity, band->lo, band->hi, member, config, period_s, velocity_per_accel_s);
  return model::FamilyCovers(family, plant, period_s, run_s);
}

}  // namespace shapebench::bench

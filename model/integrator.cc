#include "model/integrator.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/format.h"
#include "common/validation_error.h"

namespace shapebench::model {

void PlantIntegrator::AdvancePeriod(const double* drive_accel, long /*same_input_periods*/,
                                    double* outputs) {
  SetInput(Eigen::Map<const Eigen::VectorXd>(drive_accel, num_inputs()));
  const int width = output_width();
  for (int j = 0; j < substeps(); ++j) {
    Step();
    const Eigen::VectorXd all = Output();
    WriteSelected(all.data(), outputs + static_cast<std::ptrdiff_t>(j) * width);
  }
}

// The fast paths an integrator does not offer (Capabilities() says which it does).
namespace {
[[noreturn]] void NotOffered(const char* call) {
  throw std::logic_error(std::string("PlantIntegrator::") + call +
                         ": not offered by this integrator (see Capabilities())");
}
}  // namespace

bool PlantIntegrator::WatchExtremum(int /*row*/) { NotOffered("WatchExtremum"); }
void PlantIntegrator::AdvanceAtRest(long /*periods*/) { NotOffered("AdvanceAtRest"); }
void PlantIntegrator::AdvancePeriodToEnd(const double* /*drive_accel*/, double* /*outputs*/) {
  NotOffered("AdvancePeriodToEnd");
}
void PlantIntegrator::WriteDeferredSubsteps(double* /*outputs*/) const { NotOffered("WriteDeferredSubsteps"); }

void PlantIntegrator::WriteSelected(const double* all, double* outputs) const {
  if (selected_rows_.empty()) {
    std::copy(all, all + num_outputs(), outputs);
    return;
  }
  for (std::size_t i = 0; i < selected_rows_.size(); ++i) outputs[i] = all[selected_rows_[i]];
}

IntegratorMethod ResolveMethod(IntegratorMethod method, const LinearPlant& /*plant*/) {
  // Every plant a LinearPlant describes is linear (machine forms, kinematic and servo
  // drives): its exact discretisation is exact and the fastest. A nonlinear element would
  // make this CVODE.
  return method == IntegratorMethod::kAuto ? IntegratorMethod::kExact : method;
}

void IntegratorConfig::validate() const {
  // Looser than 1e-6, no shipped scenario keeps its ratio metrics within 1e-4 of the exact
  // path; tighter than 1e-12 is below what CVODE can resolve in double precision over a
  // run's steps (docs/accuracy.md).
  if (!(rtol >= kTightestRtol && rtol <= 1.0e-6)) {
    throw ValidationError("rtol", "must be in [1e-12, 1e-6] (docs/accuracy.md)" + FormatGot(rtol));
  }
  if (!(atol_scale > 0.0) || !std::isfinite(atol_scale)) {
    throw ValidationError("atol_scale", "must be finite and > 0" + FormatGot(atol_scale));
  }
  if (max_num_steps < 1) {
    throw ValidationError("max_num_steps",
                          "must be >= 1" + FormatGot(static_cast<double>(max_num_steps)));
  }
  // CVODE reads a bound of 1 or less as "its default" (1.5): refused rather than surprising.
  if (!(tuning.eta_max_fixed_step > 1.0) || !std::isfinite(tuning.eta_max_fixed_step)) {
    throw ValidationError("tuning.eta_max_fixed_step",
                          "must be finite and > 1" + FormatGot(tuning.eta_max_fixed_step));
  }
  if (output_substeps < 0 || output_substeps > 1000) {
    throw ValidationError("output_substeps",
                          "must be in [0, 1000] (0 = automatic)" + FormatGot(output_substeps));
  }
}

}  // namespace shapebench::model

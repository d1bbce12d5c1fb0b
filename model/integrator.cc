#include "model/integrator.h"

#include <cmath>
#include <sstream>

#include "common/format.h"
#include "common/validation_error.h"
#include "model/cvode_integrator.h"
#include "model/exact_integrator.h"

namespace shapebench::model {
namespace {

std::string Got(double value) { return " (got " + FormatNumber(value) + ")"; }

void CheckPlantShapes(const LinearPlant& plant) {
  const int n = plant.num_states();
  const bool ok = plant.A.cols() == n && plant.B_accel.rows() == n && plant.B_vel.rows() == n &&
                  plant.B_vel.cols() == plant.B_accel.cols() && plant.C.cols() == n &&
                  static_cast<int>(plant.state_kinds.size()) == n && n > 0 &&
                  plant.num_inputs() > 0;
  if (!ok) throw std::invalid_argument("MakeIntegrator: inconsistent LinearPlant dimensions");
}

}  // namespace

void IntegratorConfig::validate() const {
  if (!(rtol > 0.0 && rtol <= 1.0e-2)) {
    throw ValidationError("rtol", "must be in (0, 1e-2]" + Got(rtol));
  }
  if (!(atol_scale > 0.0) || !std::isfinite(atol_scale)) {
    throw ValidationError("atol_scale", "must be finite and > 0" + Got(atol_scale));
  }
  if (max_num_steps < 1) {
    throw ValidationError("max_num_steps",
                          "must be >= 1" + Got(static_cast<double>(max_num_steps)));
  }
  if (output_substeps < 0 || output_substeps > 1000) {
    throw ValidationError("output_substeps",
                          "must be in [0, 1000] (0 = automatic)" + Got(output_substeps));
  }
}

std::unique_ptr<PlantIntegrator> MakeIntegrator(const LinearPlant& plant,
                                                const IntegratorConfig& config, double period_s,
                                                int substeps, double scale_accel_m_s2) {
  config.validate();
  CheckPlantShapes(plant);
  if (!(period_s > 0.0) || !std::isfinite(period_s)) {
    throw std::invalid_argument("MakeIntegrator: period_s must be finite and > 0" + Got(period_s));
  }
  if (substeps < 1) {
    throw std::invalid_argument(
        "MakeIntegrator: substeps must be >= 1 (resolve "
        "output_substeps = 0 before)" +
        Got(substeps));
  }
  if (!(scale_accel_m_s2 >= 0.0) || !std::isfinite(scale_accel_m_s2)) {
    throw std::invalid_argument("MakeIntegrator: scale_accel_m_s2 must be finite and >= 0" +
                                Got(scale_accel_m_s2));
  }
  switch (config.method) {
    case IntegratorMethod::kExact:
      return std::make_unique<ExactIntegrator>(plant, period_s, substeps);
    case IntegratorMethod::kCvode:
      return std::make_unique<CvodeIntegrator>(plant, config, period_s, substeps, scale_accel_m_s2);
  }
  throw std::invalid_argument("MakeIntegrator: unknown integrator method");
}

}  // namespace shapebench::model

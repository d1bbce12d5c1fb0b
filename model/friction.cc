// FrictionConfig::validate: each number named by its key, with what the model allows.
#include "model/friction.h"

#include <string>

#include "common/format.h"
#include "common/validation_error.h"

namespace shapebench::model {
namespace {

std::string ModelName(FrictionModel model) {
  for (const auto& [name, value] : FrictionConfig::ModelChoices()) {
    if (value == model) return name;
  }
  return "none";
}

void NonNegative(const char* field, double value, const char* meaning) {
  if (!(value >= 0.0) || !std::isfinite(value)) {
    throw ValidationError(field, std::string("must be finite and >= 0 (") + meaning + ")" + FormatGot(value));
  }
}

void Positive(const char* field, double value, const char* meaning, FrictionModel model) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw ValidationError(field, std::string("must be finite and > 0 for model ") + ModelName(model) +
                                     " (" + meaning + ")" + FormatGot(value));
  }
}

// A key the model does not read must stay at its default (0): set, it would be ignored.
void Unused(const char* field, double value, FrictionModel model, const char* used_by) {
  if (value != 0.0) {
    throw ValidationError(field, std::string("is not used by model ") + ModelName(model) + " (only by " +
                                     used_by + "); remove it or choose that model" + FormatGot(value));
  }
}

}  // namespace

void FrictionConfig::validate() const {
  if (model == FrictionModel::kNone) {
    const bool any = coulomb_n != 0.0 || !std::isnan(static_n) || stribeck_velocity_m_s != 0.0 ||
                     viscous_n_s_m != 0.0 || sigma0_n_m != 0.0 || sigma1_n_s_m != 0.0;
    if (any) {
      throw ValidationError("model", "friction numbers are given but no model; allowed: coulomb, "
                                     "stribeck or lugre");
    }
    return;
  }
  NonNegative("coulomb_n", coulomb_n, "N, the sliding friction force F_c");
  if (!std::isnan(static_n)) {
    NonNegative("static_n", static_n, "N, the breakaway force F_s");
    if (static_n < coulomb_n) {
      throw ValidationError("static_n", "must be >= coulomb_n (" + FormatNumber(coulomb_n) +
                                            "): the breakaway force is at least the sliding force" +
                                            FormatGot(static_n));
    }
  }
  NonNegative("viscous_n_s_m", viscous_n_s_m, "N s/m, the viscous part sigma2");
  if (model == FrictionModel::kCoulomb) {
    Unused("stribeck_velocity_m_s", stribeck_velocity_m_s, model, "stribeck and lugre");
  } else {
    Positive("stribeck_velocity_m_s", stribeck_velocity_m_s, "m/s, the Stribeck velocity v_s", model);
  }
  if (model == FrictionModel::kLuGre) {
    // z' = w - sigma0 |w| z / g(w) divides by g, which falls to F_c at speed.
    Positive("coulomb_n", coulomb_n, "N, the sliding force F_c: the bristle law divides by it", model);
    Positive("sigma0_n_m", sigma0_n_m, "N/m, the bristle stiffness", model);
    NonNegative("sigma1_n_s_m", sigma1_n_s_m, "N s/m, the bristle damping");
  } else {
    Unused("sigma0_n_m", sigma0_n_m, model, "lugre");
    Unused("sigma1_n_s_m", sigma1_n_s_m, model, "lugre");
  }
}

}  // namespace shapebench::model

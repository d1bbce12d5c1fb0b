// Friction between two moving ends (a carriage on its guideways, a table, a motor), the
// force laws of docs/nonlinear.md. w is the relative velocity of the two ends; every law
// returns the force that opposes it (positive for w > 0).
//
//   coulomb   F = F_c sign(w) + sigma2 w while sliding; sticking (w held at 0) while the
//             force needed to hold it stays within F_s (stiction): events, no smoothing.
//   stribeck  the same with the sliding force g(w) sign(w) + sigma2 w,
//             g(w) = F_c + (F_s - F_c) exp(-(w / v_s)^2): falling from F_s at rest.
//   lugre     the LuGre bristle model (Canudas de Wit et al. 1995): bristle deflection z,
//             z' = w - sigma0 |w| z / g(w),  F = sigma0 z + sigma1 z' + sigma2 w.
//             Smooth (no events) but stiff: sigma0 / g(w) |w| is fast.
#pragma once

#include <cmath>

#include "common/field_list.h"

namespace shapebench::model {

enum class FrictionModel { kNone, kCoulomb, kStribeck, kLuGre };

struct FrictionConfig {
  FrictionModel model = FrictionModel::kNone;  // none: no friction
  double coulomb_n = 0.0;              // F_c, the sliding force (>= 0)
  double static_n = NAN;               // F_s, the breakaway force (>= F_c); not given: F_c
  double stribeck_velocity_m_s = 0.0;  // v_s (stribeck, lugre: > 0)
  double viscous_n_s_m = 0.0;          // sigma2 (>= 0)
  double sigma0_n_m = 0.0;             // lugre: bristle stiffness (> 0)
  double sigma1_n_s_m = 0.0;           // lugre: bristle damping (>= 0)

  template <typename Archive>
  void Serialize(Archive* a) {  // the field list (common/field_list.h)
    a->Visit("model", &model, ModelChoices());
    a->Visit("coulomb_n", &coulomb_n);
    a->Visit("static_n", &static_n);
    a->Visit("stribeck_velocity_m_s", &stribeck_velocity_m_s);
    a->Visit("viscous_n_s_m", &viscous_n_s_m);
    a->Visit("sigma0_n_m", &sigma0_n_m);
    a->Visit("sigma1_n_s_m", &sigma1_n_s_m);
  }
  static Choices<FrictionModel> ModelChoices() {
    return {{"none", FrictionModel::kNone},
            {"coulomb", FrictionModel::kCoulomb},
            {"stribeck", FrictionModel::kStribeck},
            {"lugre", FrictionModel::kLuGre}};
  }

  bool present() const { return model != FrictionModel::kNone; }
  // Coulomb and Stribeck stick and slip (events); LuGre is smooth.
  bool sticks() const { return model == FrictionModel::kCoulomb || model == FrictionModel::kStribeck; }
  double StaticN() const { return std::isnan(static_n) ? coulomb_n : static_n; }
  // Throws ValidationError naming the field ("coulomb_n", "sigma0_n_m", ...) and what is allowed.
  void validate() const;

  // g(w): the sliding force without the viscous part, at speed |w| (coulomb: F_c).
  double SlidingLevel(double w) const {
    if (model == FrictionModel::kCoulomb) return coulomb_n;
    const double r = w / stribeck_velocity_m_s;
    return coulomb_n + (StaticN() - coulomb_n) * std::exp(-r * r);
  }
  // dg/dw.
  double SlidingLevelSlope(double w) const {
    if (model == FrictionModel::kCoulomb) return 0.0;
    const double r = w / stribeck_velocity_m_s;
    return -2.0 * r / stribeck_velocity_m_s * (StaticN() - coulomb_n) * std::exp(-r * r);
  }
  // The steady sliding force at constant w (every model): g(w) sign(w) + sigma2 w.
  double SteadyForce(double w) const {
    const double sign = w > 0.0 ? 1.0 : w < 0.0 ? -1.0 : 0.0;
    return SlidingLevel(w) * sign + viscous_n_s_m * w;
  }
};

}  // namespace shapebench::model

#include "model/nonlinear_element.h"

#include <cmath>

namespace shapebench::model {
namespace {

double Sign(double x) { return x > 0.0 ? 1.0 : x < 0.0 ? -1.0 : 0.0; }

// Backlash and the force limit: the upper edge (+b/2, +L) rising enters +1, falling leaves
// it; the lower alike.
int EdgeMode(const int* found, int mode) {
  if (found[0] != 0) mode = found[0] > 0 ? 1 : 0;
  if (found[1] != 0) mode = found[1] < 0 ? -1 : 0;
  return mode;
}

}  // namespace

int FrictionElement::RestMode(double w) const {
  return w != 0.0 || !(friction.StaticN() > 0.0) ? (w < 0.0 ? -1 : 1) : 0;
}

double FrictionElement::BristleRate(double w, double zeta, double* dw, double* dzeta) const {
  const FrictionConfig& f = friction;
  const double g = f.SlidingLevel(w);
  const double aw = std::abs(w);
  if (dw != nullptr) {
    *dw = 1.0 - f.sigma0_n_m * zeta * (Sign(w) * g - aw * f.SlidingLevelSlope(w)) / (g * g);
    *dzeta = -f.sigma0_n_m * aw / g;
  }
  return w - f.sigma0_n_m * aw * zeta / g;
}

double FrictionElement::Force(double w, int mode, double zeta, double* dw, double* dzeta) const {
  const FrictionConfig& f = friction;
  double force = 0.0;
  double slope = 0.0;
  double slope_zeta = 0.0;
  if (HasBristle()) {
    double rate_w = 0.0;
    double rate_zeta = 0.0;
    const double rate = BristleRate(w, zeta, &rate_w, &rate_zeta);
    force = BristleForce(w, zeta, rate);
    slope = f.sigma1_n_s_m * rate_w + f.viscous_n_s_m;
    slope_zeta = f.sigma0_n_m + f.sigma1_n_s_m * rate_zeta;
  } else {
    const double s = static_cast<double>(mode);
    force = s * f.SlidingLevel(w) + f.viscous_n_s_m * w;
    slope = s * f.SlidingLevelSlope(w) + f.viscous_n_s_m;
  }
  if (dw != nullptr) {
    *dw = slope;
    *dzeta = slope_zeta;
  }
  return force;
}

void FrictionElement::Roots(double w, int mode, double holding_force, double* g) const {
  // F_s = 0 (then F_c = 0): the force does not depend on the direction; nothing to find.
  if (Sticks() && friction.StaticN() == 0.0) {
    g[0] = 1.0;
    return;
  }
  const bool stuck = Sticks() && mode == 0;
  g[0] = stuck ? friction.StaticN() - std::abs(holding_force) : Sticks() ? mode * w : w;
}

int FrictionElement::ModeAfterRoots(const int* /*found*/, int mode, double force) const {
  if (!Sticks()) return mode;  // LuGre: the kink of |w| changes no mode
  // w reached 0: stuck (unless NonlinearDynamics finds F* beyond F_s); or it breaks loose.
  return mode != 0 ? 0 : (force < 0.0 ? -1 : 1);
}

int BacklashElement::RestMode(double w) const {
  return std::abs(w) <= 0.5 * backlash_m ? 0 : static_cast<int>(Sign(w));
}

double BacklashElement::Force(double w, int mode, double /*zeta*/, double* dw, double* dzeta) const {
  // k (|d| - b/2) sign(d) - k d: -k d in the gap, -k b/2 sign(d) in contact.
  double force = 0.0;
  double slope = 0.0;
  if (mode == 0) {
    force = -stiffness_n_m * w;
    slope = -stiffness_n_m;
  } else {
    force = -0.5 * stiffness_n_m * backlash_m * mode;
  }
  if (dw != nullptr) {
    *dw = slope;
    *dzeta = 0.0;
  }
  return force;
}

void BacklashElement::Roots(double w, int /*mode*/, double /*holding_force*/, double* g) const {
  g[0] = w - 0.5 * backlash_m;
  g[1] = w + 0.5 * backlash_m;
}

int BacklashElement::ModeAfterRoots(const int* found, int mode, double /*force*/) const {
  return EdgeMode(found, mode);
}

int SaturationElement::RestMode(double w) const {
  return std::abs(w) <= limit_n ? 0 : static_cast<int>(Sign(w));
}

double SaturationElement::Force(double w, int mode, double /*zeta*/, double* dw, double* dzeta) const {
  double force = 0.0;
  double slope = 0.0;
  if (mode != 0) {
    force = mode * limit_n - w;
    slope = -1.0;
  }
  if (dw != nullptr) {
    *dw = slope;
    *dzeta = 0.0;
  }
  return force;
}

void SaturationElement::Roots(double w, int /*mode*/, double /*holding_force*/, double* g) const {
  g[0] = w - limit_n;
  g[1] = w + limit_n;
}

int SaturationElement::ModeAfterRoots(const int* found, int mode, double /*force*/) const {
  return EdgeMode(found, mode);
}

}  // namespace shapebench::model

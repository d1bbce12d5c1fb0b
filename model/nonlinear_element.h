// The kinds of nonlinear element (model/nonlinear_plant.h), each answering for its own
// force, event roots and modes; NonlinearDynamics keeps the state, the stuck set and what
// couples the elements. w is the element's row value (docs/nonlinear.md has the laws).
// Every kind has the same members, so a std::visit over NonlinearLaw reaches any of them.
#pragma once

#include <variant>

#include "model/friction.h"

namespace shapebench::model {

// Friction: w the relative velocity; modes +-1 sliding, 0 stuck (Coulomb and Stribeck
// only). One root: a sliding element's s w (it stops), a stuck one's F_s - |F*| (it breaks
// loose), LuGre's w (the kink of |w|: a restart only).
struct FrictionElement {
  FrictionConfig friction;

  static constexpr int kRoots = 1;
  bool Sticks() const { return friction.sticks(); }
  bool HasBristle() const { return friction.model == FrictionModel::kLuGre; }
  int RestMode(double w) const;
  // The force of a sliding element (LuGre: from its bristle state zeta), and its slopes by
  // w and by zeta when dw is not null. A stuck element's is NonlinearDynamics' to solve.
  double Force(double w, int mode, double zeta, double* dw, double* dzeta) const;
  // `holding_force`: F* of a stuck element (read only then).
  void Roots(double w, int mode, double holding_force, double* g) const;
  // -1 where only a falling crossing is an event (CVodeSetRootDirection), else 0.
  void RootDirections(int* directions) const { directions[0] = Sticks() ? -1 : 0; }
  // The mode after a root (`found` per root: +1 rising, -1 falling, 0 none); `force` its
  // force there: a stuck element slides the way it pushes.
  int ModeAfterRoots(const int* found, int mode, double force) const;

  // LuGre: the bristle rate zeta' and, with dw, its slopes by w and by zeta.
  double BristleRate(double w, double zeta, double* dw, double* dzeta) const;
  double BristleForce(double w, double zeta, double rate) const {
    return friction.sigma0_n_m * zeta + friction.sigma1_n_s_m * rate + friction.viscous_n_s_m * w;
  }
};

// Backlash: w the stretch d; the force k (|d| - b/2) sign(d) less the linear spring's k d.
// Modes -1, 0 (in the gap), +1; roots d = +b/2, d = -b/2.
struct BacklashElement {
  double stiffness_n_m = 0.0;  // the contact stiffness k
  double backlash_m = 0.0;     // the whole play b

  static constexpr int kRoots = 2;
  bool Sticks() const { return false; }
  int RestMode(double w) const;
  double Force(double w, int mode, double zeta, double* dw, double* dzeta) const;
  void Roots(double w, int mode, double holding_force, double* g) const;
  void RootDirections(int* directions) const { directions[0] = directions[1] = 0; }
  int ModeAfterRoots(const int* found, int mode, double force) const;
};

// The drive's force limit: w the motor force F_m; the clamped force less F_m. Modes -1, 0
// (within), +1; roots F_m = +L, F_m = -L.
struct SaturationElement {
  double limit_n = 0.0;

  static constexpr int kRoots = 2;
  bool Sticks() const { return false; }
  int RestMode(double w) const;
  double Force(double w, int mode, double zeta, double* dw, double* dzeta) const;
  void Roots(double w, int mode, double holding_force, double* g) const;
  void RootDirections(int* directions) const { directions[0] = directions[1] = 0; }
  int ModeAfterRoots(const int* found, int mode, double force) const;
};

using NonlinearLaw = std::variant<FrictionElement, BacklashElement, SaturationElement>;

inline int NumRoots(const NonlinearLaw& law) {
  return std::visit([](const auto& l) { return l.kRoots; }, law);
}

}  // namespace shapebench::model

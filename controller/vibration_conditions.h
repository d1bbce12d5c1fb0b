// Shapers defined by conditions on their residual vibration (the extra-insensitive family,
// controller/shapers/ei.cc), solved exactly for a damped mode.
//
// Frequencies are ratios r of the design frequency w0 (the mode's undamped natural
// frequency) and times are phases w0 t, so that a design does not depend on w0. The residual
// of impulses A_j at phases p_j (p_1 = 0), for a mode at r w0 of damping ratio zeta, is the
// standard shaper formula (impulse.h's ResidualVibration)
//   V(r) = e^{-zeta r p_n} |R(r)|,  R(r) = sum A_j e^{r c p_j},  c = zeta + i sqrt(1 - zeta^2).
#pragma once

#include <optional>
#include <vector>

namespace shapebench::controller {

enum class ConditionKind {
  kZero,  // V(r) = 0: R(r) = 0, two real equations
  kHump,  // V(r) = the tolerance and dV/dr = 0 there: a local maximum touching it
};

struct VibrationCondition {
  ConditionKind kind = ConditionKind::kZero;
  double ratio = 1.0;  // r; an unknown unless `fixed`
  bool fixed = false;
};

// A design: its impulses in phases and its conditions. Solvable when the unknowns (n
// amplitudes, n - 1 phases, the free ratios) are as many as the equations (the amplitudes
// summing to 1, two per condition): 2 n - 1 + free = 1 + 2 conditions.
struct ConditionedShaper {
  std::vector<double> amplitudes;
  std::vector<double> phases;  // w0 t_j, ascending from 0
  std::vector<VibrationCondition> conditions;
};

// V(r) of `shaper` for a mode of damping ratio zeta (the formula above).
double ConditionedResidual(const ConditionedShaper& shaper, double ratio, double zeta);

// The design meeting `undamped`'s conditions for a mode of damping ratio `zeta` with the
// hump height `tolerance`: Newton's method on all unknowns at once, continued in zeta from
// `undamped` (a solution at zeta 0) in steps of at most 0.02, each converged to rounding.
// nullopt when Newton does not converge or the solution leaves the undamped one's branch
// (an amplitude <= 0, phases not ascending, the conditions' ratios out of their order).
std::optional<ConditionedShaper> SolveForDamping(const ConditionedShaper& undamped, double zeta,
                                                 double tolerance);

}  // namespace shapebench::controller

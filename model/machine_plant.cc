// BuildPlant and AnalyzeModes for both machine forms (machine.h), on the helpers that build
// on its config types (coupled_modes.h, lumped_matrices.h).
#include "model/machine.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <variant>

#include "common/math_constants.h"
#include "model/coupled_modes.h"
#include "model/lumped_matrices.h"

namespace shapebench::model {
namespace {

// A coupled form spans three axes: BuildMachinePlant and AnalyzeMachineModes build it
// (model/coupled_modes.h); the one-axis view would drop its cross terms.
void RefuseCoupled(const ModalMachineConfig& config, const char* what) {
  if (config.coupled()) {
    throw std::logic_error(std::string(what) + ": a coupled modal form (participation, shape) spans three axes; "
                           "use the multi-axis machine (multi_axis_machine.h)");
  }
}

LinearPlant BuildFormPlant(const ModalMachineConfig& config) {
  RefuseCoupled(config, "BuildPlant");
  LinearPlant plant = ModalOscillatorPlant(config, 1, 1);
  for (std::size_t i = 0; i < config.modes.size(); ++i) {
    const int q = 2 * static_cast<int>(i);  // states [q_i, q_i']
    plant.B_accel(q + 1, 0) = -1.0;
    plant.C(0, q) = config.modes[i].gain;
  }
  return plant;
}

// Squared undamped natural frequencies, ascending: K phi = w^2 M phi.
Eigen::VectorXd UndampedEigenvalues(const LumpedMatrices& m) {
  const Eigen::MatrixXd M = m.mass_kg.asDiagonal();
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(m.K, M, Eigen::EigenvaluesOnly);
  return solver.eigenvalues();
}

LinearPlant BuildFormPlant(const LumpedMachineConfig& config) {
  const LumpedMatrices m = AssembleLumped(config);
  const int nb = static_cast<int>(m.mass_kg.size());
  const int n = 2 * nb;
  const Eigen::VectorXd inv_mass = m.mass_kg.cwiseInverse();
  LinearPlant plant;
  plant.A = Eigen::MatrixXd::Zero(n, n);
  plant.A.topRightCorner(nb, nb).setIdentity();
  plant.A.bottomLeftCorner(nb, nb) = -(inv_mass.asDiagonal() * m.K);
  plant.A.bottomRightCorner(nb, nb) = -(inv_mass.asDiagonal() * m.C);
  plant.B_accel = Eigen::MatrixXd::Zero(n, 1);
  plant.B_accel.bottomRows(nb) = inv_mass.cwiseProduct(m.force_per_accel);  // -g
  plant.B_vel = Eigen::MatrixXd::Zero(n, 1);
  plant.B_vel.bottomRows(nb) = -inv_mass.cwiseProduct(m.velocity_load);
  plant.C = Eigen::MatrixXd::Zero(1, n);
  plant.C.leftCols(nb) = m.output.transpose();
  plant.state_kinds.assign(nb, StateKind::kPosition);
  plant.state_kinds.resize(n, StateKind::kVelocity);
  plant.max_frequency_rad_s = std::sqrt(std::max(0.0, UndampedEigenvalues(m).maxCoeff()));
  return plant;
}

ModalAnalysis AnalyzeForm(const ModalMachineConfig& config) {
  RefuseCoupled(config, "AnalyzeModes");
  ModalAnalysis analysis;
  analysis.modes.reserve(config.modes.size());
  double signed_static = 0.0;
  for (const ModalMode& mode : config.modes) {
    const double w = kTwoPi * mode.frequency_hz;
    signed_static += mode.gain / (w * w);
  }
  for (const ModalMode& mode : config.modes) {
    const double w = kTwoPi * mode.frequency_hz;
    const double share = signed_static != 0.0 ? mode.gain / (w * w) / signed_static : 0.0;
    analysis.modes.push_back({mode.frequency_hz, mode.damping_ratio, share});
  }
  // Modes written in ascending order (one mode, a sweep point) keep it: a stable sort
  // would not move them, and its buffer costs a sweep point a third of the analysis.
  const auto lower = [](const ModeInfo& a, const ModeInfo& b) { return a.frequency_hz < b.frequency_hz; };
  if (!std::is_sorted(analysis.modes.begin(), analysis.modes.end(), lower)) {
    std::stable_sort(analysis.modes.begin(), analysis.modes.end(), lower);
  }
  analysis.static_deflection_per_accel_s2 = std::abs(signed_static);
  return analysis;
}

ModalAnalysis AnalyzeForm(const LumpedMachineConfig& config) {
  const LumpedMatrices m = AssembleLumped(config);
  const Eigen::MatrixXd M = m.mass_kg.asDiagonal();
  // Ascending eigenvalues; eigenvectors mass-normalised (phi^T M phi = I).
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(m.K, M);
  const double signed_static = m.output.dot(m.K.llt().solve(m.force_per_accel));
  ModalAnalysis analysis;
  for (int i = 0; i < solver.eigenvalues().size(); ++i) {
    const double w2 = solver.eigenvalues()(i);
    const double w = std::sqrt(std::max(0.0, w2));
    const Eigen::VectorXd phi = solver.eigenvectors().col(i);
    // Projection of C on the undamped mode: exact for proportional (classical) damping,
    // the usual estimate otherwise (the off-diagonal coupling terms are ignored).
    const double zeta = phi.dot(m.C * phi) / (2.0 * w);
    const double modal_static = m.output.dot(phi) * phi.dot(m.force_per_accel) / w2;
    const double share = signed_static != 0.0 ? modal_static / signed_static : 0.0;
    analysis.modes.push_back({w / kTwoPi, zeta, share});
  }
  analysis.static_deflection_per_accel_s2 = std::abs(signed_static);
  return analysis;
}

// No damping anywhere: every mode's energy is conserved once the base stops.
bool FormConservesEnergy(const ModalMachineConfig& config) {
  for (const ModalMode& mode : config.modes) {
    if (mode.damping_ratio != 0.0) return false;
  }
  return true;
}

bool FormConservesEnergy(const LumpedMachineConfig& config) {
  for (const LumpedElement& element : config.elements) {
    if (element.damping_n_s_m != 0.0) return false;
    if (element.friction.present()) return false;  // dissipates while it slides
  }
  const LumpedDamping& damping = config.damping;
  switch (damping.kind) {
    case LumpedDampingKind::kElements: return true;
    case LumpedDampingKind::kRayleigh:
      return damping.rayleigh.alpha == 0.0 && damping.rayleigh.beta == 0.0;
    case LumpedDampingKind::kModal:
      return std::all_of(damping.modal.begin(), damping.modal.end(),
                         [](double zeta) { return zeta == 0.0; });
  }
  return true;
}

}  // namespace

// Each form answers through its own overloads: std::visit over a generic lambda that
// calls them does not compile for a form that lacks one (no silent fallback).
LinearPlant BuildPlant(const MachineConfig& machine) {
  machine.validate();
  return std::visit([](const auto& form) { return BuildFormPlant(form); }, machine.form);
}

ModalAnalysis AnalyzeModes(const MachineConfig& machine) {
  machine.validate();
  return std::visit([](const auto& form) { return AnalyzeForm(form); }, machine.form);
}

bool ConservesEnergy(const MachineConfig& machine) {
  return std::visit([](const auto& form) { return FormConservesEnergy(form); }, machine.form);
}

}  // namespace shapebench::model

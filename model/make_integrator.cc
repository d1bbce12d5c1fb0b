// MakeIntegrator (model/integrator.h): the integrator a method stands for, with the inputs
// that reach no state left out. Apart from integrator.cc, which the integrators build on.
#include "model/integrator.h"

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/format.h"
#include "model/cvode_integrator.h"
#include "model/exact_integrator.h"

namespace shapebench::model {
namespace {

void CheckPlantShapes(const LinearPlant& plant) {
  const int n = plant.num_states();
  const bool ok = plant.A.cols() == n && plant.B_accel.rows() == n && plant.B_vel.rows() == n &&
                  plant.B_vel.cols() == plant.B_accel.cols() && plant.C.cols() == n &&
                  static_cast<int>(plant.state_kinds.size()) == n && n > 0 &&
                  plant.num_inputs() > 0 &&
                  (plant.tolerance_group.empty() ||
                   static_cast<int>(plant.tolerance_group.size()) == n);
  bool groups_ok = plant.group_frequency_rad_s.empty() ||
                   static_cast<int>(plant.group_frequency_rad_s.size()) >=
                       plant.NumToleranceGroups();
  for (int group : plant.tolerance_group) groups_ok = groups_ok && group >= 0;
  if (!ok || !groups_ok) {
    throw std::invalid_argument("MakeIntegrator: inconsistent LinearPlant dimensions");
  }
}

// The inputs (columns of B_accel, B_vel) that reach some state.
std::vector<int> UsedInputs(const LinearPlant& plant) {
  std::vector<int> used;
  for (int j = 0; j < plant.num_inputs(); ++j) {
    if (plant.B_accel.col(j).cwiseAbs().maxCoeff() > 0.0 ||
        plant.B_vel.col(j).cwiseAbs().maxCoeff() > 0.0) {
      used.push_back(j);
    }
  }
  return used;
}

// The plant with only the inputs `used` (in order).
LinearPlant SelectInputs(const LinearPlant& plant, const std::vector<int>& used) {
  LinearPlant reduced = plant;
  const int m = static_cast<int>(used.size());
  reduced.B_accel.resize(plant.num_states(), m);
  reduced.B_vel.resize(plant.num_states(), m);
  for (int j = 0; j < m; ++j) {
    reduced.B_accel.col(j) = plant.B_accel.col(used[j]);
    reduced.B_vel.col(j) = plant.B_vel.col(used[j]);
  }
  return reduced;
}

// Feeds an integrator of the reduced plant from the full input vectors.
class InputSelectingIntegrator final : public PlantIntegrator {
 public:
  InputSelectingIntegrator(std::unique_ptr<PlantIntegrator> inner, std::vector<int> used,
                           int num_inputs)
      : inner_(std::move(inner)),
        used_(std::move(used)),
        num_inputs_(num_inputs),
        selected_(used_.size()) {}

  void Reset(const Eigen::VectorXd& drive_velocity) override {
    inner_->Reset(Select(drive_velocity, "Reset"));
  }
  void SetInput(const Eigen::VectorXd& drive_accel) override {
    inner_->SetInput(Select(drive_accel, "SetInput"));
  }
  void Step() override { inner_->Step(); }
  Eigen::VectorXd Output() const override { return inner_->Output(); }
  Eigen::VectorXd PlantState() const override { return inner_->PlantState(); }
  double Time() const override { return inner_->Time(); }
  IntegratorStats Stats() const override { return inner_->Stats(); }
  long Work() const override { return inner_->Work(); }
  long PeriodWorkAtLeast() const override { return inner_->PeriodWorkAtLeast(); }
  int num_inputs() const override { return num_inputs_; }
  int num_outputs() const override { return inner_->num_outputs(); }
  int substeps() const override { return inner_->substeps(); }
  bool OutputRowIsZero(int row) const override { return inner_->OutputRowIsZero(row); }
  // Only the holds: the other fast paths are the exact integrator's, which selects its
  // inputs itself (ExactIntegrator::TakeFullInputs) and is never wrapped.
  IntegratorCapabilities Capabilities() const override {
    IntegratorCapabilities caps;
    caps.input_holds = inner_->Capabilities().input_holds;
    return caps;
  }
  void SelectOutputs(const std::vector<int>& rows) override {
    PlantIntegrator::SelectOutputs(rows);
    inner_->SelectOutputs(rows);
  }
  void AdvancePeriod(const double* drive_accel, long same_input_periods,
                     double* outputs) override {
    for (std::size_t j = 0; j < used_.size(); ++j) selected_[j] = drive_accel[used_[j]];
    inner_->AdvancePeriod(selected_.data(), same_input_periods, outputs);
  }

 private:
  Eigen::VectorXd Select(const Eigen::VectorXd& full, const char* call) const {
    if (full.size() != num_inputs_) {
      throw std::invalid_argument(std::string("PlantIntegrator::") + call +
                                  ": wrong input vector size");
    }
    Eigen::VectorXd selected(static_cast<Eigen::Index>(used_.size()));
    for (std::size_t j = 0; j < used_.size(); ++j) selected(j) = full(used_[j]);
    return selected;
  }

  std::unique_ptr<PlantIntegrator> inner_;
  std::vector<int> used_;
  int num_inputs_;
  std::vector<double> selected_;  // AdvancePeriod's input, without allocating per tick
};

std::unique_ptr<PlantIntegrator> MakeFullIntegrator(const LinearPlant& plant,
                                                    const IntegratorConfig& config,
                                                    double period_s, int substeps,
                                                    double scale_accel_m_s2,
                                                    double scale_velocity_m_s) {
  switch (ResolveMethod(config.method, plant)) {
    case IntegratorMethod::kAuto:  // resolved above
    case IntegratorMethod::kExact:
      return std::make_unique<ExactIntegrator>(plant, period_s, substeps);
    case IntegratorMethod::kCvode:
      return std::make_unique<CvodeIntegrator>(plant, config, period_s, substeps,
                                               scale_accel_m_s2, scale_velocity_m_s);
  }
  throw std::invalid_argument("MakeIntegrator: unknown integrator method");
}

}  // namespace

std::unique_ptr<PlantIntegrator> MakeIntegrator(const LinearPlant& plant,
                                                const IntegratorConfig& config, double period_s,
                                                int substeps, double scale_accel_m_s2,
                                                double scale_velocity_m_s) {
  config.validate();
  CheckPlantShapes(plant);
  if (!(period_s > 0.0) || !std::isfinite(period_s)) {
    throw std::invalid_argument("MakeIntegrator: period_s must be finite and > 0" + FormatGot(period_s));
  }
  if (substeps < 1) {
    throw std::invalid_argument(
        "MakeIntegrator: substeps must be >= 1 (resolve "
        "output_substeps = 0 before)" +
        FormatGot(substeps));
  }
  if (!(scale_accel_m_s2 >= 0.0) || !std::isfinite(scale_accel_m_s2)) {
    throw std::invalid_argument("MakeIntegrator: scale_accel_m_s2 must be finite and >= 0" +
                                FormatGot(scale_accel_m_s2));
  }
  if (!(scale_velocity_m_s >= 0.0) || !std::isfinite(scale_velocity_m_s)) {
    throw std::invalid_argument("MakeIntegrator: scale_velocity_m_s must be finite and >= 0" +
                                FormatGot(scale_velocity_m_s));
  }
  std::vector<int> used = UsedInputs(plant);
  if (used.empty()) used.push_back(0);  // nothing drives the plant: keep one input anyway
  if (static_cast<int>(used.size()) == plant.num_inputs()) {
    return MakeFullIntegrator(plant, config, period_s, substeps, scale_accel_m_s2,
                              scale_velocity_m_s);
  }
  if (ResolveMethod(config.method, plant) == IntegratorMethod::kExact) {
    // The exact integrator picks its inputs itself (one virtual call less per period).
    auto exact = std::make_unique<ExactIntegrator>(SelectInputs(plant, used), period_s, substeps);
    exact->TakeFullInputs(std::move(used), plant.num_inputs());
    return exact;
  }
  return std::make_unique<InputSelectingIntegrator>(
      MakeFullIntegrator(SelectInputs(plant, used), config, period_s, substeps,
                         scale_accel_m_s2, scale_velocity_m_s),
      std::move(used), plant.num_inputs());
}

}  // namespace shapebench::model

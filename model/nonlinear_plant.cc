// BuildStructureElements: the lumped form's nonlinear elements over BuildPlant's state.
#include "model/nonlinear_plant.h"

#include <cmath>
#include <string>
#include <variant>

#include "common/format.h"
#include "common/validation_error.h"
#include "model/lumped_matrices.h"
#include "model/machine.h"

namespace shapebench::model {
namespace {

std::vector<NonlinearElement> FormElements(const ModalMachineConfig&) { return {}; }

// BuildPlant's lumped state is x = [y; y'] with y = q - g u (lumped_matrices.h). An
// element's stretch is D q + d u = D y + (D g + d) u, its rate D y' + (D g + d) v; a force
// F along the stretch is the generalised force -D^T F on q, so y'' gains -M^-1 D^T F.
std::vector<NonlinearElement> FormElements(const LumpedMachineConfig& config) {
  std::vector<NonlinearElement> result;
  const LumpedMatrices m = AssembleLumped(config);
  const int nb = static_cast<int>(m.mass_kg.size());
  for (std::size_t i = 0; i < config.elements.size(); ++i) {
    const LumpedElement& e = config.elements[i];
    if (!e.nonlinear()) continue;
    const auto row = static_cast<Eigen::Index>(i);
    const Eigen::VectorXd D = m.element_D.row(row).transpose();
    const std::string field = "elements[" + std::to_string(i) + "]";
    NonlinearElement element;
    element.name = field + " (" + e.name + ")";
    element.row_x = Eigen::VectorXd::Zero(2 * nb);
    element.row_v = Eigen::VectorXd::Zero(1);
    element.column_x = Eigen::VectorXd::Zero(2 * nb);
    element.column_x.tail(nb) = -D.cwiseQuotient(m.mass_kg);
    element.driven_share = m.element_d(row);
    if (e.friction.present()) {
      element.law = FrictionElement{e.friction};
      element.row_x.tail(nb) = D;
      element.row_v(0) = m.rigid_stretch(row);
    } else {
      // g is O(1) (rigid motion per unit driven motion), so is the stretch.
      if (std::abs(m.rigid_stretch(row)) > 1e-9) {
        throw ValidationError(field, "element \"" + e.name + "\" (" + e.from + " - " + e.to +
                                         ") has backlash and stretches by " +
                                         FormatNumber(m.rigid_stretch(row)) +
                                         " per unit of driven motion when the structure follows "
                                         "the driven point rigidly; a backlash element must lie "
                                         "on the drive's path (e.g. from driven to the table it "
                                         "moves), where the rigid motion does not stretch it");
      }
      element.law = BacklashElement{e.stiffness_n_m, e.backlash_m};
      element.row_x.head(nb) = D;
    }
    result.push_back(std::move(element));
  }
  return result;
}

}  // namespace

std::vector<NonlinearElement> BuildStructureElements(const MachineConfig& machine) {
  return std::visit([](const auto& form) { return FormElements(form); }, machine.form);
}

}  // namespace shapebench::model

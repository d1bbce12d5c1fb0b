#include "model/lumped_matrices.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>

#include <Eigen/Eigenvalues>

namespace shapebench::model {
namespace {

// An endpoint's position as D q + d u.
struct EndpointMap {
  Eigen::RowVectorXd D;
  double d = 0.0;
};

class EndpointMapper {
 public:
  explicit EndpointMapper(const LumpedMachineConfig& config)
      : num_bodies_(static_cast<int>(config.bodies.size())) {
    for (int i = 0; i < num_bodies_; ++i) index_[config.bodies[i].name] = i;
    driven_ref_ = Map(config.driven_relative_to);
    driven_ref_.d = 1.0;
  }

  EndpointMap Map(const std::string& name) const {
    if (name == "driven") return driven_ref_;
    EndpointMap map{Eigen::RowVectorXd::Zero(num_bodies_), 0.0};
    if (name != "ground") map.D(index_.at(name)) = 1.0;
    return map;
  }

 private:
  int num_bodies_;
  std::unordered_map<std::string, int> index_;
  EndpointMap driven_ref_;
};

// C of a `damping:` block (machine.h, LumpedDamping) from M and K. K is positive definite
// (validate(): every body is tied to ground or the held driven point), so there is no
// rigid-body mode; a zero-frequency mode would still get no damping from the modal list.
Eigen::MatrixXd BlockDamping(const LumpedDamping& damping, const Eigen::VectorXd& mass_kg,
                             const Eigen::MatrixXd& K) {
  const Eigen::MatrixXd M = mass_kg.asDiagonal();
  if (damping.kind == LumpedDampingKind::kRayleigh) {
    return damping.rayleigh.alpha * M + damping.rayleigh.beta * K;
  }
  // Ascending eigenvalues; eigenvectors mass-normalised (Phi^T M Phi = I), so
  // Phi^T C Phi = diag(2 zeta_i w_i) exactly: every mode keeps its shape and gets its zeta.
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(K, M);
  const Eigen::VectorXd& w2 = solver.eigenvalues();
  const int n = static_cast<int>(w2.size());
  Eigen::VectorXd modal_c = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < n; ++i) {
    if (!(w2(i) > 1e-12 * w2(n - 1))) continue;  // rigid: no damping
    const std::size_t entry = std::min<std::size_t>(static_cast<std::size_t>(i), damping.modal.size() - 1);
    modal_c(i) = 2.0 * damping.modal[entry] * std::sqrt(w2(i));
  }
  const Eigen::MatrixXd MPhi = M * solver.eigenvectors();
  const Eigen::MatrixXd C = MPhi * modal_c.asDiagonal() * MPhi.transpose();
  return 0.5 * (C + C.transpose());  // symmetric to the last bit
}

}  // namespace

LumpedMatrices AssembleLumped(const LumpedMachineConfig& config) {
  const int n = static_cast<int>(config.bodies.size());
  const EndpointMapper mapper(config);
  LumpedMatrices m;
  m.mass_kg.resize(n);
  for (int i = 0; i < n; ++i) m.mass_kg(i) = config.bodies[i].mass_kg;
  m.K = Eigen::MatrixXd::Zero(n, n);
  m.C = Eigen::MatrixXd::Zero(n, n);
  m.K_u = Eigen::VectorXd::Zero(n);
  m.C_u = Eigen::VectorXd::Zero(n);
  for (const LumpedElement& e : config.elements) {
    const EndpointMap from = mapper.Map(e.from);
    const EndpointMap to = mapper.Map(e.to);
    const Eigen::RowVectorXd D = from.D - to.D;
    const double d = from.d - to.d;
    // Potential 0.5 k Delta^2 and dissipation 0.5 c Delta'^2, differentiated by q.
    m.K += e.stiffness_n_m * D.transpose() * D;
    m.C += e.damping_n_s_m * D.transpose() * D;
    m.K_u += e.stiffness_n_m * d * D.transpose();
    m.C_u += e.damping_n_s_m * d * D.transpose();
  }
  m.g = m.K.llt().solve(-m.K_u);
  m.force_per_accel = -m.mass_kg.cwiseProduct(m.g);
  if (config.damping.kind == LumpedDampingKind::kElements) {
    m.velocity_load = m.C * m.g + m.C_u;
  } else {
    // Dissipation 0.5 y'^T C y' with y = q - g u: by q' it is C q' - C g u', so C_u = -C g,
    // and by u' the drive's reaction -g^T C y' = C_u^T y'. The rigid motion is not damped.
    m.C = BlockDamping(config.damping, m.mass_kg, m.K);
    m.C_u = -(m.C * m.g);
    m.velocity_load = Eigen::VectorXd::Zero(n);
  }
  const auto num_elements = static_cast<Eigen::Index>(config.elements.size());
  m.rigid_stretch.resize(num_elements);
  m.element_D.resize(num_elements, n);
  m.element_d.resize(num_elements);
  for (Eigen::Index i = 0; i < num_elements; ++i) {
    const LumpedElement& e = config.elements[static_cast<std::size_t>(i)];
    const EndpointMap from = mapper.Map(e.from);
    const EndpointMap to = mapper.Map(e.to);
    m.element_D.row(i) = from.D - to.D;
    m.element_d(i) = from.d - to.d;
    m.rigid_stretch(i) = (from.D - to.D).dot(m.g) + (from.d - to.d);
  }
  const EndpointMap body = mapper.Map(config.output_body);
  const EndpointMap relative = mapper.Map(config.output_relative_to);
  m.output = (body.D - relative.D).transpose();
  return m;
}

}  // namespace shapebench::model

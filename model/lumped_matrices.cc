#include "model/lumped_matrices.h"

#include <string>
#include <unordered_map>

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
  m.velocity_load = m.C * m.g + m.C_u;
  m.rigid_stretch.resize(static_cast<Eigen::Index>(config.elements.size()));
  for (std::size_t i = 0; i < config.elements.size(); ++i) {
    const LumpedElement& e = config.elements[i];
    const EndpointMap from = mapper.Map(e.from);
    const EndpointMap to = mapper.Map(e.to);
    m.rigid_stretch(static_cast<Eigen::Index>(i)) = (from.D - to.D).dot(m.g) + (from.d - to.d);
  }
  const EndpointMap body = mapper.Map(config.output_body);
  const EndpointMap relative = mapper.Map(config.output_relative_to);
  m.output = (body.D - relative.D).transpose();
  return m;
}

}  // namespace shapebench::model

// NonlinearDynamics: the equations are in nonlinear_dynamics.h and docs/nonlinear.md.
#include "model/nonlinear_dynamics.h"

#include <algorithm>
#include <cmath>
#include <variant>

namespace shapebench::model {

void NonlinearDynamics::Sparse::Assign(const Eigen::VectorXd& v) {
  index.clear();
  value.clear();
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (v(i) != 0.0) {
      index.push_back(static_cast<int>(i));
      value.push_back(v(i));
    }
  }
}

double NonlinearDynamics::Sparse::Dot(const double* x) const {
  double sum = 0.0;
  for (std::size_t k = 0; k < index.size(); ++k) sum += value[k] * x[index[k]];
  return sum;
}

NonlinearDynamics::NonlinearDynamics(const NonlinearPlant& plant) {
  const LinearPlant& p = plant.linear;
  const int n = p.num_states();
  const int m = p.num_inputs();
  nz_ = n + m;
  a_z_ = p.AugmentedA();
  a_sparse_.resize(nz_);
  for (int i = 0; i < nz_; ++i) {
    for (int j = 0; j < nz_; ++j) {
      if (a_z_(i, j) != 0.0) a_sparse_[i].emplace_back(j, a_z_(i, j));
    }
  }
  forcing_ = Eigen::VectorXd::Zero(nz_);
  const int count = static_cast<int>(plant.elements.size());
  Eigen::MatrixXd rows(nz_, count);
  Eigen::MatrixXd columns = Eigen::MatrixXd::Zero(nz_, count);
  for (int i = 0; i < count; ++i) {
    const NonlinearElement& config = plant.elements[i];
    rows.col(i) << config.row_x, config.row_v;
    columns.col(i).head(n) = config.column_x;
    Element e;
    e.config = config;
    e.row.Assign(rows.col(i));
    e.column.Assign(columns.col(i));
    e.row_a.Assign(a_z_.transpose() * rows.col(i));
    const auto* friction = std::get_if<FrictionElement>(&config.law);
    if (friction != nullptr && friction->HasBristle()) e.bristle = num_bristles_++;
    e.sticks = friction != nullptr && friction->Sticks();
    e.root = num_roots_;
    num_roots_ += NumRoots(config.law);
    elements_.push_back(std::move(e));
  }
  coupling_ = rows.transpose() * columns;
  force_.assign(count, 0.0);
  value_.assign(count, 0.0);
  rate_.assign(count, 0.0);
  offset_value_.assign(count, 0.0);
  offset_rate_.assign(count, 0.0);
  grads_ = Eigen::MatrixXd::Zero(size(), count);
}

std::vector<double> NonlinearDynamics::BristleScales() const {
  std::vector<double> scales;
  for (const Element& e : elements_) {
    if (e.bristle >= 0) scales.push_back(Friction(e).friction.StaticN() / Friction(e).friction.sigma0_n_m);
  }
  return scales;
}

void NonlinearDynamics::SetForcing(const Eigen::VectorXd& forcing) {
  forcing_ = forcing;
  for (Element& e : elements_) e.row_forcing = e.row.Dot(forcing_.data());
}

double NonlinearDynamics::Force(const Element& e, double w, const double* y, double* dw,
                                double* dzeta) const {
  const double zeta = e.bristle >= 0 ? y[nz_ + e.bristle] : 0.0;
  return std::visit([&](const auto& law) { return law.Force(w, e.mode, zeta, dw, dzeta); }, e.config.law);
}

void NonlinearDynamics::RebuildStuckSet() {
  stuck_.clear();
  for (int i = 0; i < num_elements(); ++i) {
    if (Stuck(elements_[i])) stuck_.push_back(i);
  }
  const int s = static_cast<int>(stuck_.size());
  stuck_rhs_.resize(s);
  if (s < 2) return;
  Eigen::MatrixXd g(s, s);
  for (int a = 0; a < s; ++a) {
    for (int b = 0; b < s; ++b) g(a, b) = coupling_(stuck_[a], stuck_[b]);
  }
  // Two stuck elements in parallel make G_SS singular: the least-norm split of the force.
  stuck_solver_.compute(g);
}

// The stuck forces F_S keep every stuck w' = row_a z + row . forcing + sum_j G_ij F_j at 0.
void NonlinearDynamics::SolveStuck(const double* y) {
  const int s = static_cast<int>(stuck_.size());
  for (int a = 0; a < s; ++a) {
    const int i = stuck_[a];
    double rate = elements_[i].row_a.Dot(y) + elements_[i].row_forcing + offset_rate_[i];
    for (int j = 0; j < num_elements(); ++j) {
      if (!Stuck(elements_[j])) rate += coupling_(i, j) * force_[j];
    }
    stuck_rhs_(a) = -rate;
  }
  if (s == 1) {
    force_[stuck_[0]] = stuck_rhs_(0) / coupling_(stuck_[0], stuck_[0]);
    return;
  }
  const Eigen::VectorXd f = stuck_solver_.solve(stuck_rhs_);
  for (int a = 0; a < s; ++a) force_[stuck_[a]] = f(a);
}

void NonlinearDynamics::Forces(const double* y) {
  for (int i = 0; i < num_elements(); ++i) {
    const Element& e = elements_[i];
    value_[i] = Value(i, y);
    if (e.bristle >= 0) {
      // LuGre: the bristle rate once (its exp), for the force and for zeta' (Rhs).
      const FrictionElement& f = Friction(e);
      rate_[i] = f.BristleRate(value_[i], y[nz_ + e.bristle], nullptr, nullptr);
      force_[i] = f.BristleForce(value_[i], y[nz_ + e.bristle], rate_[i]);
    } else if (!Stuck(e)) {
      force_[i] = Force(e, value_[i], y, nullptr, nullptr);
    }
  }
  if (!stuck_.empty()) SolveStuck(y);
}

void NonlinearDynamics::Rhs(const double* y, double* ydot) {
  Forces(y);
  for (int r = 0; r < nz_; ++r) {
    double sum = forcing_[r];
    for (const auto& [c, a] : a_sparse_[r]) sum += a * y[c];
    ydot[r] = sum;
  }
  for (int i = 0; i < num_elements(); ++i) {
    const Element& e = elements_[i];
    for (std::size_t k = 0; k < e.column.index.size(); ++k) ydot[e.column.index[k]] += e.column.value[k] * force_[i];
    if (e.bristle >= 0) ydot[nz_ + e.bristle] = rate_[i];
  }
  if (!stuck_.empty()) RefineStuck(ydot);
}

// One step of iterative refinement of the holding forces, from the rates just summed: F*
// cancels terms of the size of the loop's gains times its states (a servo's velocity
// integral winding up against a stuck motor reaches 1e8 m/s^2 on it), whose rounding would
// leave a stuck w' of 1e-8 m/s^2 and let a held motor creep by nanometres (issue 32).
void NonlinearDynamics::RefineStuck(double* ydot) {
  const int s = static_cast<int>(stuck_.size());
  for (int a = 0; a < s; ++a) {
    const int i = stuck_[a];
    stuck_rhs_(a) = -(elements_[i].row.Dot(ydot) + offset_rate_[i]);
  }
  const Eigen::VectorXd f = s == 1 ? Eigen::VectorXd(stuck_rhs_ / coupling_(stuck_[0], stuck_[0]))
                                   : Eigen::VectorXd(stuck_solver_.solve(stuck_rhs_));
  for (int a = 0; a < s; ++a) {
    const Element& e = elements_[stuck_[a]];
    for (std::size_t k = 0; k < e.column.index.size(); ++k) ydot[e.column.index[k]] += e.column.value[k] * f(a);
    force_[stuck_[a]] += f(a);
  }
}

void NonlinearDynamics::Roots(const double* y, double* g) {
  // Only a stuck element's root reads a force (its holding force, which depends on the
  // others'); without one the roots need the rows alone (no LuGre exp at every output).
  if (stuck_.empty()) {
    for (int i = 0; i < num_elements(); ++i) value_[i] = Value(i, y);
  } else {
    Forces(y);
  }
  for (int i = 0; i < num_elements(); ++i) {
    const Element& e = elements_[i];
    std::visit([&](const auto& law) { law.Roots(value_[i], e.mode, force_[i], g + e.root); }, e.config.law);
  }
}

std::vector<std::vector<int>> NonlinearDynamics::Blocks() const {
  const int n = size();
  std::vector<int> parent(n);
  for (int i = 0; i < n; ++i) parent[i] = i;
  auto find = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  auto join = [&](int a, int b) { parent[find(a)] = find(b); };
  for (int r = 0; r < nz_; ++r) {
    for (const auto& entry : a_sparse_[r]) join(r, entry.first);
  }
  for (const Element& e : elements_) {
    std::vector<int> touched = e.row.index;
    touched.insert(touched.end(), e.row_a.index.begin(), e.row_a.index.end());
    touched.insert(touched.end(), e.column.index.begin(), e.column.index.end());
    if (e.bristle >= 0) touched.push_back(nz_ + e.bristle);
    for (int i : touched) join(i, touched.front());  // (an element touches its row at least)
  }
  std::vector<std::vector<int>> blocks;
  std::vector<int> block_of(n, -1);
  for (int i = 0; i < n; ++i) {
    const int root = find(i);
    if (block_of[root] < 0) {
      block_of[root] = static_cast<int>(blocks.size());
      blocks.emplace_back();
    }
    blocks[block_of[root]].push_back(i);
  }
  return blocks;
}

std::vector<int> NonlinearDynamics::RootDirections() const {
  std::vector<int> directions(num_roots_, 0);
  for (const Element& e : elements_) {
    std::visit([&](const auto& law) { law.RootDirections(directions.data() + e.root); }, e.config.law);
  }
  return directions;
}

void NonlinearDynamics::Jacobian(const double* y, double* jac) {
  const int size_y = size();
  Eigen::Map<Eigen::MatrixXd> J(jac, size_y, size_y);
  J.setZero();
  J.topLeftCorner(nz_, nz_) = a_z_;
  Forces(y);
  grads_.setZero();
  for (int i = 0; i < num_elements(); ++i) {
    const Element& e = elements_[i];
    if (Stuck(e)) continue;
    double dw = 0.0;
    double dzeta = 0.0;
    Force(e, value_[i], y, &dw, &dzeta);
    for (std::size_t k = 0; k < e.row.index.size(); ++k) grads_(e.row.index[k], i) = dw * e.row.value[k];
    if (e.bristle >= 0) {
      grads_(nz_ + e.bristle, i) = dzeta;
      double rate_w = 0.0;
      double rate_zeta = 0.0;
      Friction(e).BristleRate(value_[i], y[nz_ + e.bristle], &rate_w, &rate_zeta);
      for (std::size_t k = 0; k < e.row.index.size(); ++k) J(nz_ + e.bristle, e.row.index[k]) = rate_w * e.row.value[k];
      J(nz_ + e.bristle, nz_ + e.bristle) = rate_zeta;
    }
  }
  if (!stuck_.empty()) {
    // dF_S/dy = -G_SS^-1 (row_a + sum over the others of G_Sj dF_j/dy).
    const int s = static_cast<int>(stuck_.size());
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(s, size_y);
    for (int a = 0; a < s; ++a) {
      const Element& e = elements_[stuck_[a]];
      for (std::size_t k = 0; k < e.row_a.index.size(); ++k) rhs(a, e.row_a.index[k]) -= e.row_a.value[k];
      for (int j = 0; j < num_elements(); ++j) {
        if (!Stuck(elements_[j])) rhs.row(a) -= coupling_(stuck_[a], j) * grads_.col(j).transpose();
      }
    }
    const Eigen::MatrixXd grad = s == 1 ? Eigen::MatrixXd(rhs / coupling_(stuck_[0], stuck_[0]))
                                        : Eigen::MatrixXd(stuck_solver_.solve(rhs));
    for (int a = 0; a < s; ++a) grads_.col(stuck_[a]) = grad.row(a).transpose();
  }
  for (int i = 0; i < num_elements(); ++i) {
    const Element& e = elements_[i];
    for (std::size_t k = 0; k < e.column.index.size(); ++k) {
      J.row(e.column.index[k]) += e.column.value[k] * grads_.col(i).transpose();
    }
  }
}

void NonlinearDynamics::InitModes(const double* y) {
  for (int i = 0; i < num_elements(); ++i) {
    Element& e = elements_[i];
    const double w = Value(i, y);
    e.mode = std::visit([&](const auto& law) { return law.RestMode(w); }, e.config.law);
  }
  Settle(y);
}

// A stuck element holds while |F*| <= F_s; one with F_s = 0 holds nothing (it would stay
// stuck at F* = 0, where |F*| = F_s has no crossing to find).
bool NonlinearDynamics::Settle(const double* y) {
  bool changed = false;
  for (;;) {
    RebuildStuckSet();
    if (stuck_.empty()) return changed;
    Forces(y);
    int worst = -1;
    double excess = 0.0;
    for (int i : stuck_) {
      const double f_s = Friction(elements_[i]).friction.StaticN();
      const double over = std::abs(force_[i]) - f_s;
      if ((over > 0.0 || f_s == 0.0) && (worst < 0 || over > excess)) {
        worst = i;
        excess = over;
      }
    }
    if (worst < 0) return changed;
    elements_[worst].mode = force_[worst] < 0.0 ? -1 : 1;  // slides the way F* pushes
    changed = true;
  }
}

bool NonlinearDynamics::ReleaseOverloaded(const double* y) { return Settle(y); }

void NonlinearDynamics::Project(double* y) {
  const int s = static_cast<int>(stuck_.size());
  if (s == 0) return;
  Eigen::VectorXd w(s);
  for (int a = 0; a < s; ++a) w(a) = -Value(stuck_[a], y);
  const Eigen::VectorXd impulse = s == 1 ? Eigen::VectorXd(w / coupling_(stuck_[0], stuck_[0]))
                                         : Eigen::VectorXd(stuck_solver_.solve(w));
  for (int a = 0; a < s; ++a) {
    const Element& e = elements_[stuck_[a]];
    for (std::size_t k = 0; k < e.column.index.size(); ++k) y[e.column.index[k]] += e.column.value[k] * impulse(a);
  }
}

bool NonlinearDynamics::HandleRoots(const int* found, double* y) {
  Forces(y);

  bool changed = false;
  bool sticks = false;
  for (int i = 0; i < num_elements(); ++i) {
    Element& e = elements_[i];
    const int* own = found + e.root;
    if (std::all_of(own, own + NumRoots(e.config.law), [](int f) { return f == 0; })) continue;
    changed = true;  // at least a restart (LuGre: the kink of |w|)
    const int before = e.mode;
    e.mode = std::visit([&](const auto& law) { return law.ModeAfterRoots(own, e.mode, force_[i]); }, e.config.law);
    // w reached 0: stuck, unless Settle finds F* beyond F_s.
    if (Sticks(e) && before != 0 && e.mode == 0) sticks = true;
  }
  RebuildStuckSet();
  if (sticks) Project(y);
  Settle(y);
  return changed;
}

}  // namespace shapebench::model

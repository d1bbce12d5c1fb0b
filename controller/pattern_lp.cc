// The CLP wrapper; see the header.
#include "controller/pattern_lp.h"

#include <ClpSimplex.hpp>
#include <CoinHelperFunctions.hpp>

namespace shapebench::controller {

struct DenseLp::Clp {
  ClpSimplex model;
};

DenseLp::DenseLp(const std::vector<double>& objective, double upper_bound)
    : clp_(std::make_unique<Clp>()), columns_(objective.size()) {
  ClpSimplex& m = clp_->model;
  m.setLogLevel(0);
  m.resize(0, static_cast<int>(columns_));
  for (std::size_t j = 0; j < columns_; ++j) {
    m.setColumnBounds(static_cast<int>(j), 0.0, upper_bound);
    m.setObjectiveCoefficient(static_cast<int>(j), objective[j]);
  }
}

DenseLp::~DenseLp() = default;

void DenseLp::AddRow(const std::vector<double>& coefficients, double lower, double upper) {
  std::vector<int> columns;
  std::vector<double> values;
  for (std::size_t j = 0; j < coefficients.size() && j < columns_; ++j) {
    if (coefficients[j] != 0.0) {
      columns.push_back(static_cast<int>(j));
      values.push_back(coefficients[j]);
    }
  }
  clp_->model.addRow(static_cast<int>(columns.size()), columns.data(), values.data(), lower, upper);
}

DenseLp::Outcome DenseLp::Solve() {
  ClpSimplex& m = clp_->model;
  m.dual();
  if (m.isProvenOptimal()) return Outcome::kOptimal;
  if (m.isProvenPrimalInfeasible()) return Outcome::kInfeasible;
  return Outcome::kFailed;
}

std::vector<double> DenseLp::Solution() const {
  const double* x = clp_->model.primalColumnSolution();
  return std::vector<double>(x, x + columns_);
}

}  // namespace shapebench::controller

// The CLP wrapper; see the header.
#include "controller/pattern_lp.h"

#include <ClpSimplex.hpp>

namespace shapebench::controller {

struct DenseLp::Clp {
  ClpSimplex model;
  // Rows waiting for the next Solve, added in one batch: one addRow at a time (each
  // growing CLP's matrix) made the two-mode design 12 times slower.
  std::vector<CoinBigIndex> starts{0};
  std::vector<int> columns;
  std::vector<double> values;
  std::vector<double> lower;
  std::vector<double> upper;
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
  Clp& c = *clp_;
  for (std::size_t j = 0; j < coefficients.size() && j < columns_; ++j) {
    if (coefficients[j] != 0.0) {
      c.columns.push_back(static_cast<int>(j));
      c.values.push_back(coefficients[j]);
    }
  }
  c.starts.push_back(static_cast<CoinBigIndex>(c.columns.size()));
  c.lower.push_back(lower);
  c.upper.push_back(upper);
}

DenseLp::Outcome DenseLp::Solve() {
  Clp& c = *clp_;
  ClpSimplex& m = c.model;
  if (!c.lower.empty()) {
    m.addRows(static_cast<int>(c.lower.size()), c.lower.data(), c.upper.data(), c.starts.data(), c.columns.data(),
              c.values.data());
    c.starts.assign(1, 0);
    c.columns.clear();
    c.values.clear();
    c.lower.clear();
    c.upper.clear();
  }
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

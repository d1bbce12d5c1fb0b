// A dense linear program over x >= 0 (minimise c.x subject to rows lower <= A x <= upper),
// solved by COIN-OR CLP's dual simplex, rows added between solves with the last basis kept
// (the cutting planes of pattern_design.cc). Hides CLP from every other file.
#pragma once

#include <memory>
#include <vector>

namespace shapebench::controller {

class DenseLp {
 public:
  enum class Outcome { kOptimal, kInfeasible, kFailed };

  // `objective.size()` columns, each in [0, upper_bound].
  DenseLp(const std::vector<double>& objective, double upper_bound);
  ~DenseLp();
  DenseLp(const DenseLp&) = delete;
  DenseLp& operator=(const DenseLp&) = delete;

  // One row over every column (zeros skipped).
  void AddRow(const std::vector<double>& coefficients, double lower, double upper);
  Outcome Solve();
  // The columns' values after kOptimal.
  std::vector<double> Solution() const;

 private:
  struct Clp;
  std::unique_ptr<Clp> clp_;
  std::size_t columns_ = 0;
};

}  // namespace shapebench::controller

// The work an identification takes (model/modal_identification.h), in multiply-adds estimated
// from its sizes before each part runs, and the budget every part is charged to
// (IdentificationOptions::max_work): counted, never timed, so the same verdict on every host.
#pragma once

#include <string>

namespace shapebench::model {

// The stabilisation diagram and one LSFD: the lag sums (lines x (4 M + 1) lags x (FRFs + 2)),
// at each order o the normal equations and the companion matrix's eigenvalues ((2 FRFs + 12)
// (2 o + 1)^3), and each FRF's modal constants (a QR of 2 lines x (2 M + 2)^2).
double IdentificationWork(int lines, int frfs, int max_order);

// One nonlinear refinement of `modes` poles (RefineModalModel): 50 iterations of a dense QR of
// every residual by every unknown.
double RefinementWork(int lines, int frfs, int modes);

// One LSFD of `modes` poles (FitLinear) and its squared error.
double LsfdWork(int lines, int frfs, int modes);

class WorkBudget;

// Throws SolverError("WORK_LIMIT") before a fit when its diagram of `lines` lines up to
// `max_order` exceeds what `budget` has left (in a sub-band, what the sub-bands below
// left), naming its key.
void RequireWithinWork(int lines, int frfs, int max_order, const WorkBudget& budget);

// The identification's budget: each part is charged before it runs; past the limit,
// SolverError("WORK_LIMIT") naming `key`, the part and the work spent.
class WorkBudget {
 public:
  WorkBudget(double limit, std::string key) : limit_(limit), key_(std::move(key)) {}
  // Throws when used() + work exceeds the limit; `what` names the part ("refining 5 modes
  // over 2501 lines").
  void Charge(double work, const std::string& what);
  double used() const { return used_; }
  double remaining() const { return limit_ - used_; }
  double limit() const { return limit_; }
  const std::string& key() const { return key_; }

 private:
  double limit_;
  std::string key_;
  double used_ = 0.0;
};

}  // namespace shapebench::model

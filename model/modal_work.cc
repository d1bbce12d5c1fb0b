// The identification's work estimates and budget (model/modal_work.h).
#include "model/modal_work.h"

#include <cmath>
#include <string>

#include "common/format.h"
#include "model/integrator.h"

namespace shapebench::model {

double IdentificationWork(int lines, int frfs, int max_order) {
  const double l = lines;
  const double r = frfs;
  const double m = max_order;
  double work = l * (4.0 * m + 1.0) * (r + 2.0) + r * 2.0 * l * (2.0 * m + 2.0) * (2.0 * m + 2.0);
  for (int o = 1; o <= max_order; ++o) work += (2.0 * r + 12.0) * std::pow(2.0 * o + 1.0, 3);
  return work;
}

double RefinementWork(int lines, int frfs, int modes) {
  const double unknowns = 2.0 * modes + frfs * (2.0 * modes + 2.0);
  return 50.0 * 2.0 * lines * frfs * unknowns * unknowns;
}

namespace {

// The limit a WORK_LIMIT message suggests: the power of ten at or above `work`, `decades`
// higher.
double PowerOfTenAbove(double work, double decades) { return std::pow(10.0, std::ceil(std::log10(work)) + decades); }

}  // namespace

double LsfdWork(int lines, int frfs, int modes) {
  const double unknowns = 2.0 * modes + 2.0;
  return 2.0 * lines * unknowns * (unknowns + frfs) + 2.0 * lines * frfs * (modes + 1.0);
}

void WorkBudget::Charge(double work, const std::string& what) {
  if (!(used_ + work > limit_)) {
    used_ += work;
    return;
  }
  const double suggested = PowerOfTenAbove(used_ + work, 1.0);
  throw SolverError("WORK_LIMIT", what + " would bring the identification's work to about " +
                                      FormatNumber(used_ + work, 3) + " multiply-adds, more than " + key_ + " (" +
                                      FormatNumber(limit_, 3) + "; " + FormatNumber(used_, 3) +
                                      " spent before it); stopped, no mode is reported: raise " + key_ + " (e.g. to " +
                                      FormatNumber(suggested, 3) + "), or narrow the band");
}

// Refused before the fit starts when its work exceeds max_work (ten copies of a
// record at order 200 took 40 s; a thousand records an estimated hour); in a sub-band,
// max_work is what the sub-bands below left.
void RequireWithinWork(int lines, int frfs, int max_order, const WorkBudget& budget) {
  const double max_work = budget.remaining();
  const double spent = budget.used();
  const std::string& key = budget.key();
  const double work = IdentificationWork(lines, frfs, max_order);
  if (!(work > max_work)) return;
  const double suggested = PowerOfTenAbove(work + spent, 0.0);
  throw SolverError("WORK_LIMIT", "identifying " + std::to_string(frfs) + " FRF" + (frfs == 1 ? "" : "s") + " of " +
                                      std::to_string(lines) + " lines up to order " + std::to_string(max_order) +
                                      " would take about " + FormatNumber(work, 3) +
                                      " multiply-adds, more than " + key + " (" +
                                      FormatNumber(spent + max_work, 3) + ")" +
                                      (spent > 0.0 ? " less the " + FormatNumber(spent, 3) + " spent on the sub-bands "
                                                     "below; stopped, no mode is reported" : "; nothing was fitted") +
                                      ": raise " + key + " (e.g. to " + FormatNumber(suggested, 3) +
                                      "), or lower the order, narrow the band or take fewer records");
}

}  // namespace shapebench::model

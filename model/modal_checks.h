// The identification's checks before and after the fit (model/modal_identification.h):
// its work against the budget before the diagram, finite results after it.
#pragma once

#include "model/modal_identification.h"

namespace shapebench::model {

// Throws SolverError("WORK_LIMIT") before the fit when the diagram of `lines` lines up to
// `max_order` exceeds options.max_work (in a sub-band, what the sub-bands below left after
// spending `spent`).
void RequireWithinWork(int lines, int frfs, int max_order, const IdentificationOptions& options, double spent);

// Throws ValidationError("frf") when the fit's error or modes are not finite numbers.
void RequireFinite(const ModalIdentification& result);

}  // namespace shapebench::model

// The registry's shapers and the patent's methods 1-4 held to a design's specification
// (`shapebench design`'s report, docs/design.md): each designed at every band's centre
// (frequency and damping, the tolerance as vibration_tolerance), the designs convolved,
// kept when non-negative and within the tolerance over every band, ranked by duration.
#pragma once

#include <string>
#include <vector>

#include "controller/impulse.h"
#include "controller/pattern_design.h"

namespace shapebench::controller {

struct ShaperAgainstSpec {
  std::string method;  // the registry key
  double duration_s = 0.0;
  std::vector<double> worst_v;  // per band
  bool meets = false;           // non-negative and worst_v <= tolerance on every band
  std::vector<Impulse> impulses;
};

// Every registry shaper of kind kPatentStep or kImpulse (their default parameters, the
// tolerance for the ei family), those meeting the spec first by duration, then the rest by
// duration. A shaper that cannot be designed for a band (its own validation) is left out.
std::vector<ShaperAgainstSpec> CompareRegistryShapers(const DesignSpec& spec);

// The largest V of `impulses` over `band` (WorstResidualOverBand's points).
double WorstImpulseResidualOverBand(const std::vector<Impulse>& impulses, const DesignBand& band,
                                    int frequencies = 2001);

}  // namespace shapebench::controller

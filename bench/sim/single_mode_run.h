// A run of one structural mode under the kinematic drive along one straight line, in
// closed form: the sweep users run most (the natural-period sweep of the patent's SDOF
// case, JP2551868B2 (seed 004) paras. 11-23) at the cost of the bare zero-order hold.
//
// The plant is q'' + 2 zeta w q' + w^2 q = -a (model/machine.h), deflection = gain q, the
// tool error the deflection. Over a period with a held, x = q + a / w^2 is a damped
// oscillation, so everything the exact path finds with matrices is written out here:
// - the period's transition (Van Loan's block exponential of the general path): cos, sin
//   and exp of the mode, once per run;
// - the extremum inside a period: where q' changes sign, w_d t = atan2(w_d q0', zeta w q0'
//   + w^2 x0) (mod pi) (model/tick_extremum.h's single-pole closed form);
// - the residual amplitude at motion end and at the cruise probes: sqrt(x^2 + ((q' +
//   zeta w x) / w_d)^2) times |gain| (the pole pair's 2 |c v z| of model/free_response.h);
// - the settling tail from the residual window's end: model/band_crossing.h on the one
//   pole pair, then the last sample outside the band on the run's sample grid.
// The output substeps are computed only in the periods where one can change a metric (the
// contour error near the line's ends, the settling band's last sample), as the deferred
// substeps of the general path (deferred_substeps.h) decide it.
//
// The metrics are those of the general exact path to rounding, not bit for bit: its
// transition comes from a balanced matrix exponential, this one from cos and sin, a few
// ulps apart, and 1,000 periods carry that to about 1e-13 of the deflection
// (tests/bench/single_mode_run_test.cc compares the two within 1e-11).
#pragma once

#include "bench/sim/command_samples.h"
#include "bench/sim/cosim.h"
#include "bench/sim/scenario.h"
#include "controller/controller.h"
#include "controller/path_geometry.h"

namespace shapebench::bench {

// Runs the scenario here when it is such a run and needs no trace, filling *result (its
// metrics, residual_modes, substeps, simulated_s, stats); false, *result untouched, when
// it is not: a servo drive, several modes or axes, a lumped form, CVODE, a stroke limit,
// an arc or a program of several blocks, a critically damped mode, a view off the axis.
// Throws ValidationError as RunScenario does (an invalid machine, the run's limits).
bool RunSingleMode(const Scenario& scenario, const controller::MultiAxisCommand& command,
                   const CommandSamples& samples, const controller::PathGeometry& path, RunResult* result);

// Whether RunSingleMode takes the scenario (before its command's samples exist).
bool SingleModeQualifies(const Scenario& scenario, const controller::PathGeometry& path);

}  // namespace shapebench::bench

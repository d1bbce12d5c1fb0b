// The simulation inside an exported FMU: the machine part (the plant, stepped exactly when
// linear, by CVODE otherwise) or the controller part (the scenario's command, a period a
// step). The FMI functions (fmi2_exports.cc, fmi3_exports.cc) call these through Instance
// (fmu_instance.h); the values array is indexed by value reference.
#pragma once

#include <memory>
#include <vector>

#include "bench/fmu/fmu_layout.h"
#include "bench/scenario/scenario.h"

namespace shapebench::bench::fmu {

class Slave {
 public:
  virtual ~Slave() = default;
  // The outputs before the first step (and the calculated parameters).
  virtual void WriteInitialOutputs(std::vector<double>* values) = 0;
  // Reads the inputs from `values`, advances from t to t + h, writes the outputs. Throws
  // std::runtime_error saying why it cannot (a step size it does not take, solver trouble).
  virtual void DoStep(double t, double h, std::vector<double>* values) = 0;
};

// Throws ValidationError or std::runtime_error.
std::unique_ptr<Slave> MakeMachineSlave(const Scenario& scenario, const Layout& layout);
std::unique_ptr<Slave> MakeControllerSlave(const Scenario& scenario, const Layout& layout);

}  // namespace shapebench::bench::fmu

// An FMU's modelDescription.xml as the master needs it (FMI 2.0 and 3.0 co-simulation):
// the version, the token the binary checks, the co-simulation model identifier (the
// binary's name), and the scalar variables with their value references, causality,
// variability, unit and start value. Only what the import master uses is read.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace shapebench::bench {

// A bad or missing FMU, a modelDescription the master cannot use, a variable that does not
// exist: the scenario reader locates it at the key that named the FMU (exit 2).
class FmuError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class FmiVersion { k2, k3 };

struct FmuVariable {
  std::string name;
  unsigned value_reference = 0;
  std::string type;         // the element: Real, Integer, ... (2.0); Float64, Int32, ... (3.0)
  std::string causality;    // parameter, calculatedParameter, input, output, local, independent, ...
  std::string variability;  // constant, fixed, tunable, discrete, continuous
  std::string unit;         // as declared ("" when none)
  std::optional<double> start;
  bool array = false;       // a 3.0 array variable (<Dimension>): not a scalar the master can map
  int line = 0;             // in modelDescription.xml, for messages

  // A scalar double: Real (2.0) or Float64 (3.0).
  bool IsDouble() const { return !array && (type == "Real" || type == "Float64"); }
};

struct ModelDescription {
  FmiVersion version = FmiVersion::k2;
  std::string fmi_version;       // as written: "2.0", "3.0"
  std::string model_name;
  std::string token;             // guid (2.0) or instantiationToken (3.0)
  std::string model_identifier;  // of <CoSimulation>: the binary's file name
  bool can_handle_variable_step = false;
  bool once_per_process = false;  // canBeInstantiatedOnlyOncePerProcess
  std::vector<FmuVariable> variables;
  std::string file;  // where it was read from, for messages

  const FmuVariable* Find(const std::string& name) const;
  // The names of the double variables of that causality, comma-separated, for the
  // "allowed" part of a message (at most a screenful).
  std::string DoubleNames(const std::string& causality) const;
};

// Parses `path` (a modelDescription.xml). `shown` names it in messages (the .fmu's path and
// the member). Throws FmuError: unreadable or malformed XML, an fmiVersion other than 2.x
// or 3.x, no <CoSimulation>, a variable without name or valueReference.
ModelDescription ParseModelDescription(const std::string& path, const std::string& shown);

}  // namespace shapebench::bench

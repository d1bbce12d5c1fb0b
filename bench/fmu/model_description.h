// modelDescription.xml of an exported FMU (FMI 2.0 or 3.0 co-simulation), and the FMU's own
// consistency check of such a file (docs/fmi.md#validation): value references unique,
// causality / variability / initial combinations the standard allows with the start values
// they require, every unit declared, every output in the model structure. The XML schema
// check is xmllint's, against the standard's schema files (tests/data/fmi/).
#pragma once

#include <string>
#include <vector>

#include "bench/fmu/fmu_layout.h"

namespace shapebench::bench::fmu {

struct DescriptionInfo {
  std::string model_name;        // the scenario's name
  std::string model_identifier;  // the shared library's name, a C identifier
  std::string token;             // InstantiationToken
  std::string description;
  std::string generation_tool;   // "shapebench VERSION"
  int fmi_version = 2;           // 2 or 3
};

std::string WriteModelDescription(const Layout& layout, const DescriptionInfo& info);

// The problems found in a modelDescription.xml (FMI 2.0 or 3.0, told by fmiVersion), one
// sentence each naming the variable; empty when it is consistent.
std::vector<std::string> CheckModelDescription(const std::string& xml);

// A C identifier made of `name`: other characters become '_', a leading digit gets one.
std::string ModelIdentifier(const std::string& name);

}  // namespace shapebench::bench::fmu

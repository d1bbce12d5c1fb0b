#include "bench/fmu/model_description.h"

#include <cctype>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <pugixml.hpp>

namespace shapebench::bench::fmu {
namespace {

const char* CausalityName(Causality c) {
  switch (c) {
    case Causality::kIndependent: return "independent";
    case Causality::kParameter: return "parameter";
    case Causality::kCalculatedParameter: return "calculatedParameter";
    case Causality::kInput: return "input";
    case Causality::kOutput: return "output";
  }
  return "local";
}

const char* InitialName(Initial i) {
  return i == Initial::kExact ? "exact" : i == Initial::kCalculated ? "calculated" : "";
}

std::string Number(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

void AddUnits(pugi::xml_node root) {
  pugi::xml_node units = root.append_child("UnitDefinitions");
  for (const UnitDefinition& u : UnitDefinitions()) {
    pugi::xml_node unit = units.append_child("Unit");
    unit.append_attribute("name") = u.name.c_str();
    pugi::xml_node base = unit.append_child("BaseUnit");
    if (u.kg != 0) base.append_attribute("kg") = u.kg;
    if (u.m != 0) base.append_attribute("m") = u.m;
    if (u.s != 0) base.append_attribute("s") = u.s;
  }
}

void AddHeader(pugi::xml_node root, const Layout& layout, const DescriptionInfo& info) {
  const bool v3 = info.fmi_version == 3;
  root.append_attribute("fmiVersion") = v3 ? "3.0" : "2.0";
  root.append_attribute("modelName") = info.model_name.c_str();
  root.append_attribute(v3 ? "instantiationToken" : "guid") = info.token.c_str();
  root.append_attribute("description") = info.description.c_str();
  root.append_attribute("generationTool") = info.generation_tool.c_str();
  root.append_attribute("variableNamingConvention") = "structured";
  if (!v3) root.append_attribute("numberOfEventIndicators") = 0;
  pugi::xml_node cs = root.append_child("CoSimulation");
  cs.append_attribute("modelIdentifier") = info.model_identifier.c_str();
  cs.append_attribute("canHandleVariableCommunicationStepSize") =
      layout.part == Part::kMachine ? "true" : "false";
  if (!v3) cs.append_attribute("canNotUseMemoryManagementFunctions") = "true";
  AddUnits(root);
  pugi::xml_node categories = root.append_child("LogCategories");
  for (const char* name : {"logStatusError", "logStatusWarning", "logInfo"}) {
    categories.append_child("Category").append_attribute("name") = name;
  }
  pugi::xml_node experiment = root.append_child("DefaultExperiment");
  experiment.append_attribute("startTime") = "0";
  experiment.append_attribute("stopTime") = Number(layout.stop_s).c_str();
  experiment.append_attribute("stepSize") = Number(layout.step_s).c_str();
}

void SetCommon(pugi::xml_node node, const Variable& v) {
  node.append_attribute("name") = v.name.c_str();
  node.append_attribute("valueReference") = v.value_reference;
  if (!v.description.empty()) node.append_attribute("description") = v.description.c_str();
  node.append_attribute("causality") = CausalityName(v.causality);
  node.append_attribute("variability") = v.variability == Variability::kFixed ? "fixed" : "continuous";
  if (v.initial != Initial::kDefault) node.append_attribute("initial") = InitialName(v.initial);
}

void AddVariables(pugi::xml_node root, const Layout& layout, bool v3) {
  pugi::xml_node variables = root.append_child("ModelVariables");
  for (const Variable& v : layout.variables) {
    pugi::xml_node node = variables.append_child(v3 ? "Float64" : "ScalarVariable");
    SetCommon(node, v);
    pugi::xml_node real = v3 ? node : node.append_child("Real");
    if (!v.unit.empty()) real.append_attribute("unit") = v.unit.c_str();
    if (v.has_start) real.append_attribute("start") = Number(v.start).c_str();
  }
}

bool IsInitialUnknown(const Variable& v) {
  return v.causality == Causality::kOutput || v.causality == Causality::kCalculatedParameter;
}

void AddStructure(pugi::xml_node root, const Layout& layout, bool v3) {
  pugi::xml_node structure = root.append_child("ModelStructure");
  // FMI 2.0 names variables by their 1-based position, FMI 3.0 by value reference.
  pugi::xml_node outputs = v3 ? structure : structure.append_child("Outputs");
  for (const Variable& v : layout.variables) {
    if (v.causality != Causality::kOutput) continue;
    if (v3) outputs.append_child("Output").append_attribute("valueReference") = v.value_reference;
    if (!v3) outputs.append_child("Unknown").append_attribute("index") = v.value_reference + 1;
  }
  pugi::xml_node initial = v3 ? structure : structure.append_child("InitialUnknowns");
  for (const Variable& v : layout.variables) {
    if (!IsInitialUnknown(v)) continue;
    if (v3) initial.append_child("InitialUnknown").append_attribute("valueReference") = v.value_reference;
    if (!v3) initial.append_child("Unknown").append_attribute("index") = v.value_reference + 1;
  }
}

}  // namespace

std::string WriteModelDescription(const Layout& layout, const DescriptionInfo& info) {
  pugi::xml_document doc;
  pugi::xml_node declaration = doc.append_child(pugi::node_declaration);
  declaration.append_attribute("version") = "1.0";
  declaration.append_attribute("encoding") = "UTF-8";
  pugi::xml_node root = doc.append_child("fmiModelDescription");
  AddHeader(root, layout, info);
  AddVariables(root, layout, info.fmi_version == 3);
  AddStructure(root, layout, info.fmi_version == 3);
  std::ostringstream out;
  doc.save(out, "  ", pugi::format_default, pugi::encoding_utf8);
  return out.str();
}

std::string ModelIdentifier(const std::string& name) {
  std::string id;
  for (const char c : name) id += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  if (id.empty() || std::isdigit(static_cast<unsigned char>(id[0]))) id = "_" + id;
  return id;
}

}  // namespace shapebench::bench::fmu

#include "bench/fmi/model_description.h"

#include <cerrno>
#include <cstdlib>
#include <string>

#include <pugixml.hpp>

namespace shapebench::bench {
namespace {

// The 1-based line of an XML node, from its byte offset (pugixml keeps only the offset).
int LineOf(const std::string& text, std::ptrdiff_t offset) {
  int line = 1;
  for (std::ptrdiff_t i = 0; i < offset && i < static_cast<std::ptrdiff_t>(text.size()); ++i) {
    if (text[static_cast<std::size_t>(i)] == '\n') ++line;
  }
  return line;
}

std::optional<double> StartValue(const pugi::xml_node& holder, const std::string& where) {
  const pugi::xml_attribute start = holder.attribute("start");
  if (!start) return std::nullopt;
  const char* text = start.value();
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text, &end);
  if (end == text || *end != '\0') {
    if (holder.name() != std::string("Real") && holder.name() != std::string("Float64")) return std::nullopt;
    throw FmuError(where + ": start=\"" + std::string(text) + "\" is not a number");
  }
  return value;
}

unsigned ValueReference(const pugi::xml_node& variable, const std::string& where) {
  const pugi::xml_attribute vr = variable.attribute("valueReference");
  if (!vr) throw FmuError(where + ": no valueReference");
  const char* text = vr.value();
  char* end = nullptr;
  errno = 0;
  const unsigned long value = std::strtoul(text, &end, 10);
  if (end == text || *end != '\0' || errno != 0 || value > 0xffffffffUL || text[0] == '-') {
    throw FmuError(where + ": valueReference=\"" + std::string(text) + "\" is not an unsigned 32-bit integer");
  }
  return static_cast<unsigned>(value);
}

// One variable: 2.0 <ScalarVariable> with its type element inside, 3.0 the type element itself.
FmuVariable ReadVariable(const pugi::xml_node& variable, FmiVersion version, const std::string& text,
                         const std::string& shown) {
  FmuVariable v;
  v.line = LineOf(text, variable.offset_debug());
  const std::string where = shown + ":" + std::to_string(v.line);
  v.name = variable.attribute("name").value();
  if (v.name.empty()) throw FmuError(where + ": a variable without a name");
  v.value_reference = ValueReference(variable, where + " (" + v.name + ")");
  v.causality = variable.attribute("causality").as_string("local");
  v.variability = variable.attribute("variability").as_string("continuous");
  pugi::xml_node holder = variable;  // where type, unit and start are
  if (version == FmiVersion::k2) {
    holder = variable.first_child();
    while (holder && holder.type() != pugi::node_element) holder = holder.next_sibling();
    if (!holder) throw FmuError(where + " (" + v.name + "): no type element (Real, Integer, ...)");
  } else {
    v.array = static_cast<bool>(variable.child("Dimension"));
  }
  v.type = holder.name();
  v.unit = holder.attribute("unit").value();
  v.start = StartValue(holder, where + " (" + v.name + ")");
  return v;
}

}  // namespace

const FmuVariable* ModelDescription::Find(const std::string& name) const {
  for (const FmuVariable& v : variables) {
    if (v.name == name) return &v;
  }
  return nullptr;
}

std::string ModelDescription::DoubleNames(const std::string& causality) const {
  std::string names;
  int shown = 0;
  for (const FmuVariable& v : variables) {
    if (!v.IsDouble() || v.causality != causality) continue;
    if (++shown > 20) return names + ", ...";
    names += (names.empty() ? "" : ", ") + v.name;
  }
  return names.empty() ? "(none)" : names;
}

ModelDescription ParseModelDescription(const std::string& path, const std::string& shown) {
  pugi::xml_document document;
  std::string text;
  {
    pugi::xml_parse_result parsed = document.load_file(path.c_str());
    if (parsed.status == pugi::status_file_not_found || parsed.status == pugi::status_io_error) {
      throw FmuError(shown + ": cannot be read");
    }
    // The text again for line numbers (offsets are all pugixml keeps).
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (f != nullptr) {
      char buffer[4096];
      std::size_t n;
      while ((n = std::fread(buffer, 1, sizeof buffer, f)) > 0) text.append(buffer, n);
      std::fclose(f);
    }
    if (!parsed) {
      throw FmuError(shown + ":" + std::to_string(LineOf(text, parsed.offset)) + ": malformed XML (" +
                     parsed.description() + ")");
    }
  }
  const pugi::xml_node root = document.child("fmiModelDescription");
  if (!root) throw FmuError(shown + ": no <fmiModelDescription> root element");
  ModelDescription md;
  md.file = shown;
  md.fmi_version = root.attribute("fmiVersion").value();
  if (md.fmi_version.rfind("2.", 0) == 0) {
    md.version = FmiVersion::k2;
    md.token = root.attribute("guid").value();
  } else if (md.fmi_version.rfind("3.", 0) == 0) {
    md.version = FmiVersion::k3;
    md.token = root.attribute("instantiationToken").value();
  } else {
    throw FmuError(shown + ": fmiVersion \"" + md.fmi_version + "\": the master reads FMI 2.0 and 3.0");
  }
  md.model_name = root.attribute("modelName").value();
  const pugi::xml_node cs = root.child("CoSimulation");
  if (!cs) throw FmuError(shown + ": no <CoSimulation> element: the master drives co-simulation FMUs only");
  md.model_identifier = cs.attribute("modelIdentifier").value();
  if (md.model_identifier.empty()) throw FmuError(shown + ": <CoSimulation> without a modelIdentifier");
  md.can_handle_variable_step = cs.attribute("canHandleVariableCommunicationStepSize").as_bool(false);
  md.once_per_process = cs.attribute("canBeInstantiatedOnlyOncePerProcess").as_bool(false);
  const pugi::xml_node variables = root.child("ModelVariables");
  for (const pugi::xml_node& node : variables.children()) {
    if (node.type() != pugi::node_element) continue;
    if (md.version == FmiVersion::k2 && std::string(node.name()) != "ScalarVariable") continue;
    md.variables.push_back(ReadVariable(node, md.version, text, shown));
  }
  return md;
}

}  // namespace shapebench::bench

// CheckModelDescription (model_description.h): the FMU's own consistency, beyond the
// schema (FMI 2.0 section 2.2.7 and FMI 3.0 section 2.4.7: the causality / variability /
// initial table, start values, units, the model structure).
#include <map>
#include <set>
#include <string>
#include <vector>

#include <pugixml.hpp>

#include "bench/fmu/model_description.h"

namespace shapebench::bench::fmu {
namespace {

struct Seen {
  std::string name;
  std::string causality;
  std::string variability;
  std::string initial;
  bool has_start = false;
  std::string unit;
  unsigned value_reference = 0;
};

// The initial values the standard allows for a causality and variability; the first is the
// default. Empty set with ok: initial must be left out. Not ok: the combination is refused.
struct Allowed {
  bool ok = false;
  std::vector<std::string> initials;
};

Allowed AllowedInitials(const std::string& causality, const std::string& variability) {
  const bool fixed_or_tunable = variability == "fixed" || variability == "tunable";
  const bool moving = variability == "discrete" || variability == "continuous";
  if (causality == "independent") return {variability == "continuous", {}};
  if (causality == "input") return {moving, {}};
  if (causality == "parameter") return {fixed_or_tunable, {"exact"}};
  if (causality == "calculatedParameter") return {fixed_or_tunable, {"calculated", "approx"}};
  if (causality == "output") {
    if (variability == "constant") return {true, {"exact"}};
    return {moving, {"calculated", "exact", "approx"}};
  }
  if (causality == "local") {
    if (variability == "constant") return {true, {"exact"}};
    if (fixed_or_tunable) return {true, {"calculated", "approx"}};
    return {moving, {"calculated", "exact", "approx"}};
  }
  return {};
}

// Whether a start value is required (true) or forbidden (false) for this combination.
bool StartRequired(const std::string& causality, const std::string& initial) {
  if (causality == "input") return true;
  if (causality == "independent") return false;
  return initial == "exact" || initial == "approx";
}

void CheckCombination(const Seen& v, std::vector<std::string>* problems) {
  const std::string who = "variable " + v.name + ": ";
  const Allowed allowed = AllowedInitials(v.causality, v.variability);
  if (!allowed.ok) {
    problems->push_back(who + "causality " + v.causality + " with variability " + v.variability +
                        " is not allowed");
    return;
  }
  std::string initial = v.initial;
  if (allowed.initials.empty()) {
    if (!initial.empty()) problems->push_back(who + "initial must be left out for causality " + v.causality);
  } else {
    if (initial.empty()) initial = allowed.initials.front();
    bool listed = false;
    for (const std::string& i : allowed.initials) listed = listed || i == initial;
    if (!listed) {
      problems->push_back(who + "initial " + initial + " is not allowed with causality " + v.causality +
                          " and variability " + v.variability);
    }
  }
  const bool required = StartRequired(v.causality, initial);
  if (required && !v.has_start) problems->push_back(who + "a start value is required");
  if (!required && v.has_start) problems->push_back(who + "a start value is not allowed");
}

std::vector<Seen> ReadVariables(pugi::xml_node root, bool v3) {
  std::vector<Seen> seen;
  for (pugi::xml_node node : root.child("ModelVariables").children()) {
    if (node.type() != pugi::node_element) continue;
    const pugi::xml_node typed = v3 ? node : node.first_child();
    Seen v;
    v.name = node.attribute("name").as_string();
    v.causality = node.attribute("causality").as_string("local");
    v.variability = node.attribute("variability").as_string("continuous");
    v.initial = node.attribute("initial").as_string();
    v.has_start = !typed.attribute("start").empty();
    v.unit = typed.attribute("unit").as_string();
    v.value_reference = node.attribute("valueReference").as_uint(~0u);
    seen.push_back(v);
  }
  return seen;
}

// Every output in the model structure's outputs, and nothing else there.
void CheckStructure(pugi::xml_node root, bool v3, const std::vector<Seen>& vars,
                    std::vector<std::string>* problems) {
  std::set<unsigned> listed;  // value references
  pugi::xml_node structure = root.child("ModelStructure");
  if (v3) {
    for (pugi::xml_node o : structure.children("Output")) listed.insert(o.attribute("valueReference").as_uint(~0u));
  } else {
    for (pugi::xml_node o : structure.child("Outputs").children("Unknown")) {
      const unsigned index = o.attribute("index").as_uint(0);
      if (index == 0 || index > vars.size()) {
        problems->push_back("ModelStructure: output index " + std::to_string(index) + " is no variable");
        continue;
      }
      listed.insert(vars[index - 1].value_reference);
    }
  }
  for (const Seen& v : vars) {
    const bool is_listed = listed.count(v.value_reference) > 0;
    if (v.causality == "output" && !is_listed) problems->push_back("variable " + v.name + ": output missing from ModelStructure");
    if (v.causality != "output" && is_listed) problems->push_back("variable " + v.name + ": listed as an output in ModelStructure but is " + v.causality);
  }
}

}  // namespace

std::vector<std::string> CheckModelDescription(const std::string& xml) {
  std::vector<std::string> problems;
  pugi::xml_document doc;
  const pugi::xml_parse_result parsed = doc.load_string(xml.c_str());
  if (!parsed) return {std::string("not XML: ") + parsed.description()};
  const pugi::xml_node root = doc.child("fmiModelDescription");
  const std::string version = root.attribute("fmiVersion").as_string();
  if (version != "2.0" && version.rfind("3.", 0) != 0) return {"fmiVersion \"" + version + "\" is neither 2.0 nor 3.x"};
  const bool v3 = version != "2.0";
  std::set<std::string> units;
  for (pugi::xml_node u : root.child("UnitDefinitions").children("Unit")) units.insert(u.attribute("name").as_string());
  const std::vector<Seen> vars = ReadVariables(root, v3);
  std::map<unsigned, std::string> by_reference;
  std::set<std::string> names;
  for (const Seen& v : vars) {
    if (v.value_reference == ~0u) problems.push_back("variable " + v.name + ": no valueReference");
    const auto [it, fresh] = by_reference.emplace(v.value_reference, v.name);
    if (!fresh) problems.push_back("variable " + v.name + ": valueReference " + std::to_string(v.value_reference) + " is also variable " + it->second + "'s");
    if (!names.insert(v.name).second) problems.push_back("variable " + v.name + ": the name is used twice");
    if (!v.unit.empty() && units.count(v.unit) == 0) problems.push_back("variable " + v.name + ": unit " + v.unit + " is not in UnitDefinitions");
    CheckCombination(v, &problems);
  }
  CheckStructure(root, v3, vars, &problems);
  return problems;
}

}  // namespace shapebench::bench::fmu

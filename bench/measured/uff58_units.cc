// FRF units from records 9 and 10 (bench/measured/uff58_units.h).
#include "bench/measured/uff58_units.h"

#include <cctype>
#include <vector>

namespace shapebench::bench {
namespace {

constexpr double kStandardGravity = 9.80665;  // m/s^2 per g

struct Quantity {
  const char* label;
  FrfResponse response;
  double scale;
};

const std::vector<Quantity>& Numerators() {
  static const std::vector<Quantity> kQuantities = {
      {"m", FrfResponse::kDisplacement, 1.0},     {"mm", FrfResponse::kDisplacement, 1e-3},
      {"um", FrfResponse::kDisplacement, 1e-6},   {"m/s", FrfResponse::kVelocity, 1.0},
      {"mm/s", FrfResponse::kVelocity, 1e-3},     {"m/s2", FrfResponse::kAcceleration, 1.0},
      {"mm/s2", FrfResponse::kAcceleration, 1e-3}, {"g", FrfResponse::kAcceleration, kStandardGravity}};
  return kQuantities;
}

const Quantity* Numerator(const std::string& normalized) {
  for (const Quantity& q : Numerators()) {
    if (normalized == q.label) return &q;
  }
  return nullptr;
}

struct Denominator {
  FrfExcitation excitation;
  double scale;
};

std::optional<Denominator> DenominatorOf(const std::string& normalized) {
  if (normalized == "n") return Denominator{FrfExcitation::kForce, 1.0};
  if (normalized == "m/s2") return Denominator{FrfExcitation::kAcceleration, 1.0};
  if (normalized == "mm/s2") return Denominator{FrfExcitation::kAcceleration, 1e-3};
  if (normalized == "g") return Denominator{FrfExcitation::kAcceleration, kStandardGravity};
  return std::nullopt;
}

std::optional<FrfResponse> ResponseOfType(long type) {
  if (type == 8) return FrfResponse::kDisplacement;
  if (type == 11) return FrfResponse::kVelocity;
  if (type == 12) return FrfResponse::kAcceleration;
  return std::nullopt;
}

std::optional<FrfExcitation> ExcitationOfType(long type) {
  if (type == 13 || type == 9) return FrfExcitation::kForce;
  if (type == 12) return FrfExcitation::kAcceleration;
  return std::nullopt;
}

// "(1/N)*(m/s2)" -> "1/nm/s2" -> m/s2 per N; "(m/s2)/N", "m/N", "(m/s2)/(m/s2)".
bool SplitCombined(const std::string& u, const Quantity** numerator, std::optional<Denominator>* denominator) {
  if (u.rfind("1/n", 0) == 0 && (*numerator = Numerator(u.substr(3)))) {
    *denominator = Denominator{FrfExcitation::kForce, 1.0};
    return true;
  }
  for (std::size_t slash = u.find('/'); slash != std::string::npos; slash = u.find('/', slash + 1)) {
    const Quantity* top = Numerator(u.substr(0, slash));
    const std::optional<Denominator> bottom = DenominatorOf(u.substr(slash + 1));
    if (top && bottom) {
      *numerator = top;
      *denominator = bottom;
      return true;
    }
  }
  return false;
}

const char* ResponseName(FrfResponse response) {
  switch (response) {
    case FrfResponse::kDisplacement: return "m";
    case FrfResponse::kVelocity: return "m/s";
    case FrfResponse::kAcceleration: return "m/s2";
  }
  return "?";
}

}  // namespace

std::string NormalizedUnits(const std::string& label) {
  std::string u;
  for (std::size_t i = 0; i < label.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(label[i]);
    if (c == 0xc2 && i + 1 < label.size()) continue;  // UTF-8 lead byte of ² and µ
    if (c == 0xb2) {  // ² (latin-1, or the UTF-8 tail)
      u += '2';
    } else if (c == 0xb5) {  // µ
      u += 'u';
    } else if (c == ' ' || c == '(' || c == ')' || c == '[' || c == ']' || c == '\t') {
      continue;
    } else {
      u += static_cast<char>(std::tolower(c));
    }
  }
  for (const char* power : {"**2", "^2"}) {
    for (std::size_t at = u.find(power); at != std::string::npos; at = u.find(power)) u.replace(at, std::string(power).size(), "2");
  }
  for (std::size_t at = u.find('*'); at != std::string::npos; at = u.find('*')) u.erase(at, 1);
  if (u == "none") return "";
  return u;
}

std::optional<FrfUnits> UnderstandFrfUnits(const UffCharacteristics& numerator,
                                           const UffCharacteristics& denominator, std::string* problem,
                                           int* problem_record) {
  const std::string top_label = NormalizedUnits(numerator.units_label);
  const std::string bottom_label = NormalizedUnits(denominator.units_label);
  const Quantity* top = Numerator(top_label);
  std::optional<Denominator> bottom = DenominatorOf(bottom_label);
  std::optional<FrfResponse> response = ResponseOfType(numerator.specific_data_type);
  std::optional<FrfExcitation> excitation = ExcitationOfType(denominator.specific_data_type);
  if (!bottom && !excitation) {
    const Quantity* combined_top = nullptr;
    if (SplitCombined(top_label, &combined_top, &bottom)) top = combined_top;
  }
  FrfUnits units;
  // A label of the same quantity as the type gives the scale (g, mm); a type alone is SI.
  if (response) {
    units.response = *response;
    if (top && top->response == *response) units.scale = top->scale;
  } else if (top) {
    units.response = top->response;
    units.scale = top->scale;
  } else {
    *problem_record = 9;
    *problem = "unknown ordinate units: specific data type " + std::to_string(numerator.specific_data_type) +
               ", units label '" + numerator.units_label +
               "'; expected displacement (8), velocity (11) or acceleration (12), or a units label m, mm, um, "
               "m/s, mm/s, m/s2, mm/s2 or g (or one holding the denominator too, e.g. (m/s2)/N)";
    return std::nullopt;
  }
  if (excitation) {
    units.excitation = *excitation;
    if (bottom && bottom->excitation == *excitation) units.scale /= bottom->scale;
  } else if (bottom) {
    units.excitation = bottom->excitation;
    units.scale /= bottom->scale;
  } else {
    *problem_record = 10;
    *problem = "unknown denominator units: specific data type " + std::to_string(denominator.specific_data_type) +
               ", units label '" + denominator.units_label +
               "'; expected excitation force (13), reaction force (9) or acceleration (12), or a units label N, "
               "m/s2, mm/s2 or g (or a record 9 label holding both, e.g. (m/s2)/N)";
    return std::nullopt;
  }
  units.shown = std::string(ResponseName(units.response)) +
                (units.excitation == FrfExcitation::kForce ? " per N" : " per m/s2");
  return units;
}

}  // namespace shapebench::bench

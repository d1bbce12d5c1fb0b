// What a dataset 58 FRF measures, from records 9 (ordinate numerator) and 10 (ordinate
// denominator): their specific data types first (8 displacement, 11 velocity, 12
// acceleration; 13 excitation force, 9 reaction force), then their units labels (columns
// 48-67), then one label of record 9 holding both (e.g. "(1/N)*(m/s²)", "(m/s2)/N").
#pragma once

#include <optional>
#include <string>

namespace shapebench::bench {

// What the FRF's ordinate numerator measures: its power of (j w) over a receptance.
enum class FrfResponse { kDisplacement = 0, kVelocity = 1, kAcceleration = 2 };
// What it is divided by: an excitation force (an impact or shaker test) or a base
// acceleration (transmissibility).
enum class FrfExcitation { kForce, kAcceleration };

// Records 8-11: Format(I10,3I5,2(1X,20A1)).
struct UffCharacteristics {
  long specific_data_type = 0;
  std::string axis_label;   // trimmed; "NONE" when unused
  std::string units_label;  // trimmed
};

struct FrfUnits {
  FrfResponse response = FrfResponse::kAcceleration;
  FrfExcitation excitation = FrfExcitation::kForce;
  double scale = 1.0;  // to SI: m, m/s, m/s^2 per N or per m/s^2
  std::string shown;   // e.g. "m/s2 per N"
};

// The label's quantity and scale, lower-cased with blanks, brackets and '*' dropped and
// ², ^2, **2 read as 2, µ as u: m, mm, um, m/s, mm/s, m/s2, mm/s2, g (numerators);
// n, m/s2, mm/s2, g (denominators). Empty when it is none of them.
std::string NormalizedUnits(const std::string& label);

// The units of an FRF, or nullopt with *problem saying which record (9 or 10) is unknown
// and *problem_record its number.
std::optional<FrfUnits> UnderstandFrfUnits(const UffCharacteristics& numerator,
                                           const UffCharacteristics& denominator, std::string* problem,
                                           int* problem_record);

}  // namespace shapebench::bench

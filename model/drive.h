// The drive between command and plant.
#pragma once

namespace shapebench::model {

enum class DriveType { kKinematic };

// kinematic: the driven point follows the command exactly, the command's acceleration
// held over each interpolation period (SPEC section 3).
struct DriveConfig {
  DriveType type = DriveType::kKinematic;
};

}  // namespace shapebench::model

// The G-code dialects the bench reads (`program_dialect:`), and what differs between them,
// each from its controller's manual (docs/gcode.md lists them side by side):
//   fanuc     Fanuc Series 0i/30i (the default): G4 P in ms without a decimal point, or
//             X/U in s; G61 and G64 without P/Q; I/J/K always incremental.
//   linuxcnc  LinuxCNC's RS274NGC: G4 P in s; G61, G61.1, G64 [P [Q]]; G90.1/G91.1;
//             G28/G30 without axis words return every axis.
//   grbl      grbl 1.1: G4 P in s; G61 only (grbl's junction rule); G91.1 only; G28/G30
//             as LinuxCNC.
// G codes are handled in tenths (G90.1 is 901, G1 is 10) so that the decimal ones stay
// exact integers.
#pragma once

#include <optional>
#include <string>

#include <Eigen/Dense>

namespace shapebench::controller {

enum class Dialect { kFanuc, kLinuxcnc, kGrbl };

const char* DialectName(Dialect dialect);  // "fanuc", "linuxcnc", "grbl"

// When an arc's end point counts as on its circle: the start and end radii (in the plane)
// differ by at most absolute_mm, or by at most relative * radius and max_mm at once.
struct ArcTolerance {
  double absolute_mm = 0.0;
  double relative = 0.0;
  double max_mm = 0.0;
};

// Fanuc: the bench's 1 um (the least input increment; parameter No. 3410 is the machine
// builder's) or 1e-6 of the radius. LinuxCNC and grbl (the same rule in both): 0.005 mm,
// or up to 0.5 mm when within 0.1 % of the radius.
ArcTolerance DefaultArcTolerance(Dialect dialect);

bool ArcEndAccepted(const ArcTolerance& tolerance, double difference_mm, double radius_mm);

// The largest accepted difference at `radius_mm`, for messages.
double ArcToleranceAtMm(const ArcTolerance& tolerance, double radius_mm);

// How the part-program words are read: the dialect and the settings it leaves to the
// machine. `*_key` names each setting in messages (the scenario's keys).
struct ProgramOptions {
  Dialect dialect = Dialect::kFanuc;
  std::optional<ArcTolerance> arc_tolerance;  // unset: DefaultArcTolerance(dialect)
  std::optional<Eigen::Vector3d> g28_mm;      // G28's reference position (machine = part)
  std::optional<Eigen::Vector3d> g30_mm;      // G30's
  // Loop passes, subroutine calls and M99 jumps a program may make (subprogram_expander.h).
  long max_iterations = 1000000;
  std::string dialect_key = "program_dialect";
  std::string max_iterations_key = "program_max_iterations";
  std::string reference_key = "machine.reference_mm";
  std::string arc_tolerance_key = "program_arc_tolerance";

  ArcTolerance ArcRule() const {
    return arc_tolerance ? *arc_tolerance : DefaultArcTolerance(dialect);
  }
};

// The G code of a G word's value in tenths (G90.1 -> 901), -1 when it has more than one
// decimal or is out of range.
int GTenths(double value);

// "G90.1" for 901.
std::string GName(int tenths);

// Whether `dialect` has the G code (those ProgramBuilder models).
bool DialectHasG(Dialect dialect, int tenths);

// The dialects other than `dialect` that have the G code, "linuxcnc and grbl"; "" if none.
std::string OtherDialectsWithG(Dialect dialect, int tenths);

// The words a program of `dialect` may hold, for "allowed: ..." in messages.
std::string AllowedWords(Dialect dialect);

}  // namespace shapebench::controller

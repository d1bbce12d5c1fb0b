#include "controller/gcode_dialect.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace shapebench::controller {

const char* DialectName(Dialect dialect) {
  switch (dialect) {
    case Dialect::kLinuxcnc: return "linuxcnc";
    case Dialect::kGrbl: return "grbl";
    case Dialect::kFanuc: break;
  }
  return "fanuc";
}

ArcTolerance DefaultArcTolerance(Dialect dialect) {
  if (dialect == Dialect::kFanuc) {
    return {0.001, 1e-6, std::numeric_limits<double>::infinity()};
  }
  // LinuxCNC's rs274ngc and grbl's gcode.c: an error above 0.5 mm, or above 0.005 mm and
  // 0.1 % of the radius.
  return {0.005, 1e-3, 0.5};
}

bool ArcEndAccepted(const ArcTolerance& tolerance, double difference_mm, double radius_mm) {
  if (difference_mm <= tolerance.absolute_mm) return true;
  return difference_mm <= tolerance.max_mm && difference_mm <= tolerance.relative * radius_mm;
}

double ArcToleranceAtMm(const ArcTolerance& tolerance, double radius_mm) {
  return std::max(tolerance.absolute_mm,
                  std::min(tolerance.max_mm, tolerance.relative * radius_mm));
}

int GTenths(double value) {
  if (!(value >= 0 && value <= 1000)) return -1;
  const double tenths = std::round(value * 10);
  if (std::abs(tenths - value * 10) > 1e-6) return -1;
  return static_cast<int>(tenths);
}

std::string GName(int tenths) {
  std::string name = "G" + std::to_string(tenths / 10);
  if (tenths % 10 != 0) name += "." + std::to_string(tenths % 10);
  return name;
}

bool DialectHasG(Dialect dialect, int tenths) {
  static const std::vector<int> kAll = {0,   10,  20,  30,  40,  170, 180, 190,
                                        200, 210, 280, 300, 610, 900, 910};
  if (std::find(kAll.begin(), kAll.end(), tenths) != kAll.end()) return true;
  switch (tenths) {
    case 640: return dialect != Dialect::kGrbl;             // grbl: G61 only
    case 611: case 901: return dialect == Dialect::kLinuxcnc;
    case 911: return dialect != Dialect::kFanuc;             // Fanuc: I/J/K incremental
    default: return false;
  }
}

std::string OtherDialectsWithG(Dialect dialect, int tenths) {
  std::string names;
  for (const Dialect other : {Dialect::kFanuc, Dialect::kLinuxcnc, Dialect::kGrbl}) {
    if (other == dialect || !DialectHasG(other, tenths)) continue;
    names += (names.empty() ? "" : " and ") + std::string(DialectName(other));
  }
  return names;
}

std::string AllowedWords(Dialect dialect) {
  std::string path_modes = "G61, G64";
  std::string arc_modes;
  std::string dwell = "P (ms, no decimal point) or X/U (s)";
  if (dialect == Dialect::kLinuxcnc) {
    path_modes = "G61, G61.1, G64 (P, Q)";
    arc_modes = "G90.1, G91.1, ";
    dwell = "P (s)";
  } else if (dialect == Dialect::kGrbl) {
    path_modes = "G61";
    arc_modes = "G91.1, ";
    dwell = "P (s)";
  }
  return "G0-G3, G4 with " + dwell + ", G17-G19, G20, G21, G28, G30, " + path_modes + ", G90, "
         "G91, " + arc_modes + "G40, G43, G44, G49, G54-G59, G80, G94, F, X, Y, Z, I, J, K, R, "
         "N, and O, T, S, H, D, M (read and ignored)";
}

}  // namespace shapebench::controller

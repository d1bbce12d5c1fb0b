#include "controller/program_arcs.h"

#include <algorithm>
#include <cmath>

#include "common/format.h"

namespace shapebench::controller {
namespace {

// An arc's end coincides with its start (a full circle) within 1e-6 mm in the plane.
constexpr double kCoincideM = 1e-9;

std::string PlaneName(Plane plane) {
  switch (plane) {
    case Plane::kZX: return "G18 (ZX plane)";
    case Plane::kYZ: return "G19 (YZ plane)";
    case Plane::kXY: break;
  }
  return "G17 (XY plane)";
}

std::string PlaneCentreWords(Plane plane) {
  switch (plane) {
    case Plane::kZX: return "K, I";
    case Plane::kYZ: return "J, K";
    case Plane::kXY: break;
  }
  return "I, J";
}

std::string Mm(double metres) { return FormatNumber(metres * 1e3) + " mm"; }

// I/J/K: only the two of the plane.
void CheckArcCentreWords(const BlockWords& words, const ProgramBlock& arc, PlaneAxes axes) {
  for (int a = 0; a < kNumAxes; ++a) {
    const int w = words.at(kCentreLetters[a]);
    if (w >= 0 && a == axes.n) {
      throw words.WordError(w, "'" + words.Shown(w) + "' is not a centre word of " +
                                   PlaneName(arc.plane) + "; allowed: " +
                                   PlaneCentreWords(arc.plane));
    }
  }
}

// I/J/K or R, exactly one of the two forms.
void RequireOneCentreForm(const BlockWords& words, MotionKind motion) {
  const int r_word = words.at('R');
  const int first_centre_word = words.FirstCentreWord();
  if (r_word >= 0 && first_centre_word >= 0) {
    throw words.WordError(r_word, "an arc takes its centre as I/J/K or as R, not both");
  }
  if (r_word < 0 && first_centre_word < 0) {
    const std::string message =
        "an arc (" + MotionName(motion) + ") needs its centre: I/J/K offsets or a radius R";
    throw words.motion_word() >= 0 ? words.WordError(words.motion_word(), message)
                                   : words.BlockError(message);
  }
}

// The arc's chord start -> end in its plane.
struct Chord {
  double du, dv, length;
};

Chord ChordOf(const ProgramBlock& arc, PlaneAxes axes) {
  const double du = arc.end_m[axes.u] - arc.start_m[axes.u];
  const double dv = arc.end_m[axes.v] - arc.start_m[axes.v];
  return {du, dv, std::hypot(du, dv)};
}

// The dialect's tolerance at `radius_m`, in m.
double ToleranceM(const ArcContext& context, double radius_m) {
  return ArcToleranceAtMm(context.tolerance, radius_m * 1e3) * 1e-3;
}

// R: the centre on the chord's perpendicular bisector, on the side G2/G3 and R's sign say.
Eigen::Vector3d CentreFromRadius(const BlockWords& words, const ArcContext& context,
                                 const ProgramBlock& arc, PlaneAxes axes, const Chord& chord,
                                 bool full_circle) {
  const int r_word = words.at('R');
  const double r = words.value(r_word) * context.unit_m;
  if (r == 0) throw words.WordError(r_word, "R must not be 0");
  if (full_circle) {
    throw words.WordError(r_word, "R cannot describe a full circle (the end point is the "
                                  "start point); use I/J/K");
  }
  const double half_chord = chord.length / 2;
  const double radius = std::abs(r);
  if (radius < half_chord - ToleranceM(context, radius)) {
    throw words.WordError(r_word, "'" + words.Shown(r_word) + "' is shorter than half the "
                                  "chord (" + Mm(half_chord) + "); allowed: |R| >= " +
                                  Mm(half_chord));
  }
  const double h = std::sqrt(std::max(0.0, radius * radius - half_chord * half_chord));
  // (nu, nv): the unit normal to the left of the chord's direction start -> end. A CCW
  // arc of at most 180 degrees has its centre on the left, a CW one on the right; R < 0
  // (the longer arc) swaps the sides.
  const double nu = -chord.dv / chord.length;
  const double nv = chord.du / chord.length;
  const double side = (arc.kind == MotionKind::kArcCcw ? 1.0 : -1.0) * (r > 0 ? 1.0 : -1.0);
  const Eigen::Vector3d& start = arc.start_m;
  Eigen::Vector3d centre = start;
  centre[axes.u] = start[axes.u] + chord.du / 2 + side * h * nu;
  centre[axes.v] = start[axes.v] + chord.dv / 2 + side * h * nv;
  return centre;
}

// I/J/K: offsets from the start (G91.1) or the centre itself (G90.1, both words needed).
Eigen::Vector3d CentreOfWords(const BlockWords& words, const ArcContext& context,
                              const ProgramBlock& arc, PlaneAxes axes) {
  Eigen::Vector3d centre = arc.start_m;
  for (const int a : {axes.u, axes.v}) {
    const int w = words.at(kCentreLetters[a]);
    if (w >= 0) {
      centre[a] = (context.absolute_centre ? 0.0 : arc.start_m[a]) + words.value(w) * context.unit_m;
    } else if (context.absolute_centre) {
      throw words.WordError(words.FirstCentreWord(),
                            "under G90.1 (absolute arc centre) an arc needs both centre words "
                            "of " + PlaneName(arc.plane) + " (" + PlaneCentreWords(arc.plane) +
                            "); '" + std::string(1, kCentreLetters[a]) + "' is missing");
    }
  }
  return centre;
}

// The centre of I/J/K; the end must lie on the circle (the dialect's rule).
Eigen::Vector3d CentreFromOffsets(const BlockWords& words, const ArcContext& context,
                                  const ProgramBlock& arc, PlaneAxes axes) {
  const Eigen::Vector3d centre = CentreOfWords(words, context, arc, axes);
  const Eigen::Vector3d& start = arc.start_m;
  const Eigen::Vector3d& end = arc.end_m;
  const double start_radius =
      std::hypot(start[axes.u] - centre[axes.u], start[axes.v] - centre[axes.v]);
  const double end_radius = std::hypot(end[axes.u] - centre[axes.u], end[axes.v] - centre[axes.v]);
  const int first_centre_word = words.FirstCentreWord();
  if (start_radius <= kCoincideM) {
    throw words.WordError(first_centre_word,
                          "arc radius is 0: the centre given by I/J/K is the start point");
  }
  const double difference = std::abs(start_radius - end_radius);
  const double radius = std::max(start_radius, end_radius);
  if (!ArcEndAccepted(context.tolerance, difference * 1e3, radius * 1e3)) {
    throw words.WordError(first_centre_word,
                          "arc end point is not on the circle: start radius " +
                              Mm(start_radius) + ", end radius " + Mm(end_radius) +
                              " (difference " + Mm(difference) + "); allowed: at most " +
                              Mm(ToleranceM(context, radius)) + " (the " +
                              DialectName(words.dialect()) + " rule; " + context.tolerance_key +
                              " sets it)");
  }
  return centre;
}

}  // namespace

std::string MotionName(MotionKind motion) {
  return motion == MotionKind::kRapid    ? "G0"
         : motion == MotionKind::kLinear ? "G1"
         : motion == MotionKind::kArcCw  ? "G2"
                                         : "G3";
}

bool CompleteArc(const BlockWords& words, const ArcContext& context, ProgramBlock* arc) {
  const PlaneAxes axes = AxesOf(arc->plane);
  CheckArcCentreWords(words, *arc, axes);
  if (!words.HasAxisWord() && words.FirstCentreWord() < 0 && words.at('R') < 0) return false;
  RequireOneCentreForm(words, arc->kind);
  const Chord chord = ChordOf(*arc, axes);
  const bool full_circle = chord.length <= kCoincideM;
  if (full_circle) {
    arc->end_m[axes.u] = arc->start_m[axes.u];
    arc->end_m[axes.v] = arc->start_m[axes.v];
  }
  arc->center_m = words.at('R') >= 0
                      ? CentreFromRadius(words, context, *arc, axes, chord, full_circle)
                      : CentreFromOffsets(words, context, *arc, axes);
  return true;
}

}  // namespace shapebench::controller

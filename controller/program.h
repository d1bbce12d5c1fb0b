// A part program as the planner sees it: blocks with absolute end points in metres, the
// modal state (G90/G91, G17-G19, F) already resolved. Built from `program:` (YAML list),
// `program_file:` (G-code) or `move:` (one block) by ProgramBuilder.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace shapebench::controller {

constexpr int kNumAxes = 3;  // x, y, z: index 0, 1, 2 everywhere

enum class MotionKind { kRapid, kLinear, kArcCw, kArcCcw, kDwell };  // G0 G1 G2 G3 G4

// The arc plane and its axes (first, second, normal): G17 XY (x, y, z), G18 ZX (z, x, y),
// G19 YZ (y, z, x). CW/CCW are seen from the positive normal axis, as on Fanuc.
enum class Plane { kXY, kZX, kYZ };

// A plane's first (u), second (v) and normal (n) axis indices.
struct PlaneAxes {
  int u, v, n;
};

constexpr PlaneAxes AxesOf(Plane plane) {
  switch (plane) {
    case Plane::kZX: return {2, 0, 1};
    case Plane::kYZ: return {1, 2, 0};
    case Plane::kXY: break;
  }
  return {0, 1, 2};
}

struct ProgramBlock {
  MotionKind kind = MotionKind::kLinear;
  Eigen::Vector3d start_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d end_m = Eigen::Vector3d::Zero();
  // Arcs: the absolute centre; its normal-axis coordinate equals start_m's. An arc whose
  // end equals its start (in the plane) is a full circle. A change of the normal-axis
  // coordinate makes a helix.
  Eigen::Vector3d center_m = Eigen::Vector3d::Zero();
  Plane plane = Plane::kXY;
  // The F word in effect, m/s; NaN when none was programmed yet (the planner then uses
  // controller.feed_mm_min). Rapid blocks run at controller.rapid_feed_mm_min instead.
  double feed_m_s = NAN;
  double dwell_s = 0.0;  // G4
  // LinuxCNC's G64 in effect at the block's end (controller/corner_blend.h): >= 0 the
  // corner it ends in may be rounded by a tangent arc whose midpoint lies within this
  // distance of the corner (G64 P, m; infinity for G64 without P: the best speed, no
  // tolerance); < 0 (G61, G61.1, every mode of fanuc and grbl): no blending, the corner
  // rule (grbl: its junction rule, junction_deviation_rule below). merge_tolerance_m:
  // G64 Q, collinear lines within it run as one (0: none).
  double blend_tolerance_m = -1.0;
  double merge_tolerance_m = 0.0;
  // Where the block came from, for messages: the G-code line (1-based) or the index of
  // the `program:` entry (0-based).
  int source_line = 0;
};

struct Program {
  Eigen::Vector3d start_m = Eigen::Vector3d::Zero();
  std::vector<ProgramBlock> blocks;
  // What the reader dropped and the run should say (e.g. the G-code words the bench does
  // not model, controller/gcode_parser.h); GenerateProgramCommand passes them on.
  std::vector<std::string> warnings;
  // The blocks' source_line are G-code line numbers (ParseGcode), not `program:` indices.
  bool gcode_lines = false;
  // The G-code file those lines are in, as the scenario resolved it ("" for `program:`,
  // `move:` and text parsed without a file): where a run's attribution points.
  std::string source_file;
  // grbl's dialect: every junction takes grbl's junction-deviation speed
  // (controller.junction_deviation_mm, controller/block_planner.h) instead of the corner rule.
  bool junction_deviation_rule = false;
};

}  // namespace shapebench::controller

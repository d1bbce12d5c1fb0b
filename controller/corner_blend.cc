#include "controller/corner_blend.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace shapebench::controller {
namespace {

bool Blends(const ProgramBlock& block) { return block.blend_tolerance_m >= 0.0; }

bool StraightFeed(const PathElement& e) { return e.kind == MotionKind::kLinear && e.length_m > 0.0; }

bool SameFeed(double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }

// A straight stretch of the blended path: programmed elements first..last (more than one
// when Q merged them), and how much of each end the blends take.
struct Line {
  Eigen::Vector3d start_m, end_m, direction;
  double length_m = 0.0;
  std::size_t first = 0, last = 0;
  double trim_start_m = 0.0, trim_end_m = 0.0;
  double source_start_m = 0.0, source_length_m = 0.0;
  // The programmed path's arc length at `x` metres along the stretch.
  double SourceAt(double x) const { return source_start_m + x / length_m * source_length_m; }
};

// Whether the inner vertices of elements first..last lie within `tolerance` of the line
// from first's start to last's end, between its ends.
bool WithinChord(const std::vector<PathElement>& elements, std::size_t first, std::size_t last, double tolerance) {
  const Eigen::Vector3d& a = elements[first].start_m;
  const Eigen::Vector3d chord = elements[last].end_m - a;
  const double length = chord.norm();
  if (length == 0.0) return false;
  const Eigen::Vector3d d = chord / length;
  for (std::size_t i = first; i < last; ++i) {
    const Eigen::Vector3d v = elements[i].end_m - a;
    const double along = v.dot(d);
    if (along < 0.0 || along > length || (v - along * d).norm() > tolerance) return false;
  }
  return true;
}

// The stretch starting at straight element i: with G64 Q, as far as the merge reaches.
Line StretchAt(const Program& program, const std::vector<PathElement>& elements, std::size_t i) {
  std::size_t last = i;
  while (last + 1 < elements.size() && last + 1 - i < static_cast<std::size_t>(kMaxMerged)) {
    const ProgramBlock& here = program.blocks[static_cast<std::size_t>(elements[last].block)];
    const std::size_t next = last + 1;
    if (!(Blends(here) && here.merge_tolerance_m > 0.0 && StraightFeed(elements[next]) &&
          SameFeed(program.blocks[static_cast<std::size_t>(elements[next].block)].feed_m_s,
                   program.blocks[static_cast<std::size_t>(elements[i].block)].feed_m_s) &&
          WithinChord(elements, i, next, here.merge_tolerance_m))) {
      break;
    }
    last = next;
  }
  Line line;
  line.first = i;
  line.last = last;
  line.start_m = elements[i].start_m;
  line.end_m = elements[last].end_m;
  line.length_m = i == last ? elements[i].length_m : (line.end_m - line.start_m).norm();
  line.direction = i == last ? elements[i].direction : Eigen::Vector3d((line.end_m - line.start_m) / line.length_m);
  line.source_start_m = elements[i].source_start_s_m;
  line.source_length_m = elements[last].source_start_s_m + elements[last].source_length_m - line.source_start_m;
  return line;
}

// The part of a stretch the blends leave (the programmed element itself when they leave
// all of a single block); nothing when they take it all.
void EmitPiece(const Line& line, const std::vector<PathElement>& elements, std::vector<PathElement>* out) {
  if (line.first == line.last && line.trim_start_m == 0.0 && line.trim_end_m == 0.0) {
    out->push_back(elements[line.first]);
    return;
  }
  const double length = line.length_m - line.trim_start_m - line.trim_end_m;
  if (!(length > 0.0)) return;
  PathElement e = elements[line.first];
  e.start_m = line.trim_start_m > 0.0 ? Eigen::Vector3d(line.start_m + line.trim_start_m * line.direction) : line.start_m;
  e.end_m = line.trim_end_m > 0.0 ? Eigen::Vector3d(line.end_m - line.trim_end_m * line.direction) : line.end_m;
  e.direction = line.direction;
  e.length_m = length;
  e.source_start_s_m = line.SourceAt(line.trim_start_m);
  e.source_length_m = line.SourceAt(line.length_m - line.trim_end_m) - e.source_start_s_m;
  out->push_back(e);
}

// The blend's tangent length at the corner from `a` to `b` under tolerance P (0: none),
// its radius and turn.
double TangentLength(const Line& a, const Line& b, double tolerance_m, double min_radius_m, double* radius_m,
                     double* turn_rad) {
  const Eigen::Vector3d& d1 = a.direction;
  const Eigen::Vector3d& d2 = b.direction;
  if ((d2 - d1).cwiseAbs().maxCoeff() <= 1e-9) return 0.0;  // no corner (the planner's test)
  const double turn = std::atan2(d1.cross(d2).norm(), d1.dot(d2));
  const double half_cos = std::cos(0.5 * turn);
  if (half_cos < 1e-6) return 0.0;  // a reversal: the arc would shrink to the corner
  const double half_tan = std::tan(0.5 * turn);
  double length = 0.5 * std::min(a.length_m, b.length_m);
  // r (1 / cos(theta/2) - 1) <= P.
  if (std::isfinite(tolerance_m)) length = std::min(length, tolerance_m * half_cos / (1.0 - half_cos) * half_tan);
  if (!(length > 0.0 && half_tan > 0.0 && length / half_tan >= min_radius_m)) return 0.0;
  *radius_m = length / half_tan;
  *turn_rad = turn;
  return length;
}

PathElement BlendArc(const Line& a, const Line& b, double length_m, double radius_m, double turn_rad,
                     int block) {
  PathElement e;
  e.kind = MotionKind::kArcCcw;
  e.blend = true;
  e.block = block;
  e.start_m = a.end_m - length_m * a.direction;
  e.end_m = b.start_m + length_m * b.direction;
  const Eigen::Vector3d inward = (b.direction - a.direction.dot(b.direction) * a.direction).normalized();
  e.center_m = e.start_m + radius_m * inward;
  e.u_dir = -inward;
  e.v_dir = a.direction;
  e.start_radius_m = radius_m;
  e.end_radius_m = radius_m;
  e.sweep_rad = turn_rad;
  e.length_m = radius_m * turn_rad;
  e.source_start_s_m = a.SourceAt(a.length_m - length_m);
  e.source_length_m = b.SourceAt(length_m) - e.source_start_s_m;
  return e;
}

}  // namespace

std::optional<PathGeometry> BlendCorners(const Program& program, const PathGeometry& programmed,
                                         double min_radius_m) {
  if (std::none_of(program.blocks.begin(), program.blocks.end(), Blends)) return std::nullopt;
  const std::vector<PathElement>& elements = programmed.elements();
  std::vector<PathElement> out;
  out.reserve(elements.size() * 2);
  std::optional<Line> pending;  // the last stretch, its end not yet known
  for (std::size_t i = 0; i < elements.size();) {
    if (!StraightFeed(elements[i])) {
      if (pending) EmitPiece(*pending, elements, &out);
      pending.reset();
      out.push_back(elements[i++]);
      continue;
    }
    Line line = StretchAt(program, elements, i);
    i = line.last + 1;
    if (pending) {
      const ProgramBlock& corner_block = program.blocks[static_cast<std::size_t>(elements[pending->last].block)];
      double radius = 0.0, turn = 0.0;
      const double length =
          Blends(corner_block)
              ? TangentLength(*pending, line, corner_block.blend_tolerance_m, min_radius_m, &radius, &turn)
              : 0.0;
      if (length > 0.0) {
        pending->trim_end_m = length;
        line.trim_start_m = length;
        EmitPiece(*pending, elements, &out);
        out.push_back(BlendArc(*pending, line, length, radius, turn, elements[pending->last].block));
      } else {
        EmitPiece(*pending, elements, &out);
      }
    }
    pending = line;
  }
  if (pending) EmitPiece(*pending, elements, &out);
  return PathGeometry(programmed.start_m(), std::move(out));
}

double SourcePosition(const PathGeometry& blended, double s_m, std::size_t* hint) {
  if (blended.elements().empty()) return s_m;
  *hint = blended.ElementAt(s_m, *hint);
  const PathElement& e = blended.elements()[*hint];
  if (e.length_m == 0.0) return e.source_start_s_m;
  const double fraction = std::clamp((s_m - e.start_s_m) / e.length_m, 0.0, 1.0);
  return e.source_start_s_m + fraction * e.source_length_m;
}

}  // namespace shapebench::controller

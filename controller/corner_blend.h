// LinuxCNC's G64 (continuous path mode): the corners between straight feed moves rounded
// within the path tolerance, the path the interpolator then runs.
//
// Geometry. Two lines meeting at corner C with unit directions d1, d2 turn by
// theta = atan2(|d1 x d2|, d1 . d2). The blend is the circular arc of radius r tangent to
// both, in their plane: it leaves the first line and joins the second at L = r tan(theta/2)
// from C. Its midpoint, on the bisector, is the point furthest from C, at
// r (1 / cos(theta/2) - 1); P bounds that distance, as LinuxCNC's blend arcs do
// (blendmath.c: the tolerance is the distance from the corner to the arc), so every point
// of the blend lies within P of the corner and within r (1 - cos(theta/2)) <= P of the
// programmed lines. L is further limited to half of each line (the other half may be
// taken by the blend at the line's other end). G64 without P: only that limit (LinuxCNC:
// the best speed, no tolerance). No blend where P is 0, at a reversal
// (cos(theta/2) < 1e-6), or where either block is not a straight feed move (G0, arcs,
// dwells, zero-length blocks), or where r < min_radius_m: there the planner's corner rule
// applies. GenerateProgramCommand sets min_radius_m = 16 a T^2, a blend speed sqrt(a r) of
// 4 a T (8 mm/s at 2 m/s^2 and 1 ms): below it the periods the planner's guards hold at the
// blend's speed (block_planner.cc) cost more than the stop (a square of 2.5 mm blocks ran
// slower than under G61 at P 0.004 mm, r = 15 um).
//
// Q (LinuxCNC's naive CAM detector): consecutive straight feed moves at one feed whose
// inner vertices all lie within Q of the line from the first's start to the last's end
// are run as that one line (at most kMaxMerged blocks), before the corners are blended.
//
// Speed (controller/block_planner.h): a blend is run at one speed, at most the lower feed
// of the two blocks and sqrt(a r), so its centripetal acceleration v^2 / r, the only
// acceleration on it, stays within the acc/dec's a on every axis; the speed changes happen
// on the lines, where each axis sees a times its direction cosine. The look-ahead's
// backward pass lowers a blend's speed until the lines after it can slow down for what
// follows.
#pragma once

#include <optional>

#include "controller/path_geometry.h"
#include "controller/program.h"

namespace shapebench::controller {

constexpr int kMaxMerged = 64;  // G64 Q: blocks merged into one line at most

// The blended path, or nothing when no block of `program` is under G64 (the programmed
// path is then the one run, bit for bit). Each element's block is the programmed block
// it starts in, and source_start_s_m/source_length_m place it on `programmed`.
std::optional<PathGeometry> BlendCorners(const Program& program, const PathGeometry& programmed,
                                         double min_radius_m = 0.0);

// The programmed path's arc length at arc length `s_m` of `blended` (linear within each
// element; `hint` as PathGeometry::ElementAt's).
double SourcePosition(const PathGeometry& blended, double s_m, std::size_t* hint);

}  // namespace shapebench::controller

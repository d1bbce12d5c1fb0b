#include "controller/program_builder.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "common/format.h"
#include "controller/block_words.h"
#include "controller/program_arcs.h"

namespace shapebench::controller {
namespace {

constexpr double kInchM = 25.4e-3;
constexpr double kMinuteS = 60.0;

// The modal state after the block's words (G17-G19, G20/G21, G90/G91, G90.1/G91.1, F,
// G0-G3).

Plane PlaneAfter(const BlockWords& words, Plane plane) {
  if (words.plane_word() < 0) return plane;
  const int code = words.code(words.plane_word());
  return code == 170 ? Plane::kXY : code == 180 ? Plane::kZX : Plane::kYZ;
}

bool IncrementalAfter(const BlockWords& words, bool incremental) {
  return words.distance_word() >= 0 ? words.code(words.distance_word()) == 910 : incremental;
}

bool AbsoluteCentreAfter(const BlockWords& words, bool absolute) {
  const int w = words.arc_distance_word();
  return w >= 0 ? words.code(w) == 901 : absolute;
}

double UnitAfter(const BlockWords& words, double unit_m) {
  const int w = words.units_word();
  return w >= 0 ? (words.code(w) == 200 ? kInchM : 1e-3) : unit_m;
}

// F in mm/min or in/min, checked (0 < F, at most kMaxFeedMmMin in mm/min), as m/s.
double FeedAfter(const BlockWords& words, double feed_m_s, double unit_m) {
  const int f = words.at('F');
  if (f < 0) return feed_m_s;
  const double feed = words.value(f);
  const std::string unit = unit_m == kInchM ? "in/min, G20" : "mm/min";
  if (!(feed > 0)) {
    throw words.WordError(f, "F must be > 0 (" + unit + "), got '" + words.Shown(f) + "'");
  }
  if (feed * unit_m * 1e3 > kMaxFeedMmMin) {
    throw words.WordError(f, "F must be at most " +
                                 (unit_m == kInchM ? FormatNumber(kMaxFeedMmMin / 25.4, 7)
                                                   : std::string("1000000")) +
                                 " (" + unit + "), got '" + words.Shown(f) + "'");
  }
  return feed * unit_m / kMinuteS;
}

MotionKind MotionAfter(const BlockWords& words, MotionKind motion) {
  if (words.motion_word() < 0) return motion;
  static constexpr MotionKind kKinds[] = {MotionKind::kRapid, MotionKind::kLinear,
                                          MotionKind::kArcCw, MotionKind::kArcCcw};
  return kKinds[words.code(words.motion_word()) / 10];
}

bool IsArc(MotionKind motion) {
  return motion == MotionKind::kArcCw || motion == MotionKind::kArcCcw;
}

bool IsFanuc(const BlockWords& words) { return words.dialect() == Dialect::kFanuc; }

// The words that belong to one G code only: P (G4, G64), Q (G64), U (Fanuc's G4).
void CheckBoundWords(const BlockWords& words) {
  const int nonmodal = words.nonmodal_word();
  const bool dwell = nonmodal >= 0 && words.code(nonmodal) == 40;
  const int mode = words.path_mode_word();
  const bool blending = mode >= 0 && words.code(mode) == 640;
  const std::string dialect = DialectName(words.dialect());
  if (words.at('P') >= 0 && !dwell && !blending) {
    throw words.WordError(words.at('P'), "'" + words.Shown(words.at('P')) + "': P is allowed "
                                         "only with G4 (dwell) or linuxcnc's G64 (blending "
                                         "tolerance)");
  }
  if (words.at('Q') >= 0 && !blending) {
    throw words.WordError(words.at('Q'), "'" + words.Shown(words.at('Q')) + "': Q is allowed "
                                         "only with linuxcnc's G64 P (naive CAM tolerance)");
  }
  if (words.at('U') >= 0 && !(dwell && IsFanuc(words))) {
    throw words.WordError(words.at('U'), "'" + words.Shown(words.at('U')) + "': U is allowed "
                                         "only as fanuc's G4 dwell time in s (the bench has "
                                         "no U axis); dialect " + dialect);
  }
}

// Fanuc's G4: P in ms without a decimal point, or X/U in s; no motion in the block.
double FanucDwellSeconds(const BlockWords& words) {
  if (words.motion_word() >= 0) {
    throw words.WordError(words.motion_word(),
                          "G4 (dwell) cannot share a block with '" +
                              words.Shown(words.motion_word()) + "' in the fanuc dialect "
                              "(linuxcnc and grbl dwell, then move); program the motion in its "
                              "own block");
  }
  for (const char letter : {'Y', 'Z', 'I', 'J', 'K', 'R'}) {
    if (words.at(letter) >= 0) {
      throw words.WordError(words.at(letter), "'" + words.Shown(words.at(letter)) +
                                                  "' is not allowed in a G4 (dwell) block; "
                                                  "allowed: P (ms) or X/U (s) for the time, F, "
                                                  "G17-G19, G20, G21, G90, G91, N");
    }
  }
  int time_word = -1;
  for (const char letter : {'P', 'X', 'U'}) {
    const int w = words.at(letter);
    if (w < 0) continue;
    if (time_word >= 0) {
      throw words.WordError(w, "G4 takes its dwell time as one of P (ms), X (s) and U (s)");
    }
    time_word = w;
  }
  if (time_word < 0) {
    throw words.WordError(words.nonmodal_word(), "G4 needs its dwell time: P in ms (e.g. "
                                                 "P500) or X/U in s (e.g. X0.5)");
  }
  const bool in_ms = time_word == words.at('P');
  if (in_ms && words.HasDecimalPoint(time_word)) {
    throw words.WordError(time_word,
                          "'" + words.Shown(time_word) + "': the fanuc dialect reads G4's P as "
                          "an integer of milliseconds without a decimal point (P500 is 0.5 s); "
                          "linuxcnc and grbl read a decimal P in seconds (program_dialect: "
                          "linuxcnc or grbl); allowed here: P in ms, or X/U in s (X0.5)");
  }
  return words.value(time_word) * (in_ms ? 1e-3 : 1.0);
}

// LinuxCNC's and grbl's G4: P in s.
double SecondsDwellSeconds(const BlockWords& words) {
  const int p = words.at('P');
  if (p < 0) {
    throw words.WordError(words.nonmodal_word(),
                          std::string("G4 needs its dwell time: P in s (e.g. P0.5) in the ") +
                              DialectName(words.dialect()) + " dialect (fanuc reads X in s)");
  }
  return words.value(p);
}

// A G4 block's dwell (>= 0 s).
ProgramBlock DwellBlock(const BlockWords& words, const ProgramBlock& here) {
  const double seconds = IsFanuc(words) ? FanucDwellSeconds(words) : SecondsDwellSeconds(words);
  if (seconds < 0) {
    int time_word = words.at('P');
    for (const char letter : {'X', 'U'}) {
      if (time_word < 0 && IsFanuc(words)) time_word = words.at(letter);
    }
    throw words.WordError(time_word, "dwell must be >= 0, got '" + words.Shown(time_word) + "'");
  }
  ProgramBlock dwell = here;
  dwell.kind = MotionKind::kDwell;
  dwell.end_m = here.start_m;
  dwell.center_m = here.start_m;
  dwell.dwell_s = seconds;
  return dwell;
}

// X, Y, Z: absolute, or incremental from the start; the axes without a word stay.
Eigen::Vector3d EndPoint(const BlockWords& words, const Eigen::Vector3d& start_m,
                         bool incremental, double unit_m) {
  Eigen::Vector3d end = start_m;
  for (int a = 0; a < kNumAxes; ++a) {
    const int w = words.at(kAxisLetters[a]);
    if (w < 0) continue;
    const double value_m = words.value(w) * unit_m;
    end[a] = incremental ? start_m[a] + value_m : value_m;
  }
  return end;
}

// A G0/G1 block: no arc words; it moves when it has an axis word and its end is not its
// start.
bool LinearBlockMoves(const BlockWords& words, const ProgramBlock& move) {
  for (const int w : {words.FirstCentreWord(), words.at('R')}) {
    if (w >= 0) {
      throw words.WordError(w, "'" + words.Shown(w) + "' belongs to an arc (G2/G3); the "
                               "active motion is " + MotionName(move.kind));
    }
  }
  return words.HasAxisWord() && move.end_m != move.start_m;
}

}  // namespace

ProgramBuilder::ProgramBuilder(const Eigen::Vector3d& start_m, ProgramOptions options)
    : options_(std::move(options)), position_m_(start_m) {
  program_.start_m = start_m;
  program_.junction_deviation_rule = options_.dialect == Dialect::kGrbl;
}

void ProgramBuilder::AddRapid(const ProgramBlock& here, const Eigen::Vector3d& end_m) {
  if (end_m == position_m_) return;
  ProgramBlock rapid = here;
  rapid.kind = MotionKind::kRapid;
  rapid.start_m = position_m_;
  rapid.end_m = end_m;
  rapid.center_m = position_m_;
  program_.blocks.push_back(rapid);
  position_m_ = end_m;
}

// G28/G30: a rapid move to the intermediate point, then one to the reference position
// along the returning axes.
void ProgramBuilder::ReferenceReturn(const BlockWords& words, const ProgramBlock& here) {
  const int g = words.nonmodal_word();
  const bool g28 = words.code(g) == 280;
  if (words.motion_word() >= 0) {
    throw words.WordError(words.motion_word(), "'" + words.Shown(g) + "' and '" +
                                                   words.Shown(words.motion_word()) +
                                                   "' in one block both use the axis words; "
                                                   "program the motion in its own block");
  }
  for (const int w : {words.FirstCentreWord(), words.at('R')}) {
    if (w >= 0) {
      throw words.WordError(w, "'" + words.Shown(w) + "' is not allowed with '" + words.Shown(g) +
                                   "'; allowed: X, Y, Z (the intermediate point), F, N");
    }
  }
  const auto& reference = g28 ? options_.g28_mm : options_.g30_mm;
  const std::string key = options_.reference_key + (g28 ? ".g28" : ".g30");
  if (!reference) {
    throw words.WordError(g, "'" + words.Shown(g) + "' returns to the reference position " + key +
                                 ", which is not set; allowed: give " + options_.reference_key +
                                 ": {" + (g28 ? "g28" : "g30") + ": {x, y, z}} in mm (the "
                                 "bench has no work offsets: machine and program coordinates "
                                 "agree)");
  }
  const Eigen::Vector3d intermediate = EndPoint(words, position_m_, incremental_, unit_m_);
  // Without axis words LinuxCNC and grbl return every axis; Fanuc none.
  const bool every_axis = !words.HasAxisWord() && !IsFanuc(words);
  Eigen::Vector3d target = intermediate;
  for (int a = 0; a < kNumAxes; ++a) {
    if (every_axis || words.at(kAxisLetters[a]) >= 0) target[a] = (*reference)[a] * 1e-3;
  }
  AddRapid(here, intermediate);
  AddRapid(here, target);
}

// G61/G61.1/G64: linuxcnc's G64 blends the corners within P (controller/corner_blend.h,
// Q merges collinear lines); fanuc's G64 (cutting mode) runs as every mode does here, by
// the corner rule without in-position check, and says so once.
void ProgramBuilder::NotePathMode(const BlockWords& words, int line) {
  const int w = words.path_mode_word();
  const bool blending = w >= 0 && words.code(w) == 640;
  if (blending && IsFanuc(words)) {
    for (const char letter : {'P', 'Q'}) {
      if (words.at(letter) < 0) continue;
      throw words.WordError(words.at(letter),
                            "'" + words.Shown(words.at(letter)) + "' with G64 (blending "
                            "tolerance) is linuxcnc's; the fanuc dialect's G64 takes no P or "
                            "Q; allowed: G64 alone, or program_dialect: linuxcnc");
    }
  }
  if (blending && words.at('Q') >= 0 && words.at('P') < 0) {
    throw words.WordError(words.at('Q'), "G64's Q needs a P (LinuxCNC: G64 P- Q-)");
  }
  for (const char letter : {'P', 'Q'}) {
    if (blending && words.at(letter) >= 0 && words.value(words.at(letter)) < 0) {
      throw words.WordError(words.at(letter), "'" + words.Shown(words.at(letter)) +
                                                  "': G64's tolerance must be >= 0");
    }
  }
  if (w >= 0 && words.dialect() == Dialect::kLinuxcnc) {
    const bool has_p = words.at('P') >= 0;
    blend_tolerance_m_ = !blending ? -1.0
                         : has_p   ? words.value(words.at('P')) * unit_m_
                                   : std::numeric_limits<double>::infinity();
    merge_tolerance_m_ = blending && words.at('Q') >= 0 ? words.value(words.at('Q')) * unit_m_ : 0.0;
  }
  if (!blending || !IsFanuc(words) || blending_warned_) return;
  blending_warned_ = true;
  program_.warnings.push_back(
      "G64 (line " + std::to_string(line) + ", cutting mode) runs as G61 does here: corners "
      "follow the controller's corner rule (corner_velocity_change_mm_min), without "
      "in-position check; blending within a tolerance is linuxcnc's G64 P");
}

void ProgramBuilder::Apply(const Block& block) {
  const BlockWords words(block, options_.dialect);
  // Modal words first, wherever they stand in the block.
  plane_ = PlaneAfter(words, plane_);
  incremental_ = IncrementalAfter(words, incremental_);
  absolute_centre_ = AbsoluteCentreAfter(words, absolute_centre_);
  unit_m_ = UnitAfter(words, unit_m_);
  feed_m_s_ = FeedAfter(words, feed_m_s_, unit_m_);
  CheckBoundWords(words);
  NotePathMode(words, block.source_line);

  ProgramBlock move;  // from here, in the modal state after the block
  move.start_m = position_m_;
  move.plane = plane_;
  move.feed_m_s = feed_m_s_;
  move.source_line = block.source_line;
  move.blend_tolerance_m = blend_tolerance_m_;
  move.merge_tolerance_m = merge_tolerance_m_;
  const int nonmodal = words.nonmodal_word();
  if (nonmodal >= 0 && words.code(nonmodal) == 40) {
    program_.blocks.push_back(DwellBlock(words, move));
    if (IsFanuc(words)) return;  // LinuxCNC and grbl: the block's motion follows
  } else if (nonmodal >= 0) {
    ReferenceReturn(words, move);
    return;
  }

  motion_ = MotionAfter(words, motion_);
  move.kind = motion_;
  move.end_m = EndPoint(words, position_m_, incremental_, unit_m_);
  const ArcContext arc{unit_m_, absolute_centre_, options_.ArcRule(), options_.arc_tolerance_key};
  if (!(IsArc(motion_) ? CompleteArc(words, arc, &move) : LinearBlockMoves(words, move))) return;
  program_.blocks.push_back(move);
  position_m_ = move.end_m;
}

}  // namespace shapebench::controller

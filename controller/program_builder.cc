#include "controller/program_builder.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <utility>

#include "common/format.h"

namespace shapebench::controller {
namespace {

constexpr double kMmToM = 1e-3;
constexpr double kMmPerMinToMPerS = 1.0 / 60000.0;
// An arc's end coincides with its start (a full circle) within 1e-6 mm in the plane.
constexpr double kCoincideM = 1e-9;
// Start and end radii agree within 1e-3 mm, or 1e-6 of the radius when that is larger.
constexpr double kRadiusToleranceM = 1e-6;
constexpr double kRadiusToleranceRelative = 1e-6;

double RadiusTolerance(double radius_m) {
  return std::max(kRadiusToleranceM, kRadiusToleranceRelative * radius_m);
}

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

std::string Mm(double metres) { return FormatNumber(metres / kMmToM) + " mm"; }

constexpr char kAxisLetters[] = "XYZ";
constexpr char kCentreLetters[] = "IJK";

// The words of one block, each checked on its own (a finite number; a supported letter or
// G code) and indexed by where it sits (-1: absent): letters other than G by letter, G
// words by modal group. Throws ProgramError for a second word of a letter or G group.
class BlockWords {
 public:
  explicit BlockWords(const Block& block);

  int at(char letter) const { return at_[static_cast<std::size_t>(letter - 'A')]; }
  double value(int i) const { return words_[static_cast<std::size_t>(i)].value; }
  int code(int i) const { return codes_[static_cast<std::size_t>(i)]; }  // of a G word
  int motion_word() const { return motion_word_; }      // G0-G3
  int dwell_word() const { return dwell_word_; }        // G4
  int plane_word() const { return plane_word_; }        // G17-G19
  int distance_word() const { return distance_word_; }  // G90, G91

  bool HasAxisWord() const;     // any of X, Y, Z
  int FirstCentreWord() const;  // the first of I/J/K in the block

  // As written ("G01"), or letter and value when there is no text.
  std::string Shown(int i) const;
  ProgramError WordError(int i, const std::string& message) const;
  ProgramError BlockError(const std::string& message) const;

 private:
  void IndexGWord(int i);
  void IndexAddressWord(int i);
  void TakeGroup(int* slot, int i, const std::string& rule);
  ProgramError Unsupported(int i) const;

  const std::vector<Word>& words_;
  int line_;
  std::array<int, 26> at_;
  int motion_word_ = -1, dwell_word_ = -1, plane_word_ = -1, distance_word_ = -1,
      units_word_ = -1;
  std::vector<int> codes_;  // the G code of each G word, -1 for the others
};

BlockWords::BlockWords(const Block& block)
    : words_(block.words), line_(block.source_line), codes_(block.words.size(), -1) {
  at_.fill(-1);
  for (std::size_t k = 0; k < words_.size(); ++k) {
    const int i = static_cast<int>(k);
    if (!std::isfinite(words_[k].value)) {
      throw WordError(i, "number out of range in '" + Shown(i) + "'");
    }
    if (words_[k].letter == 'G') {
      IndexGWord(i);
    } else {
      IndexAddressWord(i);
    }
  }
}

void BlockWords::IndexGWord(int i) {
  const double number = value(i);
  if (number != std::floor(number) || number < 0) {
    throw WordError(i, "malformed number '" + Shown(i) + "': G takes an integer, e.g. G1");
  }
  if (number > 1000) throw Unsupported(i);
  const int code = static_cast<int>(number);
  codes_[static_cast<std::size_t>(i)] = code;
  if (code >= 0 && code <= 3) {
    TakeGroup(&motion_word_, i, "one motion word (G0-G3) per block");
  } else if (code == 4) {
    TakeGroup(&dwell_word_, i, "");
  } else if (code >= 17 && code <= 19) {
    TakeGroup(&plane_word_, i, "one plane word (G17, G18, G19) per block");
  } else if (code == 90 || code == 91) {
    TakeGroup(&distance_word_, i, "one of G90 (absolute) and G91 (incremental) per block");
  } else if (code == 20) {
    throw WordError(i, "inch input (G20) is not supported; allowed: G21 (mm)");
  } else if (code == 21) {
    TakeGroup(&units_word_, i, "");
  } else {
    throw Unsupported(i);
  }
}

void BlockWords::IndexAddressWord(int i) {
  const char letter = words_[static_cast<std::size_t>(i)].letter;
  if (letter < 'A' || letter > 'Z' || std::strchr("FXYZIJKRPN", letter) == nullptr) {
    throw Unsupported(i);
  }
  int& slot = at_[static_cast<std::size_t>(letter - 'A')];
  if (slot >= 0) {
    throw WordError(i, "word " + std::string(1, letter) + " repeated in one block ('" +
                           Shown(slot) + "' and '" + Shown(i) +
                           "'); each word at most once per block");
  }
  slot = i;
}

// The word of a G group; a second one is an error (the same code twice, or `rule`).
void BlockWords::TakeGroup(int* slot, int i, const std::string& rule) {
  if (*slot >= 0) {
    if (code(*slot) == code(i)) {
      throw WordError(i, "word '" + Shown(i) + "' repeated in one block; each word at most "
                         "once per block");
    }
    throw WordError(i, "'" + Shown(*slot) + "' and '" + Shown(i) + "' in one block; " + rule);
  }
  *slot = i;
}

bool BlockWords::HasAxisWord() const {
  for (int a = 0; a < kNumAxes; ++a) {
    if (at(kAxisLetters[a]) >= 0) return true;
  }
  return false;
}

int BlockWords::FirstCentreWord() const {
  int first = -1;
  for (int a = 0; a < kNumAxes; ++a) {
    const int w = at(kCentreLetters[a]);
    if (w >= 0 && (first < 0 || w < first)) first = w;
  }
  return first;
}

std::string BlockWords::Shown(int i) const {
  const Word& word = words_[static_cast<std::size_t>(i)];
  return word.text.empty() ? std::string(1, word.letter) + FormatNumber(word.value) : word.text;
}

ProgramError BlockWords::WordError(int i, const std::string& message) const {
  return ProgramError(line_, words_[static_cast<std::size_t>(i)].column, i, message);
}

ProgramError BlockWords::BlockError(const std::string& message) const {
  return ProgramError(line_, words_.empty() ? 0 : words_.front().column, -1, message);
}

ProgramError BlockWords::Unsupported(int i) const {
  return WordError(i, "unsupported word '" + Shown(i) + "'; allowed: " + kSupportedWords);
}

// The modal state after the block's words (G17-G19, G90/G91, F, G0-G3).

Plane PlaneAfter(const BlockWords& words, Plane plane) {
  if (words.plane_word() < 0) return plane;
  const int code = words.code(words.plane_word());
  return code == 17 ? Plane::kXY : code == 18 ? Plane::kZX : Plane::kYZ;
}

bool IncrementalAfter(const BlockWords& words, bool incremental) {
  return words.distance_word() >= 0 ? words.code(words.distance_word()) == 91 : incremental;
}

// F in mm/min, checked (0 < F <= kMaxFeedMmMin), as m/s.
double FeedAfter(const BlockWords& words, double feed_m_s) {
  const int f = words.at('F');
  if (f < 0) return feed_m_s;
  const double feed_mm_min = words.value(f);
  if (!(feed_mm_min > 0)) {
    throw words.WordError(f, "F must be > 0 (mm/min), got '" + words.Shown(f) + "'");
  }
  if (feed_mm_min > kMaxFeedMmMin) {
    throw words.WordError(f, "F must be at most 1000000 (mm/min), got '" + words.Shown(f) + "'");
  }
  return feed_mm_min * kMmPerMinToMPerS;
}

MotionKind MotionAfter(const BlockWords& words, MotionKind motion) {
  if (words.motion_word() < 0) return motion;
  static constexpr MotionKind kKinds[] = {MotionKind::kRapid, MotionKind::kLinear,
                                          MotionKind::kArcCw, MotionKind::kArcCcw};
  return kKinds[words.code(words.motion_word())];
}

bool IsArc(MotionKind motion) {
  return motion == MotionKind::kArcCw || motion == MotionKind::kArcCcw;
}

std::string MotionName(MotionKind motion) {
  return motion == MotionKind::kRapid    ? "G0"
         : motion == MotionKind::kLinear ? "G1"
         : motion == MotionKind::kArcCw  ? "G2"
                                         : "G3";
}

// A G4 block: its time (P in ms or X in s, one of them, >= 0) and no motion word.
ProgramBlock DwellBlock(const BlockWords& words, const ProgramBlock& here) {
  if (words.motion_word() >= 0) {
    throw words.WordError(words.motion_word(),
                          "G4 (dwell) cannot share a block with '" +
                              words.Shown(words.motion_word()) +
                              "'; program the motion in its own block");
  }
  for (const char letter : {'Y', 'Z', 'I', 'J', 'K', 'R'}) {
    if (words.at(letter) >= 0) {
      throw words.WordError(words.at(letter), "'" + words.Shown(words.at(letter)) +
                                                  "' is not allowed in a G4 (dwell) block; "
                                                  "allowed: P (ms) or X (s) for the time, F, "
                                                  "G17-G19, G21, G90, G91, N");
    }
  }
  const int p = words.at('P'), x = words.at('X');
  if (p >= 0 && x >= 0) {
    throw words.WordError(std::max(p, x), "G4 takes its dwell time as P (ms) or X (s), not both");
  }
  if (p < 0 && x < 0) {
    throw words.WordError(words.dwell_word(), "G4 needs its dwell time: P in ms (e.g. P500) or "
                                              "X in s (e.g. X0.5)");
  }
  const int time_word = p >= 0 ? p : x;
  const double value = words.value(time_word);
  if (value < 0) {
    throw words.WordError(time_word, "dwell must be >= 0, got '" + words.Shown(time_word) + "'");
  }
  ProgramBlock dwell = here;
  dwell.kind = MotionKind::kDwell;
  dwell.end_m = here.start_m;
  dwell.center_m = here.start_m;
  dwell.dwell_s = p >= 0 ? value * 1e-3 : value;
  return dwell;
}

// X, Y, Z: absolute, or incremental from the start; the axes without a word stay.
Eigen::Vector3d EndPoint(const BlockWords& words, const Eigen::Vector3d& start_m,
                         bool incremental) {
  Eigen::Vector3d end = start_m;
  for (int a = 0; a < kNumAxes; ++a) {
    const int w = words.at(kAxisLetters[a]);
    if (w < 0) continue;
    const double value_m = words.value(w) * kMmToM;
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

// I/J/K: only the two of the plane, or R, exactly one of the two forms.
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

// R: the centre on the chord's perpendicular bisector, on the side G2/G3 and R's sign say.
Eigen::Vector3d CentreFromRadius(const BlockWords& words, const ProgramBlock& arc,
                                 PlaneAxes axes, const Chord& chord, bool full_circle) {
  const int r_word = words.at('R');
  const double r = words.value(r_word) * kMmToM;
  if (r == 0) throw words.WordError(r_word, "R must not be 0");
  if (full_circle) {
    throw words.WordError(r_word, "R cannot describe a full circle (the end point is the "
                                  "start point); use I/J/K");
  }
  const double half_chord = chord.length / 2;
  const double radius = std::abs(r);
  if (radius < half_chord - RadiusTolerance(radius)) {
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

// I/J/K: the centre as offsets from the start; the end must lie on the circle (within
// RadiusTolerance).
Eigen::Vector3d CentreFromOffsets(const BlockWords& words, const ProgramBlock& arc,
                                  PlaneAxes axes) {
  const Eigen::Vector3d& start = arc.start_m;
  const Eigen::Vector3d& end = arc.end_m;
  Eigen::Vector3d centre = start;
  for (const int a : {axes.u, axes.v}) {
    const int w = words.at(kCentreLetters[a]);
    if (w >= 0) centre[a] = start[a] + words.value(w) * kMmToM;
  }
  const double start_radius =
      std::hypot(start[axes.u] - centre[axes.u], start[axes.v] - centre[axes.v]);
  const double end_radius = std::hypot(end[axes.u] - centre[axes.u], end[axes.v] - centre[axes.v]);
  const int first_centre_word = words.FirstCentreWord();
  if (start_radius <= kCoincideM) {
    throw words.WordError(first_centre_word,
                          "arc radius is 0: the centre given by I/J/K is the start point");
  }
  const double tolerance = RadiusTolerance(std::max(start_radius, end_radius));
  if (std::abs(start_radius - end_radius) > tolerance) {
    throw words.WordError(first_centre_word,
                          "arc end point is not on the circle: start radius " +
                              Mm(start_radius) + ", end radius " + Mm(end_radius) +
                              " (difference " + Mm(std::abs(start_radius - end_radius)) +
                              "); allowed: at most " + Mm(tolerance));
  }
  return centre;
}

// A G2/G3 block: its centre (and, for a full circle, its end set to the start exactly).
// False for a block that only makes G2/G3 modal.
bool CompleteArc(const BlockWords& words, ProgramBlock* arc) {
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
  arc->center_m = words.at('R') >= 0 ? CentreFromRadius(words, *arc, axes, chord, full_circle)
                                     : CentreFromOffsets(words, *arc, axes);
  return true;
}

}  // namespace

const char* const kSupportedWords =
    "G0-G4, G17-G19, G21, G90, G91, F, X, Y, Z, I, J, K, R, P, N";

ProgramError::ProgramError(int line, int column, int word_index, std::string message)
    : std::runtime_error((column > 0 ? std::to_string(line) + ":" + std::to_string(column)
                                     : std::to_string(line)) +
                         ": " + message),
      line_(line),
      column_(column),
      word_index_(word_index),
      message_(std::move(message)) {}

ProgramBuilder::ProgramBuilder(const Eigen::Vector3d& start_m) : position_m_(start_m) {
  program_.start_m = start_m;
}

void ProgramBuilder::Apply(const Block& block) {
  const BlockWords words(block);
  // Modal words first, wherever they stand in the block.
  plane_ = PlaneAfter(words, plane_);
  incremental_ = IncrementalAfter(words, incremental_);
  feed_m_s_ = FeedAfter(words, feed_m_s_);

  ProgramBlock move;  // from here, in the modal state after the block
  move.start_m = position_m_;
  move.plane = plane_;
  move.feed_m_s = feed_m_s_;
  move.source_line = block.source_line;
  if (words.dwell_word() >= 0) {
    program_.blocks.push_back(DwellBlock(words, move));
    return;
  }
  if (words.at('P') >= 0) {
    throw words.WordError(words.at('P'), "'" + words.Shown(words.at('P')) +
                                             "': P (dwell time in ms) is allowed only with G4");
  }

  motion_ = MotionAfter(words, motion_);
  move.kind = motion_;
  move.end_m = EndPoint(words, position_m_, incremental_);
  if (!(IsArc(motion_) ? CompleteArc(words, &move) : LinearBlockMoves(words, move))) return;
  program_.blocks.push_back(move);
  position_m_ = move.end_m;
}

}  // namespace shapebench::controller

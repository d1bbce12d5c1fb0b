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

// The plane's first, second and normal axis.
struct PlaneAxes {
  int u, v, n;
};

PlaneAxes AxesOf(Plane plane) {
  switch (plane) {
    case Plane::kZX: return {2, 0, 1};
    case Plane::kYZ: return {1, 2, 0};
    case Plane::kXY: break;
  }
  return {0, 1, 2};
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
  const std::vector<Word>& words = block.words;
  const int line = block.source_line;

  auto shown = [&](int i) {
    const Word& word = words[static_cast<std::size_t>(i)];
    return word.text.empty() ? std::string(1, word.letter) + FormatNumber(word.value)
                             : word.text;
  };
  auto word_error = [&](int i, const std::string& message) {
    return ProgramError(line, words[static_cast<std::size_t>(i)].column, i, message);
  };
  auto block_error = [&](const std::string& message) {
    return ProgramError(line, words.empty() ? 0 : words.front().column, -1, message);
  };
  auto unsupported = [&](int i) {
    return word_error(i, "unsupported word '" + shown(i) + "'; allowed: " + kSupportedWords);
  };

  // Where each word sits in the block (-1: absent): letters other than G by letter, G
  // words by modal group.
  std::array<int, 26> at;
  at.fill(-1);
  int motion_word = -1, dwell_word = -1, plane_word = -1, distance_word = -1, units_word = -1;
  std::vector<int> codes(words.size(), -1);  // the G code of each G word

  auto take_group = [&](int* slot, int i, const std::string& rule) {
    if (*slot >= 0) {
      if (codes[static_cast<std::size_t>(*slot)] == codes[static_cast<std::size_t>(i)]) {
        throw word_error(i, "word '" + shown(i) + "' repeated in one block; each word at most "
                            "once per block");
      }
      throw word_error(i, "'" + shown(*slot) + "' and '" + shown(i) + "' in one block; " + rule);
    }
    *slot = i;
  };

  for (std::size_t k = 0; k < words.size(); ++k) {
    const int i = static_cast<int>(k);
    const Word& word = words[k];
    if (!std::isfinite(word.value)) {
      throw word_error(i, "number out of range in '" + shown(i) + "'");
    }
    if (word.letter == 'G') {
      if (word.value != std::floor(word.value) || word.value < 0) {
        throw word_error(i, "malformed number '" + shown(i) + "': G takes an integer, e.g. G1");
      }
      if (word.value > 1000) throw unsupported(i);
      const int code = static_cast<int>(word.value);
      codes[k] = code;
      if (code >= 0 && code <= 3) {
        take_group(&motion_word, i, "one motion word (G0-G3) per block");
      } else if (code == 4) {
        take_group(&dwell_word, i, "");
      } else if (code >= 17 && code <= 19) {
        take_group(&plane_word, i, "one plane word (G17, G18, G19) per block");
      } else if (code == 90 || code == 91) {
        take_group(&distance_word, i, "one of G90 (absolute) and G91 (incremental) per block");
      } else if (code == 20) {
        throw word_error(i, "inch input (G20) is not supported; allowed: G21 (mm)");
      } else if (code == 21) {
        take_group(&units_word, i, "");
      } else {
        throw unsupported(i);
      }
      continue;
    }
    if (word.letter < 'A' || word.letter > 'Z' ||
        std::strchr("FXYZIJKRPN", word.letter) == nullptr) {
      throw unsupported(i);
    }
    int& slot = at[static_cast<std::size_t>(word.letter - 'A')];
    if (slot >= 0) {
      throw word_error(i, "word " + std::string(1, word.letter) + " repeated in one block ('" +
                              shown(slot) + "' and '" + shown(i) +
                              "'); each word at most once per block");
    }
    slot = i;
  }
  auto word_at = [&](char letter) { return at[static_cast<std::size_t>(letter - 'A')]; };
  auto value_at = [&](char letter) {
    return words[static_cast<std::size_t>(word_at(letter))].value;
  };

  // Modal words first, wherever they stand in the block.
  if (plane_word >= 0) {
    const int code = codes[static_cast<std::size_t>(plane_word)];
    plane_ = code == 17 ? Plane::kXY : code == 18 ? Plane::kZX : Plane::kYZ;
  }
  if (distance_word >= 0) incremental_ = codes[static_cast<std::size_t>(distance_word)] == 91;
  if (word_at('F') >= 0) {
    const double feed_mm_min = value_at('F');
    if (!(feed_mm_min > 0)) {
      throw word_error(word_at('F'), "F must be > 0 (mm/min), got '" + shown(word_at('F')) + "'");
    }
    if (feed_mm_min > kMaxFeedMmMin) {
      throw word_error(word_at('F'), "F must be at most 1000000 (mm/min), got '" + shown(word_at('F')) + "'");
    }
    feed_m_s_ = feed_mm_min * kMmPerMinToMPerS;
  }

  if (dwell_word >= 0) {
    if (motion_word >= 0) {
      throw word_error(motion_word, "G4 (dwell) cannot share a block with '" +
                                        shown(motion_word) + "'; program the motion in its own "
                                        "block");
    }
    for (const char letter : {'Y', 'Z', 'I', 'J', 'K', 'R'}) {
      if (word_at(letter) >= 0) {
        throw word_error(word_at(letter), "'" + shown(word_at(letter)) +
                                              "' is not allowed in a G4 (dwell) block; allowed: "
                                              "P (ms) or X (s) for the time, F, G17-G19, G21, "
                                              "G90, G91, N");
      }
    }
    const int p = word_at('P'), x = word_at('X');
    if (p >= 0 && x >= 0) {
      throw word_error(std::max(p, x), "G4 takes its dwell time as P (ms) or X (s), not both");
    }
    if (p < 0 && x < 0) {
      throw word_error(dwell_word, "G4 needs its dwell time: P in ms (e.g. P500) or X in s "
                                   "(e.g. X0.5)");
    }
    const int time_word = p >= 0 ? p : x;
    const double value = words[static_cast<std::size_t>(time_word)].value;
    if (value < 0) {
      throw word_error(time_word, "dwell must be >= 0, got '" + shown(time_word) + "'");
    }
    ProgramBlock dwell;
    dwell.kind = MotionKind::kDwell;
    dwell.start_m = position_m_;
    dwell.end_m = position_m_;
    dwell.center_m = position_m_;
    dwell.plane = plane_;
    dwell.feed_m_s = feed_m_s_;
    dwell.dwell_s = p >= 0 ? value * 1e-3 : value;
    dwell.source_line = line;
    program_.blocks.push_back(dwell);
    return;
  }
  if (word_at('P') >= 0) {
    throw word_error(word_at('P'), "'" + shown(word_at('P')) +
                                       "': P (dwell time in ms) is allowed only with G4");
  }

  if (motion_word >= 0) {
    static constexpr MotionKind kKinds[] = {MotionKind::kRapid, MotionKind::kLinear,
                                            MotionKind::kArcCw, MotionKind::kArcCcw};
    motion_ = kKinds[codes[static_cast<std::size_t>(motion_word)]];
  }
  const bool arc = motion_ == MotionKind::kArcCw || motion_ == MotionKind::kArcCcw;
  const std::string motion_name = motion_ == MotionKind::kRapid    ? "G0"
                                  : motion_ == MotionKind::kLinear ? "G1"
                                  : motion_ == MotionKind::kArcCw  ? "G2"
                                                                   : "G3";

  bool has_axis = false;
  Eigen::Vector3d end = position_m_;
  for (int a = 0; a < kNumAxes; ++a) {
    const int w = word_at(kAxisLetters[a]);
    if (w < 0) continue;
    has_axis = true;
    const double value_m = words[static_cast<std::size_t>(w)].value * kMmToM;
    end[a] = incremental_ ? position_m_[a] + value_m : value_m;
  }
  int first_centre_word = -1;  // the first of I/J/K in the block
  for (int a = 0; a < kNumAxes; ++a) {
    const int w = word_at(kCentreLetters[a]);
    if (w >= 0 && (first_centre_word < 0 || w < first_centre_word)) first_centre_word = w;
  }
  const int r_word = word_at('R');

  ProgramBlock out;
  out.kind = motion_;
  out.start_m = position_m_;
  out.plane = plane_;
  out.feed_m_s = feed_m_s_;
  out.source_line = line;

  if (!arc) {
    for (const int w : {first_centre_word, r_word}) {
      if (w >= 0) {
        throw word_error(w, "'" + shown(w) + "' belongs to an arc (G2/G3); the active motion "
                            "is " + motion_name);
      }
    }
    if (!has_axis || end == position_m_) return;  // nothing moves
    out.end_m = end;
    program_.blocks.push_back(out);
    position_m_ = end;
    return;
  }

  const PlaneAxes axes = AxesOf(plane_);
  for (int a = 0; a < kNumAxes; ++a) {
    const int w = word_at(kCentreLetters[a]);
    if (w >= 0 && a == axes.n) {
      throw word_error(w, "'" + shown(w) + "' is not a centre word of " + PlaneName(plane_) +
                              "; allowed: " + PlaneCentreWords(plane_));
    }
  }
  if (!has_axis && first_centre_word < 0 && r_word < 0) return;  // a modal G2/G3 only
  if (r_word >= 0 && first_centre_word >= 0) {
    throw word_error(r_word, "an arc takes its centre as I/J/K or as R, not both");
  }
  if (r_word < 0 && first_centre_word < 0) {
    const std::string message =
        "an arc (" + motion_name + ") needs its centre: I/J/K offsets or a radius R";
    throw motion_word >= 0 ? word_error(motion_word, message) : block_error(message);
  }

  const Eigen::Vector3d start = position_m_;
  const double du = end[axes.u] - start[axes.u];
  const double dv = end[axes.v] - start[axes.v];
  const double chord = std::hypot(du, dv);
  const bool full_circle = chord <= kCoincideM;
  if (full_circle) {
    end[axes.u] = start[axes.u];
    end[axes.v] = start[axes.v];
  }
  Eigen::Vector3d centre = start;
  if (r_word >= 0) {
    const double r = value_at('R') * kMmToM;
    if (r == 0) throw word_error(r_word, "R must not be 0");
    if (full_circle) {
      throw word_error(r_word, "R cannot describe a full circle (the end point is the start "
                               "point); use I/J/K");
    }
    const double half_chord = chord / 2;
    const double radius = std::abs(r);
    if (radius < half_chord - RadiusTolerance(radius)) {
      throw word_error(r_word, "'" + shown(r_word) + "' is shorter than half the chord (" +
                                   Mm(half_chord) + "); allowed: |R| >= " + Mm(half_chord));
    }
    const double h = std::sqrt(std::max(0.0, radius * radius - half_chord * half_chord));
    // (nu, nv): the unit normal to the left of the chord's direction start -> end. A CCW
    // arc of at most 180 degrees has its centre on the left, a CW one on the right; R < 0
    // (the longer arc) swaps the sides.
    const double nu = -dv / chord;
    const double nv = du / chord;
    const double side =
        (motion_ == MotionKind::kArcCcw ? 1.0 : -1.0) * (r > 0 ? 1.0 : -1.0);
    centre[axes.u] = start[axes.u] + du / 2 + side * h * nu;
    centre[axes.v] = start[axes.v] + dv / 2 + side * h * nv;
  } else {
    for (const int a : {axes.u, axes.v}) {
      const int w = word_at(kCentreLetters[a]);
      if (w >= 0) centre[a] = start[a] + words[static_cast<std::size_t>(w)].value * kMmToM;
    }
    const double start_radius =
        std::hypot(start[axes.u] - centre[axes.u], start[axes.v] - centre[axes.v]);
    const double end_radius =
        std::hypot(end[axes.u] - centre[axes.u], end[axes.v] - centre[axes.v]);
    if (start_radius <= kCoincideM) {
      throw word_error(first_centre_word,
                       "arc radius is 0: the centre given by I/J/K is the start point");
    }
    const double tolerance = RadiusTolerance(std::max(start_radius, end_radius));
    if (std::abs(start_radius - end_radius) > tolerance) {
      throw word_error(first_centre_word,
                       "arc end point is not on the circle: start radius " + Mm(start_radius) +
                           ", end radius " + Mm(end_radius) + " (difference " +
                           Mm(std::abs(start_radius - end_radius)) + "); allowed: at most " +
                           Mm(tolerance));
    }
  }
  out.end_m = end;
  out.center_m = centre;
  program_.blocks.push_back(out);
  position_m_ = end;
}

}  // namespace shapebench::controller

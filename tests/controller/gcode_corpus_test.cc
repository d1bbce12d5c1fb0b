// Real part programs nobody here wrote (tests/data/gcode/*/README.md names each one's
// repository, path, commit and licence), read in their controller's dialect and planned to
// their end, or refused for a feature kept refused (kRefused). Each program's block end
// points and arc centres are checked against an independent reader written here (plain
// words, #<name> constants, G20/G21, G90/G91, G17-G19, I/J/K or R, G4, G28); dwell times
// against the manuals' definitions (LinuxCNC and grbl: G4 P in s).
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "controller/controller.h"
#include "controller/gcode_parser.h"

namespace shapebench::controller {
namespace {

namespace fs = std::filesystem;

const std::string kCorpus = std::string(SHAPEBENCH_SOURCE_DIR) + "/tests/data/gcode";
const Eigen::Vector3d kG28Mm(0, 0, 40);  // a machine's reference position, for G28
constexpr double kEndTolM = 1e-9;
// An R arc's centre comes from a square root that loses digits near a half circle (h =
// sqrt(r^2 - c^2) with r = c): 1e-7 m covers it for the radii here (below 100 mm).
constexpr double kCentreTolM = 1e-7;

// The programs kept refused, each for a feature the bench does not model, and why.
const std::map<std::string, std::string> kRefused = {
    {"linuxcnc/spiral.ngc", "'@' (polar coordinates"},
};

std::string Read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

Dialect DialectOf(const std::string& folder) {
  return folder == "ugs" || folder == "bcnc" ? Dialect::kGrbl : Dialect::kLinuxcnc;
}

// What the independent reader expects of one block.
struct Expected {
  MotionKind kind;
  Eigen::Vector3d end_m, centre_m;
  double dwell_s;
};

// The independent reader: one line at a time, written from the RS274NGC manual.
class Oracle {
 public:
  explicit Oracle(Dialect dialect) : dialect_(dialect) {}
  void Line(std::string text);
  std::vector<Expected> expected;

 private:
  double Value(const std::string& number) const {
    if (!number.empty() && number[0] == '#') return named_.at(number.substr(2, number.size() - 3));
    return std::strtod(number.c_str(), nullptr);
  }
  void Move(const std::map<char, double>& words);
  void Arc(const std::map<char, double>& words, const Eigen::Vector3d& end);

  Dialect dialect_;
  std::map<std::string, double> named_;
  Eigen::Vector3d here_ = Eigen::Vector3d::Zero();
  int motion_ = 1, plane_ = 17;
  double unit_m_ = 1e-3;
  bool incremental_ = false;
};

void Oracle::Line(std::string text) {
  for (std::size_t open; (open = text.find('(')) != std::string::npos;) {
    text.erase(open, text.find(')', open) - open + 1);
  }
  text = text.substr(0, text.find(';'));
  std::string lower;
  for (const char c : text) {
    if (c != ' ' && c != '\t' && c != '\r') lower += static_cast<char>(std::tolower(c));
  }
  if (lower.empty() || lower == "%") return;
  if (lower.rfind("#<", 0) == 0) {  // #<name>=number
    named_[lower.substr(2, lower.find('>') - 2)] = std::strtod(lower.c_str() + lower.find('=') + 1, nullptr);
    return;
  }
  std::map<char, double> words;
  std::vector<double> g_codes;
  for (std::size_t pos = 0; pos < lower.size();) {
    const char letter = static_cast<char>(std::toupper(lower[pos++]));
    std::size_t end = pos;
    if (end < lower.size() && lower[end] == '#') {
      end = lower.find('>', end) + 1;
    } else {
      while (end < lower.size() && (std::isdigit(lower[end]) || lower[end] == '.' || lower[end] == '-' || lower[end] == '+')) ++end;
    }
    const double value = Value(lower.substr(pos, end - pos));
    pos = end;
    if (letter == 'G') g_codes.push_back(value);
    else words[letter] = value;
  }
  bool dwell = false, home = false;
  for (const double g : g_codes) {
    if (g <= 3) motion_ = static_cast<int>(g);
    if (g == 4) dwell = true;
    if (g == 17 || g == 18 || g == 19) plane_ = static_cast<int>(g);
    if (g == 20) unit_m_ = 25.4e-3;
    if (g == 21) unit_m_ = 1e-3;
    if (g == 90) incremental_ = false;
    if (g == 91) incremental_ = true;
    if (g == 28) home = true;
  }
  if (dwell) {  // LinuxCNC and grbl: P in seconds
    expected.push_back({MotionKind::kDwell, here_, here_, words.at('P')});
    return;
  }
  if (home) {  // to the intermediate point, then the named axes (all without one) home
    Eigen::Vector3d mid = here_;
    bool any = false;
    for (int a = 0; a < 3; ++a) {
      const auto w = words.find("XYZ"[a]);
      if (w == words.end()) continue;
      any = true;
      mid[a] = (incremental_ ? here_[a] : 0.0) + w->second * unit_m_;
    }
    Eigen::Vector3d target = mid;
    for (int a = 0; a < 3; ++a) {
      if (!any || words.count("XYZ"[a]) > 0) target[a] = kG28Mm[a] * 1e-3;
    }
    for (const Eigen::Vector3d& p : {mid, target}) {
      if (p != here_) expected.push_back({MotionKind::kRapid, p, p, 0.0});
      here_ = p;
    }
    return;
  }
  Move(words);
}

void Oracle::Move(const std::map<char, double>& words) {
  Eigen::Vector3d end = here_;
  bool axis = false;
  for (int a = 0; a < 3; ++a) {
    const auto w = words.find("XYZ"[a]);
    if (w == words.end()) continue;
    axis = true;
    end[a] = (incremental_ ? here_[a] : 0.0) + w->second * unit_m_;
  }
  if (motion_ >= 2) {
    if (axis || words.count('I') || words.count('J') || words.count('K') || words.count('R')) Arc(words, end);
    return;
  }
  if (!axis || end == here_) return;
  expected.push_back({motion_ == 0 ? MotionKind::kRapid : MotionKind::kLinear, end, end, 0.0});
  here_ = end;
}

// The centre: from I/J/K, or of the two circles of radius |R| through both points, the one
// that makes the turn (CW for G2 seen from the plane's normal) at most half a turn (R > 0).
void Oracle::Arc(const std::map<char, double>& words, const Eigen::Vector3d& end) {
  const int u = plane_ == 17 ? 0 : plane_ == 18 ? 2 : 1;
  const int v = plane_ == 17 ? 1 : plane_ == 18 ? 0 : 2;
  Eigen::Vector3d centre = here_;
  const auto r = words.find('R');
  if (r == words.end()) {
    for (const int a : {u, v}) {
      const auto w = words.find("IJK"[a]);
      if (w != words.end()) centre[a] = here_[a] + w->second * unit_m_;
    }
  } else {
    const double radius = std::abs(r->second) * unit_m_;
    const double du = end[u] - here_[u], dv = end[v] - here_[v];
    const double chord = std::hypot(du, dv);
    const double h = std::sqrt(std::max(0.0, radius * radius - chord * chord / 4));
    const bool ccw = motion_ == 3;
    for (const double side : {1.0, -1.0}) {
      Eigen::Vector3d c = here_;
      c[u] = here_[u] + du / 2 - side * h * dv / chord;
      c[v] = here_[v] + dv / 2 + side * h * du / chord;
      const double cross = (here_[u] - c[u]) * (end[v] - c[v]) - (here_[v] - c[v]) * (end[u] - c[u]);
      const bool minor = ccw ? cross >= 0 : cross <= 0;
      if (minor == (r->second > 0)) centre = c;
    }
  }
  expected.push_back({motion_ == 2 ? MotionKind::kArcCw : MotionKind::kArcCcw, end, centre, 0.0});
  here_ = end;
}

struct CorpusFile {
  std::string folder, name;
  fs::path path;
};

std::vector<CorpusFile> CorpusFiles() {
  std::vector<CorpusFile> files;
  for (const auto& folder : fs::directory_iterator(kCorpus)) {
    for (const auto& file : fs::directory_iterator(folder.path())) {
      if (file.path().extension() == ".md") continue;
      files.push_back({folder.path().filename().string(), file.path().filename().string(), file.path()});
    }
  }
  return files;
}

// Tests that the corpus holds at least 20 programs from at least 4 origins, each with its
// licence note.
TEST(GcodeCorpusTest, AtLeastTwentyProgramsFromFourOrigins) {
  const std::vector<CorpusFile> files = CorpusFiles();
  EXPECT_GE(files.size(), 20u);
  std::map<std::string, int> origins;
  for (const CorpusFile& file : files) {
    ++origins[file.folder];
    const std::string note = Read(fs::path(kCorpus) / file.folder / "README.md");
    EXPECT_NE(note.find("Licence"), std::string::npos) << file.folder;
    EXPECT_NE(note.find("`" + file.name + "`"), std::string::npos) << file.folder << "/" << file.name;
  }
  EXPECT_GE(origins.size(), 4u);
}

// Tests that every corpus program is read in its dialect with the geometry the independent
// reader expects and planned to its last end point, or refused naming the feature.
TEST(GcodeCorpusTest, EveryProgramRunsOrIsRefusedForAKeptFeature) {
  std::size_t checked = 0, planned = 0, arcs = 0, dwells = 0;
  for (const CorpusFile& file : CorpusFiles()) {
    const std::string key = file.folder + "/" + file.name;
    SCOPED_TRACE(key);
    GcodeOptions options;
    options.program.dialect = DialectOf(file.folder);
    options.program.g28_mm = kG28Mm;
    const std::string text = Read(file.path);
    const auto refused = kRefused.find(key);
    if (refused != kRefused.end()) {
      try {
        ParseGcode(text, Eigen::Vector3d::Zero(), {}, options);
        ADD_FAILURE() << "expected a refusal: " << refused->second;
      } catch (const ProgramError& error) {
        EXPECT_NE(std::string(error.what()).find(refused->second), std::string::npos) << error.what();
      }
      continue;
    }
    const Program program = ParseGcode(text, Eigen::Vector3d::Zero(), {}, options);
    if (text.find(" sub") == std::string::npos) {  // the reader here knows no O-words
      Oracle oracle(options.program.dialect);
      std::istringstream lines(text);
      for (std::string line; std::getline(lines, line);) oracle.Line(line);
      ASSERT_EQ(program.blocks.size(), oracle.expected.size());
      ++checked;
      for (std::size_t k = 0; k < program.blocks.size(); ++k) {
        const ProgramBlock& block = program.blocks[k];
        const Expected& want = oracle.expected[k];
        EXPECT_EQ(block.kind, want.kind) << "block " << k << " line " << block.source_line;
        EXPECT_LE((block.end_m - want.end_m).norm(), kEndTolM) << "line " << block.source_line;
        dwells += want.kind == MotionKind::kDwell ? 1 : 0;
        if (want.kind == MotionKind::kArcCw || want.kind == MotionKind::kArcCcw) {
          ++arcs;
          EXPECT_LE((block.center_m - want.centre_m).norm(), kCentreTolM) << "line " << block.source_line;
        }
        EXPECT_DOUBLE_EQ(block.dwell_s, want.dwell_s) << "line " << block.source_line;
      }
    }
    if (program.blocks.empty()) continue;
    const MultiAxisCommand command = GenerateProgramCommand(ControllerConfig{}, program);
    ++planned;
    for (int a = 0; a < kNumAxes; ++a) {
      double position = command.start_m[a];
      for (std::size_t k = 1; k <= command.axes[a].num_ticks(); ++k) position += command.axes[a].increment_m(k);
      EXPECT_NEAR(position, program.blocks.back().end_m[a], 1e-6) << "axis " << a;
    }
  }
  // All but spiral.ngc (refused) and increment.ngc (a subroutine file, no blocks, read by
  // the O-words it holds) are checked against the reader here and planned.
  EXPECT_EQ(checked, CorpusFiles().size() - 2);
  EXPECT_EQ(planned, CorpusFiles().size() - 2);
  EXPECT_GE(arcs, 100u);
  EXPECT_GE(dwells, 1u);
}

}  // namespace
}  // namespace shapebench::controller

#include "bench/scenario/program_reader.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

#include "bench/config/config_document.h"
#include "bench/config/input_path.h"
#include "controller/gcode_parser.h"
#include "controller/program_builder.h"

namespace shapebench::bench {
namespace {

const std::vector<std::string> kBlockKeys = {"g", "x", "y", "z", "i", "j",
                                             "k", "r", "f", "p", "q", "n"};

controller::Word MakeWord(char letter, double value, const std::string& text) {
  controller::Word word;
  word.letter = letter;
  word.value = value;
  word.text = text;
  return word;
}

// `{x, y, z}` in mm, all three.
Eigen::Vector3d ReadPointMm(const NodeReader& point) {
  point.ExpectMap({"x", "y", "z"});
  Eigen::Vector3d mm;
  const char* const names[] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    const auto value = point.Child(names[a]);
    if (!value) throw point.Error(std::string("missing '") + names[a] + "'; give x, y and z (mm)");
    mm[a] = value->AsNumber();
  }
  return mm;
}

void ReadReferencePositions(const NodeReader& reference, controller::ProgramOptions* options) {
  reference.ExpectMap({"g28", "g30"});
  if (auto g28 = reference.Child("g28")) options->g28_mm = ReadPointMm(*g28);
  if (auto g30 = reference.Child("g30")) options->g30_mm = ReadPointMm(*g30);
}

// `program_arc_tolerance: {absolute_mm, relative, max_mm}`, each >= 0; the ones not given
// keep the dialect's.
void ReadArcTolerance(const NodeReader& node, controller::ProgramOptions* options) {
  node.ExpectMap({"absolute_mm", "relative", "max_mm"});
  controller::ArcTolerance tolerance = options->ArcRule();
  node.Read("absolute_mm", &tolerance.absolute_mm);
  node.Read("relative", &tolerance.relative);
  node.Read("max_mm", &tolerance.max_mm);
  for (const char* key : {"absolute_mm", "relative", "max_mm"}) {
    const auto child = node.Child(key);
    if (child && !(child->AsNumber() >= 0)) throw child->Error(std::string(key) + " must be >= 0");
  }
  options->arc_tolerance = tolerance;
}

}  // namespace

controller::GcodeOptions ReadProgramOptions(const NodeReader& top) {
  controller::GcodeOptions options;
  options.strict_key = "program_strict";
  if (auto strict = top.Child("program_strict")) {
    if (!top.Has("program_file")) {
      throw strict->Error("program_strict applies to a G-code file; give program_file, or remove "
                          "program_strict");
    }
    top.Read<bool>("program_strict", {{"true", true}, {"false", false}}, &options.strict);
  }
  top.Read<controller::Dialect>("program_dialect",
                                {{"fanuc", controller::Dialect::kFanuc},
                                 {"linuxcnc", controller::Dialect::kLinuxcnc},
                                 {"grbl", controller::Dialect::kGrbl}},
                                &options.program.dialect);
  if (auto iterations = top.Child("program_max_iterations")) {
    options.program.max_iterations = iterations->AsInteger();
    if (options.program.max_iterations <= 0) {
      throw iterations->Error("program_max_iterations must be > 0 (loop passes, subprogram "
                              "calls and M99 jumps a program may make)");
    }
  }
  if (auto tolerance = top.Child("program_arc_tolerance")) {
    ReadArcTolerance(*tolerance, &options.program);
  }
  if (auto machine = top.Child("machine"); machine && machine->IsMap()) {
    if (auto reference = machine->Child("reference_mm")) {
      ReadReferencePositions(*reference, &options.program);
    }
  }
  return options;
}

controller::Program ReadProgramList(const NodeReader& program, const Eigen::Vector3d& start_m,
                                    const controller::ProgramOptions& options) {
  controller::ProgramBuilder builder(start_m, options);
  const std::vector<NodeReader> entries = program.Elements();
  for (std::size_t index = 0; index < entries.size(); ++index) {
    const NodeReader& entry = entries[index];
    entry.ExpectMap(kBlockKeys);
    controller::Block block;
    block.source_line = static_cast<int>(index);
    std::vector<NodeReader> word_nodes;  // the YAML value of each word of `block`
    auto add_g = [&](const NodeReader& node) {
      const double code = node.AsNumber();  // 1, or 91.1
      block.words.push_back(MakeWord('G', code, "G" + node.node().Scalar()));
      word_nodes.push_back(node);
    };
    for (const auto& [key, value] : entry.Entries()) {
      if (key == "g") {
        if (value.node().IsSequence()) {
          for (const NodeReader& element : value.Elements()) add_g(element);
        } else {
          add_g(value);
        }
        continue;
      }
      const char letter = static_cast<char>(std::toupper(static_cast<unsigned char>(key[0])));
      const double number = key == "n" ? static_cast<double>(value.AsInteger())
                                       : value.AsNumber();
      block.words.push_back(MakeWord(letter, number, std::string(1, letter) + value.node().Scalar()));
      word_nodes.push_back(value);
    }
    try {
      builder.Apply(block);
    } catch (const controller::ProgramError& error) {
      if (error.word_index() >= 0 &&
          static_cast<std::size_t>(error.word_index()) < word_nodes.size()) {
        throw word_nodes[static_cast<std::size_t>(error.word_index())].Error(error.message());
      }
      throw entry.Error(error.message());
    }
  }
  return builder.TakeProgram();
}

controller::Program ReadProgramFile(const NodeReader& program_file,
                                    const Eigen::Vector3d& start_m,
                                    const controller::GcodeLimits& limits,
                                    const controller::GcodeOptions& options) {
  const std::string reference = program_file.AsString();
  const std::string file = ResolvedInputPath(program_file);
  const std::string shown =
      file == reference ? "'" + reference + "'" : "'" + reference + "' (" + file + ")";
  std::string text;
  std::string error;
  if (!ReadInputFile(file, &text, &error)) {
    throw program_file.Error("G-code file " + shown + ": " + error);
  }
  try {
    controller::Program program = controller::ParseGcode(text, start_m, limits, options);
    program.source_file = file;
    return program;
  } catch (const controller::ProgramError& error) {
    throw ConfigError(file, std::max(1, error.line()), std::max(1, error.column()),
                      program_file.path(), error.message());
  }
}

}  // namespace shapebench::bench

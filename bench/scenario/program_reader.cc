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
                                             "k", "r", "f", "p", "n"};

controller::Word MakeWord(char letter, double value, const std::string& text) {
  controller::Word word;
  word.letter = letter;
  word.value = value;
  word.text = text;
  return word;
}

}  // namespace

controller::Program ReadProgramList(const NodeReader& program, const Eigen::Vector3d& start_m) {
  controller::ProgramBuilder builder(start_m);
  const std::vector<NodeReader> entries = program.Elements();
  for (std::size_t index = 0; index < entries.size(); ++index) {
    const NodeReader& entry = entries[index];
    entry.ExpectMap(kBlockKeys);
    controller::Block block;
    block.source_line = static_cast<int>(index);
    std::vector<NodeReader> word_nodes;  // the YAML value of each word of `block`
    auto add_g = [&](const NodeReader& node) {
      const long code = node.AsInteger();
      block.words.push_back(MakeWord('G', static_cast<double>(code),
                                     "G" + std::to_string(code)));
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
    return controller::ParseGcode(text, start_m, limits, options);
  } catch (const controller::ProgramError& error) {
    throw ConfigError(file, std::max(1, error.line()), std::max(1, error.column()),
                      program_file.path(), error.message());
  }
}

}  // namespace shapebench::bench

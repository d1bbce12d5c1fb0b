// Shared helpers of the bench tests: scratch directories, fixture paths, and running
// the built CLI (SHAPEBENCH_BINARY) as a child process.
#pragma once

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/config/config_error.h"
#include "common/csv.h"
#include "tests/support/cli_binary.h"

namespace shapebench::bench {

// The repository's top: the CLI runs from there, fixtures are read below it.
inline const std::string kSourceDir = SHAPEBENCH_SOURCE_DIR;

}  // namespace shapebench::bench

namespace shapebench::bench::testing {

// In a child about to exec the CLI: bound its memory to `bytes` (see kUnderAddressSanitizer).
inline void LimitChildMemory(unsigned long bytes) {
  if (kUnderAddressSanitizer) {
    const char* old = std::getenv("ASAN_OPTIONS");
    const std::string options = std::string(old != nullptr ? old : "") + ":hard_rss_limit_mb=" +
                                std::to_string(bytes >> 20);
    setenv("ASAN_OPTIONS", options.c_str(), 1);
  } else {
    const rlimit limit{bytes, bytes};
    setrlimit(RLIMIT_AS, &limit);
  }
}

// `args` followed by `more`: a command line and the options every case adds.
inline std::vector<std::string> Args(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

// The ConfigError `read` throws (a failure when it throws none).
template <typename Read>
ConfigError ErrorOf(Read read) {
  try {
    read();
  } catch (const ConfigError& error) {
    return error;
  }
  ADD_FAILURE() << "no ConfigError";
  return ConfigError("", 0, 0, "", "");
}

// Expects the error at FILE:LINE:COL with this key path and a message containing a part.
inline void ExpectError(const ConfigError& error, const std::string& file, int line, int column,
                        const std::string& key_path, const std::string& message_part) {
  EXPECT_EQ(error.file(), file) << error.what();
  EXPECT_EQ(error.line(), line) << error.what();
  EXPECT_EQ(error.column(), column) << error.what();
  EXPECT_EQ(error.key_path(), key_path) << error.what();
  EXPECT_NE(error.message().find(message_part), std::string::npos) << error.what();
}

// A fresh directory under the system temp dir, removed with everything in it.
class ScratchDir {
 public:
  ScratchDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "shapebench_test_XXXXXX").string();
    path_ = mkdtemp(pattern.data());
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  std::string File(const std::string& name) const { return (path_ / name).string(); }
  // Writes `text` to `name` (parent directories created) and returns its path.
  std::string Write(const std::string& name, const std::string& text) const {
    const std::filesystem::path file = path_ / name;
    std::filesystem::create_directories(file.parent_path());
    std::ofstream(file) << text;
    return file.string();
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

inline std::string DataPath(const std::string& name) {
  return std::string(SHAPEBENCH_SOURCE_DIR) + "/tests/bench/data/" + name;
}

inline std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Every record of a CSV file (results.csv and the like), failing the test if its last
// row is torn (a partial line).
inline std::vector<std::vector<std::string>> ReadCsv(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  CsvReader reader(in);
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> fields;
  while (reader.Next(&fields)) rows.push_back(fields);
  EXPECT_FALSE(reader.torn()) << path;
  return rows;
}

// The output directory of a sweep stopped with rows ahead (bench/sweep/rows_ahead.h),
// made in `out` from the finished run in `whole`: its manifest, results.csv.partial with
// the header and the rows of points 0..in_order-1, and results.csv.ahead with the header,
// the rows of the points `ahead` in that order, and then a row torn by a kill. Returns
// those points as SHAPEBENCH_TEST_HANG_POINT takes them ("60,61,...").
inline std::string WriteSweepDirWithRowsAhead(const std::string& whole, const std::string& out, std::size_t in_order,
                                              const std::vector<std::size_t>& ahead) {
  const std::vector<std::vector<std::string>> rows = ReadCsv(whole + "/results.csv");
  std::filesystem::create_directories(out);
  std::filesystem::copy_file(whole + "/manifest.json", out + "/manifest.json");
  std::ofstream partial(out + "/results.csv.partial", std::ios::binary);
  for (std::size_t i = 0; i <= in_order && i < rows.size(); ++i) partial << CsvRecord(rows[i]);
  std::ofstream file(out + "/results.csv.ahead", std::ios::binary);
  file << CsvRecord(rows[0]);
  std::string points;
  for (const std::size_t point : ahead) {
    file << CsvRecord(rows.at(point + 1));
    points += (points.empty() ? "" : ",") + std::to_string(point);
  }
  file << CsvRecord(rows.back()).substr(0, 6);  // torn: no end of record
  return points;
}

struct CliResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string ShellQuoted(const std::string& text) {
  std::string quoted = "'";
  for (const char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

// Runs shell `command` (its own redirections none) with stdout and stderr captured.
inline CliResult RunCapturing(const std::string& command) {
  ScratchDir capture;
  const std::string redirected =
      command + " >" + ShellQuoted(capture.File("out")) + " 2>" + ShellQuoted(capture.File("err"));
  const int status = std::system(redirected.c_str());
  CliResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = ReadText(capture.File("out"));
  result.err = ReadText(capture.File("err"));
  return result;
}

// Runs the CLI with `args` in `work_dir`, capturing stdout and stderr. `wrapper`, when
// given, is shell text put before the binary (an environment assignment, `prlimit ...`).
inline CliResult RunCli(const std::vector<std::string>& args, const std::string& work_dir,
                        const std::string& wrapper = "") {
  std::string command = "cd " + ShellQuoted(work_dir) + " && " + wrapper + ShellQuoted(SHAPEBENCH_BINARY);
  for (const auto& arg : args) command += " " + ShellQuoted(arg);
  return RunCapturing(command);
}

// Starts the CLI as a child process in `work_dir` and returns its pid (the caller waits
// for it or signals it). stdout goes to /dev/null, stderr to `err_file` (empty: /dev/null).
inline pid_t SpawnCli(const std::vector<std::string>& args, const std::string& work_dir,
                      const std::string& err_file = "") {
  const pid_t pid = fork();
  if (pid == 0) {
    const int null = open("/dev/null", O_WRONLY);
    const int err = err_file.empty() ? null : open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(null, STDOUT_FILENO);
    dup2(err, STDERR_FILENO);
    if (chdir(work_dir.c_str()) != 0) _exit(127);
    std::vector<char*> argv;
    std::string binary = SHAPEBENCH_BINARY;
    argv.push_back(binary.data());
    std::vector<std::string> copies = args;
    for (auto& arg : copies) argv.push_back(arg.data());
    argv.push_back(nullptr);
    execv(binary.c_str(), argv.data());
    _exit(127);
  }
  return pid;
}

}  // namespace shapebench::bench::testing

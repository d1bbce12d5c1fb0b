// gnuplot driven through a pipe with the data inline: no user string reaches a shell,
// titles are quoted for gnuplot, the PNG is written to a temporary name and renamed.
#pragma once

#include <cstdio>
#include <functional>
#include <string>

#include "common/atomic_file.h"

namespace shapebench::bench {

// A gnuplot single-quoted string ('' is the only escape; control characters, newlines
// and NUL included, become spaces).
std::string GnuplotQuoted(const std::string& text);

// Why the file at `path` is not a complete PNG (no PNG signature at its start, no IEND
// chunk at its end, empty, unreadable), or "" when it is one.
std::string PngDefect(const std::string& path);

// Commits `temp` as `path_png` when it holds a complete PNG; otherwise throws
// std::runtime_error naming `path_png` and the defect (the temporary file is then removed
// by its destructor, nothing appears under `path_png`).
void CommitPng(TempFile& temp, const std::string& path_png);

// Runs gnuplot, `script` writing its commands for a PNG at `output_path` (a temporary
// name), then renames it to `path_png`. Throws std::runtime_error naming `path_png` when
// gnuplot is missing, fails or writes no complete PNG.
void RunGnuplot(const std::string& path_png,
                const std::function<void(std::FILE* gnuplot, const std::string& output_path)>& script);

// Runs gnuplot, `script` writing its commands for an SVG at `output_path` (a temporary
// file, removed after), and returns the <svg> element (the XML prolog dropped, for inlining
// in HTML). Throws std::runtime_error naming `what` when gnuplot is missing or fails.
std::string RunGnuplotSvg(const std::string& what,
                          const std::function<void(std::FILE* gnuplot, const std::string& output_path)>& script);

}  // namespace shapebench::bench

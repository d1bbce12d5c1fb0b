// gnuplot driven through a pipe with the data inline: no user string reaches a shell,
// titles are quoted for gnuplot, the PNG is written to a temporary name and renamed.
#pragma once

#include <cstdio>
#include <functional>
#include <string>

namespace shapebench::bench {

// A gnuplot single-quoted string ('' is the only escape; control characters, newlines
// and NUL included, become spaces).
std::string GnuplotQuoted(const std::string& text);

// Runs gnuplot, `script` writing its commands for a PNG at `output_path` (a temporary
// name), then renames it to `path_png`. Throws std::runtime_error naming `path_png` when
// gnuplot is missing, fails or writes nothing.
void RunGnuplot(const std::string& path_png,
                const std::function<void(std::FILE* gnuplot, const std::string& output_path)>& script);

}  // namespace shapebench::bench

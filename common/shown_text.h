// User text echoed in messages and on the terminal: cut to a readable length, with its
// control characters made visible (a name with ESC [ 2 J must not clear the screen).
#pragma once

#include <cstddef>
#include <string>

namespace shapebench {

// Longest user value an error message quotes in full.
constexpr std::size_t kMaxShownChars = 200;

// `text` itself, or its first kMaxShownChars bytes (not splitting a UTF-8 character),
// "..." and its full length.
std::string ClippedForMessage(const std::string& text);

// `text` with C0 controls (but tab, and newline when `keep_newlines`), DEL and the C1
// controls (UTF-8 U+0080..U+009F) as visible escapes: "\x1b", "\x7f", "\u009b".
std::string TerminalSafe(const std::string& text, bool keep_newlines = false);

}  // namespace shapebench

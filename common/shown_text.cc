#include "common/shown_text.h"

#include <cstdio>

namespace shapebench {

std::string ClippedForMessage(const std::string& text) {
  if (text.size() <= kMaxShownChars) return text;
  std::size_t cut = kMaxShownChars;
  // Back to the start of a UTF-8 character (continuation bytes are 10xxxxxx).
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;
  return text.substr(0, cut) + "... (" + std::to_string(text.size()) + " characters in all)";
}

std::string TerminalSafe(const std::string& text, bool keep_newlines) {
  std::string safe;
  safe.reserve(text.size());
  char escape[12];
  for (std::size_t i = 0; i < text.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    const unsigned char next = i + 1 < text.size() ? static_cast<unsigned char>(text[i + 1]) : 0;
    if ((c < 0x20 && c != '\t' && !(c == '\n' && keep_newlines)) || c == 0x7F) {
      std::snprintf(escape, sizeof escape, "\\x%02x", c);
      safe += escape;
    } else if (c == 0xC2 && next >= 0x80 && next <= 0x9F) {
      std::snprintf(escape, sizeof escape, "\\u%04x", next);
      safe += escape;
      ++i;
    } else {
      safe += static_cast<char>(c);
    }
  }
  return safe;
}

}  // namespace shapebench

#include "common/decimal.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>

namespace shapebench {
namespace {

// Digits from *i on: how many.
std::size_t Digits(std::string_view text, std::size_t* i) {
  const std::size_t start = *i;
  while (*i < text.size() && std::isdigit(static_cast<unsigned char>(text[*i])) != 0) ++*i;
  return *i - start;
}

}  // namespace

bool IsDecimalText(std::string_view text) {
  std::size_t i = 0;
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
  std::size_t mantissa = Digits(text, &i);
  if (i < text.size() && text[i] == '.') {
    ++i;
    mantissa += Digits(text, &i);
  }
  if (mantissa == 0) return false;
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
    if (Digits(text, &i) == 0) return false;
  }
  return i == text.size();
}

bool ParseDecimal(std::string_view text, double* value) {
  if (!IsDecimalText(text)) return false;
  const std::string copy(text);
  errno = 0;
  const double parsed = std::strtod(copy.c_str(), nullptr);
  if ((errno == ERANGE && std::isinf(parsed)) || !std::isfinite(parsed)) return false;
  *value = parsed;
  return true;
}

}  // namespace shapebench

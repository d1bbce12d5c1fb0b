// std::string::ends_with before C++20.
#pragma once

#include <string_view>

namespace shapebench {

inline bool EndsWith(std::string_view text, std::string_view suffix) {
  return text.size() >= suffix.size() && text.substr(text.size() - suffix.size()) == suffix;
}

}  // namespace shapebench

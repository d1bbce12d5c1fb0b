// Legends that survive real labels: a series named by what differs between the series
// (`method: zvd` when each is a whole pattern mapping), titles too long for the key cut
// and tagged, the full names listed once in a caption under the plot. A gnuplot key whose
// titles are wider than the page draws nothing and warns on stderr.
#pragma once

#include <cstddef>
#include <cstdio>
#include <string>
#include <vector>

namespace shapebench::bench {

// The longest legend title drawn whole.
constexpr std::size_t kMaxLegendChars = 36;

struct FittedLegend {
  std::vector<std::string> titles;   // one per name, at most max_chars characters (UTF-8)
  std::vector<std::string> caption;  // "[n] full name" for each name shortened or cut
};

// Titles for `names` (`full_names[i]` what names[i] stands for; equal when nothing was
// left out): a name longer than `max_chars` is cut to "[n] start…", and every name
// that differs from its full name, or was cut, gets a caption line "[n] full name".
// `max_chars`: a key of one title a row (vertical) has the page's width.
FittedLegend FitLegend(const std::vector<std::string>& names, const std::vector<std::string>& full_names,
                       std::size_t max_chars = kMaxLegendChars);

// What tells the `values` of a swept key apart: for YAML flow mappings ("{method: zvd,
// frequency_hz: 25}") the entries whose values differ between them ("method: zvd"; all of
// them when none differs); other values as they are ("" when the list is empty).
std::vector<std::string> DifferingParts(const std::vector<std::string>& values);

// Draws the caption's lines as labels at the bottom left of the page, one a line, and
// returns how many character rows they take (to add to the bottom margin).
std::size_t WriteCaption(std::FILE* gnuplot, const std::vector<std::string>& caption, int height_px);

// The screen height (0..1) of `rows` caption rows on a page `height_px` tall.
double CaptionHeight(std::size_t rows, int height_px);

}  // namespace shapebench::bench

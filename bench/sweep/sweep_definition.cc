#include "bench/sweep/sweep_definition.h"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "bench/config/rule_location.h"
#include "common/csv.h"

namespace shapebench::bench {
namespace {

// printf's "%.15g" (std::to_chars' general format with a precision is that, to the
// character), without printf's cost: a sweep writes one a point.
std::string Digits15(double value) {
  char text[40];
  const std::to_chars_result written = std::to_chars(text, text + sizeof text, value, std::chars_format::general, 15);
  return std::string(text, written.ptr);
}

// The position of the `index`-th grid override's value for this point.
std::pair<int, int> OverridePosition(const Sweep& sweep, const SweepPoint& point, int index) {
  const std::vector<std::uint64_t> digits = sweep.AxisIndices(point.index);
  int k = 0;
  for (std::size_t a = 0; a < sweep.axes.size(); ++a) {
    for (const auto& values : sweep.axes[a].keys) {
      if (++k == index) return values.Position(digits[a]);
    }
  }
  return {1, 1};
}

}  // namespace

std::uint64_t SweepValues::size() const {
  if (kind == Kind::kSampled) return draw ? draw->size() : 0;
  return kind == Kind::kList ? static_cast<std::uint64_t>(texts.size()) : steps;
}

std::string SweepValues::Text(std::uint64_t i) const {
  if (kind == Kind::kList) return texts[i];
  if (kept_texts != nullptr) return (*kept_texts)[i];
  if (kind == Kind::kSampled) return Digits15(draw->Value(i));
  if (i == 0) return ShortestDouble(from);
  if (i + 1 == steps) return ShortestDouble(to);
  // Inner values in 15 significant digits: 15.3, not 15.300000000000001 (the value a
  // point runs with is the text it shows).
  const double last = static_cast<double>(steps - 1);
  const double k = static_cast<double>(i);
  const double value =
      kind == Kind::kLinear
          ? from + (to - from) * k / last
          : std::exp(std::log(from) + (std::log(to) - std::log(from)) * k / last);
  return Digits15(value);
}

void SweepValues::AssignText(std::uint64_t i, std::string* text) const {
  if (kind == Kind::kList) {
    *text = texts[i];
  } else if (kept_texts != nullptr) {
    *text = (*kept_texts)[i];
  } else {
    *text = Text(i);
  }
}

void SweepValues::KeepTexts() {
  if ((kind != Kind::kLinear && kind != Kind::kLog) || steps > kKeptTexts) return;
  kept_texts = nullptr;  // Text() makes them
  auto made = std::make_shared<std::vector<std::string>>();
  made->reserve(steps);
  for (std::uint64_t i = 0; i < steps; ++i) made->push_back(Text(i));
  kept_texts = std::move(made);
}

std::string SweepValues::Yaml(std::uint64_t i) const {
  return kind == Kind::kList ? yamls[i] : Text(i);
}

std::pair<int, int> SweepValues::Position(std::uint64_t i) const {
  return kind == Kind::kList ? positions[i] : std::make_pair(line, column);
}

std::vector<std::string> Sweep::Keys() const {
  std::vector<std::string> keys;
  for (const auto& axis : axes) {
    for (const auto& values : axis.keys) keys.push_back(values.key);
  }
  return keys;
}

std::vector<std::uint64_t> Sweep::AxisIndices(std::uint64_t point) const {
  std::vector<std::uint64_t> digits(axes.size(), 0);
  for (std::size_t a = axes.size(); a-- > 0;) {
    digits[a] = point % axes[a].size();
    point /= axes[a].size();
  }
  return digits;
}

std::string SweepPoint::Label() const {
  std::string label;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    label += (i == 0 ? "" : ", ") + keys[i] + "=" + texts[i];
  }
  return label;
}

SweepPoint MakePoint(const Sweep& sweep, std::uint64_t index, const std::vector<Override>& sets) {
  SweepPoint point;
  MakePointInto(sweep, index, sets, &point);
  return point;
}

void MakePointInto(const Sweep& sweep, std::uint64_t index, const std::vector<Override>& sets, SweepPoint* point) {
  point->index = index;
  std::size_t keys = 0;
  for (const SweepAxis& axis : sweep.axes) keys += axis.keys.size();
  point->keys.resize(keys);
  point->texts.resize(keys);
  point->overrides.resize(keys + sets.size());
  std::uint64_t rest = index;  // the axes' digits, last axis fastest (Sweep::AxisIndices)
  std::size_t k = keys;
  for (std::size_t a = sweep.axes.size(); a-- > 0;) {
    const std::uint64_t digit = rest % sweep.axes[a].size();
    rest /= sweep.axes[a].size();
    for (std::size_t j = sweep.axes[a].keys.size(); j-- > 0;) {
      const SweepValues& values = sweep.axes[a].keys[j];
      --k;
      point->keys[k] = values.key;
      values.AssignText(digit, &point->texts[k]);
      // Yaml is Text except for a list's values (one conversion a point, not two).
      point->overrides[k].key_path = values.key;
      point->overrides[k].value_yaml =
          values.kind == SweepValues::Kind::kList ? values.yamls[digit] : point->texts[k];
    }
  }
  std::copy(sets.begin(), sets.end(), point->overrides.begin() + static_cast<std::ptrdiff_t>(keys));
}

std::string OverridesKey(std::vector<Override>::const_iterator first,
                         std::vector<Override>::const_iterator last) {
  std::string key;
  for (; first != last; ++first) key += first->key_path + "=" + first->value_yaml + "\n";
  return key;
}

namespace {

// The point's override `index` as the user knows it: a grid value's place in the sweep
// file, or the --set counted among the --set options.
std::string PointMention(const Sweep& sweep, const SweepPoint& point, int index) {
  const int grid_overrides = static_cast<int>(point.keys.size());
  if (index > grid_overrides) return OverrideMention(index - grid_overrides);
  const auto [line, column] = OverridePosition(sweep, point, index);
  return sweep.file + ":" + std::to_string(line) + ":" + std::to_string(column);
}

// A rule's message names its other keys' origins as "(--set:N)" (rule_location.h),
// counting the point's overrides: renumbered here as the location is.
std::string RenumberedMentions(const Sweep& sweep, const SweepPoint& point, const std::string& message) {
  const std::string open = "(" + std::string(kOverrideSource) + ":";
  std::string text;
  std::size_t from = 0;
  for (std::size_t at; (at = message.find(open, from)) != std::string::npos;) {
    std::size_t end = at + open.size();
    while (end < message.size() && message[end] >= '0' && message[end] <= '9') ++end;
    const bool mention = end > at + open.size() && end - at - open.size() <= 9 && end < message.size() &&
                         message[end] == ')';
    const int index = mention ? std::stoi(message.substr(at + open.size(), end - at - open.size())) : 0;
    if (!mention || index < 1 || index > static_cast<int>(point.overrides.size())) {
      text += message.substr(from, at + open.size() - from);
      from = at + open.size();
      continue;
    }
    text += message.substr(from, at - from) + "(" + PointMention(sweep, point, index) + ")";
    from = end + 1;
  }
  return text + message.substr(from);
}

}  // namespace

ConfigError RelocatePointError(const Sweep& sweep, const SweepPoint& point, const ConfigError& error) {
  if (error.file() != kOverrideSource) return error;
  const int grid_overrides = static_cast<int>(point.keys.size());
  const std::string message = RenumberedMentions(sweep, point, error.message());
  if (error.line() >= 1 && error.line() <= grid_overrides) {
    const auto [line, column] = OverridePosition(sweep, point, error.line());
    return ConfigError(sweep.file, line, column, error.key_path(), message);
  }
  return ConfigError(kOverrideSource, error.line() - grid_overrides, 1, error.key_path(), message);
}

bool IsGridOverrideError(const SweepPoint& point, const ConfigError& error) {
  return error.file() == kOverrideSource && error.line() >= 1 &&
         error.line() <= static_cast<int>(point.keys.size());
}

}  // namespace shapebench::bench

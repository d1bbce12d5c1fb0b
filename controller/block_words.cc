#include "controller/block_words.h"

#include <cmath>
#include <cstring>

#include "common/format.h"

namespace shapebench::controller {

BlockWords::BlockWords(const Block& block, Dialect dialect)
    : words_(block.words), line_(block.source_line), dialect_(dialect),
      codes_(block.words.size(), -1) {
  at_.fill(-1);
  for (std::size_t k = 0; k < words_.size(); ++k) {
    const int i = static_cast<int>(k);
    if (!std::isfinite(words_[k].value)) {
      throw WordError(i, "number out of range in '" + Shown(i) + "'");
    }
    if (words_[k].letter == 'G') {
      IndexGWord(i);
    } else {
      IndexAddressWord(i);
    }
  }
}

void BlockWords::IndexGWord(int i) {
  const double number = value(i);
  const int code = GTenths(number);
  if (number < 0 || (code < 0 && number <= 1000)) {
    throw WordError(i, "malformed number '" + Shown(i) + "': G takes an integer or one decimal, "
                       "e.g. G1, G91.1");
  }
  if (code < 0 || !DialectHasG(dialect_, code)) throw Unsupported(i);
  codes_[static_cast<std::size_t>(i)] = code;
  if (code <= 30) {
    TakeGroup(&motion_word_, i, "one motion word (G0-G3) per block");
  } else if (code == 40 || code == 280 || code == 300) {
    TakeGroup(&nonmodal_word_, i, "one of G4, G28 and G30 per block");
  } else if (code >= 170 && code <= 190) {
    TakeGroup(&plane_word_, i, "one plane word (G17, G18, G19) per block");
  } else if (code == 900 || code == 910) {
    TakeGroup(&distance_word_, i, "one of G90 (absolute) and G91 (incremental) per block");
  } else if (code == 901 || code == 911) {
    TakeGroup(&arc_distance_word_, i, "one of G90.1 and G91.1 per block");
  } else if (code == 200 || code == 210) {
    TakeGroup(&units_word_, i, "one of G20 (inch) and G21 (mm) per block");
  } else {
    TakeGroup(&path_mode_word_, i, "one path mode (G61, G61.1, G64) per block");
  }
}

void BlockWords::IndexAddressWord(int i) {
  const char letter = words_[static_cast<std::size_t>(i)].letter;
  if (letter < 'A' || letter > 'Z' || std::strchr("FXYZIJKRPQNU", letter) == nullptr) {
    throw Unsupported(i);
  }
  int& slot = at_[static_cast<std::size_t>(letter - 'A')];
  if (slot >= 0) {
    throw WordError(i, "word " + std::string(1, letter) + " repeated in one block ('" +
                           Shown(slot) + "' and '" + Shown(i) +
                           "'); each word at most once per block");
  }
  slot = i;
}

// The word of a G group; a second one is an error (the same code twice, or `rule`).
void BlockWords::TakeGroup(int* slot, int i, const std::string& rule) {
  if (*slot >= 0) {
    if (code(*slot) == code(i)) {
      throw WordError(i, "word '" + Shown(i) + "' repeated in one block; each word at most "
                         "once per block");
    }
    throw WordError(i, "'" + Shown(*slot) + "' and '" + Shown(i) + "' in one block; " + rule);
  }
  *slot = i;
}

bool BlockWords::HasAxisWord() const {
  for (int a = 0; a < kNumAxes; ++a) {
    if (at(kAxisLetters[a]) >= 0) return true;
  }
  return false;
}

int BlockWords::FirstCentreWord() const {
  int first = -1;
  for (int a = 0; a < kNumAxes; ++a) {
    const int w = at(kCentreLetters[a]);
    if (w >= 0 && (first < 0 || w < first)) first = w;
  }
  return first;
}

bool BlockWords::HasDecimalPoint(int i) const {
  const Word& word = words_[static_cast<std::size_t>(i)];
  if (word.text.empty()) return word.value != std::floor(word.value);
  return word.text.find('.') != std::string::npos;
}

std::string BlockWords::Shown(int i) const {
  const Word& word = words_[static_cast<std::size_t>(i)];
  return word.text.empty() ? std::string(1, word.letter) + FormatNumber(word.value) : word.text;
}

ProgramError BlockWords::WordError(int i, const std::string& message) const {
  return ProgramError(line_, words_[static_cast<std::size_t>(i)].column, i, message);
}

ProgramError BlockWords::BlockError(const std::string& message) const {
  return ProgramError(line_, words_.empty() ? 0 : words_.front().column, -1, message);
}

ProgramError BlockWords::Unsupported(int i) const {
  const Word& word = words_[static_cast<std::size_t>(i)];
  const std::string dialect = DialectName(dialect_);
  std::string why;
  if (word.letter == 'G') {
    const int code = GTenths(word.value);
    const std::string others = code >= 0 ? OtherDialectsWithG(dialect_, code) : "";
    if (!others.empty()) {
      why = " is not in the " + dialect + " dialect; " + others + " read it (program_dialect: " +
            others.substr(0, others.find(' ')) + ")";
    }
  }
  if (why.empty()) why = " is not read by the bench (dialect " + dialect + ")";
  return WordError(i, "unsupported word '" + Shown(i) + "'" + why + "; allowed: " +
                          AllowedWords(dialect_));
}

}  // namespace shapebench::controller

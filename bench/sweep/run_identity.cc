#include "bench/sweep/run_identity.h"

#include <cstddef>
#include <utility>

namespace shapebench::bench {
namespace {

// A value as the message shows it: quoted, or "none" when empty.
std::string ShownIdentityValue(const std::string& value) {
  if (value.empty()) return "none";
  std::string shown = "\"";
  for (const char c : value) {
    if (c == '\n') {
      shown += "\\n";
    } else if (c == '"' || c == '\\') {
      shown += std::string("\\") + c;
    } else {
      shown += c;
    }
  }
  return shown + "\"";
}

}  // namespace

void RunIdentity::Add(const std::string& what, const std::string& value) { fields_.emplace_back(what, value); }

std::string RunIdentity::Encode() const {
  std::string bytes;
  for (const auto& [what, value] : fields_) {
    bytes += what;
    bytes += '\0';
    bytes += value;
    bytes += '\0';
  }
  return bytes;
}

RunIdentity RunIdentity::Decode(const std::string& bytes) {
  RunIdentity identity;
  std::vector<std::string> parts;
  std::size_t at = 0;
  while (at < bytes.size()) {
    const std::size_t end = bytes.find('\0', at);
    if (end == std::string::npos) {
      parts.push_back(bytes.substr(at));
      break;
    }
    parts.push_back(bytes.substr(at, end - at));
    at = end + 1;
  }
  for (std::size_t i = 0; i < parts.size(); i += 2) {
    identity.Add(parts[i], i + 1 < parts.size() ? parts[i + 1] : std::string());
  }
  return identity;
}

std::string IdentityDifference(const std::string& rank0, const std::string& other, int rank) {
  if (rank0 == other) return "";
  const RunIdentity mine = RunIdentity::Decode(rank0);
  const RunIdentity theirs = RunIdentity::Decode(other);
  std::string text;
  auto add = [&](const std::string& what, const std::string& its, const std::string& ours) {
    text += (text.empty() ? "" : "; ") + what + " " + ShownIdentityValue(its) + " on rank " + std::to_string(rank) +
            ", " + ShownIdentityValue(ours) + " on rank 0";
  };
  const auto& a = mine.fields();
  const auto& b = theirs.fields();
  const std::pair<std::string, std::string> none;
  for (std::size_t i = 0; i < a.size() || i < b.size(); ++i) {
    const auto& ours = i < a.size() ? a[i] : none;
    const auto& its = i < b.size() ? b[i] : none;
    if (ours != its) add(ours.first.empty() ? its.first : ours.first, its.second, ours.second);
  }
  return text.empty() ? "its identity differs in its bytes (another shapebench build?)" : text;
}

std::string RankMismatchMessage(const std::vector<std::string>& identities, const std::vector<int>& differing) {
  const int ranks = static_cast<int>(identities.size());
  const int first = differing.front();
  std::string others;
  for (std::size_t i = 1; i < differing.size(); ++i) {
    others += (others.empty() ? "" : ", ") + std::to_string(differing[i]);
  }
  return "MPI rank " + std::to_string(first) + " of " + std::to_string(ranks) +
         " does not run what rank 0 runs: " +
         IdentityDifference(identities[0], identities[static_cast<std::size_t>(first)], first) +
         (others.empty() ? "" : " (rank " + others + " differ" + (differing.size() > 2 ? "" : "s") + " from rank 0 too)") +
         "; every rank must run the same command on the same files with the same --set options "
         "and the same shapebench; nothing was run";
}

}  // namespace shapebench::bench

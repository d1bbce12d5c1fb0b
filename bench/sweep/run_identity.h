// What every MPI rank of one run must share (bench/sweep/sweep_mpi.h, docs/scaling.md):
// the command, the sweep files, the --set options, each sweep's hash (base as read, grid,
// --set, metrics), the shard and shapebench's version. Each rank sends its identity to
// the others before the first point (Distributor::Agree); rank 0 stops the run (exit 2)
// naming the first rank whose identity differs from its own, and what differs, instead of
// writing rows of two different sweeps into one results.csv.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace shapebench::bench {

class RunIdentity {
 public:
  // One field: what it is ("--set options") and its value as shown in the message.
  void Add(const std::string& what, const std::string& value);
  // The bytes ranks exchange: each field's name and value, each ended by a NUL (argv and
  // file names hold none).
  std::string Encode() const;
  static RunIdentity Decode(const std::string& bytes);
  const std::vector<std::pair<std::string, std::string>>& fields() const { return fields_; }

 private:
  std::vector<std::pair<std::string, std::string>> fields_;
};

// Why `other` (rank `rank`'s identity, encoded) is not `rank0` (rank 0's): each field
// that differs with both values, e.g. `--set options "a.b=1" on rank 2, none on rank 0`;
// "" when they are the same bytes.
std::string IdentityDifference(const std::string& rank0, const std::string& other, int rank);

// Rank 0's refusal when ranks `differing` (each > 0, at least one) run something else;
// `identities` are every rank's, encoded: "MPI rank R of N does not run what rank 0 runs:
// WHAT DIFFERS (rank S differs from rank 0 too); every rank must run ...".
std::string RankMismatchMessage(const std::vector<std::string>& identities, const std::vector<int>& differing);

}  // namespace shapebench::bench

// What MPI ranks compare before the first point (bench/sweep/run_identity.h): the
// message rank 0 stops with names the rank and each field that differs, with both values.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/sweep/run_identity.h"

namespace shapebench::bench {
namespace {

RunIdentity SweepIdentity(const std::string& sets, const std::string& hash) {
  RunIdentity identity;
  identity.Add("command", "check");
  identity.Add("sweep files", "configs/sweeps/natural_period.yaml");
  identity.Add("--set options", sets);
  identity.Add("sweep hashes", hash);
  identity.Add("shapebench version", "v1");
  return identity;
}

// Tests that identities round-trip through their bytes, that equal ones have no
// difference, and that the refusal names the first differing rank, each field that
// differs with both values (an empty one as none, a quote escaped), and the other ranks.
TEST(RunIdentity, RefusalNamesTheRankAndWhatDiffers) {
  const std::string mine = SweepIdentity("", "aaaa").Encode();
  const std::string theirs = SweepIdentity("controller.feed_mm_min=20000", "bbbb").Encode();
  EXPECT_EQ(RunIdentity::Decode(theirs).fields(), SweepIdentity("controller.feed_mm_min=20000", "bbbb").fields());
  EXPECT_EQ(IdentityDifference(mine, mine, 1), "");
  EXPECT_EQ(IdentityDifference(mine, theirs, 2),
            "--set options \"controller.feed_mm_min=20000\" on rank 2, none on rank 0; "
            "sweep hashes \"bbbb\" on rank 2, \"aaaa\" on rank 0");
  EXPECT_EQ(RankMismatchMessage({mine, mine, theirs, theirs}, {2, 3}),
            "MPI rank 2 of 4 does not run what rank 0 runs: --set options \"controller.feed_mm_min=20000\" on rank "
            "2, none on rank 0; sweep hashes \"bbbb\" on rank 2, \"aaaa\" on rank 0 (rank 3 differs from rank 0 "
            "too); every rank must run the same command on the same files with the same --set options and the same "
            "shapebench; nothing was run");
  RunIdentity quoted;
  quoted.Add("command", "say \"x\"");
  EXPECT_EQ(IdentityDifference(mine, quoted.Encode(), 1).rfind("command \"say \\\"x\\\"\" on rank 1, \"check\" on rank 0", 0),
            0u);
}

}  // namespace
}  // namespace shapebench::bench

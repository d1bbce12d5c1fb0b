// Two runs' metrics compared bit for bit (a NaN, an undefined metric, equal to a NaN).
#pragma once

#include <cstring>
#include <string>

#include <gtest/gtest.h>

#include "bench/scenario/metrics.h"

namespace shapebench::bench::testing {

inline void ExpectSameBits(const Metrics& a, const Metrics& b, const std::string& what) {
  const auto x = a.Named();
  const auto y = b.Named();
  ASSERT_EQ(x.size(), y.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    EXPECT_EQ(std::memcmp(&x[i].second, &y[i].second, sizeof(double)), 0)
        << what << ": " << x[i].first << " " << x[i].second << " vs " << y[i].second;
  }
}

}  // namespace shapebench::bench::testing

// The CLI the tests run as a child process, and whether it runs under AddressSanitizer.
// Both come from the environment ctest gives a test executable: the plain suite runs the
// build's own shapebench, make test-sanitize's twins (tests/CMakeLists.txt) the sanitized
// one, from the same compiled test code.
#pragma once

#include <cstdlib>
#include <string>

namespace shapebench::bench::testing {

// SHAPEBENCH_BINARY from the environment, else the build's shapebench.
inline const std::string& CliBinary() {
  static const std::string binary = [] {
    const char* from_env = std::getenv("SHAPEBENCH_BINARY");
    return std::string(from_env != nullptr && *from_env != '\0' ? from_env
                                                                 : SHAPEBENCH_DEFAULT_BINARY);
  }();
  return binary;
}

// AddressSanitizer reserves terabytes of address space for its shadow memory, so a child
// run under an address-space limit (RLIMIT_AS, prlimit --as) cannot start under it. There
// the memory bound is ASan's own: an RSS limit in ASAN_OPTIONS (hard_rss_limit_mb), which
// ends the child like the limit would. ctest sets SHAPEBENCH_CLI_UNDER_ASAN for the
// sanitized twins (a test executable itself compiled with ASan knows it anyway).
inline const bool kUnderAddressSanitizer = [] {
#if defined(__SANITIZE_ADDRESS__)
  return true;
#endif
  const char* flag = std::getenv("SHAPEBENCH_CLI_UNDER_ASAN");
  return flag != nullptr && *flag != '\0' && std::string(flag) != "0";
}();

}  // namespace shapebench::bench::testing

// Where the tests name the CLI (a C string, as the compile definition it replaces was).
#define SHAPEBENCH_BINARY (::shapebench::bench::testing::CliBinary().c_str())

// libFuzzer entry of ModalFileTarget (fuzz/fuzz_targets.h).
#include <cstdint>
#include <string>

#include "fuzz/fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > shapebench::fuzz::kMaxInput) return -1;  // not added to the corpus
  shapebench::fuzz::ModalFileTarget(std::string(reinterpret_cast<const char*>(data), size));
  return 0;
}

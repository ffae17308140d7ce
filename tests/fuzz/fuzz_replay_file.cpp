// fuzz_replay_file.cpp — libFuzzer entry for the "replay_file" target (body: fuzz_targets.h).
#include <cstddef>
#include <cstdint>

#include "fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  (void)tandem::fuzz::run_replay_file(std::span<const uint8_t>(data, size));
  return 0;
}

// fuzz_scene.cpp — libFuzzer entry for the "scene" target (body: fuzz_targets.h).
#include <cstddef>
#include <cstdint>

#include "fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  (void)tandem::fuzz::run_scene(std::span<const uint8_t>(data, size));
  return 0;
}

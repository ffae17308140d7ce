// fuzz_session_packet.cpp — libFuzzer entry for the "session_packet" target (body: fuzz_targets.h).
#include <cstddef>
#include <cstdint>

#include "fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  (void)tandem::fuzz::run_session_packet(std::span<const uint8_t>(data, size));
  return 0;
}

// splitmix64.h — one fully specified 64-bit pseudo-random sequence
// (SplitMix64: a Weyl increment, then two xor-shift-multiply mixes), used
// wherever Tandem draws "random" scene data or test inputs: the same seed
// gives the same numbers on every platform, unlike the standard library's
// distributions. Integer only.
#pragma once

#include <cstdint>

namespace tandem {

/// Advances *state by the golden-ratio increment and returns the mixed
/// value. Wraps modulo 2^64 (unsigned arithmetic, no UB).
constexpr uint64_t splitmix64_next(uint64_t* state) {
  uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace tandem

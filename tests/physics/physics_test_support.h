// Helpers shared by the physics tests: a world that is destroyed at the end
// of a test case, the usual tick, and a Q32 → long double conversion for
// oracles and messages (tests only).
#pragma once

#include <catch2/catch.hpp>

#include "physics/tandem.h"
#include "../test_world.h"

namespace tandem::test_support {

/// 2^32 as a long double.
inline constexpr long double k_two32 = 4294967296.0L;
/// A Q32.32 value as a long double (exact: 64-bit mantissa on x86).
inline long double ld(Q32 v) { return static_cast<long double>(v.raw) / k_two32; }
/// The tick used by the tests: the raw value nearest 1/60 s.
inline const Q32 k_dt = Q32::from_ratio(1, 60);

/// A world created from `def` and destroyed when the test case ends.
struct ScopedWorld : UniqueWorld {
  explicit ScopedWorld(const WorldDef& def = default_world_def()) : UniqueWorld(test_world::require_world(def).release()) {}
};

}  // namespace tandem::test_support

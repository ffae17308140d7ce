// test_continuous_filter.cpp — continuous collision's slow-body filter
// (continuous_surely_slow, physics/continuous.cpp) decides on exact unsigned
// integers what fixed.h's saturating form (|d.x| + |d.y| + turn)·2 ≤
// min_extent decides, for every input the step can give it: d from a
// saturating subtraction (never the raw minimum), turn ≥ 0, and min_extent
// of either sign. Raw extremes included, where the saturating sums clip.
#include <catch2/catch.hpp>

#include <cstdint>

#include "fixed/splitmix64.h"
#include "ignore_fixed_faults.h"
#include "physics/world.h"

namespace {

using namespace tandem;

/// A raw value: mostly near `typical`, sometimes an extreme or anything.
int64_t raw_value(uint64_t* state, int64_t typical) {
  const uint64_t pick = splitmix64_next(state) % 8;
  if (pick == 0) return static_cast<int64_t>(splitmix64_next(state));
  if (pick == 1) {
    const int64_t extremes[] = {INT64_MAX, INT64_MIN + 1, INT64_MAX / 2, INT64_MAX / 3, 0, 1, -1};
    return extremes[splitmix64_next(state) % 7];
  }
  return static_cast<int64_t>(splitmix64_next(state) % (2 * static_cast<uint64_t>(typical) + 1)) - typical;
}

}  // namespace

TEST_CASE("continuous collision's slow-body filter equals the saturating form", "[physics][continuous]") {
  const test_support::IgnoreFixedFaults ignore;
  uint64_t state = 0x51077;
  const int64_t one = int64_t{1} << 32;
  int64_t slow = 0, not_slow = 0;
  for (int32_t k = 0; k < 400000; ++k) {
    int64_t dx = raw_value(&state, one);
    int64_t dy = raw_value(&state, one);
    if (dx == INT64_MIN) dx = INT64_MIN + 1;  // a saturating subtraction never returns it
    if (dy == INT64_MIN) dy = INT64_MIN + 1;
    int64_t turn = raw_value(&state, one / 4);
    if (k % 16 != 0) turn = turn < 0 ? (turn == INT64_MIN ? INT64_MAX : -turn) : turn;  // mostly ≥ 0, as in a step
    const int64_t min_extent = k % 32 == 0 ? -raw_value(&state, one) : raw_value(&state, one) & INT64_MAX;
    const Vec2 d{Q32::from_raw(dx), Q32::from_raw(dy)};
    const Q32 t = Q32::from_raw(turn), m = Q32::from_raw(min_extent);
    const bool got = continuous_surely_slow(d, t, m);
    const bool saturating = (abs(d.x) + abs(d.y) + t) * 2 <= m;
    // The filter may only say "slow" where the saturating form does; where
    // turn or min_extent is negative it answers false and leaves the
    // decision to the exact test after it (the body is then judged by
    // |d| + turn, which is at most the saturating form's sum).
    INFO("d " << dx << ", " << dy << " turn " << turn << " min_extent " << min_extent);
    if (turn >= 0 && min_extent >= 0) {
      REQUIRE(got == saturating);
    } else {
      REQUIRE(!got);
    }
    (got ? slow : not_slow) += 1;
  }
  // Both answers occur often (the test is not one-sided).
  CHECK(slow > 10000);
  CHECK(not_slow > 10000);
}

// test_fast_math.cpp — physics/fast_math.h must give the checked operators'
// bits for every input, saturating ones included: release builds with a
// native 128-bit type use its fast paths, other builds the checked operators,
// and the stress (seed 94) reaches saturation inside the API limits.
#include <catch2/catch.hpp>

#include <cstdint>
#include <vector>

#include "fixed/splitmix64.h"
#include "physics/fast_math.h"

namespace {

using tandem::Q32;

void ignore_fault(tandem::FixedFault, const char*) {}

/// Raw values at and around every boundary the saturation tests use, plus
/// random values of every magnitude.
std::vector<int64_t> edge_values() {
  std::vector<int64_t> v = {0, 1, -1, INT64_MAX, -INT64_MAX, INT64_MAX - 1, -INT64_MAX + 1, int64_t{1} << 31,
                            (int64_t{1} << 31) - 1, -(int64_t{1} << 31), int64_t{1} << 32, -(int64_t{1} << 32),
                            int64_t{1} << 62, -(int64_t{1} << 62), (int64_t{1} << 62) + 1, int64_t{3} << 61};
  // Products near the saturation limit 2^95 − 2^31: a·b with a = 2^47.
  for (int64_t d = -3; d <= 3; ++d) v.push_back((int64_t{1} << 48) + d);
  uint64_t state = 94;
  for (int i = 0; i < 200; ++i) {
    const uint64_t r = tandem::splitmix64_next(&state);
    const int shift = static_cast<int>(r % 63);
    const int64_t x = static_cast<int64_t>(tandem::splitmix64_next(&state) >> (shift + 1));
    v.push_back((r & (uint64_t{1} << 63)) != 0 ? -x : x);
  }
  return v;
}

}  // namespace

TEST_CASE("fast_math: mul, add, sub, sum2, diff2 give the checked operators' bits, saturated ones included",
          "[fast_math]") {
  const tandem::FixedFaultHandler old = tandem::set_fixed_fault_handler(&ignore_fault);
  const std::vector<int64_t> v = edge_values();
  int64_t saturated = 0;
  for (int64_t ra : v) {
    for (int64_t rb : v) {
      const Q32 a = Q32::from_raw(ra), b = Q32::from_raw(rb);
      const Q32 p = a * b;
      if (p.raw == INT64_MAX || p.raw == -INT64_MAX) ++saturated;
      REQUIRE(tandem::fast::mul(a, b).raw == p.raw);
      REQUIRE(tandem::fast::add(a, b).raw == (a + b).raw);
      REQUIRE(tandem::fast::sub(a, b).raw == (a - b).raw);
      const Q32 c = Q32::from_raw(rb ^ 0x5555), d = Q32::from_raw(ra / 3);
      REQUIRE(tandem::fast::sum2(a, b, c, d).raw ==
              tandem::detail::sum_products(a.raw, b.raw, c.raw, d.raw, "test").raw);
      REQUIRE(tandem::fast::diff2(a, b, c, d).raw ==
              tandem::detail::sum_products(a.raw, b.raw, tandem::detail::neg_raw(c.raw), d.raw, "test").raw);
    }
  }
  // Exactly at the rounding limit: 2^32·(2^63 − 1) + c·d = 2^95 − 2^31 (+ 0 or
  // −1) rounds to 2^63 (saturates) or to 2^63 − 1 (does not).
  const Q32 one = Q32::one(), max = Q32::from_raw(INT64_MAX), min = Q32::from_raw(-INT64_MAX);
  for (int64_t c : {(int64_t{1} << 31) - 1, int64_t{1} << 31, (int64_t{1} << 31) + 1}) {
    for (int64_t sign : {1, -1}) {
      const Q32 cc = Q32::from_raw(sign * c), a = sign > 0 ? max : min;
      REQUIRE(tandem::fast::sum2(one, a, cc, Q32::from_raw(1)).raw ==
              tandem::detail::sum_products(one.raw, a.raw, cc.raw, 1, "test").raw);
    }
  }
  CHECK(tandem::fast::sum2(one, max, Q32::from_raw(int64_t{1} << 31), Q32::from_raw(1)).raw == INT64_MAX);
  CHECK(tandem::fast::sum2(one, max, Q32::from_raw((int64_t{1} << 31) - 1), Q32::from_raw(1)).raw == INT64_MAX);
  tandem::set_fixed_fault_handler(old);
  CHECK(saturated > 1000);  // the edges are really exercised
}

// test_wide.cpp — wide.h's two 128-bit paths and fixed.h's two Q32.32
// products must give the same bits.
//
// Three layers, so every target is covered, including i686 where the native
// path does not exist:
//  1. Exact values worked out by hand (the derivation is in each comment),
//     checked on the portable path at compile time (static_assert: constant
//     evaluation also rejects any undefined behaviour), at run time through
//     opaque inputs, and on the native path where it exists.
//  2. An independent reference written here — 32-bit limbs, bit-serial
//     shift-and-add multiplication, restoring division, schoolbook rounding —
//     compared with the portable path (and the path the build selected) on
//     seeded random inputs, on every target.
//  3. Native against portable, bit for bit, on millions of seeded random
//     inputs and edge values (targets with __int128).
//
// Inputs come from a seeded std::mt19937_64 drawing raw integers, shaped to
// hit limb boundaries: halves of 0, 1, 2^31−1, 2^31, 2^32−2, 2^32−1, powers of
// two ± small, small magnitudes of both signs, and the 64-bit extremes.
#include <catch2/catch.hpp>

#include <array>
#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>

#include "fixed/fault.h"
#include "fixed/fixed.h"
#include "fixed/wide.h"

using tandem::Q32;
using tandem::wide::U128;
namespace portable = tandem::wide::portable;

namespace {

// Random samples per comparison. The native/portable comparisons are cheap;
// the bit-serial reference runs on a quarter as many.
#if defined(TANDEM_ACCURACY_SAMPLES)
constexpr uint64_t k_samples = TANDEM_ACCURACY_SAMPLES;
#elif defined(NDEBUG)
constexpr uint64_t k_samples = 2'000'000;
#else
constexpr uint64_t k_samples = 1'000'000;
#endif
constexpr uint64_t k_reference_samples = k_samples / 4 > 10'000 ? k_samples / 4 : 10'000;

constexpr uint64_t k_max64 = ~uint64_t{0};
constexpr uint64_t k_top = uint64_t{1} << 63;

// --- formatting for failure messages --------------------------------------------

std::string hex(uint64_t v) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "0x%016" PRIx64, v);
  return buf;
}
std::string hex(U128 v) { return "{lo " + hex(v.lo) + ", hi " + hex(v.hi) + "}"; }

// Counts mismatches in a loop and reports the first few with their inputs, so
// a loop of millions makes a handful of Catch2 assertions, not millions.
struct Mismatches {
  uint64_t count = 0;
  void report(const std::string& what) {
    if (++count <= 5) FAIL_CHECK(what);
  }
};

// --- opaque inputs: keep the optimiser from folding runtime checks ----------------

uint64_t opaque(uint64_t v) {
  volatile uint64_t x = v;
  return x;
}
int64_t opaque_s(int64_t v) {
  volatile int64_t x = v;
  return x;
}
U128 opaque(U128 v) { return U128{opaque(v.lo), opaque(v.hi)}; }

// --- input generation --------------------------------------------------------------

/// A 32-bit limb: one of the boundary patterns, or random.
uint64_t draw_limb(std::mt19937_64& rng) {
  constexpr std::array<uint64_t, 7> k_limbs = {0, 1, 0x7FFFFFFF, 0x80000000, 0xFFFFFFFE, 0xFFFFFFFF, 0x80000001};
  const uint64_t r = rng();
  const uint64_t pick = r % 10;
  return pick < k_limbs.size() ? k_limbs[static_cast<size_t>(pick)] : (r >> 32);
}

/// A 64-bit value shaped to hit boundaries (raw draws only, no std
/// distributions: those differ across standard libraries).
uint64_t draw_u64(std::mt19937_64& rng) {
  constexpr std::array<uint64_t, 12> k_edges = {0,         1,         2,         3,           k_max64,     k_max64 - 1,
                                                k_top,     k_top - 1, k_top + 1, 0xFFFFFFFFu, 0x100000000u, 10'000'000'000'000'000'000u};
  const uint64_t r = rng();
  const unsigned shift = static_cast<unsigned>((r >> 8) & 63);
  switch (r & 7) {
    case 0: return k_edges[static_cast<size_t>((r >> 16) % k_edges.size())];
    case 1:
    case 2: return (draw_limb(rng) << 32) | draw_limb(rng);
    case 3: return rng() >> shift;                        // small magnitudes
    case 4: return ~(rng() >> shift);                     // small negatives
    case 5: return (uint64_t{1} << shift) + (rng() & 3) - 2;  // powers of two ± 2, wrapping
    default: return rng();
  }
}

int64_t draw_s64(std::mt19937_64& rng) { return static_cast<int64_t>(draw_u64(rng)); }  // modulo 2^64 (C++20)

U128 draw_u128(std::mt19937_64& rng) {
  const uint64_t r = rng();
  if ((r & 3) == 0) return tandem::wide::from_s64(draw_s64(rng));  // sign-extended
  return U128{draw_u64(rng), draw_u64(rng)};
}

/// Two raw Q32.32 values whose exact product lies exactly halfway between two
/// representable values: |a·b| = odd·2^31 (odd × 2^j times odd × 2^(31−j)),
/// with random signs and magnitudes from tiny to saturating.
std::array<int64_t, 2> draw_tie(std::mt19937_64& rng) {
  const uint64_t r = rng();
  const unsigned j = static_cast<unsigned>(r % 32);
  uint64_t a = ((rng() >> ((r >> 8) % 64)) | 1u) << j;
  uint64_t b = ((rng() >> ((r >> 16) % 64)) | 1u) << (31 - j);
  if ((r >> 24) & 1u) a = 0u - a;  // negation keeps the form odd·2^j (mod 2^64)
  if ((r >> 25) & 1u) b = 0u - b;
  return {static_cast<int64_t>(a), static_cast<int64_t>(b)};
}

/// A division n / d whose quotient fits in 64 bits: d ≠ 0, n.hi < d.
struct Division {
  U128 n;
  uint64_t d;
};
Division draw_division(std::mt19937_64& rng) {
  uint64_t d = draw_u64(rng);
  if (d == 0) d = 1 + (rng() >> 1);
  const uint64_t r = rng();
  uint64_t hi;
  switch (r & 3) {
    case 0: hi = d - 1; break;  // largest quotients
    case 1: hi = 0; break;      // 64-bit dividends
    case 2: hi = draw_u64(rng) % d; break;
    default: hi = rng() % d; break;
  }
  return Division{U128{draw_u64(rng), hi}, d};
}

// --- the independent reference: four 32-bit limbs, least significant first ------
// Plain loops with carries held in 64-bit integers; no code shared with wide.h.

using Limbs = std::array<uint64_t, 4>;  // each element < 2^32

constexpr Limbs to_limbs(U128 v) {
  return Limbs{v.lo & 0xFFFFFFFFu, v.lo >> 32, v.hi & 0xFFFFFFFFu, v.hi >> 32};
}
constexpr U128 from_limbs(const Limbs& l) { return U128{l[0] | (l[1] << 32), l[2] | (l[3] << 32)}; }

constexpr Limbs ref_add(const Limbs& a, const Limbs& b, uint64_t carry_in = 0) {
  Limbs r{};
  uint64_t carry = carry_in;
  for (size_t i = 0; i < 4; ++i) {
    const uint64_t s = a[i] + b[i] + carry;  // < 2^34
    r[i] = s & 0xFFFFFFFFu;
    carry = s >> 32;
  }
  return r;  // the final carry is 2^128: dropped (modulo 2^128)
}
constexpr Limbs ref_not(const Limbs& a) {
  Limbs r{};
  for (size_t i = 0; i < 4; ++i) r[i] = a[i] ^ 0xFFFFFFFFu;
  return r;
}
constexpr Limbs ref_neg(const Limbs& a) { return ref_add(ref_not(a), Limbs{}, 1); }
constexpr Limbs ref_sub(const Limbs& a, const Limbs& b) { return ref_add(a, ref_not(b), 1); }
constexpr Limbs ref_shl1(const Limbs& a, uint64_t bit_in) {
  Limbs r{};
  uint64_t carry = bit_in;
  for (size_t i = 0; i < 4; ++i) {
    r[i] = ((a[i] << 1) | carry) & 0xFFFFFFFFu;
    carry = a[i] >> 31;
  }
  return r;
}
constexpr bool ref_less(const Limbs& a, const Limbs& b) {
  for (size_t i = 4; i-- > 0;) {
    if (a[i] != b[i]) return a[i] < b[i];
  }
  return false;
}
/// a × b by shift-and-add, one bit of b at a time (most significant first).
constexpr Limbs ref_mul_u64(uint64_t a, uint64_t b) {
  const Limbs la = to_limbs(U128{a, 0});
  Limbs acc{};
  for (int bit = 63; bit >= 0; --bit) {
    acc = ref_shl1(acc, 0);
    if ((b >> bit) & 1u) acc = ref_add(acc, la);
  }
  return acc;
}
constexpr uint64_t magnitude(int64_t v) { return v < 0 ? 0u - static_cast<uint64_t>(v) : static_cast<uint64_t>(v); }
constexpr Limbs ref_mul_s64(int64_t a, int64_t b) {
  const Limbs m = ref_mul_u64(magnitude(a), magnitude(b));
  return ((a < 0) != (b < 0)) ? ref_neg(m) : m;
}
/// Restoring division, one bit at a time: n / d and n % d (n.hi < d, d ≠ 0).
constexpr uint64_t ref_div(U128 n, uint64_t d, uint64_t* out_rem) {
  const Limbs ln = to_limbs(n), ld = to_limbs(U128{d, 0});
  Limbs rem{};
  uint64_t q = 0;
  for (int bit = 127; bit >= 0; --bit) {
    rem = ref_shl1(rem, (ln[static_cast<size_t>(bit / 32)] >> (bit % 32)) & 1u);
    q <<= 1;  // the quotient's high 64 bits are zero when n.hi < d
    if (!ref_less(rem, ld)) {
      rem = ref_sub(rem, ld);
      q |= 1u;
    }
  }
  *out_rem = from_limbs(rem).lo;
  return q;
}
/// Q32.32 product: exact product, magnitude rounded half up (so ties go away
/// from zero), saturated to ±(2^63 − 1). *out_overflow set when saturated.
constexpr int64_t ref_mul_q32(int64_t a, int64_t b, bool* out_overflow) {
  Limbs m = ref_mul_u64(magnitude(a), magnitude(b));
  m = ref_add(m, Limbs{0x80000000u, 0, 0, 0});  // + one half ulp (2^31)
  // Divide by 2^32: drop the lowest limb.
  const bool too_big = m[3] != 0 || m[2] > 0x7FFFFFFFu;
  *out_overflow = too_big;
  const uint64_t mag = too_big ? static_cast<uint64_t>(INT64_MAX) : (m[1] | (m[2] << 32));
  const int64_t s = static_cast<int64_t>(mag);
  return ((a < 0) != (b < 0)) ? -s : s;
}

// The reference checks itself against the same hand-computed values below.
static_assert(from_limbs(ref_mul_u64(k_max64, k_max64)) == U128{1, k_max64 - 1});
static_assert(from_limbs(ref_mul_s64(INT64_MIN, 1)) == U128{k_top, k_max64});

// --- hand-computed values ----------------------------------------------------------

struct MulU64Case {
  uint64_t a, b;
  U128 product;
};
constexpr std::array<MulU64Case, 10> k_mul_u64_cases = {{
    {0, k_max64, {0, 0}},
    {1, k_max64, {k_max64, 0}},
    // (2^64−1)^2 = 2^128 − 2^65 + 1: hi = 2^64 − 2, lo = 1.
    {k_max64, k_max64, {1, k_max64 - 1}},
    // 2^32 · 2^32 = 2^64.
    {0x100000000u, 0x100000000u, {0, 1}},
    // (2^32−1)^2 = 2^64 − 2^33 + 1.
    {0xFFFFFFFFu, 0xFFFFFFFFu, {0xFFFFFFFE00000001u, 0}},
    // (2^32+1)(2^32−1) = 2^64 − 1.
    {0x100000001u, 0xFFFFFFFFu, {k_max64, 0}},
    // (2^32+1)^2 = 2^64 + 2^33 + 1.
    {0x100000001u, 0x100000001u, {0x200000001u, 1}},
    // 10^18 · 10^18 = 10^36 = 0x00C097CE7BC90715'B34B9F1000000000.
    {1'000'000'000'000'000'000u, 1'000'000'000'000'000'000u, {0xB34B9F1000000000u, 0x00C097CE7BC90715u}},
    // 2^63 · 2^63 = 2^126.
    {k_top, k_top, {0, uint64_t{1} << 62}},
    // 2^63 · 2 = 2^64.
    {k_top, 2, {0, 1}},
}};

struct MulS64Case {
  int64_t a, b;
  U128 product;  // two's complement
};
constexpr std::array<MulS64Case, 10> k_mul_s64_cases = {{
    {-1, -1, {1, 0}},
    {-1, 1, {k_max64, k_max64}},
    {0, INT64_MIN, {0, 0}},
    // −2^63 · −1 = 2^63.
    {INT64_MIN, -1, {k_top, 0}},
    // −2^63 · 1 = −2^63: sign-extended.
    {INT64_MIN, 1, {k_top, k_max64}},
    // (−2^63)^2 = 2^126.
    {INT64_MIN, INT64_MIN, {0, uint64_t{1} << 62}},
    // (2^63−1)^2 = 2^126 − 2^64 + 1.
    {INT64_MAX, INT64_MAX, {1, 0x3FFFFFFFFFFFFFFFu}},
    // (2^63−1)(−2^63) = −2^126 + 2^63 ≡ 2^128 − 2^126 + 2^63.
    {INT64_MAX, INT64_MIN, {k_top, 0xC000000000000000u}},
    // −3 · 5 = −15 ≡ 2^128 − 15.
    {-3, 5, {k_max64 - 14, k_max64}},
    // −2^32 · 2^32 = −2^64: hi all ones, lo zero.
    {-0x100000000, 0x100000000, {0, k_max64}},
}};

struct BinaryCase {
  U128 a, b, result;
};
// a + b modulo 2^128.
constexpr std::array<BinaryCase, 5> k_add_cases = {{
    {{k_max64, k_max64}, {1, 0}, {0, 0}},          // 2^128 − 1 + 1 wraps to 0
    {{k_max64, 0}, {1, 0}, {0, 1}},                // carry into hi
    {{k_top, 0}, {k_top, 0}, {0, 1}},              // 2^63 + 2^63 = 2^64
    {{k_max64, k_max64}, {k_max64, k_max64}, {k_max64 - 1, k_max64}},  // −1 + −1 = −2
    {{5, 7}, {7, 5}, {12, 12}},
}};
// a − b modulo 2^128.
constexpr std::array<BinaryCase, 5> k_sub_cases = {{
    {{0, 0}, {1, 0}, {k_max64, k_max64}},  // 0 − 1 = −1
    {{0, 1}, {1, 0}, {k_max64, 0}},        // 2^64 − 1: borrow from hi
    // (7·2^64 + 5) − (5·2^64 + 7) = 2·2^64 − 2 = 2^64 + (2^64 − 2).
    {{5, 7}, {7, 5}, {k_max64 - 1, 1}},
    {{0, k_top}, {1, 0}, {k_max64, k_top - 1}},  // −2^127 − 1 wraps to 2^127 − 1
    {{12, 12}, {12, 12}, {0, 0}},
}};
struct NegCase {
  U128 a, result;
};
constexpr std::array<NegCase, 5> k_neg_cases = {{
    {{0, 0}, {0, 0}},
    {{1, 0}, {k_max64, k_max64}},          // −1
    {{0, 1}, {0, k_max64}},                // −2^64
    {{0, k_top}, {0, k_top}},              // −(−2^127) wraps to itself
    {{k_max64, k_max64}, {1, 0}},          // −(−1) = 1
}};
struct DivCase {
  U128 n;
  uint64_t d, quotient, remainder;
};
constexpr std::array<DivCase, 10> k_div_cases = {{
    {{0, 1}, 2, k_top, 0},  // 2^64 / 2 = 2^63
    {{5, 0}, 3, 1, 2},
    {{12345, 0}, 1, 12345, 0},
    // n = (d−1)·2^64 + 2^64 − 1 = d·2^64 − 1 = d·(2^64 − 1) + (d − 1).
    {{k_max64, 2}, 3, k_max64, 2},
    {{k_max64, 0xFFFFFFFF00000000u}, 0xFFFFFFFF00000001u, k_max64, 0xFFFFFFFF00000000u},
    // 2^127 − 1 = (2^63 + 1)(2^64 − 2) + 1.
    {{k_max64, k_top - 1}, k_top + 1, k_max64 - 1, 1},
    // 10^36 / 10^18 = 10^18; (10^36 + 12345) / 10^18 = 10^18 rem 12345.
    {{0xB34B9F1000000000u, 0x00C097CE7BC90715u}, 1'000'000'000'000'000'000u, 1'000'000'000'000'000'000u, 0},
    {{0xB34B9F1000003039u, 0x00C097CE7BC90715u}, 1'000'000'000'000'000'000u, 1'000'000'000'000'000'000u, 12345},
    // 2^64 = (2^64 − 1)·1 + 1.
    {{0, 1}, k_max64, 1, 1},
    // (2^31 − 1)·2^64 / 2^31 = (2^31 − 1)·2^33 = 0xFFFFFFFE00000000.
    {{0, 0x7FFFFFFFu}, 0x80000000u, 0xFFFFFFFE00000000u, 0},
}};

struct MulQ32Case {
  int64_t a, b;  // raw Q32.32
  int64_t product;
  bool saturates;
};
constexpr int64_t k_one = int64_t{1} << 32;
constexpr int64_t k_half = int64_t{1} << 31;
constexpr std::array<MulQ32Case, 16> k_mul_q32_cases = {{
    {k_one, k_one, k_one, false},
    {3 * k_half, 2 * k_one, 3 * k_one, false},   // 1.5 × 2 = 3
    {1, k_half, 1, false},                       // 2^-32 × 0.5 = half an ulp: tie, away from zero
    {-1, k_half, -1, false},                     // −half an ulp: away from zero
    {3, k_half, 2, false},                       // 1.5 ulp → 2
    {-3, k_half, -2, false},                     // −1.5 ulp → −2
    {1, k_half - 1, 0, false},                   // just under half an ulp → 0
    {-1, k_half - 1, 0, false},
    {1, 1, 0, false},                            // 2^-64 → 0
    {INT64_MAX, k_one, INT64_MAX, false},        // max × 1: exact
    {-INT64_MAX, k_one, -INT64_MAX, false},
    {INT64_MAX, INT64_MAX, INT64_MAX, true},     // max² saturates
    {INT64_MAX, -INT64_MAX, -INT64_MAX, true},   // to the symmetric range
    {INT64_MIN, k_one, -INT64_MAX, true},        // −2^31 itself is outside ±max
    {INT64_MIN, -k_one, INT64_MAX, true},
    {int64_t{1} << 48, int64_t{1} << 47, INT64_MAX, true},  // 2^16 × 2^15 = 2^31 > max
}};

// Compile-time: the portable path on every case (no UB, or this would not compile).
constexpr bool portable_matches_hand_values() {
  for (const auto& c : k_mul_u64_cases) {
    if (!(portable::mul_u64(c.a, c.b) == c.product)) return false;
    if (!(portable::mul_u64(c.b, c.a) == c.product)) return false;
  }
  for (const auto& c : k_mul_s64_cases) {
    if (!(portable::mul_s64(c.a, c.b) == c.product)) return false;
    if (!(portable::mul_s64(c.b, c.a) == c.product)) return false;
  }
  for (const auto& c : k_add_cases) {
    if (!(portable::add(c.a, c.b) == c.result) || !(portable::add(c.b, c.a) == c.result)) return false;
  }
  for (const auto& c : k_sub_cases) {
    if (!(portable::sub(c.a, c.b) == c.result)) return false;
  }
  for (const auto& c : k_neg_cases) {
    if (!(portable::neg(c.a) == c.result)) return false;
  }
  for (const auto& c : k_div_cases) {
    uint64_t rem = 0;
    if (portable::div_u128_u64(c.n, c.d, &rem) != c.quotient || rem != c.remainder) return false;
  }
  for (const auto& c : k_mul_q32_cases) {
    if (c.saturates) continue;  // saturation reports a fault: not a constant expression in checked builds
    if (tandem::mul_portable(Q32::from_raw(c.a), Q32::from_raw(c.b)).raw != c.product) return false;
  }
  return true;
}
static_assert(portable_matches_hand_values(), "wide.h portable path disagrees with a hand-computed value");

// --- fault counting ------------------------------------------------------------------

int g_faults = 0;
void count_fault(tandem::FixedFault, const char*) { ++g_faults; }

/// Installs the counting handler for one scope and restores the old one.
struct CountFaults {
  tandem::FixedFaultHandler old;
  CountFaults() : old(tandem::set_fixed_fault_handler(count_fault)) { g_faults = 0; }
  ~CountFaults() { tandem::set_fixed_fault_handler(old); }
  CountFaults(const CountFaults&) = delete;
  CountFaults& operator=(const CountFaults&) = delete;
};

constexpr int k_fault_per_saturation = TANDEM_FIXED_CHECKS ? 1 : 0;

}  // namespace

// --- layer 1: hand-computed values at run time ----------------------------------------

TEST_CASE("wide: portable path matches hand-computed values", "[fixed][wide]") {
  for (const auto& c : k_mul_u64_cases) {
    INFO("mul_u64(" << hex(c.a) << ", " << hex(c.b) << ")");
    CHECK(portable::mul_u64(opaque(c.a), opaque(c.b)) == c.product);
    CHECK(tandem::wide::mul_u64(opaque(c.a), opaque(c.b)) == c.product);
  }
  for (const auto& c : k_mul_s64_cases) {
    INFO("mul_s64(" << c.a << ", " << c.b << ")");
    CHECK(portable::mul_s64(opaque_s(c.a), opaque_s(c.b)) == c.product);
    CHECK(tandem::wide::mul_s64(opaque_s(c.a), opaque_s(c.b)) == c.product);
  }
  for (const auto& c : k_add_cases) {
    INFO("add(" << hex(c.a) << ", " << hex(c.b) << ")");
    CHECK(portable::add(opaque(c.a), opaque(c.b)) == c.result);
    CHECK(tandem::wide::add(opaque(c.a), opaque(c.b)) == c.result);
  }
  for (const auto& c : k_sub_cases) {
    INFO("sub(" << hex(c.a) << ", " << hex(c.b) << ")");
    CHECK(portable::sub(opaque(c.a), opaque(c.b)) == c.result);
    CHECK(tandem::wide::sub(opaque(c.a), opaque(c.b)) == c.result);
  }
  for (const auto& c : k_neg_cases) {
    INFO("neg(" << hex(c.a) << ")");
    CHECK(portable::neg(opaque(c.a)) == c.result);
    CHECK(tandem::wide::neg(opaque(c.a)) == c.result);
  }
  for (const auto& c : k_div_cases) {
    INFO("div_u128_u64(" << hex(c.n) << ", " << hex(c.d) << ")");
    uint64_t rem = ~uint64_t{0};
    CHECK(portable::div_u128_u64(opaque(c.n), opaque(c.d), &rem) == c.quotient);
    CHECK(rem == c.remainder);
    rem = ~uint64_t{0};
    CHECK(tandem::wide::div_u128_u64(opaque(c.n), opaque(c.d), &rem) == c.quotient);
    CHECK(rem == c.remainder);
  }
}

TEST_CASE("wide: Q32.32 product matches hand-computed values", "[fixed][wide]") {
  CountFaults faults;
  for (const auto& c : k_mul_q32_cases) {
    INFO("raw " << c.a << " * raw " << c.b);
    const Q32 a = Q32::from_raw(opaque_s(c.a)), b = Q32::from_raw(opaque_s(c.b));
    g_faults = 0;
    CHECK(tandem::mul_portable(a, b).raw == c.product);
    CHECK(g_faults == (c.saturates ? k_fault_per_saturation : 0));
    g_faults = 0;
    CHECK((a * b).raw == c.product);
    CHECK(g_faults == (c.saturates ? k_fault_per_saturation : 0));
    // Swapped operands and negation symmetry: (−a)·b = −(a·b) (±max is symmetric).
    CHECK(tandem::mul_portable(b, a).raw == c.product);
    if (c.a != INT64_MIN) CHECK(tandem::mul_portable(Q32::from_raw(-c.a), b).raw == -c.product);
  }
}

#if defined(__SIZEOF_INT128__)
TEST_CASE("wide: native path matches hand-computed values", "[fixed][wide]") {
  namespace native = tandem::wide::native;
  for (const auto& c : k_mul_u64_cases) {
    INFO("mul_u64(" << hex(c.a) << ", " << hex(c.b) << ")");
    CHECK(native::mul_u64(opaque(c.a), opaque(c.b)) == c.product);
  }
  for (const auto& c : k_mul_s64_cases) {
    INFO("mul_s64(" << c.a << ", " << c.b << ")");
    CHECK(native::mul_s64(opaque_s(c.a), opaque_s(c.b)) == c.product);
  }
  for (const auto& c : k_add_cases) CHECK(native::add(opaque(c.a), opaque(c.b)) == c.result);
  for (const auto& c : k_sub_cases) CHECK(native::sub(opaque(c.a), opaque(c.b)) == c.result);
  for (const auto& c : k_neg_cases) CHECK(native::neg(opaque(c.a)) == c.result);
  for (const auto& c : k_div_cases) {
    INFO("div_u128_u64(" << hex(c.n) << ", " << hex(c.d) << ")");
    uint64_t rem = ~uint64_t{0};
    CHECK(native::div_u128_u64(opaque(c.n), opaque(c.d), &rem) == c.quotient);
    CHECK(rem == c.remainder);
  }
  CountFaults faults;
  for (const auto& c : k_mul_q32_cases) {
    INFO("raw " << c.a << " * raw " << c.b);
    g_faults = 0;
    CHECK(tandem::mul_native(Q32::from_raw(opaque_s(c.a)), Q32::from_raw(opaque_s(c.b))).raw == c.product);
    CHECK(g_faults == (c.saturates ? k_fault_per_saturation : 0));
  }
}
#endif

// --- layer 2: portable (and the selected path) against the bit-serial reference -------

TEST_CASE("wide: portable path matches an independent reference", "[fixed][wide]") {
  std::mt19937_64 rng(0x7A4DE11'0001u);
  Mismatches bad;
  for (uint64_t i = 0; i < k_reference_samples; ++i) {
    const uint64_t ua = draw_u64(rng), ub = draw_u64(rng);
    const U128 ref_u = from_limbs(ref_mul_u64(ua, ub));
    if (!(portable::mul_u64(ua, ub) == ref_u) || !(tandem::wide::mul_u64(ua, ub) == ref_u)) {
      bad.report("mul_u64(" + hex(ua) + ", " + hex(ub) + "): reference " + hex(ref_u) + ", portable " +
                 hex(portable::mul_u64(ua, ub)) + ", selected " + hex(tandem::wide::mul_u64(ua, ub)));
    }
    const int64_t sa = static_cast<int64_t>(ua), sb = static_cast<int64_t>(ub);
    const U128 ref_s = from_limbs(ref_mul_s64(sa, sb));
    if (!(portable::mul_s64(sa, sb) == ref_s) || !(tandem::wide::mul_s64(sa, sb) == ref_s)) {
      bad.report("mul_s64(" + std::to_string(sa) + ", " + std::to_string(sb) + "): reference " + hex(ref_s) +
                 ", portable " + hex(portable::mul_s64(sa, sb)));
    }
    const U128 x = draw_u128(rng), y = draw_u128(rng);
    const U128 ref_add_xy = from_limbs(ref_add(to_limbs(x), to_limbs(y)));
    const U128 ref_sub_xy = from_limbs(ref_sub(to_limbs(x), to_limbs(y)));
    const U128 ref_neg_x = from_limbs(ref_neg(to_limbs(x)));
    if (!(portable::add(x, y) == ref_add_xy) || !(tandem::wide::add(x, y) == ref_add_xy)) {
      bad.report("add(" + hex(x) + ", " + hex(y) + "): reference " + hex(ref_add_xy));
    }
    if (!(portable::sub(x, y) == ref_sub_xy) || !(tandem::wide::sub(x, y) == ref_sub_xy)) {
      bad.report("sub(" + hex(x) + ", " + hex(y) + "): reference " + hex(ref_sub_xy));
    }
    if (!(portable::neg(x) == ref_neg_x) || !(tandem::wide::neg(x) == ref_neg_x)) {
      bad.report("neg(" + hex(x) + "): reference " + hex(ref_neg_x));
    }
    const Division dv = draw_division(rng);
    uint64_t ref_rem = 0, p_rem = 0, s_rem = 0;
    const uint64_t ref_q = ref_div(dv.n, dv.d, &ref_rem);
    const uint64_t p_q = portable::div_u128_u64(dv.n, dv.d, &p_rem);
    const uint64_t s_q = tandem::wide::div_u128_u64(dv.n, dv.d, &s_rem);
    if (p_q != ref_q || p_rem != ref_rem || s_q != ref_q || s_rem != ref_rem) {
      bad.report("div_u128_u64(" + hex(dv.n) + ", " + hex(dv.d) + "): reference q " + hex(ref_q) + " r " +
                 hex(ref_rem) + ", portable q " + hex(p_q) + " r " + hex(p_rem));
    }
  }
  INFO(k_reference_samples << " samples per function");
  CHECK(bad.count == 0);
}

TEST_CASE("wide: division identity n = q·d + r, r < d", "[fixed][wide]") {
  // Needs no reference at all: checked with the (separately tested) portable
  // multiply and add, on every target.
  std::mt19937_64 rng(0x7A4DE11'0002u);
  Mismatches bad;
  for (uint64_t i = 0; i < k_samples; ++i) {
    const Division dv = draw_division(rng);
    uint64_t rem = 0;
    const uint64_t q = portable::div_u128_u64(dv.n, dv.d, &rem);
    const U128 back = portable::add(portable::mul_u64(q, dv.d), U128{rem, 0});
    if (!(back == dv.n) || rem >= dv.d) {
      bad.report("div_u128_u64(" + hex(dv.n) + ", " + hex(dv.d) + ") = " + hex(q) + " r " + hex(rem));
    }
  }
  INFO(k_samples << " samples");
  CHECK(bad.count == 0);
}

TEST_CASE("wide: mul_portable matches the reference Q32.32 product", "[fixed][wide]") {
  CountFaults faults;
  std::mt19937_64 rng(0x7A4DE11'0003u);
  Mismatches bad;
  uint64_t saturated = 0, ties = 0;
  for (uint64_t i = 0; i < k_reference_samples; ++i) {
    int64_t a = draw_s64(rng), b = draw_s64(rng);
    if ((i & 3) == 0) {
      const auto tie = draw_tie(rng);
      a = tie[0];
      b = tie[1];
    }
    bool overflow = false;
    const int64_t expected = ref_mul_q32(a, b, &overflow);
    g_faults = 0;
    const int64_t got = tandem::mul_portable(Q32::from_raw(a), Q32::from_raw(b)).raw;
    const int64_t got_op = (Q32::from_raw(a) * Q32::from_raw(b)).raw;
    const int expected_faults = overflow ? 2 * k_fault_per_saturation : 0;
    if (got != expected || got_op != expected || g_faults != expected_faults) {
      bad.report("raw " + std::to_string(a) + " * raw " + std::to_string(b) + ": reference " +
                 std::to_string(expected) + ", mul_portable " + std::to_string(got) + ", operator* " +
                 std::to_string(got_op) + ", faults " + std::to_string(g_faults));
    }
    saturated += overflow ? 1u : 0u;
    ties += (static_cast<uint64_t>(a) * static_cast<uint64_t>(b) & 0xFFFFFFFFu) == 0x80000000u ? 1u : 0u;
  }
  INFO(k_reference_samples << " samples, " << saturated << " saturated, " << ties << " exact ties");
  CHECK(bad.count == 0);
  // The generator must actually reach both interesting regions.
  CHECK(saturated > 0);
  CHECK(ties > 0);
}

// --- layer 3: native against portable, bit for bit --------------------------------------

#if defined(__SIZEOF_INT128__)
TEST_CASE("wide: native and portable paths agree bit for bit", "[fixed][wide]") {
  namespace native = tandem::wide::native;
  std::mt19937_64 rng(0x7A4DE11'0004u);
  Mismatches bad;
  for (uint64_t i = 0; i < k_samples; ++i) {
    const uint64_t ua = draw_u64(rng), ub = draw_u64(rng);
    if (!(native::mul_u64(ua, ub) == portable::mul_u64(ua, ub))) {
      bad.report("mul_u64(" + hex(ua) + ", " + hex(ub) + "): native " + hex(native::mul_u64(ua, ub)) +
                 ", portable " + hex(portable::mul_u64(ua, ub)));
    }
    const int64_t sa = draw_s64(rng), sb = draw_s64(rng);
    if (!(native::mul_s64(sa, sb) == portable::mul_s64(sa, sb))) {
      bad.report("mul_s64(" + std::to_string(sa) + ", " + std::to_string(sb) + "): native " +
                 hex(native::mul_s64(sa, sb)) + ", portable " + hex(portable::mul_s64(sa, sb)));
    }
    const U128 x = draw_u128(rng), y = draw_u128(rng);
    if (!(native::add(x, y) == portable::add(x, y))) bad.report("add(" + hex(x) + ", " + hex(y) + ")");
    if (!(native::sub(x, y) == portable::sub(x, y))) bad.report("sub(" + hex(x) + ", " + hex(y) + ")");
    if (!(native::neg(x) == portable::neg(x))) bad.report("neg(" + hex(x) + ")");
    const Division dv = draw_division(rng);
    uint64_t n_rem = 0, p_rem = 0;
    const uint64_t n_q = native::div_u128_u64(dv.n, dv.d, &n_rem);
    const uint64_t p_q = portable::div_u128_u64(dv.n, dv.d, &p_rem);
    if (n_q != p_q || n_rem != p_rem) {
      bad.report("div_u128_u64(" + hex(dv.n) + ", " + hex(dv.d) + "): native q " + hex(n_q) + " r " + hex(n_rem) +
                 ", portable q " + hex(p_q) + " r " + hex(p_rem));
    }
  }
  INFO(k_samples << " samples per function");
  CHECK(bad.count == 0);
}

TEST_CASE("wide: mul_native and mul_portable agree bit for bit", "[fixed][wide]") {
  CountFaults faults;
  std::mt19937_64 rng(0x7A4DE11'0005u);
  Mismatches bad;
  uint64_t saturated = 0;
  for (uint64_t i = 0; i < k_samples; ++i) {
    int64_t a = draw_s64(rng), b = draw_s64(rng);
    if ((i & 3) == 0) {
      const auto tie = draw_tie(rng);
      a = tie[0];
      b = tie[1];
    }
    const Q32 qa = Q32::from_raw(a), qb = Q32::from_raw(b);
    g_faults = 0;
    const int64_t n = tandem::mul_native(qa, qb).raw;
    const int native_faults = g_faults;
    g_faults = 0;
    const int64_t p = tandem::mul_portable(qa, qb).raw;
    if (n != p || native_faults != g_faults) {
      bad.report("raw " + std::to_string(a) + " * raw " + std::to_string(b) + ": native " + std::to_string(n) +
                 " (" + std::to_string(native_faults) + " faults), portable " + std::to_string(p) + " (" +
                 std::to_string(g_faults) + " faults)");
    }
    saturated += (n == INT64_MAX || n == -INT64_MAX) ? 1u : 0u;
  }
  INFO(k_samples << " samples, " << saturated << " at ±max");
  CHECK(bad.count == 0);
  CHECK(saturated > 0);
}
#endif

// Tests for fixed/vec2.h: Vec2, Rot, Transform, Mat22, AABB, Vec2Q16.
//
// Oracles: where the compiler has __int128 the exact Q64.64 values are formed
// here independently of wide.h and rounded with a magnitude-based rule, so
// dot, cross, rotate, length and AABB centre are checked bit for bit. Without
// __int128 (i686) a long double oracle is used with a tolerance that covers
// its 64-bit mantissa. Trigonometric references come from long double libm
// (tests only). All random inputs are raw integers from a seeded
// std::mt19937_64.
//
// Loop sizes: 1M per property in optimised builds; 50k without NDEBUG
// (sanitizer and debug builds), where each operation is 10-50× slower.
// Every bound asserted below is derived in the comment beside it, never
// copied from a measurement. Measured maxima are reported through INFO
// (visible with `-s`).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdint>
#include <random>
#include <string>

#include "fixed/vec2.h"

using namespace tandem;

namespace {

#ifdef NDEBUG
constexpr int k_iterations = 1'000'000;
#else
constexpr int k_iterations = 50'000;
#endif

constexpr long double k_two32 = 4294967296.0L;
constexpr int64_t k_one = int64_t{1} << 32;

// --- fault counting ---------------------------------------------------------

int g_fault_count = 0;
void count_fault(FixedFault, const char*) { ++g_fault_count; }

/// Installs the counting handler for its lifetime (so saturating cases do not
/// abort debug builds) and restores the previous one.
struct FaultCounter {
  FixedFaultHandler previous;
  FaultCounter() : previous(set_fixed_fault_handler(&count_fault)) { g_fault_count = 0; }
  ~FaultCounter() { set_fixed_fault_handler(previous); }
  FaultCounter(const FaultCounter&) = delete;
  FaultCounter& operator=(const FaultCounter&) = delete;
  int count() const { return g_fault_count; }
};

// --- random raw values ------------------------------------------------------

/// A raw value with a random bit length 0..max_bits (so every scale is
/// covered) and a random sign; |raw| < 2^max_bits ≤ 2^63.
int64_t random_raw(std::mt19937_64& rng, unsigned max_bits = 63) {
  const uint64_t r = rng();
  const unsigned bits = static_cast<unsigned>(r % (max_bits + 1u));
  const uint64_t m = bits == 0 ? 0u : rng() >> (64u - bits);
  const int64_t v = static_cast<int64_t>(m);
  return (r >> 63) != 0 ? -v : v;
}

/// A raw value uniform in [−limit, limit] (limit < 2^62).
int64_t uniform_raw(std::mt19937_64& rng, int64_t limit) {
  const uint64_t span = 2 * static_cast<uint64_t>(limit) + 1;
  return static_cast<int64_t>(rng() % span) - limit;
}

Q32 q(int64_t raw) { return Q32::from_raw(raw); }
Vec2 v2(int64_t x, int64_t y) { return {q(x), q(y)}; }
long double ld(int64_t raw) { return static_cast<long double>(raw) / k_two32; }
int64_t to_raw(long double x) { return static_cast<int64_t>(std::llroundl(x * k_two32)); }

/// Failure bookkeeping for big loops: a Catch assertion per iteration would
/// dominate the run time, so count failures and keep the first description.
struct Failures {
  int count = 0;
  std::string first;
  void add(const std::string& what) {
    if (count++ == 0) first = what;
  }
};

std::string show(Vec2 v) { return "(" + std::to_string(v.x.raw) + ", " + std::to_string(v.y.raw) + ")"; }

// --- exact oracles ----------------------------------------------------------

#if defined(__SIZEOF_INT128__)
__extension__ typedef __int128 i128;
__extension__ typedef unsigned __int128 u128;

/// The exact value p / 2^32 rounded to nearest, ties away from zero, then
/// saturated to ±INT64_MAX (*saturated says whether it was).
int64_t round_q64(i128 p, bool* saturated) {
  const bool negative = p < 0;
  u128 m = negative ? u128{0} - static_cast<u128>(p) : static_cast<u128>(p);
  m = (m + (u128{1} << 31)) >> 32;
  *saturated = m > static_cast<u128>(INT64_MAX);
  if (*saturated) return negative ? -INT64_MAX : INT64_MAX;
  const int64_t r = static_cast<int64_t>(m);
  return negative ? -r : r;
}
#endif

/// The correctly rounded a·b + c·d (raw Q32.32 in, raw out); *saturated set
/// when the result is out of range. `tolerance` is 0 with the exact oracle,
/// else the long double oracle's own error bound in raw units.
int64_t oracle_sum_products(int64_t a, int64_t b, int64_t c, int64_t d, bool* saturated, long double* tolerance) {
#if defined(__SIZEOF_INT128__)
  *tolerance = 0;
  return round_q64(static_cast<i128>(a) * b + static_cast<i128>(c) * d, saturated);
#else
  const long double pa = static_cast<long double>(a) * static_cast<long double>(b);
  const long double pc = static_cast<long double>(c) * static_cast<long double>(d);
  const long double exact = (pa + pc) / k_two32;
  // Each product and the sum carry a relative error ≤ 2^-64 of the products'
  // magnitudes; plus one unit for the final rounding.
  *tolerance = (std::fabs(pa) + std::fabs(pc)) / k_two32 * 0x1p-62L + 1.0L;
  *saturated = std::fabs(exact) > 9223372036854775807.0L + *tolerance;
  if (*saturated) return exact < 0 ? -INT64_MAX : INT64_MAX;
  return static_cast<int64_t>(std::llroundl(exact));
#endif
}

/// True when `got` matches the oracle's a·b + c·d.
bool matches_sum_products(int64_t got, int64_t a, int64_t b, int64_t c, int64_t d, bool* saturated) {
  long double tol = 0;
  const int64_t want = oracle_sum_products(a, b, c, d, saturated, &tol);
  if (tol == 0) return got == want;
  if (*saturated) return got == want;
  return std::fabs(static_cast<long double>(got) - static_cast<long double>(want)) <= tol;
}

/// length(v).raw is correctly rounded: r − ½ ≤ √S ≤ r + ½ with S = X² + Y²,
/// i.e. (2r − 1)² ≤ 4S ≤ (2r + 1)². Divided by 4 to stay in 128 bits (S is
/// an integer and no tie is possible): r² − r < S ≤ r² + r. `error` gets
/// √S − r in raw units.
bool length_is_correctly_rounded(Vec2 v, int64_t r, bool* saturated, long double* error) {
#if defined(__SIZEOF_INT128__)
  const u128 ax = static_cast<u128>(v.x.raw < 0 ? -v.x.raw : v.x.raw);
  const u128 ay = static_cast<u128>(v.y.raw < 0 ? -v.y.raw : v.y.raw);
  const u128 s = ax * ax + ay * ay;
  const u128 max = static_cast<u128>(INT64_MAX);
  *saturated = s > max * max + max;  // √S ≥ INT64_MAX + ½
  if (*saturated) {
    *error = 0;
    return r == INT64_MAX;
  }
  if (r < 0) return false;
  const u128 ur = static_cast<u128>(r);
  // √S − r = (S − r²)/(√S + r) ≈ (S − r²)/(2r).
  const i128 diff = static_cast<i128>(s) - static_cast<i128>(ur * ur);
  *error = r == 0 ? 0 : static_cast<long double>(diff) / (2.0L * static_cast<long double>(r));
  const bool upper = s <= ur * ur + ur;
  const bool lower = r == 0 || s > ur * ur - ur;
  return upper && lower;
#else
  const long double x = static_cast<long double>(v.x.raw), y = static_cast<long double>(v.y.raw);
  const long double exact = std::sqrt(x * x + y * y);
  *saturated = exact >= 9223372036854775807.5L;
  const long double diff = exact - static_cast<long double>(r);
  // The measured error only where the long double oracle is good to ~2^-14
  // raw (S < 2^100, rounded to 64 bits: √ off by < 2^36/2^51).
  *error = *saturated || exact >= 0x1p50L ? 0 : diff;
  if (*saturated) return r == INT64_MAX;
  // The long double root is within ~2^-63 relative: allow that on top of ½.
  return std::fabs(diff) <= 0.5L + exact * 0x1p-62L;
#endif
}

/// (C² + S²) − 2^64 for raw Q32.32 components, i.e. (|q|² − 1)·2^64, as a
/// long double (exact for values up to 2^64 in magnitude where __int128
/// exists).
long double squared_length_error_q64(int64_t c, int64_t s) {
#if defined(__SIZEOF_INT128__)
  return static_cast<long double>(static_cast<i128>(c) * c + static_cast<i128>(s) * s - (i128{1} << 64));
#else
  const long double lc = static_cast<long double>(c), ls = static_cast<long double>(s);
  return (lc * lc - 18446744073709551616.0L) + ls * ls;
#endif
}

/// A random unit rotation (within 1 raw unit per component of the exact
/// cos/sin of a random angle), built without the library's sincos.
Rot random_unit_rot(std::mt19937_64& rng, long double* out_angle = nullptr) {
  const long double angle = static_cast<long double>(uniform_raw(rng, 13493037705)) / k_two32;  // [−π, π]
  if (out_angle) *out_angle = angle;
  return {q(to_raw(std::cos(angle))), q(to_raw(std::sin(angle)))};
}

/// Angle difference a − b wrapped into (−π, π], in raw units.
long double wrap_angle_raw(long double a_minus_b) {
  const long double two_pi = 2.0L * 3.14159265358979323846264338327950288L * k_two32;
  const long double pi = two_pi / 2;
  while (a_minus_b > pi) a_minus_b -= two_pi;
  while (a_minus_b <= -pi) a_minus_b += two_pi;
  return a_minus_b;
}

// The header's inline operations stay usable in constant expressions.
static_assert(dot(vec2(1, 2), vec2(3, 4)) == Q32::from_int(11));
static_assert(cross(vec2(1, 2), vec2(3, 4)) == Q32::from_int(-2));
static_assert(rotate(Rot{Q32::zero(), Q32::one()}, vec2(1, 0)) == vec2(0, 1));
static_assert(transform_inverse(Transform{vec2(1, 0), Rot{Q32::zero(), Q32::one()}}).p == vec2(0, 1));
static_assert(aabb_center(AABB{vec2(-2, 0), vec2(4, 2)}) == vec2(1, 1));
static_assert(aabb_extents(AABB{vec2(-2, 0), vec2(4, 2)}) == vec2(3, 1));
static_assert(rot_normalize_fast(rot_identity()) == rot_identity());
static_assert(determinant(Mat22{vec2(1, 3), vec2(2, 4)}) == Q32::from_int(-2));

}  // namespace

// ---------------------------------------------------------------------------
// Vec2 basics
// ---------------------------------------------------------------------------

TEST_CASE("Vec2 component-wise operations", "[fixed][vec2]") {
  const Vec2 a = vec2(3, -4);
  const Vec2 b = v2(k_one / 2, 5 * k_one);
  CHECK(a + b == v2(3 * k_one + k_one / 2, k_one));
  CHECK(a - b == v2(3 * k_one - k_one / 2, -9 * k_one));
  CHECK(-a == vec2(-3, 4));
  CHECK(q(k_one / 2) * a == v2(3 * k_one / 2, -2 * k_one));
  CHECK(a * q(k_one / 2) == v2(3 * k_one / 2, -2 * k_one));
  CHECK(a / q(2 * k_one) == v2(3 * k_one / 2, -2 * k_one));
  CHECK(abs(a) == vec2(3, 4));
  CHECK(min(a, b) == v2(k_one / 2, -4 * k_one));
  CHECK(max(a, b) == v2(3 * k_one, 5 * k_one));
  CHECK(mul_add(a, q(2 * k_one), b) == v2(4 * k_one, 6 * k_one));
  CHECK(mul_sub(a, q(2 * k_one), b) == v2(2 * k_one, -14 * k_one));
  CHECK(lerp(a, b, Q32::zero()) == a);
  CHECK(lerp(a, b, Q32::one()) == b);
  CHECK(lerp(vec2(0, 0), vec2(2, -2), q(k_one / 2)) == vec2(1, -1));
  Vec2 c = a;
  c += b;
  CHECK(c == a + b);
  c -= b;
  CHECK(c == a);
  c *= q(3 * k_one);
  CHECK(c == vec2(9, -12));
  // Scaling rounds once per component, ties away from zero: 3 raw × 0.5.
  CHECK(q(k_one / 2) * v2(3, -3) == v2(2, -2));
}

TEST_CASE("Vec2 perp and scalar cross products", "[fixed][vec2]") {
  const Vec2 v = vec2(3, 4);
  CHECK(left_perp(v) == vec2(-4, 3));
  CHECK(right_perp(v) == vec2(4, -3));
  CHECK(cross(v, q(2 * k_one)) == vec2(8, -6));   // (s·y, −s·x)
  CHECK(cross(q(2 * k_one), v) == vec2(-8, 6));   // (−s·y, s·x)
  std::mt19937_64 rng(0x7E5701);
  Failures f;
  for (int i = 0; i < 10000; ++i) {
    // Components ≤ 2^15 so the checks below cannot saturate.
    const Vec2 a = v2(random_raw(rng, 47), random_raw(rng, 47));
    const Vec2 b = v2(random_raw(rng, 47), random_raw(rng, 47));
    const Q32 s = q(random_raw(rng, 47));
    // a×b = left_perp(a)·b exactly (the same exact sum, rounded once).
    if (cross(a, b) != dot(left_perp(a), b)) f.add("cross vs perp dot " + show(a) + show(b));
    if (cross(a, b) != -cross(b, a)) f.add("cross antisymmetry " + show(a) + show(b));
    if (cross(Q32::one(), a) != left_perp(a) || cross(a, Q32::one()) != right_perp(a)) f.add("unit cross " + show(a));
    if (cross(s, a) != -cross(a, s)) f.add("scalar cross antisymmetry " + show(a));
    if (cross(a, s) != Vec2{s * a.y, -(s * a.x)}) f.add("cross(v, s) definition " + show(a));
    if (left_perp(right_perp(a)) != a || dot(left_perp(a), a) != Q32::zero()) f.add("perp " + show(a));
  }
  INFO(f.first);
  CHECK(f.count == 0);
}

// ---------------------------------------------------------------------------
// dot, cross, length_squared: exact sums rounded once
// ---------------------------------------------------------------------------

TEST_CASE("dot and cross are the correctly rounded exact sums", "[fixed][vec2]") {
  SECTION("ties round once, away from zero") {
    // 0.25 + 1.25 (in raw/2^32 units): rounded once 1.5 → 2; rounding each
    // product first would give 0 + 1 = 1.
    CHECK(dot(v2(1, 1), v2(int64_t{1} << 30, (int64_t{1} << 32) + (int64_t{1} << 30))).raw == 2);
    CHECK(dot(v2(-1, 1), v2(int64_t{1} << 30, -(int64_t{1} << 32) - (int64_t{1} << 30))).raw == -2);
    CHECK(dot(v2(3, 0), v2(int64_t{1} << 31, 0)).raw == 2);    // 1.5 → 2
    CHECK(dot(v2(-3, 0), v2(int64_t{1} << 31, 0)).raw == -2);  // −1.5 → −2
    CHECK(dot(v2(1, 0), v2((int64_t{1} << 31) - 1, 0)).raw == 0);
    CHECK(cross(v2(3, 0), v2(0, int64_t{1} << 31)).raw == 2);
    CHECK(cross(v2(0, 3), v2(int64_t{1} << 31, 0)).raw == -2);
  }
  SECTION("large operands whose products overflow 64 bits but whose sum fits") {
    // (2^31 − 1)·(2^31 − 1) − (2^31 − 1)·(2^31 − 1) = 0 with 2^62-sized terms.
    const int64_t big = INT64_MAX;
    CHECK(cross(v2(big, big), v2(big, big)).raw == 0);
    CHECK(dot(v2(big, -big), v2(big, big)).raw == 0);
    CHECK(length_squared(vec2(46340, 0)) == Q32::from_int(46340 * 46340));
  }
  SECTION("random vectors against the exact oracle") {
    FaultCounter faults;
    std::mt19937_64 rng(0xD07C5055);
    Failures f;
    int saturated = 0, in_range = 0;
    for (int i = 0; i < k_iterations; ++i) {
      const Vec2 a = v2(random_raw(rng), random_raw(rng));
      const Vec2 b = v2(random_raw(rng), random_raw(rng));
      bool sat = false;
      const int64_t d = dot(a, b).raw;
      if (!matches_sum_products(d, a.x.raw, b.x.raw, a.y.raw, b.y.raw, &sat)) f.add("dot " + show(a) + show(b));
      saturated += sat;
      in_range += !sat;
      const int64_t c = cross(a, b).raw;
      if (!matches_sum_products(c, a.x.raw, b.y.raw, -a.y.raw, b.x.raw, &sat)) f.add("cross " + show(a) + show(b));
      saturated += sat;
      in_range += !sat;
      const int64_t l2 = length_squared(a).raw;
      if (!matches_sum_products(l2, a.x.raw, a.x.raw, a.y.raw, a.y.raw, &sat)) f.add("length_squared " + show(a));
      saturated += sat;
      in_range += !sat;
    }
    INFO(f.first);
    CHECK(f.count == 0);
    INFO("saturated " << saturated << ", in range " << in_range);
    // The draw covers every scale: both outcomes are common.
    CHECK(saturated > k_iterations / 10);
    CHECK(in_range > k_iterations);
#if TANDEM_FIXED_CHECKS
    CHECK(faults.count() == saturated);  // one fault per saturated result
#else
    CHECK(faults.count() == 0);
#endif
  }
  SECTION("operands up to ±2^31 that do not saturate") {
    // |a| up to 2^31, |b| ≤ 2^-1: |a·b| < 2^31 always.
    std::mt19937_64 rng(0xB16D07);
    Failures f;
    for (int i = 0; i < k_iterations / 4; ++i) {
      const Vec2 a = v2(random_raw(rng, 63), random_raw(rng, 63));
      const Vec2 b = v2(random_raw(rng, 30), random_raw(rng, 30));
      bool sat = false;
      if (!matches_sum_products(dot(a, b).raw, a.x.raw, b.x.raw, a.y.raw, b.y.raw, &sat) || sat) f.add("dot " + show(a) + show(b));
      if (!matches_sum_products(cross(a, b).raw, a.x.raw, b.y.raw, -a.y.raw, b.x.raw, &sat) || sat)
        f.add("cross " + show(a) + show(b));
    }
    INFO(f.first);
    CHECK(f.count == 0);
  }
  SECTION("saturation has the sign of the exact result") {
    FaultCounter faults;
    CHECK(dot(vec2(100000, 0), vec2(100000, 0)) == Q32::max());
    CHECK(dot(vec2(100000, 0), vec2(-100000, 0)) == Q32::min());
    CHECK(cross(vec2(100000, 0), vec2(0, -100000)) == Q32::min());
    CHECK(length_squared(v2(INT64_MAX, -INT64_MAX)) == Q32::max());
#if TANDEM_FIXED_CHECKS
    CHECK(faults.count() == 4);
#endif
  }
}

// ---------------------------------------------------------------------------
// length, distance, normalize
// ---------------------------------------------------------------------------

TEST_CASE("length is the correctly rounded root of the exact sum of squares", "[fixed][vec2]") {
  CHECK(length(vec2(3, 4)) == Q32::from_int(5));
  CHECK(length(vec2(0, 0)) == Q32::zero());
  CHECK(length(v2(1, 1)).raw == 1);  // √2 raw → 1
  CHECK(length(v2(INT64_MAX, 0)).raw == INT64_MAX);
  CHECK(distance(vec2(1, 1), vec2(4, 5)) == Q32::from_int(5));
  FaultCounter faults;
  std::mt19937_64 rng(0x1E9674);
  Failures f;
  int saturated = 0;
  long double max_error = 0;
  for (int i = 0; i < k_iterations; ++i) {
    const Vec2 v = v2(random_raw(rng), random_raw(rng));
    const int64_t r = length(v).raw;
    bool sat = false;
    long double err = 0;
    if (!length_is_correctly_rounded(v, r, &sat, &err)) f.add("length " + show(v) + " = " + std::to_string(r));
    saturated += sat;
    if (std::fabs(err) > max_error) max_error = std::fabs(err);
  }
  INFO(f.first);
  CHECK(f.count == 0);
  INFO("max |length − exact| = " << static_cast<double>(max_error) << " raw units; saturated " << saturated);
#if defined(__SIZEOF_INT128__)
  CHECK(max_error <= 0.5L);
#else
  CHECK(max_error <= 0.5L + 0x1p-10L);
#endif
  CHECK(saturated > 0);  // both components near 2^31 do occur in the draw
#if TANDEM_FIXED_CHECKS
  CHECK(faults.count() == saturated);
#endif
}

TEST_CASE("normalize gives unit vectors along v at every scale", "[fixed][vec2]") {
  CHECK(normalize(vec2(0, 0)) == vec2(0, 0));
  CHECK(normalize(vec2(3, 4)) == v2(to_raw(0.6L), to_raw(0.8L)));
  CHECK(normalize(v2(-7, 0)) == vec2(-1, 0));
  // Tiny vectors: dividing by the Q32.32-rounded length (1 raw for (1, 1))
  // would give (1, 1) here.
  CHECK(normalize(v2(1, 1)) == v2(to_raw(0.70710678118654752440L), to_raw(0.70710678118654752440L)));
  CHECK(normalize(v2(INT64_MAX, -INT64_MAX)) ==
        v2(to_raw(0.70710678118654752440L), -to_raw(0.70710678118654752440L)));
  Q32 len;
  CHECK(length_and_normalize(vec2(0, -2), &len) == vec2(0, -1));
  CHECK(len == Q32::from_int(2));
  CHECK(length_and_normalize(vec2(0, 0), &len) == vec2(0, 0));
  CHECK(len == Q32::zero());
  CHECK(rot_normalize(Rot{q(0), q(0)}) == rot_identity());
  CHECK(rot_normalize(Rot{q(3 * k_one), q(-4 * k_one)}) == Rot{q(to_raw(0.6L)), q(to_raw(-0.8L))});

  FaultCounter faults;  // length_and_normalize's length may saturate
  std::mt19937_64 rng(0x40E3A1);
  Failures f;
  long double max_component_error = 0, max_length_error = 0;
  for (int i = 0; i < k_iterations; ++i) {
    const Vec2 v = v2(random_raw(rng), random_raw(rng));
    if (v.x.raw == 0 && v.y.raw == 0) continue;
    const Vec2 n = normalize(v);
    // Oracle: x/√(x² + y²) in long double (relative error ~2^-63, far below
    // the 2^-32 being checked). Each component is one rounded quotient with
    // a divisor good to 2^-61, so |error| ≤ ½ + 2^-30 (+ oracle slack).
    const long double x = static_cast<long double>(v.x.raw), y = static_cast<long double>(v.y.raw);
    const long double h = std::hypot(x, y);
    const long double ex = std::fabs(static_cast<long double>(n.x.raw) - x / h * k_two32);
    const long double ey = std::fabs(static_cast<long double>(n.y.raw) - y / h * k_two32);
    if (ex > 0.5L + 0x1p-29L || ey > 0.5L + 0x1p-29L) f.add("normalize direction " + show(v) + " -> " + show(n));
    max_component_error = std::max(max_component_error, std::max(ex, ey));
    // |n| − 1 in raw units ≈ (|n|² − 1)·2^31. With component errors e ≤ ½:
    // ||n| − 1| ≤ |e| ≤ ½·√2 ≈ 0.71 raw.
    const long double le = std::fabs(squared_length_error_q64(n.x.raw, n.y.raw)) / (2.0L * k_two32);
    if (le > 0.71L) f.add("normalize length " + show(v) + " -> " + show(n));
    max_length_error = std::max(max_length_error, le);
    if ((i & 15) == 0) {
      const Vec2 m = length_and_normalize(v, &len);
      if (m != n || len != length(v)) f.add("length_and_normalize " + show(v));
      const Rot r = rot_normalize(Rot{v.x, v.y});
      if (r.c != n.x || r.s != n.y) f.add("rot_normalize " + show(v));
    }
  }
  INFO(f.first);
  CHECK(f.count == 0);
  INFO("max component error " << static_cast<double>(max_component_error) << " raw, max ||n| − 1| "
                              << static_cast<double>(max_length_error) << " raw");
  CHECK(max_component_error <= 0.5L + 0x1p-29L);
}

// ---------------------------------------------------------------------------
// Rot
// ---------------------------------------------------------------------------

TEST_CASE("rotate is exactly rounded and inv_rotate undoes it", "[fixed][vec2]") {
  CHECK(rotate(rot_identity(), vec2(5, -6)) == vec2(5, -6));
  const Rot quarter{Q32::zero(), Q32::one()};
  CHECK(rotate(quarter, vec2(1, 2)) == vec2(-2, 1));
  CHECK(inv_rotate(quarter, vec2(-2, 1)) == vec2(1, 2));
  CHECK(rot_x_axis(quarter) == vec2(0, 1));
  CHECK(rot_y_axis(quarter) == vec2(-1, 0));
  CHECK(rot_inverse(quarter) == Rot{Q32::zero(), -Q32::one()});

  std::mt19937_64 rng(0x207A7E);
  Failures f;
  long double max_round_trip = 0;
  for (int i = 0; i < k_iterations; ++i) {
    // Random pairs near unit length (|m − 1| up to ~1e-3) and vectors up to
    // ±2^20 on each axis (no saturation).
    Rot r = random_unit_rot(rng);
    r.c = q(r.c.raw + uniform_raw(rng, 1 << 21));
    r.s = q(r.s.raw + uniform_raw(rng, 1 << 21));
    const Vec2 v = v2(random_raw(rng, 52), random_raw(rng, 52));
    const Vec2 w = rotate(r, v);
    bool sat = false;
    if (!matches_sum_products(w.x.raw, r.c.raw, v.x.raw, -r.s.raw, v.y.raw, &sat) ||
        !matches_sum_products(w.y.raw, r.s.raw, v.x.raw, r.c.raw, v.y.raw, &sat))
      f.add("rotate " + show(v));
    const Vec2 u = inv_rotate(r, v);
    if (!matches_sum_products(u.x.raw, r.c.raw, v.x.raw, r.s.raw, v.y.raw, &sat) ||
        !matches_sum_products(u.y.raw, -r.s.raw, v.x.raw, r.c.raw, v.y.raw, &sat))
      f.add("inv_rotate " + show(v));
    // Round trip: qᵀ(q·v + e1) + e2 = m·v + qᵀe1 + e2 with |e|∞ ≤ ½ per
    // component, so per component |back − v| ≤ |m − 1|·max|v| + ½(|c| + |s|)
    // + ½ ≤ |m − 1|·max|v| + 1.21 raw (|c| + |s| ≤ √(2m) ≤ 1.415).
    const Vec2 back = inv_rotate(r, w);
    const long double m_error = std::fabs(squared_length_error_q64(r.c.raw, r.s.raw)) / (k_two32 * k_two32);
    const long double vmax = std::max(std::fabs(static_cast<long double>(v.x.raw)), std::fabs(static_cast<long double>(v.y.raw)));
    const long double bound = m_error * vmax + 1.21L;
    const long double dx = std::fabs(static_cast<long double>(back.x.raw - v.x.raw));
    const long double dy = std::fabs(static_cast<long double>(back.y.raw - v.y.raw));
    if (dx > bound || dy > bound) f.add("round trip " + show(v) + " -> " + show(back));
    // Unit rotations: the round trip is within a few raw units of v.
    const Rot n = rot_normalize(r);
    const Vec2 back_unit = inv_rotate(n, rotate(n, v));
    const long double mu = std::fabs(squared_length_error_q64(n.c.raw, n.s.raw)) / (k_two32 * k_two32);
    const long double du = std::max(std::fabs(static_cast<long double>(back_unit.x.raw - v.x.raw)),
                                    std::fabs(static_cast<long double>(back_unit.y.raw - v.y.raw)));
    if (du > mu * vmax + 1.21L) f.add("unit round trip " + show(v));
    if (vmax < 0x1p32L) max_round_trip = std::max(max_round_trip, du);
  }
  INFO(f.first);
  CHECK(f.count == 0);
  // After rot_normalize ||q| − 1| ≤ 0.71 raw, so |m − 1| ≤ 1.42·2^-32 and
  // for |v| < 1 the round trip is within 1.42 + 1.21 raw.
  INFO("max unit round-trip error for |v| < 1: " << static_cast<double>(max_round_trip) << " raw");
  CHECK(max_round_trip <= 2.63L);
}

TEST_CASE("mul_rot and inv_mul_rot compose angles", "[fixed][vec2]") {
  const Rot quarter{Q32::zero(), Q32::one()};
  CHECK(mul_rot(quarter, quarter) == Rot{-Q32::one(), Q32::zero()});
  CHECK(inv_mul_rot(quarter, quarter) == rot_identity());
  CHECK(mul_rot(quarter, rot_inverse(quarter)) == rot_identity());

  std::mt19937_64 rng(0xC0F05E);
  Failures f;
  long double max_err = 0;
  for (int i = 0; i < k_iterations / 4; ++i) {
    long double a = 0, b = 0;
    const Rot qa = random_unit_rot(rng, &a);
    const Rot qb = random_unit_rot(rng, &b);
    // Inputs are within ½ raw unit of the exact cos/sin; the composed
    // component c_a·c_b − s_a·s_b then errs by ≤ ½(|c_b| + |s_b|) +
    // ½(|c_a| + |s_a|) + ½ ≤ ½√2·2 + ½ ≈ 1.92 raw units.
    const Rot ab = mul_rot(qa, qb);
    const Rot rel = inv_mul_rot(qa, qb);
    const long double e1 = std::max(std::fabs(static_cast<long double>(ab.c.raw) - std::cos(a + b) * k_two32),
                                    std::fabs(static_cast<long double>(ab.s.raw) - std::sin(a + b) * k_two32));
    const long double e2 = std::max(std::fabs(static_cast<long double>(rel.c.raw) - std::cos(b - a) * k_two32),
                                    std::fabs(static_cast<long double>(rel.s.raw) - std::sin(b - a) * k_two32));
    if (e1 > 1.92L || e2 > 1.92L) f.add("compose " + std::to_string(static_cast<double>(a)) + ", " + std::to_string(static_cast<double>(b)));
    max_err = std::max(max_err, std::max(e1, e2));
    // Exactly rounded sums of products.
    bool sat = false;
    if (!matches_sum_products(ab.c.raw, qa.c.raw, qb.c.raw, -qa.s.raw, qb.s.raw, &sat) ||
        !matches_sum_products(ab.s.raw, qa.s.raw, qb.c.raw, qa.c.raw, qb.s.raw, &sat) ||
        !matches_sum_products(rel.c.raw, qa.c.raw, qb.c.raw, qa.s.raw, qb.s.raw, &sat) ||
        !matches_sum_products(rel.s.raw, qa.c.raw, qb.s.raw, -qa.s.raw, qb.c.raw, &sat))
      f.add("mul_rot rounding");
    // Structural identities that hold exactly.
    if (inv_mul_rot(qa, qb) != mul_rot(rot_inverse(qa), qb)) f.add("inv_mul_rot vs mul_rot(inverse)");
  }
  INFO(f.first);
  CHECK(f.count == 0);
  INFO("max component error vs cos/sin(a ± b): " << static_cast<double>(max_err) << " raw");
  CHECK(max_err <= 1.92L);
}

TEST_CASE("rot_from_angle and rot_angle round trip", "[fixed][vec2]") {
  CHECK(rot_from_angle(Q32::zero()) == rot_identity());
  CHECK(rot_angle(rot_identity()) == Q32::zero());
  // sin/cos are within 2 raw units (fixed_math.h): allow that here.
  const Rot quarter = rot_from_angle(k_half_pi);
  CHECK(std::abs(quarter.c.raw) <= 2);
  CHECK(std::abs(quarter.s.raw - k_one) <= 2);
  CHECK(std::abs(rot_angle(Rot{Q32::zero(), Q32::one()}).raw - k_half_pi.raw) <= 2);

  std::mt19937_64 rng(0xA9E1E5);
  Failures f;
  long double max_angle_err = 0, max_rot_err = 0, max_rel_err = 0;
  const int n = k_iterations / 4;
  for (int i = 0; i < n; ++i) {
    const Q32 angle = q(uniform_raw(rng, k_pi.raw));
    const Rot r = rot_from_angle(angle);
    // Components within 2 raw units of cos/sin (fixed_math.h's bound).
    const long double a = ld(angle.raw);
    const long double ec = std::fabs(static_cast<long double>(r.c.raw) - std::cos(a) * k_two32);
    const long double es = std::fabs(static_cast<long double>(r.s.raw) - std::sin(a) * k_two32);
    if (ec > 2 || es > 2) f.add("rot_from_angle " + std::to_string(angle.raw));
    // Back to the angle: a component error δ turns the pair by at most |δ|
    // ≤ 2√2 ≈ 2.83 raw, and atan2 adds ≤ 2: within 4.83 raw (mod 2π).
    const long double back = wrap_angle_raw(static_cast<long double>(rot_angle(r).raw - angle.raw));
    if (std::fabs(back) > 4.83L) f.add("rot_angle round trip " + std::to_string(angle.raw));
    max_angle_err = std::max(max_angle_err, std::fabs(back));
    // And the other way for a pair u within ½ raw of (cos θ, sin θ): its
    // angle is within 0.71 raw of θ, atan2 adds ≤ 2, sin/cos of that angle
    // are within 2 + 2.71 of (cos θ, sin θ), and u itself ½ away: ≤ 5.21.
    const Rot u = random_unit_rot(rng);
    const Rot u2 = rot_from_angle(rot_angle(u));
    const long double eu = std::max(std::fabs(static_cast<long double>(u2.c.raw - u.c.raw)),
                                    std::fabs(static_cast<long double>(u2.s.raw - u.s.raw)));
    if (eu > 5.21L) f.add("rot_from_angle(rot_angle) " + std::to_string(u.c.raw) + ", " + std::to_string(u.s.raw));
    max_rot_err = std::max(max_rot_err, eu);
    // relative_angle(p, r) is the angle from p to r: each pair's angle is
    // within 0.71 raw of its exact angle (½ raw per component), inv_mul_rot
    // rounds by ½ per component (≤ 0.71 of turn), atan2 ≤ 2: ≤ 4.13.
    long double pa = 0, pb = 0;
    const Rot p1 = random_unit_rot(rng, &pa);
    const Rot p2 = random_unit_rot(rng, &pb);
    const long double rel = wrap_angle_raw(static_cast<long double>(relative_angle(p1, p2).raw) - (pb - pa) * k_two32);
    if (std::fabs(rel) > 4.13L) f.add("relative_angle");
    max_rel_err = std::max(max_rel_err, std::fabs(rel));
  }
  INFO(f.first);
  CHECK(f.count == 0);
  INFO("max angle round trip " << static_cast<double>(max_angle_err) << " raw, rot round trip "
                               << static_cast<double>(max_rot_err) << " raw, relative_angle "
                               << static_cast<double>(max_rel_err) << " raw");
  CHECK(max_angle_err <= 4.83L);
}

TEST_CASE("rot_normalize_fast is one Newton step with a derived error bound", "[fixed][vec2]") {
  CHECK(rot_normalize_fast(rot_identity()) == rot_identity());
  CHECK(rot_normalize_fast(Rot{Q32::zero(), -Q32::one()}) == Rot{Q32::zero(), -Q32::one()});
  // Pairs with |m − 1| = |ε| ≤ 1e-3, m = c² + s² exact. One step gives
  // m' = m·k̂² + 2k̂(c·e_c + s·e_s) + e² with k̂ = (3 − m)/2 + δk:
  //   m·k² = (1 + ε)(1 − ε/2)² = 1 − ¾ε² + ¼ε³ exactly;
  //   |δk| ≤ ½·2^-33 (m rounded, then halved) + 2^-33 (the halving rounds)
  //        = 0.75·2^-32, contributing 2·m·k·|δk| ≤ 1.503·2^-32;
  //   |e_c|, |e_s| ≤ 2^-33 (c·k, s·k rounded), contributing
  //        2k·|(c, s)|·|e| ≤ 2·1.0005·√1.001·√2·2^-33 ≤ 1.417·2^-32.
  // So |m' − (1 − ¾ε² + ¼ε³)| ≤ 2.92·2^-32 (+ e² terms ~2^-64): assert 3·2^-32.
  std::mt19937_64 rng(0xFA57);
  Failures f;
  long double worst_m = 0, worst_dev = 0, worst_eps = 0;
  int tested = 0;
  for (int i = 0; i < k_iterations; ++i) {
    long double angle = 0;
    (void)random_unit_rot(rng, &angle);
    // Scale by 1 + η (|η| ≤ 5e-4) and jitter each component independently.
    const long double eta = static_cast<long double>(uniform_raw(rng, 1 << 30)) / (1 << 30) * 5e-4L;
    const Rot r{q(to_raw(std::cos(angle) * (1 + eta)) + uniform_raw(rng, 1 << 20)),
                q(to_raw(std::sin(angle) * (1 + eta)) + uniform_raw(rng, 1 << 20))};
    const long double eps = squared_length_error_q64(r.c.raw, r.s.raw) / (k_two32 * k_two32);
    if (std::fabs(eps) > 1e-3L) continue;
    ++tested;
    const Rot n = rot_normalize_fast(r);
    const long double m_after = squared_length_error_q64(n.c.raw, n.s.raw) / (k_two32 * k_two32);  // m' − 1
    const long double predicted = -0.75L * eps * eps + 0.25L * eps * eps * eps;
    const long double dev = std::fabs(m_after - predicted) * k_two32;  // in units of 2^-32
    if (dev > 3.0L) f.add("rot_normalize_fast " + std::to_string(r.c.raw) + ", " + std::to_string(r.s.raw));
    worst_dev = std::max(worst_dev, dev);
    worst_m = std::max(worst_m, std::fabs(m_after));
    worst_eps = std::max(worst_eps, std::fabs(eps));
    // The direction is kept: n = k̂·r + e with |e| ≤ ½√2 raw, so r × n =
    // r × e is ≤ 0.71 raw before cross's own rounding: |r × n| ≤ 1 raw.
    const long double turn = std::fabs(static_cast<long double>(cross(rot_x_axis(r), rot_x_axis(n)).raw));
    if (turn > 1) f.add("rot_normalize_fast turned the pair");
  }
  INFO(f.first);
  CHECK(f.count == 0);
  CHECK(tested > k_iterations / 2);
  CHECK(worst_eps > 0.9e-3L);  // the draw reaches the edge of the range
  INFO("max |m' − 1| after one step from |m − 1| ≤ 1e-3: " << static_cast<double>(worst_m)
                                                           << "; max deviation from 1 − ¾ε² + ¼ε³: "
                                                           << static_cast<double>(worst_dev) << "·2^-32");
  // Implied: |m' − 1| ≤ ¾·(1e-3)² + ¼·(1e-3)³ + 3·2^-32.
  CHECK(worst_m <= 0.75e-6L + 0.25e-9L + 3.0L / k_two32);
}

TEST_CASE("integrate_rotation keeps |q| at 1 over 1M steps", "[fixed][vec2]") {
  // The solver's use: q ← integrate_rotation(q, ω·h) every sub-step, never
  // renormalised otherwise. Each call starts from m = (1 + ε_prev)(1 + δ²);
  // two Newton steps leave ≈ 0.42·(δ² + ε_prev)⁴ (< 10^-11 for |δ| ≤ 0.05)
  // plus the rounding of the last step, |Δm| < 3·2^-32 (derived in the
  // rot_normalize_fast test). So |q| − 1 ≈ Δm/2 stays within 1.5 raw units
  // plus the tiny Newton remainder, however many steps: assert 2 raw units.
  std::mt19937_64 rng(0x1A7E6);
  Failures f;
  Rot r = rot_identity();
  long double worst = 0, worst_angle = 0;
  constexpr int64_t k_max_delta = 214748365;  // 0.05 rad
  for (int i = 0; i < 1'000'000; ++i) {
    const Q32 delta = q(uniform_raw(rng, k_max_delta));
    const Rot next = integrate_rotation(r, delta);
    const long double len_err = std::fabs(squared_length_error_q64(next.c.raw, next.s.raw)) / (2.0L * k_two32);
    worst = std::max(worst, len_err);
    if (len_err > 2) f.add("integrate_rotation step " + std::to_string(i));
#ifdef NDEBUG
    const bool check_angle = (i & 7) == 0;
#else
    const bool check_angle = (i & 255) == 0;
#endif
    if (check_angle) {
      // The angle turned is atan(δ): the first-order update rounds each
      // component by ≤ ½ (≤ 0.71 raw of turn), each normalisation by ≤ 0.71,
      // inv_mul_rot by ≤ 0.71 and atan2 by ≤ 2: ≤ 4.84 raw.
      const long double turned = static_cast<long double>(relative_angle(r, next).raw);
      const long double err = std::fabs(turned - std::atan(ld(delta.raw)) * k_two32);
      if (err > 4.84L) f.add("integrate_rotation angle at step " + std::to_string(i));
      worst_angle = std::max(worst_angle, err);
    }
    r = next;
  }
  INFO(f.first);
  CHECK(f.count == 0);
  INFO("max ||q| − 1| over 1M steps, |δ| ≤ 0.05: " << static_cast<double>(worst) << " raw; max turn error "
                                                  << static_cast<double>(worst_angle) << " raw");
  CHECK(worst <= 2);
  // Larger steps: |δ| = 0.1 leaves 0.42·10⁻⁸ ≈ 18·2^-32 in m, 9 raw in |q|.
  r = rot_identity();
  long double worst_large = 0;
  for (int i = 0; i < 10000; ++i) {
    r = integrate_rotation(r, q((i & 1) ? 429496730 : -429496730 / 2));
    worst_large = std::max(worst_large, std::fabs(squared_length_error_q64(r.c.raw, r.s.raw)) / (2.0L * k_two32));
  }
  INFO("|δ| = 0.1: max ||q| − 1| " << static_cast<double>(worst_large) << " raw");
  CHECK(worst_large <= 0.42L * 1e-8L * k_two32 / 2 + 2);
}

// ---------------------------------------------------------------------------
// Transform
// ---------------------------------------------------------------------------

TEST_CASE("transforms compose and invert", "[fixed][vec2]") {
  const Transform id = transform_identity();
  CHECK(transform_point(id, vec2(2, 3)) == vec2(2, 3));
  const Transform t{vec2(10, -5), Rot{Q32::zero(), Q32::one()}};  // 90°, then move
  CHECK(transform_point(t, vec2(1, 0)) == vec2(10, -4));
  CHECK(inv_transform_point(t, vec2(10, -4)) == vec2(1, 0));
  CHECK(mul_transforms(t, transform_inverse(t)) == id);
  CHECK(mul_transforms(transform_inverse(t), t) == id);
  CHECK(inv_mul_transforms(t, t) == id);

  std::mt19937_64 rng(0x7A5F);
  Failures f;
  long double worst_compose = 0, worst_invert = 0;
  const int n = k_iterations / 4;
  constexpr int64_t k_limit = int64_t{1000} << 32;  // positions and points within ±1000 m
  for (int i = 0; i < n; ++i) {
    const Transform a{v2(uniform_raw(rng, k_limit), uniform_raw(rng, k_limit)), random_unit_rot(rng)};
    const Transform b{v2(uniform_raw(rng, k_limit), uniform_raw(rng, k_limit)), random_unit_rot(rng)};
    const Vec2 v = v2(uniform_raw(rng, k_limit), uniform_raw(rng, k_limit));
    // (a·b)(v) vs a(b(v)): the composed rotation is a.q·b.q + E with
    // |E| ≤ ½ raw = 2^-33 per component, which moves the point by
    // ≤ 2^-33·(|vx| + |vy|), i.e. (|vx| + |vy|)/2 raw units for v in metres.
    // The other roundings: composed ½ (rotate) + ½ (a.q·b.p); nested ½
    // (outer rotate) + 0.71 (inner rotate's ½ carried through a.q):
    // bound = (|vx| + |vy|)/2 + 2.21 raw.
    const Vec2 composed = transform_point(mul_transforms(a, b), v);
    const Vec2 nested = transform_point(a, transform_point(b, v));
    const long double vsum = (std::fabs(ld(v.x.raw)) + std::fabs(ld(v.y.raw)));
    const long double bc = vsum / 2 + 2.22L;
    const long double ec = std::max(std::fabs(static_cast<long double>(composed.x.raw - nested.x.raw)),
                                    std::fabs(static_cast<long double>(composed.y.raw - nested.y.raw)));
    if (ec > bc) f.add("compose " + show(v));
    worst_compose = std::max(worst_compose, ec / (vsum + 1));
    // Inverse point: as the rotation round trip, |m − 1|·|v| + 1.21.
    const Vec2 w = transform_point(a, v);
    const Vec2 back = inv_transform_point(a, w);
    const long double m_error = std::fabs(squared_length_error_q64(a.q.c.raw, a.q.s.raw)) / (k_two32 * k_two32);
    const long double vmax = std::max(std::fabs(static_cast<long double>(v.x.raw)), std::fabs(static_cast<long double>(v.y.raw)));
    const long double ei = std::max(std::fabs(static_cast<long double>(back.x.raw - v.x.raw)),
                                    std::fabs(static_cast<long double>(back.y.raw - v.y.raw)));
    if (ei > m_error * vmax + 1.21L) f.add("inverse point " + show(v));
    worst_invert = std::max(worst_invert, ei);
    // a⁻¹·b vs inverse(a)·b: the same rotation bit for bit; positions
    // qᵀ(p_b − p_a) + e1 vs qᵀp_b + e3 + (−qᵀp_a + e2): ≤ 1.5 raw apart
    // (both use the same, possibly non-unit, qᵀ).
    const Transform r1 = inv_mul_transforms(a, b);
    const Transform r2 = mul_transforms(transform_inverse(a), b);
    if (r1.q != r2.q) f.add("inv_mul_transforms rotation");
    if (std::abs(r1.p.x.raw - r2.p.x.raw) > 1 || std::abs(r1.p.y.raw - r2.p.y.raw) > 1)
      f.add("inv_mul_transforms position");
    // t·t⁻¹ ≈ identity: rotation c² + s² rounded once (exact when |q| rounds
    // to 1), position q·(−qᵀp) + p within |m − 1|·|p| + 1.21.
    const Transform i1 = mul_transforms(a, transform_inverse(a));
    const long double pa = std::max(std::fabs(static_cast<long double>(a.p.x.raw)), std::fabs(static_cast<long double>(a.p.y.raw)));
    if (std::abs(i1.p.x.raw) > m_error * pa + 1.21L || std::abs(i1.p.y.raw) > m_error * pa + 1.21L || i1.q.s.raw != 0)
      f.add("t·t⁻¹ " + show(i1.p));
  }
  INFO("max compose error per metre of |v|₁: " << static_cast<double>(worst_compose) << " raw; max invert error "
                                              << static_cast<double>(worst_invert) << " raw");
  INFO(f.first);
  CHECK(f.count == 0);
}

// ---------------------------------------------------------------------------
// Mat22
// ---------------------------------------------------------------------------

TEST_CASE("Mat22 multiply and determinant", "[fixed][vec2]") {
  const Mat22 m{vec2(1, 3), vec2(2, 4)};  // [[1 2] [3 4]]
  CHECK(mul(m, vec2(1, 1)) == vec2(3, 7));
  CHECK(determinant(m) == Q32::from_int(-2));
  bool ok = false;
  const Mat22 inv = inverse(m, &ok);
  CHECK(ok);
  CHECK(inv == Mat22{v2(-2 * k_one, 3 * k_one / 2), v2(k_one, -k_one / 2)});
  CHECK(solve(m, vec2(5, 11), &ok) == vec2(1, 2));
  CHECK(ok);
}

TEST_CASE("Mat22 solve on random well-conditioned systems", "[fixed][vec2]") {
  std::mt19937_64 rng(0x5017E);
  Failures f;
  long double worst_x = 0, worst_residual = 0;
  int tested = 0;
  for (int i = 0; i < k_iterations / 2; ++i) {
    // Entries at a random common scale 2^-16 .. 2^15 (value); keep systems
    // with |det| ≥ max|a|²/4 (condition number ≤ ~10).
    const unsigned scale = 16 + static_cast<unsigned>(rng() % 32);  // bits of the raw entries
    const int64_t lim = (int64_t{1} << scale) - 1;
    const Mat22 m{v2(uniform_raw(rng, lim), uniform_raw(rng, lim)), v2(uniform_raw(rng, lim), uniform_raw(rng, lim))};
    const long double a11 = ld(m.cx.x.raw), a21 = ld(m.cx.y.raw), a12 = ld(m.cy.x.raw), a22 = ld(m.cy.y.raw);
    const long double amax = std::max(std::max(std::fabs(a11), std::fabs(a12)), std::max(std::fabs(a21), std::fabs(a22)));
    // Long double products carry 2^-64 relative error; with |det| ≥ amax²/4
    // the determinant is good to 2^-61 relative.
    const long double det = a11 * a22 - a12 * a21;
    if (amax == 0 || std::fabs(det) < amax * amax / 4) continue;
    // b up to 2^10 times the largest entry, so |x| ≤ 8·2^10 (never saturates).
    const int64_t amax_raw = std::max(std::max(std::abs(m.cx.x.raw), std::abs(m.cy.x.raw)),
                                      std::max(std::abs(m.cx.y.raw), std::abs(m.cy.y.raw)));
    const Vec2 b = v2(uniform_raw(rng, amax_raw << 10), uniform_raw(rng, amax_raw << 10));
    bool ok = false;
    const Vec2 x = solve(m, b, &ok);
    if (!ok) {
      f.add("well-conditioned system reported singular");
      continue;
    }
    ++tested;
    // Oracle: Cramer in long double. Numerators may cancel, but their
    // absolute error is ≤ 2^-63·amax·max|b| value, i.e. ≤ 2^-61·2^11 value
    // = 2^-18 raw after dividing by det ≥ amax²/4; det adds |x|·2^-60.
    // Library: 0.5 + |x|·2^-63 + 2^-31 raw.
    const long double bx = ld(b.x.raw), by = ld(b.y.raw);
    const long double xe = (a22 * bx - a12 * by) / det * k_two32;
    const long double ye = (a11 * by - a21 * bx) / det * k_two32;
    const long double ex = std::fabs(static_cast<long double>(x.x.raw) - xe);
    const long double ey = std::fabs(static_cast<long double>(x.y.raw) - ye);
    const long double slack = 0x1p-16L + (std::fabs(xe) + std::fabs(ye)) * 0x1p-58L;
    if (ex > 0.5L + slack || ey > 0.5L + slack) f.add("solve x " + show(x));
    worst_x = std::max(worst_x, std::max(ex, ey));
    // Residual m·x − b: component errors ≤ ½ + slack feed through the row:
    // |r_i| ≤ (|a_i1| + |a_i2|)·(½ + slack) + ½ (mul rounds once) raw.
    const Vec2 r = mul(m, x) - b;
    const long double rb1 = (std::fabs(a11) + std::fabs(a12)) * (0.5L + slack) + 0.5L;
    const long double rb2 = (std::fabs(a21) + std::fabs(a22)) * (0.5L + slack) + 0.5L;
    if (std::fabs(static_cast<long double>(r.x.raw)) > rb1 || std::fabs(static_cast<long double>(r.y.raw)) > rb2)
      f.add("solve residual " + show(r));
    worst_residual = std::max(worst_residual, std::max(std::fabs(static_cast<long double>(r.x.raw)) / rb1,
                                                       std::fabs(static_cast<long double>(r.y.raw)) / rb2));
    // inverse(m)·b agrees with solve to within the two roundings.
    if ((i & 7) == 0) {
      const Mat22 inv = inverse(m, &ok);
      const Vec2 y = mul(inv, b);
      const long double tol = (std::fabs(bx) + std::fabs(by)) * (0.5L + slack) + 0.5L + 0.5L + slack;
      if (!ok || std::fabs(static_cast<long double>(y.x.raw - x.x.raw)) > tol ||
          std::fabs(static_cast<long double>(y.y.raw - x.y.raw)) > tol)
        f.add("inverse·b vs solve " + show(y) + " " + show(x));
    }
  }
  INFO(f.first);
  CHECK(f.count == 0);
  CHECK(tested > k_iterations / 20);
  INFO("max |x − exact| " << static_cast<double>(worst_x) << " raw; max residual / derived bound "
                          << static_cast<double>(worst_residual));
  CHECK(worst_residual <= 1);
  CHECK(worst_x <= 0.5L + 0x1p-10L);  // |x| ≤ 2^46 raw: slack ≤ 2^-16 + 2^-11
}

TEST_CASE("Mat22 solve: singular and tiny systems", "[fixed][vec2]") {
  bool ok = true;
  CHECK(solve(Mat22{}, vec2(1, 1), &ok) == vec2(0, 0));
  CHECK_FALSE(ok);
  ok = true;
  CHECK(inverse(Mat22{}, &ok) == Mat22{});
  CHECK_FALSE(ok);
  // Tiny but regular: det = 2^-34 rounds to 0 in Q32.32, but the system is
  // fine: diag(2^-17, 2^-17)·x = (2^-20, −2^-20) gives x = (1/8, −1/8).
  const Mat22 tiny{v2(int64_t{1} << 15, 0), v2(0, int64_t{1} << 15)};
  CHECK(determinant(tiny) == Q32::zero());
  CHECK(solve(tiny, v2(int64_t{1} << 12, -(int64_t{1} << 12)), &ok) == v2(k_one / 8, -k_one / 8));
  CHECK(ok);
  CHECK(inverse(tiny, &ok) == Mat22{v2(k_one << 17, 0), v2(0, k_one << 17)});
  CHECK(ok);

  std::mt19937_64 rng(0x5191);
  Failures f;
  for (int i = 0; i < 20000; ++i) {
    // Exactly singular: the second column is an integer multiple (−3..3) of
    // the first, or a row is zero.
    const Vec2 c1 = v2(random_raw(rng, 56), random_raw(rng, 56));
    const int64_t k = static_cast<int64_t>(rng() % 7) - 3;
    Mat22 m{c1, v2(c1.x.raw * k, c1.y.raw * k)};
    if ((i & 3) == 0) m = Mat22{v2(c1.x.raw, 0), v2(c1.y.raw, 0)};  // zero second row
    if ((i & 3) == 1) m = Mat22{m.cy, m.cx};                          // columns swapped
    const Vec2 b = v2(random_raw(rng, 56), random_raw(rng, 56));
    ok = true;
    const Vec2 x = solve(m, b, &ok);
    if (ok || x != vec2(0, 0)) f.add("singular solve");
    ok = true;
    if (inverse(m, &ok) != Mat22{} || ok) f.add("singular inverse");
  }
  INFO(f.first);
  CHECK(f.count == 0);

  // Nearly singular: det = 2^-64 (one unit of the exact product difference)
  // is regular; the solution leaves the range and saturates with a fault.
  FaultCounter faults;
  const Mat22 near{v2(1, 0), v2(0, 1)};  // det = 2^-64
  const Vec2 big = solve(near, vec2(1, -1), &ok);
  CHECK(ok);
  CHECK(big == Vec2{Q32::max(), Q32::min()});
#if TANDEM_FIXED_CHECKS
  CHECK(faults.count() == 2);
#endif
}

// ---------------------------------------------------------------------------
// AABB
// ---------------------------------------------------------------------------

TEST_CASE("AABB union, overlap, containment", "[fixed][vec2]") {
  const AABB a{vec2(0, 0), vec2(2, 2)};
  const AABB b{vec2(1, 1), vec2(3, 4)};
  const AABB c{vec2(2, 3), vec2(5, 5)};   // touches a's corner? no: y 3 > 2
  const AABB d{vec2(2, 2), vec2(3, 3)};   // touches a at the corner
  CHECK(aabb_is_valid(a));
  CHECK_FALSE(aabb_is_valid(AABB{vec2(1, 0), vec2(0, 1)}));
  CHECK(aabb_union(a, b) == AABB{vec2(0, 0), vec2(3, 4)});
  CHECK(aabb_overlaps(a, b));
  CHECK(aabb_overlaps(a, d));  // closed intervals: touching overlaps
  CHECK_FALSE(aabb_overlaps(a, c));
  CHECK(aabb_contains(aabb_union(a, b), a));
  CHECK_FALSE(aabb_contains(a, b));
  CHECK(aabb_contains(a, a));
  CHECK(aabb_contains_point(a, vec2(2, 0)));
  CHECK_FALSE(aabb_contains_point(a, v2(2 * k_one + 1, 0)));

  std::mt19937_64 rng(0xAABB);
  Failures f;
  const auto random_box = [&rng]() {
    const int64_t x0 = random_raw(rng, 62), x1 = random_raw(rng, 62), y0 = random_raw(rng, 62), y1 = random_raw(rng, 62);
    return AABB{v2(std::min(x0, x1), std::min(y0, y1)), v2(std::max(x0, x1), std::max(y0, y1))};
  };
  for (int i = 0; i < k_iterations / 4; ++i) {
    const AABB p = random_box(), r = random_box();
    const AABB u = aabb_union(p, r);
    if (!aabb_is_valid(u) || !aabb_contains(u, p) || !aabb_contains(u, r)) f.add("union");
    // The union is the smallest: each side comes from p or r.
    if ((u.lower.x != p.lower.x && u.lower.x != r.lower.x) || (u.upper.y != p.upper.y && u.upper.y != r.upper.y))
      f.add("union minimal");
    // Overlap oracle: intervals intersect on both axes (closed).
    const bool ox = std::max(p.lower.x.raw, r.lower.x.raw) <= std::min(p.upper.x.raw, r.upper.x.raw);
    const bool oy = std::max(p.lower.y.raw, r.lower.y.raw) <= std::min(p.upper.y.raw, r.upper.y.raw);
    if (aabb_overlaps(p, r) != (ox && oy) || aabb_overlaps(r, p) != (ox && oy)) f.add("overlap");
    const bool contains = p.lower.x.raw <= r.lower.x.raw && p.lower.y.raw <= r.lower.y.raw &&
                          r.upper.x.raw <= p.upper.x.raw && r.upper.y.raw <= p.upper.y.raw;
    if (aabb_contains(p, r) != contains) f.add("contains");
    if (!aabb_contains_point(p, aabb_center(p)) || !aabb_contains_point(p, p.lower) || !aabb_contains_point(p, p.upper))
      f.add("contains_point");
  }
  INFO(f.first);
  CHECK(f.count == 0);
}

TEST_CASE("AABB center, extents, perimeter, fatten", "[fixed][vec2]") {
  const AABB a{vec2(-1, 2), vec2(3, 5)};
  CHECK(aabb_center(a) == v2(k_one, 7 * k_one / 2));
  CHECK(aabb_extents(a) == v2(2 * k_one, 3 * k_one / 2));
  CHECK(aabb_perimeter(a) == Q32::from_int(14));
  CHECK(aabb_fatten(a, q(k_one / 2)) == AABB{v2(-3 * k_one / 2, 3 * k_one / 2), v2(7 * k_one / 2, 11 * k_one / 2)});
  // Odd raw sums round half away from zero.
  CHECK(aabb_center(AABB{v2(0, -3), v2(1, 0)}) == v2(1, -2));
  CHECK(aabb_extents(AABB{v2(0, -3), v2(1, 0)}) == v2(1, 2));

  SECTION("a box spanning the full range") {
    // No fault handler installed: in debug builds an overflow would abort.
    const AABB full{Vec2{Q32::min(), Q32::min()}, Vec2{Q32::max(), Q32::max()}};
    CHECK(aabb_center(full) == vec2(0, 0));
    CHECK(aabb_extents(full) == Vec2{Q32::max(), Q32::max()});  // (2^64 − 2)/2 = INT64_MAX
    const AABB top{Vec2{q(INT64_MAX - 1), q(INT64_MAX - 2)}, Vec2{Q32::max(), Q32::max()}};
    CHECK(aabb_center(top) == Vec2{Q32::max(), q(INT64_MAX - 1)});  // max − ½ → max; max − 1 exact
    const AABB bottom{Vec2{Q32::min(), Q32::min()}, Vec2{q(-INT64_MAX + 1), q(-INT64_MAX + 2)}};
    CHECK(aabb_center(bottom) == Vec2{Q32::min(), q(-INT64_MAX + 1)});
    FaultCounter faults;
    CHECK(aabb_perimeter(full) == Q32::max());
    CHECK(aabb_fatten(full, Q32::one()) == full);
#if TANDEM_FIXED_CHECKS
    CHECK(faults.count() > 0);
#endif
  }
  SECTION("random boxes against exact oracles") {
    std::mt19937_64 rng(0xCE7E);
    Failures f;
    for (int i = 0; i < k_iterations / 4; ++i) {
      const int64_t x0 = random_raw(rng), x1 = random_raw(rng), y0 = random_raw(rng), y1 = random_raw(rng);
      const AABB box{v2(std::min(x0, x1), std::min(y0, y1)), v2(std::max(x0, x1), std::max(y0, y1))};
      const Vec2 c = aabb_center(box), e = aabb_extents(box);
#if defined(__SIZEOF_INT128__)
      // (lo + hi)/2 and (hi − lo)/2 exactly, rounded half away from zero.
      const auto half = [](i128 s) -> i128 { return s >= 0 ? (s + 1) / 2 : -((-s + 1) / 2); };
      const i128 cx = half(static_cast<i128>(box.lower.x.raw) + box.upper.x.raw);
      const i128 cy = half(static_cast<i128>(box.lower.y.raw) + box.upper.y.raw);
      i128 ex = half(static_cast<i128>(box.upper.x.raw) - box.lower.x.raw);
      i128 ey = half(static_cast<i128>(box.upper.y.raw) - box.lower.y.raw);
      if (ex > INT64_MAX) ex = INT64_MAX;
      if (ey > INT64_MAX) ey = INT64_MAX;
      if (c.x.raw != cx || c.y.raw != cy) f.add("center " + show(box.lower) + show(box.upper));
      if (e.x.raw != ex || e.y.raw != ey) f.add("extents " + show(box.lower) + show(box.upper));
#else
      const long double cx = (static_cast<long double>(box.lower.x.raw) + static_cast<long double>(box.upper.x.raw)) / 2;
      const long double ex = (static_cast<long double>(box.upper.x.raw) - static_cast<long double>(box.lower.x.raw)) / 2;
      if (std::fabs(static_cast<long double>(c.x.raw) - cx) > 1 || std::fabs(static_cast<long double>(e.x.raw) - ex) > 1)
        f.add("center/extents");
#endif
      if (!aabb_contains_point(box, c)) f.add("center outside");
    }
    INFO(f.first);
    CHECK(f.count == 0);
  }
  SECTION("fatten and perimeter on random in-range boxes") {
    std::mt19937_64 rng(0xFA7);
    Failures f;
    for (int i = 0; i < 10000; ++i) {
      const int64_t x0 = random_raw(rng, 60), x1 = random_raw(rng, 60), y0 = random_raw(rng, 60), y1 = random_raw(rng, 60);
      const AABB box{v2(std::min(x0, x1), std::min(y0, y1)), v2(std::max(x0, x1), std::max(y0, y1))};
      const Q32 margin = q(std::abs(random_raw(rng, 40)));  // ≥ 0
      const AABB fat = aabb_fatten(box, margin);
      if (!aabb_contains(fat, box) || fat.upper.x - fat.lower.x != (box.upper.x - box.lower.x) + margin * 2)
        f.add("fatten");
      if (aabb_fatten(fat, -margin) != box) f.add("fatten inverse");
      // 2·(w + h) exactly: sides ≤ 2^28, no saturation.
      const int64_t per = 2 * ((box.upper.x.raw - box.lower.x.raw) + (box.upper.y.raw - box.lower.y.raw));
      if (aabb_perimeter(box).raw != per) f.add("perimeter");
      // extents are half the sides (ties away from zero).
      const int64_t w = box.upper.x.raw - box.lower.x.raw;
      if (aabb_extents(box).x.raw != (w + 1) / 2) f.add("extents");
    }
    INFO(f.first);
    CHECK(f.count == 0);
  }
}

// ---------------------------------------------------------------------------
// Vec2Q16
// ---------------------------------------------------------------------------

TEST_CASE("Vec2Q16 conversions round to nearest", "[fixed][vec2]") {
  CHECK(to_vec2(Vec2Q16{Q16::from_raw(1), Q16::from_raw(-65536)}) == v2(65536, -k_one));
  CHECK(to_vec2_q16(v2(32768, -32768)) == Vec2Q16{Q16::from_raw(1), Q16::from_raw(-1)});  // ties away
  CHECK(to_vec2_q16(v2(32767, -32767)) == Vec2Q16{Q16::from_raw(0), Q16::from_raw(0)});
  CHECK(to_vec2_q16(v2(3 * 32768, -3 * 32768)) == Vec2Q16{Q16::from_raw(2), Q16::from_raw(-2)});
  std::mt19937_64 rng(0x0116);
  Failures f;
  for (int i = 0; i < k_iterations / 4; ++i) {
    // In range: |raw| < 2^47 − 2^15 (i.e. below 32768 − half a Q16 unit).
    // Every other x is an exact tie (low 16 bits 0x8000).
    int64_t x = random_raw(rng, 47);
    if (i & 1) x = x < 0 ? -((-x & ~int64_t{0xFFFF}) | 0x8000) : ((x & ~int64_t{0xFFFF}) | 0x8000);
    const Vec2 v = v2(x, random_raw(rng, 47));
    if (std::abs(v.x.raw) >= (int64_t{1} << 47) - (int64_t{1} << 15) ||
        std::abs(v.y.raw) >= (int64_t{1} << 47) - (int64_t{1} << 15))
      continue;
    const Vec2Q16 w = to_vec2_q16(v);
    const auto want = [](int64_t r) {
      const int64_t m = (std::abs(r) + 32768) >> 16;
      return r < 0 ? -m : m;
    };
    if (w.x.raw != want(v.x.raw) || w.y.raw != want(v.y.raw)) f.add("to_vec2_q16 " + show(v));
    // Widening is exact and the round trip is within half a Q16.16 unit.
    const Vec2 back = to_vec2(w);
    if (std::abs(back.x.raw - v.x.raw) > 32768 || std::abs(back.y.raw - v.y.raw) > 32768) f.add("round trip " + show(v));
    if (to_vec2_q16(to_vec2(w)) != w) f.add("Q16 → Q32 → Q16 " + show(v));
  }
  INFO(f.first);
  CHECK(f.count == 0);
  FaultCounter faults;
  CHECK(to_vec2_q16(vec2(40000, -40000)) == Vec2Q16{Q16::max(), Q16::min()});
#if TANDEM_FIXED_CHECKS
  CHECK(faults.count() == 2);
#endif
}

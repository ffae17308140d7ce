// wide.h — 128-bit integer arithmetic for the fixed-point library.
//
// Design: every Q32.32 product, dot product, cross product and squared length
// goes through a 128-bit intermediate and is rounded exactly once. Two
// implementations give the same bits:
//   * native   — the compiler's `__int128` (g++/clang on 64-bit targets);
//   * portable — two 64-bit limbs, products built from 32-bit limbs. Used on
//                targets without `__int128` (i686, wasm32, MSVC) and whenever
//                TANDEM_FORCE_PORTABLE_INT128 is defined.
// Both are always compiled where `__int128` exists, so tests can compare them
// bit for bit on every platform (tests/fixed/test_wide.cpp).
//
// All arithmetic is modulo 2^128 on unsigned limbs: no signed overflow, no
// shift of a negative value, no out-of-range shift (rule 2). Signed meaning is
// two's complement, read back only where the caller knows the range.
#pragma once

#include <cstdint>

#if defined(__SIZEOF_INT128__) && !defined(TANDEM_FORCE_PORTABLE_INT128)
#define TANDEM_HAS_INT128 1
#else
#define TANDEM_HAS_INT128 0
#endif

namespace tandem::wide {

/// A 128-bit two's complement integer as two 64-bit limbs. Plain data; the
/// same layout is used by both paths so results can be compared directly.
struct U128 {
  uint64_t lo = 0;
  uint64_t hi = 0;
  friend constexpr bool operator==(U128, U128) = default;
};

// ---------------------------------------------------------------------------
// Portable path: always available, constexpr, integer limbs only.
// ---------------------------------------------------------------------------
namespace portable {

/// Unsigned 64×64 → 128 product from four 32×32 → 64 partial products.
constexpr U128 mul_u64(uint64_t a, uint64_t b) {
  const uint64_t a_lo = a & 0xFFFFFFFFu, a_hi = a >> 32;
  const uint64_t b_lo = b & 0xFFFFFFFFu, b_hi = b >> 32;
  const uint64_t p0 = a_lo * b_lo;
  const uint64_t p1 = a_lo * b_hi;
  const uint64_t p2 = a_hi * b_lo;
  const uint64_t p3 = a_hi * b_hi;
  // Middle column: cannot overflow 64 bits (3 × (2^32-1) < 2^64).
  const uint64_t mid = (p0 >> 32) + (p1 & 0xFFFFFFFFu) + (p2 & 0xFFFFFFFFu);
  U128 r;
  r.lo = (mid << 32) | (p0 & 0xFFFFFFFFu);
  r.hi = p3 + (p1 >> 32) + (p2 >> 32) + (mid >> 32);
  return r;
}

/// Two's complement negation modulo 2^128.
constexpr U128 neg(U128 a) {
  U128 r;
  r.lo = ~a.lo + 1u;
  r.hi = ~a.hi + (r.lo == 0 ? 1u : 0u);
  return r;
}

/// Signed 64×64 → 128 product (exact; |result| ≤ 2^126).
constexpr U128 mul_s64(int64_t a, int64_t b) {
  const bool neg_a = a < 0, neg_b = b < 0;
  // Magnitudes through unsigned: well defined for INT64_MIN too.
  const uint64_t ua = neg_a ? 0u - static_cast<uint64_t>(a) : static_cast<uint64_t>(a);
  const uint64_t ub = neg_b ? 0u - static_cast<uint64_t>(b) : static_cast<uint64_t>(b);
  const U128 p = mul_u64(ua, ub);
  return (neg_a != neg_b) ? neg(p) : p;
}

/// Sum modulo 2^128.
constexpr U128 add(U128 a, U128 b) {
  U128 r;
  r.lo = a.lo + b.lo;
  r.hi = a.hi + b.hi + (r.lo < a.lo ? 1u : 0u);
  return r;
}

/// Difference modulo 2^128.
constexpr U128 sub(U128 a, U128 b) {
  U128 r;
  r.lo = a.lo - b.lo;
  r.hi = a.hi - b.hi - (a.lo < b.lo ? 1u : 0u);
  return r;
}

}  // namespace portable

// ---------------------------------------------------------------------------
// Native path, where the compiler has __int128.
// ---------------------------------------------------------------------------
#if defined(__SIZEOF_INT128__)
namespace native {
__extension__ typedef unsigned __int128 u128;
__extension__ typedef __int128 s128;

constexpr u128 to_native(U128 a) { return (static_cast<u128>(a.hi) << 64) | a.lo; }
constexpr U128 from_native(u128 a) {
  return U128{static_cast<uint64_t>(a), static_cast<uint64_t>(a >> 64)};
}
/// Signed 64×64 → 128 product (exact).
constexpr U128 mul_s64(int64_t a, int64_t b) {
  return from_native(static_cast<u128>(static_cast<s128>(a) * static_cast<s128>(b)));
}
/// Unsigned 64×64 → 128 product.
constexpr U128 mul_u64(uint64_t a, uint64_t b) { return from_native(static_cast<u128>(a) * b); }
constexpr U128 add(U128 a, U128 b) { return from_native(to_native(a) + to_native(b)); }
constexpr U128 sub(U128 a, U128 b) { return from_native(to_native(a) - to_native(b)); }
constexpr U128 neg(U128 a) { return from_native(u128{0} - to_native(a)); }
}  // namespace native
#endif

// ---------------------------------------------------------------------------
// The path the library uses.
// ---------------------------------------------------------------------------
#if TANDEM_HAS_INT128
namespace impl = native;
#else
namespace impl = portable;
#endif

/// Signed 64×64 → 128 product, exact.
constexpr U128 mul_s64(int64_t a, int64_t b) { return impl::mul_s64(a, b); }
/// Unsigned 64×64 → 128 product, exact.
constexpr U128 mul_u64(uint64_t a, uint64_t b) { return impl::mul_u64(a, b); }
/// a + b modulo 2^128.
constexpr U128 add(U128 a, U128 b) { return impl::add(a, b); }
/// a − b modulo 2^128.
constexpr U128 sub(U128 a, U128 b) { return impl::sub(a, b); }
/// −a modulo 2^128.
constexpr U128 neg(U128 a) { return impl::neg(a); }

/// True when the two's complement value is negative.
constexpr bool is_negative(U128 a) { return (a.hi >> 63) != 0; }

/// Sign-extends a 64-bit value.
constexpr U128 from_s64(int64_t v) {
  return U128{static_cast<uint64_t>(v), v < 0 ? ~uint64_t{0} : uint64_t{0}};
}

/// Unsigned comparison a < b.
constexpr bool less_u(U128 a, U128 b) { return a.hi < b.hi || (a.hi == b.hi && a.lo < b.lo); }

/// Signed comparison a < b.
constexpr bool less_s(U128 a, U128 b) {
  const bool na = is_negative(a), nb = is_negative(b);
  if (na != nb) return na;
  return less_u(a, b);
}

/// Logical shift right by s, 0 ≤ s < 128.
constexpr U128 shr_u(U128 a, unsigned s) {
  if (s == 0) return a;
  if (s >= 64) return U128{a.hi >> (s - 64), 0};
  return U128{(a.lo >> s) | (a.hi << (64 - s)), a.hi >> s};
}

/// Shift left by s, 0 ≤ s < 128 (bits shifted out are lost).
constexpr U128 shl(U128 a, unsigned s) {
  if (s == 0) return a;
  if (s >= 64) return U128{0, a.lo << (s - 64)};
  return U128{a.lo << s, (a.hi << s) | (a.lo >> (64 - s))};
}

/// |a| as an unsigned magnitude (the magnitude of −2^127 is 2^127).
constexpr U128 abs_u(U128 a) { return is_negative(a) ? neg(a) : a; }

/// Number of leading zero bits (128 for zero).
constexpr int clz(U128 a) {
  if (a.hi != 0) return __builtin_clzll(a.hi);
  if (a.lo != 0) return 64 + __builtin_clzll(a.lo);
  return 128;
}

/// Rounds a signed 128-bit value divided by 2^s (1 ≤ s ≤ 64) to the nearest
/// integer, ties away from zero, and saturates to [−(2^63−1), 2^63−1].
/// *out_overflow is set when saturation happened (left untouched otherwise).
constexpr int64_t round_shift_saturate(U128 v, unsigned s, bool* out_overflow) {
  const bool negative = is_negative(v);
  U128 m = negative ? neg(v) : v;  // magnitude, ≤ 2^127
  m = add(m, U128{uint64_t{1} << (s - 1), 0});
  m = shr_u(m, s);
  if (m.hi != 0 || m.lo > static_cast<uint64_t>(INT64_MAX)) {
    *out_overflow = true;
    return negative ? -INT64_MAX : INT64_MAX;
  }
  const int64_t mag = static_cast<int64_t>(m.lo);
  return negative ? -mag : mag;
}

namespace portable {
/// Unsigned 128 / 64 division where the quotient fits in 64 bits (requires
/// n.hi < d, d ≠ 0): long division on 32-bit digits (Knuth's algorithm D, as
/// in Hacker's Delight `divlu`). Returns the quotient, writes the remainder.
constexpr uint64_t div_u128_u64(U128 n, uint64_t d, uint64_t* out_rem) {
  // Normalise so the divisor's top bit is set.
  const int s = __builtin_clzll(d);
  d <<= s;
  const uint64_t hi = s == 0 ? n.hi : (n.hi << s) | (n.lo >> (64 - s));
  const uint64_t lo = n.lo << s;
  const uint64_t d1 = d >> 32, d0 = d & 0xFFFFFFFFu;
  const uint64_t l1 = lo >> 32, l0 = lo & 0xFFFFFFFFu;
  // First quotient digit (estimate from the top digit, corrected at most twice).
  uint64_t q1 = hi / d1, r = hi - q1 * d1;
  while (q1 >> 32 != 0 || q1 * d0 > ((r << 32) | l1)) {
    --q1;
    r += d1;
    if (r >> 32 != 0) break;
  }
  const uint64_t h2 = ((hi << 32) | l1) - q1 * d;
  // Second quotient digit.
  uint64_t q0 = h2 / d1;
  r = h2 - q0 * d1;
  while (q0 >> 32 != 0 || q0 * d0 > ((r << 32) | l0)) {
    --q0;
    r += d1;
    if (r >> 32 != 0) break;
  }
  const uint64_t rem = ((h2 << 32) | l0) - q0 * d;
  *out_rem = rem >> s;
  return (q1 << 32) | q0;
}
}  // namespace portable

#if defined(__SIZEOF_INT128__)
namespace native {
/// Unsigned 128 / 64 division where the quotient fits in 64 bits (requires
/// n.hi < d, d ≠ 0). Returns the quotient, writes the remainder.
constexpr uint64_t div_u128_u64(U128 n, uint64_t d, uint64_t* out_rem) {
  const u128 nn = to_native(n);
  *out_rem = static_cast<uint64_t>(nn % d);
  return static_cast<uint64_t>(nn / d);
}
}  // namespace native
#endif

/// Unsigned 128 / 64 division where the quotient fits in 64 bits (requires
/// n.hi < d, d ≠ 0). Returns the quotient and writes the remainder.
constexpr uint64_t div_u128_u64(U128 n, uint64_t d, uint64_t* out_rem) {
  return impl::div_u128_u64(n, d, out_rem);
}

}  // namespace tandem::wide

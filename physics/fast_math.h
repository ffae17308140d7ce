// fast_math.h — in-range Q32.32 arithmetic for the narrow phase and the
// contact preparation (internal).
//
// Every function here gives the SAME BITS as the checked operator it names
// (fixed.h / vec2.h: one exact 128-bit sum of products, rounded once to
// nearest, ties away from zero) whenever that operator would not saturate.
// In release builds with a native 128-bit type it skips the fault report and
// forms a dot product as two 64×64→128 multiplies, an add and one rounding,
// but it saturates exactly where the checked operators do: callers use it
// where a range argument shows that nothing should saturate (written next to
// each use: manifold_internal.h for the narrow phase, contact_solver.cpp for
// the preparation, whose inverse-inertia bound closed the one hole the
// random-world stress found: seeds 94, 55, 9), and a crafted state outside
// those ranges must still give the same bits in every build. Debug and
// sanitizer builds (no NDEBUG) and
// targets without __int128 use the checked operators, which also report the
// fault.
#pragma once

#include <cstdint>

#include "fixed/fixed.h"
#include "fixed/vec2.h"

namespace tandem::fast {

#if TANDEM_HAS_INT128 && defined(NDEBUG)
#define TANDEM_FAST_MATH_UNCHECKED 1
__extension__ typedef __int128 s128;
__extension__ typedef unsigned __int128 u128;
/// The exact 128-bit value (a Q64.64 sum) rounded once to Q32.32.
/// round_shift's rare path: the exact test and the saturated value (out of
/// line, so the hot path stays short).
[[gnu::cold, gnu::noinline]] inline Q32 round_shift_wide(u128 sum) {
  const s128 p = static_cast<s128>(sum);
  constexpr u128 limit = (u128{1} << 95) - (u128{1} << 31);
  // |p| ≥ 2^95 − 2^31 rounds to a magnitude ≥ 2^63: saturated. One unsigned
  // compare tests −limit < p < limit (the sum offset modulo 2^128).
  if (sum + (limit - 1) >= 2 * limit - 1) return Q32::from_raw(p > 0 ? INT64_MAX : -INT64_MAX);
  return Q32::from_raw(static_cast<int64_t>((p + ((s128{1} << 31) - (p < 0 ? 1 : 0))) >> 32));
}
/// Bits 32..95 of p + 2^31 − [p < 0] for the 128-bit value p = hi·2^64 + lo:
/// p rounded to nearest (ties away from zero) and shifted right by 32, as
/// 64-bit words, branch-free (the carry out of the low word, the sign from
/// hi's top bit). Equal to the s128 formula's low 64 bits for every p; the
/// rounded Q32.32 value itself whenever it fits.
inline int64_t round_shift_words(uint64_t lo, uint64_t hi) {
  const uint64_t half = (uint64_t{1} << 31) - (hi >> 63);
  const uint64_t low = lo + half;
  const uint64_t high = hi + (low < half ? 1 : 0);
  return static_cast<int64_t>((low >> 32) | (high << 32));
}
/// The exact 128-bit value (a Q64.64 sum, modulo 2^128 as the checked path's
/// wide::add) rounded once to Q32.32 and saturated to ±(2^63 − 1) exactly
/// where the checked operators saturate: every build computes the same bits
/// even out of range (stress seed 94). No fault report. The hot path tests
/// only the high word (|p| < 2^94 cannot saturate).
inline Q32 round_shift(u128 sum) {
  const uint64_t hi = static_cast<uint64_t>(sum >> 64);
  if (hi + (uint64_t{1} << 30) >= (uint64_t{1} << 31)) [[unlikely]] return round_shift_wide(sum);
  return Q32::from_raw(round_shift_words(static_cast<uint64_t>(sum), hi));
}
inline u128 product(int64_t a, int64_t b) { return static_cast<u128>(static_cast<s128>(a) * b); }
/// a·b, rounded once.
inline Q32 mul(Q32 a, Q32 b) { return round_shift(product(a.raw, b.raw)); }
/// The saturated results of fixed.h's operator+ and operator− (rare path).
[[gnu::cold, gnu::noinline]] inline Q32 add_saturated(Q32 a) { return Q32::from_raw(a.raw > 0 ? INT64_MAX : -INT64_MAX); }
[[gnu::cold, gnu::noinline]] inline Q32 sub_saturated(Q32 a) { return Q32::from_raw(a.raw >= 0 ? INT64_MAX : -INT64_MAX); }
/// a + b, saturated exactly as fixed.h's operator+ (no fault report).
inline Q32 add(Q32 a, Q32 b) {
  int64_t r;
  if (__builtin_add_overflow(a.raw, b.raw, &r) || r == INT64_MIN) [[unlikely]] return add_saturated(a);
  return Q32::from_raw(r);
}
/// a − b, saturated exactly as fixed.h's operator− (no fault report).
inline Q32 sub(Q32 a, Q32 b) {
  int64_t r;
  if (__builtin_sub_overflow(a.raw, b.raw, &r) || r == INT64_MIN) [[unlikely]] return sub_saturated(a);
  return Q32::from_raw(r);
}
/// a·b + c·d, rounded once.
inline Q32 sum2(Q32 a, Q32 b, Q32 c, Q32 d) { return round_shift(product(a.raw, b.raw) + product(c.raw, d.raw)); }
/// a·b − c·d, rounded once.
inline Q32 diff2(Q32 a, Q32 b, Q32 c, Q32 d) { return round_shift(product(a.raw, b.raw) - product(c.raw, d.raw)); }
#else
#define TANDEM_FAST_MATH_UNCHECKED 0
inline Q32 mul(Q32 a, Q32 b) { return a * b; }
inline Q32 add(Q32 a, Q32 b) { return a + b; }
inline Q32 sub(Q32 a, Q32 b) { return a - b; }
inline Q32 sum2(Q32 a, Q32 b, Q32 c, Q32 d) { return detail::sum_products(a.raw, b.raw, c.raw, d.raw, "narrow phase"); }
inline Q32 diff2(Q32 a, Q32 b, Q32 c, Q32 d) {
  return detail::sum_products(a.raw, b.raw, detail::neg_raw(c.raw), d.raw, "narrow phase");
}
#endif

/// a + b and a − b, component-wise.
inline Vec2 add(Vec2 a, Vec2 b) { return {add(a.x, b.x), add(a.y, b.y)}; }
inline Vec2 sub(Vec2 a, Vec2 b) { return {sub(a.x, b.x), sub(a.y, b.y)}; }
/// vec2.h's dot(a, b).
inline Q32 dot(Vec2 a, Vec2 b) { return sum2(a.x, b.x, a.y, b.y); }
/// vec2.h's cross(a, b).
inline Q32 cross(Vec2 a, Vec2 b) { return diff2(a.x, b.y, a.y, b.x); }
/// vec2.h's rotate(q, v).
inline Vec2 rotate(Rot q, Vec2 v) { return {diff2(q.c, v.x, q.s, v.y), sum2(q.s, v.x, q.c, v.y)}; }
/// vec2.h's inv_rotate(q, v).
inline Vec2 inv_rotate(Rot q, Vec2 v) { return {sum2(q.c, v.x, q.s, v.y), diff2(q.c, v.y, q.s, v.x)}; }
/// vec2.h's transform_point(t, v).
inline Vec2 transform_point(Transform t, Vec2 v) { return fast::add(fast::rotate(t.q, v), t.p); }
/// vec2.h's inv_mul_transforms(a, b).
inline Transform inv_mul_transforms(Transform a, Transform b) {
  return {fast::inv_rotate(a.q, fast::sub(b.p, a.p)),
          Rot{sum2(a.q.c, b.q.c, a.q.s, b.q.s), diff2(a.q.c, b.q.s, a.q.s, b.q.c)}};
}
/// a + s·b, the product rounded once (vec2.h's mul_add).
inline Vec2 mul_add(Vec2 a, Q32 s, Vec2 b) { return {add(a.x, mul(s, b.x)), add(a.y, mul(s, b.y))}; }

/// a + t·(b − a) (vec2.h's lerp).
inline Vec2 lerp(Vec2 a, Vec2 b, Q32 t) { return fast::mul_add(a, t, fast::sub(b, a)); }

/// a / b rounded to nearest, ties away from zero: the same bits as Q32
/// division. When |a| < 2^-1 (raw < 2^31) and b ≠ 0 the shifted dividend
/// fits 63 bits and one 64-bit division does it; otherwise the checked
/// division.
inline Q32 div(Q32 a, Q32 b) {
  const uint64_t ua = detail::magnitude(a.raw), ub = detail::magnitude(b.raw);
  if (ua >= (uint64_t{1} << 31) || ub == 0) return a / b;
  const uint64_t n = ua << 32;
  uint64_t q = n / ub;
  const uint64_t rem = n - q * ub;
  if (rem >= ub - rem) ++q;
  if (q > static_cast<uint64_t>(INT64_MAX)) return a / b;  // only for ub = 1 (saturates there)
  const int64_t m = static_cast<int64_t>(q);
  return Q32::from_raw((a.raw < 0) != (b.raw < 0) ? -m : m);
}

/// 1/k for k > 0, rounded to nearest (ties away from zero): the same bits as
/// Q32::one() / k. For k ≥ 1 (raw ≥ 2^32) the quotient 2^64/raw fits 32 bits
/// and is formed with two 64-bit divisions; smaller k take the checked
/// division (which saturates at 1/k ≥ 2^31 as Q32 division does).
inline Q32 reciprocal(Q32 k) {
  const int64_t d = k.raw;
  if (d < (int64_t{1} << 32)) return Q32::one() / k;
  const uint64_t ud = static_cast<uint64_t>(d);
  const uint64_t half = uint64_t{1} << 63;  // 2^64 = 2 · 2^63
  const uint64_t q1 = half / ud, r1 = half % ud;
  const uint64_t r2 = 2 * r1;  // < 2·ud < 2^64
  uint64_t q = 2 * q1 + r2 / ud;
  const uint64_t rem = r2 % ud;
  if (rem >= ud - rem) ++q;  // 2·rem ≥ d: round half away from zero
  return Q32::from_raw(static_cast<int64_t>(q));
}

}  // namespace tandem::fast

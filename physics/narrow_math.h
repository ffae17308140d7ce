// narrow_math.h — the narrow phase's Q32.32 arithmetic (internal): one
// definition for every build, no saturation test, rounding half up.
//
// Why not fixed.h's operators or fast_math.h: those saturate (and the
// checked ones report a fault), so each sum of products pays for an overflow
// test and a sign-dependent rounding step (ties away from zero), about 25
// instructions on x86-64 against two multiplies, two adds and a shift here.
// The narrow phase does not need either:
//
// * Range (manifold_internal.h states it in full). Every coordinate the
//   manifold functions form lies in shape A's (or the reference body's) frame
//   within 2·k_max_world_coordinate + 2·k_max_shape_size < 2^21 m, raw below
//   2^53, and every direction or rotation component is at most 1 (raw 2^32).
//   A product of the two is below 2^85 and the sum of two below 2^86, so the
//   exact 128-bit sum never wraps and its rounded value (below 2^54) fits
//   int64 with room; sums and differences of two coordinates stay below
//   2^54. Nothing here can overflow for a world that respects the limits.
// * Outside the limits (a crafted state) the results wrap modulo 2^64
//   instead of saturating, through unsigned arithmetic, so there is still no
//   undefined behaviour and every build, compiler and target computes the
//   same bits: the portable path below (wide.h limbs, no __int128) is the
//   definition written out, and the native one is checked against it
//   (tests/physics/test_manifold.cpp, "narrow_math agrees with its portable
//   definition").
// * Rounding: floor((exact + 2^31) / 2^32), i.e. to nearest with ties
//   rounded up — the error bound (≤ ½ raw unit, 1.2e-10 m) is the checked
//   operators' one; only exact ties of negative values round differently
//   (toward +∞ instead of away from zero).
//
// Used by manifold.cpp, manifold_cores.cpp and manifold_chain.cpp. The
// contact solver keeps fast_math.h (its mass terms need the saturation).
#pragma once

#include <cstdint>

#include "fixed/fixed.h"
#include "fixed/vec2.h"
#include "fixed/wide.h"
#include "physics/fast_math.h"

namespace tandem::narrow_math {

/// Portable definition: (a·b + c·d + 2^31) >> 32, modulo 2^64 (wide.h limbs).
constexpr int64_t sum_products_portable(int64_t a, int64_t b, int64_t c, int64_t d) {
  const wide::U128 s = wide::add(wide::add(wide::mul_s64(a, b), wide::mul_s64(c, d)), wide::U128{uint64_t{1} << 31, 0});
  return static_cast<int64_t>((s.lo >> 32) | (s.hi << 32));
}

#if defined(__SIZEOF_INT128__) && !defined(TANDEM_FORCE_PORTABLE_INT128)
/// a·b + c·d rounded half up to Q32.32, modulo 2^64 (see the file comment).
inline int64_t sum_products(int64_t a, int64_t b, int64_t c, int64_t d) {
  __extension__ typedef __int128 s128;
  __extension__ typedef unsigned __int128 u128;
  const u128 s = static_cast<u128>(static_cast<s128>(a) * b) + static_cast<u128>(static_cast<s128>(c) * d) +
                 (u128{1} << 31);
  return static_cast<int64_t>(static_cast<uint64_t>(s >> 32));
}
#else
inline int64_t sum_products(int64_t a, int64_t b, int64_t c, int64_t d) { return sum_products_portable(a, b, c, d); }
#endif

/// −a as a raw value, modulo 2^64 (C++20 defines the conversion back).
constexpr int64_t neg_raw(int64_t a) { return static_cast<int64_t>(uint64_t{0} - static_cast<uint64_t>(a)); }

/// a + b, a − b (modulo 2^64; exact in range).
constexpr Q32 add(Q32 a, Q32 b) {
  return Q32::from_raw(static_cast<int64_t>(static_cast<uint64_t>(a.raw) + static_cast<uint64_t>(b.raw)));
}
constexpr Q32 sub(Q32 a, Q32 b) {
  return Q32::from_raw(static_cast<int64_t>(static_cast<uint64_t>(a.raw) - static_cast<uint64_t>(b.raw)));
}
constexpr Vec2 add(Vec2 a, Vec2 b) { return {add(a.x, b.x), add(a.y, b.y)}; }
constexpr Vec2 sub(Vec2 a, Vec2 b) { return {sub(a.x, b.x), sub(a.y, b.y)}; }
/// a / 2 rounded to nearest, ties away from zero: Q32's `a / 2` (fixed.h,
/// magnitude (|a| + 1) >> 1, sign restored) for every raw value, without its
/// division and sign handling: floor(a/2) plus 1 for a positive odd a.
constexpr Q32 half(Q32 a) {
  return Q32::from_raw((a.raw >> 1) + (a.raw > 0 ? (a.raw & 1) : 0));
}
/// (−v.y, v.x), the negation wrapping: fixed's left_perp except for a raw
/// −2^63, which no unit direction has.
constexpr Vec2 left_perp(Vec2 v) { return {Q32::from_raw(neg_raw(v.y.raw)), v.x}; }
/// a·b, rounded half up.
inline Q32 mul(Q32 a, Q32 b) { return Q32::from_raw(sum_products(a.raw, b.raw, 0, 0)); }
/// a·b + c·d and a·b − c·d, rounded once, half up.
inline Q32 sum2(Q32 a, Q32 b, Q32 c, Q32 d) { return Q32::from_raw(sum_products(a.raw, b.raw, c.raw, d.raw)); }
inline Q32 diff2(Q32 a, Q32 b, Q32 c, Q32 d) { return Q32::from_raw(sum_products(a.raw, b.raw, neg_raw(c.raw), d.raw)); }
inline Q32 dot(Vec2 a, Vec2 b) { return sum2(a.x, b.x, a.y, b.y); }
inline Q32 cross(Vec2 a, Vec2 b) { return diff2(a.x, b.y, a.y, b.x); }
/// q·v and qᵀ·v.
inline Vec2 rotate(Rot q, Vec2 v) { return {narrow_math::diff2(q.c, v.x, q.s, v.y), narrow_math::sum2(q.s, v.x, q.c, v.y)}; }
inline Vec2 inv_rotate(Rot q, Vec2 v) { return {narrow_math::sum2(q.c, v.x, q.s, v.y), narrow_math::diff2(q.c, v.y, q.s, v.x)}; }
/// t.q·v + t.p.
inline Vec2 transform_point(Transform t, Vec2 v) { return narrow_math::add(narrow_math::rotate(t.q, v), t.p); }
/// a⁻¹·b: B's frame → A's frame.
inline Transform inv_mul_transforms(Transform a, Transform b) {
  return {narrow_math::inv_rotate(a.q, narrow_math::sub(b.p, a.p)), Rot{narrow_math::sum2(a.q.c, b.q.c, a.q.s, b.q.s), narrow_math::diff2(a.q.c, b.q.s, a.q.s, b.q.c)}};
}
/// a + s·b and a − s·b, each product rounded once.
inline Vec2 mul_add(Vec2 a, Q32 s, Vec2 b) { return {narrow_math::add(a.x, narrow_math::mul(s, b.x)), narrow_math::add(a.y, narrow_math::mul(s, b.y))}; }
inline Vec2 mul_sub(Vec2 a, Q32 s, Vec2 b) { return {narrow_math::sub(a.x, narrow_math::mul(s, b.x)), narrow_math::sub(a.y, narrow_math::mul(s, b.y))}; }
/// a + t·(b − a).
inline Vec2 lerp(Vec2 a, Vec2 b, Q32 t) { return narrow_math::mul_add(a, t, narrow_math::sub(b, a)); }
/// a / b rounded to nearest (fast_math.h's, the same bits as Q32 division).
inline Q32 div(Q32 a, Q32 b) { return fast::div(a, b); }

/// floor(n·2^32 / d) and its remainder by long division, 32 quotient bits
/// one at a time, for 0 ≤ n ≤ d < 2^63 (so 2·r never wraps): the definition
/// the native path below is tested against.
constexpr uint64_t fraction_quotient_portable(uint64_t n, uint64_t d, uint64_t* out_rem) {
  uint64_t q = n / d, r = n % d;
  for (int i = 0; i < 32; ++i) {
    r <<= 1;
    q <<= 1;
    if (r >= d) {
      r -= d;
      q |= 1;
    }
  }
  *out_rem = r;
  return q;
}

/// floor(n·2^32 / d) and its remainder, for 0 ≤ n ≤ d, d > 0 (so the
/// quotient ≤ 2^32 and the high word n >> 32 < d). Exact integer division:
/// every path gives the same bits. On x86-64 one divq (the compilers call a
/// 128-bit division routine of ~100 instructions for the u128 form).
inline uint64_t fraction_quotient(uint64_t n, uint64_t d, uint64_t* out_rem) {
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
  uint64_t q, r;
  __asm__("divq %4" : "=a"(q), "=d"(r) : "a"(n << 32), "d"(n >> 32), "rm"(d) : "cc");
  *out_rem = r;
  return q;
#else
  return fraction_quotient_portable(n, d, out_rem);
#endif
}

/// n / d for 0 ≤ n ≤ d (a clipping fraction in [0, 1]), rounded to nearest,
/// ties away from zero: the same bits as Q32 division (and div) in that
/// range, without its 128-bit division. Outside the range (only a crafted
/// out-of-limits state) it is div.
inline Q32 fraction(Q32 n, Q32 d) {
  if (n.raw < 0 || n.raw > d.raw || d.raw <= 0) return div(n, d);
  const uint64_t ud = static_cast<uint64_t>(d.raw);
  uint64_t rem;
  uint64_t q = fraction_quotient(static_cast<uint64_t>(n.raw), ud, &rem);
  if (rem >= ud - rem) ++q;
  return Q32::from_raw(static_cast<int64_t>(q));
}

}  // namespace tandem::narrow_math

// vec2.cpp — the parts of vec2.h that need a square root, a division or the
// trigonometric functions.
//
// normalize: v/|v| is scale-free, so both components are first shifted up
// (exactly) until the larger has its top bit at 2^61. The integer root of the
// exact sum of squares then has 61+ significant bits and the one rounded
// quotient per component is within 0.5 + 2^-30 raw units of exact, for tiny
// and huge vectors alike. (Dividing by the Q32.32-rounded length instead makes
// a vector of a few raw units come out far from unit length.)
//
// Mat22: Cramer's rule with the determinant and numerators kept exact as
// 128-bit Q64.64 integers; quotient_q32() divides them once. When the
// determinant needs more than 64 bits both are shifted down together so the
// divisor fits 64 bits with its top bit set; the truncation moves the quotient
// by less than |x|·2^-63 + 2^-31 raw units before the final rounding.
#include "fixed/vec2.h"

namespace tandem {
namespace {

using wide::U128;

/// The exact two's complement 128-bit value a·b − c·d (|value| < 2^127 for
/// raw values in the symmetric range).
U128 product_difference(int64_t a, int64_t b, int64_t c, int64_t d) {
  return wide::sub(wide::mul_s64(a, b), wide::mul_s64(c, d));
}

/// n·2^32 / d for two's complement 128-bit n and d ≠ 0 (any common unit),
/// rounded to nearest, ties away from zero, as a Q32.32 raw value; saturates
/// with an overflow fault named `op`.
Q32 quotient_q32(U128 n, U128 d, const char* op) {
  const bool negative = wide::is_negative(n) != wide::is_negative(d);
  U128 nm = wide::abs_u(n);
  U128 dm = wide::abs_u(d);
  if (dm.hi != 0) {
    // Divisor wider than 64 bits: drop its low bits (and the same number of
    // the numerator's) so it lands in [2^63, 2^64).
    const unsigned s = static_cast<unsigned>(64 - wide::clz(dm));  // 1..64
    dm = wide::shr_u(dm, s);
    nm = wide::shr_u(nm, s);
  }
  bool overflow = (nm.hi >> 32) != 0;  // nm·2^32 ≥ 2^128 > max · d
  uint64_t q = static_cast<uint64_t>(INT64_MAX);
  if (!overflow) q = detail::div_round_mag(wide::shl(nm, 32), dm.lo, static_cast<uint64_t>(INT64_MAX), &overflow);
  if (overflow) {
    TANDEM_FIXED_FAULT(FixedFault::overflow, op);
    q = static_cast<uint64_t>(INT64_MAX);
  }
  (void)op;
  const int64_t m = static_cast<int64_t>(q);
  return Q32::from_raw(negative ? -m : m);
}

/// The unit vector along raw (x, y) ≠ (0, 0); see the notes at the top.
Vec2 unit_vector(int64_t x, int64_t y) {
  uint64_t ax = detail::magnitude(x), ay = detail::magnitude(y);
  const uint64_t big = ax > ay ? ax : ay;
  const int shift = __builtin_clzll(big) - 2;  // big → [2^61, 2^62)
  if (shift > 0) {
    ax <<= shift;
    ay <<= shift;
  }
  // ax, ay ≤ 2^63, so the sum of squares is ≤ 2^127 and its root < 2^64;
  // len ≥ max(ax, ay) ≥ 2^61.
  const uint64_t len = isqrt_round(wide::add(wide::mul_u64(ax, ax), wide::mul_u64(ay, ay)));
  // a·2^32 / len ≤ 2^32 (+1 from len's rounding): the high word a >> 32 is
  // below len, as div_round_mag requires, and the quotient never saturates.
  bool overflow = false;
  const uint64_t kmax = static_cast<uint64_t>(INT64_MAX);
  const int64_t ux = static_cast<int64_t>(detail::div_round_mag(U128{ax << 32, ax >> 32}, len, kmax, &overflow));
  const int64_t uy = static_cast<int64_t>(detail::div_round_mag(U128{ay << 32, ay >> 32}, len, kmax, &overflow));
  return {Q32::from_raw(x < 0 ? -ux : ux), Q32::from_raw(y < 0 ? -uy : uy)};
}

}  // namespace

Q32 length(Vec2 v) {
  const uint64_t ax = detail::magnitude(v.x.raw), ay = detail::magnitude(v.y.raw);
  const uint64_t r = isqrt_round(wide::add(wide::mul_u64(ax, ax), wide::mul_u64(ay, ay)));
  if (r > static_cast<uint64_t>(INT64_MAX)) {
    TANDEM_FIXED_FAULT(FixedFault::overflow, "Vec2 length");
    return Q32::max();
  }
  return Q32::from_raw(static_cast<int64_t>(r));
}

Q32 distance(Vec2 a, Vec2 b) { return length(b - a); }

Vec2 length_and_normalize(Vec2 v, Q32* out_length) {
  if (out_length) *out_length = length(v);
  if (v.x.raw == 0 && v.y.raw == 0) return {};
  return unit_vector(v.x.raw, v.y.raw);
}

Vec2 normalize(Vec2 v) {
  if (v.x.raw == 0 && v.y.raw == 0) return {};
  return unit_vector(v.x.raw, v.y.raw);
}

Rot rot_from_angle(Q32 angle) {
  const SinCos<Q32> sc = sincos(angle);
  return {sc.cos, sc.sin};
}

Q32 rot_angle(Rot q) { return atan2(q.s, q.c); }

Q32 relative_angle(Rot q, Rot r) {
  const Rot d = inv_mul_rot(q, r);
  return atan2(d.s, d.c);
}

Rot rot_normalize(Rot q) {
  if (q.c.raw == 0 && q.s.raw == 0) return rot_identity();
  const Vec2 n = unit_vector(q.c.raw, q.s.raw);
  return {n.x, n.y};
}

Vec2 solve(Mat22 m, Vec2 b, bool* out_ok) {
  const U128 det = product_difference(m.cx.x.raw, m.cy.y.raw, m.cy.x.raw, m.cx.y.raw);
  if (det == U128{}) {
    if (out_ok) *out_ok = false;
    return {};
  }
  if (out_ok) *out_ok = true;
  const U128 nx = product_difference(m.cy.y.raw, b.x.raw, m.cy.x.raw, b.y.raw);
  const U128 ny = product_difference(m.cx.x.raw, b.y.raw, m.cx.y.raw, b.x.raw);
  return {quotient_q32(nx, det, "Mat22 solve"), quotient_q32(ny, det, "Mat22 solve")};
}

Mat22 inverse(Mat22 m, bool* out_ok) {
  const U128 det = product_difference(m.cx.x.raw, m.cy.y.raw, m.cy.x.raw, m.cx.y.raw);
  if (det == U128{}) {
    if (out_ok) *out_ok = false;
    return {};
  }
  if (out_ok) *out_ok = true;
  // Entry e/det as Q32.32 is e_raw·2^64 / det: the entry as Q64.64 is e_raw·2^32.
  const auto entry = [&](Q32 e, bool negate) {
    const U128 n = wide::shl(wide::from_s64(e.raw), 32);
    return quotient_q32(negate ? wide::neg(n) : n, det, "Mat22 inverse");
  };
  return {{entry(m.cy.y, false), entry(m.cx.y, true)}, {entry(m.cy.x, true), entry(m.cx.x, false)}};
}

}  // namespace tandem

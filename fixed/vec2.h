// vec2.h — Vec2, Rot, Transform, Mat22 and AABB over Q32.32.
//
// Range: a Q32.32 square overflows above about 46,341, so every dot product,
// cross product, squared length, rotation and matrix product here is formed
// exactly in 128 bits (a Q64.64 intermediate) and rounded ONCE at the end
// (nearest, ties away from zero, then saturated like every Q32.32 operation).
// Rounding each product first and adding after would give different bits
// (0.25 + 1.25 rounds to 2 once, to 1 twice) and would overflow on large
// inputs whose sum is small. Lengths are the correctly rounded square root of
// the exact 128-bit sum of squares, so they only saturate when the length
// itself leaves the Q32.32 range. normalize() is scale-free: the components
// are shifted up (exactly) before the root, so tiny vectors normalize as
// precisely as large ones.
//
// Rot is a cosine/sine pair kept close to unit length. Composing rotations
// drifts by a few raw units per operation; rot_normalize_fast() pulls the pair
// back with one Newton step on 1/√(c²+s²) (no square root, no division),
// which is what integrate_rotation() and the solver use each sub-step.
// rot_normalize() is the exact version.
//
// Mat22 solve() and inverse() divide exact 128-bit numerators by the exact
// 128-bit determinant (never by a determinant rounded to Q32.32, which would
// lose most of its digits for small matrices and call a 10⁻⁵ × 10⁻⁵ system
// singular). Only an exactly zero determinant is singular.
//
// Raw INT64_MIN never comes out of an operation (the range is symmetric);
// passed in through from_raw it gives defined but unspecified results here.
//
// Vec2Q16 is the compact Q16.16 vector for inputs, network messages and
// exported transforms; it converts to and from Vec2 with fixed.h's rules.
#pragma once

#include "fixed/fixed.h"
#include "fixed/fixed_math.h"

namespace tandem {

namespace detail {

/// (a·b + c·d) / 2^32 formed exactly and rounded once (nearest, ties away
/// from zero), saturated, with an overflow fault named `op`.
constexpr Q32 sum_products(int64_t a, int64_t b, int64_t c, int64_t d, const char* op) {
#if TANDEM_HAS_INT128
  __extension__ typedef __int128 s128;
  __extension__ typedef unsigned __int128 u128;
  // Each product ≤ 2^126 in magnitude; their sum is formed modulo 2^128 so
  // that the one out-of-range case (both products 2^126) cannot be UB.
  const u128 sum = static_cast<u128>(static_cast<s128>(a) * b) + static_cast<u128>(static_cast<s128>(c) * d);
  s128 p = static_cast<s128>(sum);
  p += (s128{1} << 31) - (p < 0 ? 1 : 0);
  const s128 q = p >> 32;
  if (q > INT64_MAX || q < -INT64_MAX) {
    TANDEM_FIXED_FAULT(FixedFault::overflow, op);
    return Q32::from_raw(q > 0 ? INT64_MAX : -INT64_MAX);
  }
  (void)op;
  return Q32::from_raw(static_cast<int64_t>(q));
#else
  bool overflow = false;
  const int64_t r = wide::round_shift_saturate(wide::add(wide::mul_s64(a, b), wide::mul_s64(c, d)), 32, &overflow);
  if (overflow) TANDEM_FIXED_FAULT(FixedFault::overflow, op);
  (void)op;
  return Q32::from_raw(r);
#endif
}

/// −r for a raw value through unsigned wrap-around: no UB even for the
/// integer minimum (which operations never produce).
constexpr int64_t neg_raw(int64_t r) { return static_cast<int64_t>(0u - static_cast<uint64_t>(r)); }

}  // namespace detail

// ---------------------------------------------------------------------------
// Vec2
// ---------------------------------------------------------------------------

/// A 2D vector in Q32.32 (metres, m/s, newtons... the caller's unit).
struct Vec2 {
  Q32 x;
  Q32 y;
  friend constexpr bool operator==(Vec2, Vec2) = default;

  constexpr Vec2& operator+=(Vec2 b) { x += b.x; y += b.y; return *this; }
  constexpr Vec2& operator-=(Vec2 b) { x -= b.x; y -= b.y; return *this; }
  constexpr Vec2& operator*=(Q32 s) { x *= s; y *= s; return *this; }
};

/// Builds a vector from two integers (exact).
constexpr Vec2 vec2(int64_t x, int64_t y) { return {Q32::from_int(x), Q32::from_int(y)}; }

/// Component-wise sum, saturating.
constexpr Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
/// Component-wise difference, saturating.
constexpr Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
/// Negation; exact.
constexpr Vec2 operator-(Vec2 a) { return {-a.x, -a.y}; }
/// Scale by s; each component rounded once.
constexpr Vec2 operator*(Q32 s, Vec2 v) { return {s * v.x, s * v.y}; }
/// Scale by s; each component rounded once.
constexpr Vec2 operator*(Vec2 v, Q32 s) { return {s * v.x, s * v.y}; }
/// Divide by s; each component rounded once; s == 0 follows Q32 division.
constexpr Vec2 operator/(Vec2 v, Q32 s) { return {v.x / s, v.y / s}; }

/// a·b, exact 128-bit sum rounded once.
constexpr Q32 dot(Vec2 a, Vec2 b) { return detail::sum_products(a.x.raw, b.x.raw, a.y.raw, b.y.raw, "Vec2 dot"); }
/// a×b (the z of the 3D cross product), exact 128-bit difference rounded once.
constexpr Q32 cross(Vec2 a, Vec2 b) {
  return detail::sum_products(a.x.raw, b.y.raw, detail::neg_raw(a.y.raw), b.x.raw, "Vec2 cross");
}
/// v × s = (s·v.y, −s·v.x): a vector crossed with a scalar out of the plane.
constexpr Vec2 cross(Vec2 v, Q32 s) { return {s * v.y, -(s * v.x)}; }
/// s × v = (−s·v.y, s·v.x): a scalar out of the plane crossed with a vector.
constexpr Vec2 cross(Q32 s, Vec2 v) { return {-(s * v.y), s * v.x}; }
/// The vector turned 90° counter-clockwise: (−y, x). Exact.
constexpr Vec2 left_perp(Vec2 v) { return {-v.y, v.x}; }
/// The vector turned 90° clockwise: (y, −x). Exact.
constexpr Vec2 right_perp(Vec2 v) { return {v.y, -v.x}; }
/// a + s·b, with the product rounded once.
constexpr Vec2 mul_add(Vec2 a, Q32 s, Vec2 b) { return {a.x + s * b.x, a.y + s * b.y}; }
/// a − s·b, with the product rounded once.
constexpr Vec2 mul_sub(Vec2 a, Q32 s, Vec2 b) { return {a.x - s * b.x, a.y - s * b.y}; }
/// Component-wise |v|.
constexpr Vec2 abs(Vec2 v) { return {abs(v.x), abs(v.y)}; }
/// Component-wise minimum.
constexpr Vec2 min(Vec2 a, Vec2 b) { return {min(a.x, b.x), min(a.y, b.y)}; }
/// Component-wise maximum.
constexpr Vec2 max(Vec2 a, Vec2 b) { return {max(a.x, b.x), max(a.y, b.y)}; }
/// a + t·(b − a); t = 0 gives a exactly.
constexpr Vec2 lerp(Vec2 a, Vec2 b, Q32 t) { return mul_add(a, t, b - a); }

/// |v|², exact 128-bit sum rounded once; saturates above the Q32.32 range
/// (|v| > ~46,341).
constexpr Q32 length_squared(Vec2 v) { return dot(v, v); }
/// |b − a|²; see length_squared.
constexpr Q32 distance_squared(Vec2 a, Vec2 b) { return length_squared(b - a); }

/// |v|: the correctly rounded (error ≤ 0.5 raw unit) square root of the
/// exact sum of squares. Saturates (overflow fault) only when |v| itself is
/// ≥ 2^31, e.g. both components near the range limit.
Q32 length(Vec2 v);
/// |b − a|; see length. (b − a itself saturates if it leaves the range.)
Q32 distance(Vec2 a, Vec2 b);
/// v / |v|, dimensionless. Each component is within 0.5 raw unit (plus
/// 2^-30) of the exact quotient, for any nonzero v of any size: the
/// components are scaled up exactly before the root is taken, so the result
/// is within 1 raw unit of unit length. Never saturates. The zero vector
/// gives the zero vector.
Vec2 normalize(Vec2 v);
/// As normalize, also writing length(v) to *out_length (if not null).
Vec2 length_and_normalize(Vec2 v, Q32* out_length);

// ---------------------------------------------------------------------------
// Rot
// ---------------------------------------------------------------------------

/// A rotation as a cosine/sine pair, dimensionless, kept near unit length.
/// The default is the identity.
struct Rot {
  Q32 c = Q32::one();
  Q32 s = Q32::zero();
  friend constexpr bool operator==(Rot, Rot) = default;
};

/// The identity rotation.
constexpr Rot rot_identity() { return {}; }
/// The rotation by `angle` radians (sin and cos within 2 raw units).
Rot rot_from_angle(Q32 angle);
/// The angle of q in radians, in [−π, π].
Q32 rot_angle(Rot q);
/// The inverse rotation (transpose): exact.
constexpr Rot rot_inverse(Rot q) { return {q.c, -q.s}; }
/// q·r: rotate by r, then by q. Each component rounded once.
constexpr Rot mul_rot(Rot q, Rot r) {
  return {detail::sum_products(q.c.raw, r.c.raw, detail::neg_raw(q.s.raw), r.s.raw, "Rot multiply"),
          detail::sum_products(q.s.raw, r.c.raw, q.c.raw, r.s.raw, "Rot multiply")};
}
/// qᵀ·r: the rotation from q to r. Each component rounded once.
constexpr Rot inv_mul_rot(Rot q, Rot r) {
  return {detail::sum_products(q.c.raw, r.c.raw, q.s.raw, r.s.raw, "Rot inverse multiply"),
          detail::sum_products(q.c.raw, r.s.raw, detail::neg_raw(q.s.raw), r.c.raw, "Rot inverse multiply")};
}
/// The angle from q to r in radians, in [−π, π].
Q32 relative_angle(Rot q, Rot r);
/// v rotated by q. Each component rounded once.
constexpr Vec2 rotate(Rot q, Vec2 v) {
  return {detail::sum_products(q.c.raw, v.x.raw, detail::neg_raw(q.s.raw), v.y.raw, "rotate"),
          detail::sum_products(q.s.raw, v.x.raw, q.c.raw, v.y.raw, "rotate")};
}
/// v rotated by the inverse of q. Each component rounded once.
constexpr Vec2 inv_rotate(Rot q, Vec2 v) {
  return {detail::sum_products(q.c.raw, v.x.raw, q.s.raw, v.y.raw, "inverse rotate"),
          detail::sum_products(detail::neg_raw(q.s.raw), v.x.raw, q.c.raw, v.y.raw, "inverse rotate")};
}
/// The x axis of q: (c, s).
constexpr Vec2 rot_x_axis(Rot q) { return {q.c, q.s}; }
/// The y axis of q: (−s, c).
constexpr Vec2 rot_y_axis(Rot q) { return {-q.s, q.c}; }

/// q scaled to unit length exactly (correctly rounded length, then one
/// rounded division per component). The zero pair gives the identity.
Rot rot_normalize(Rot q);

/// q pulled towards unit length by one Newton step for 1/√m from 1, where
/// m = c² + s² (exact, rounded once): k = (3 − m)/2 (rounded), result
/// (c·k, s·k). With m = 1 + ε the new squared length is exactly
/// 1 − ¾ε² + ¼ε³ before rounding, and the rounding adds less than 3·2^-32
/// (tests/fixed/test_vec2.cpp derives and asserts this), so |q| − 1 ≈ −⅜ε².
/// Meant for pairs already near unit length (|ε| ≪ 1); it diverges for
/// m ≥ 3. Four multiplies, no root, no divide; the direction is kept to
/// within a raw unit.
constexpr Rot rot_normalize_fast(Rot q) {
  const Q32 m = detail::sum_products(q.c.raw, q.c.raw, q.s.raw, q.s.raw, "Rot normalize");
  const Q32 k = (Q32::from_int(3) - m) / 2;
  return {q.c * k, q.s * k};
}

/// q advanced by a small angle δ (radians; the step's ω·h): the first-order
/// update (c − δ·s, s + δ·c), which turns q by atan(δ) = δ − δ³/3 + … and
/// scales it by √(1 + δ²), followed by two rot_normalize_fast steps. The
/// squared-length error left is about 0.42·δ⁸ (negligible below |δ| ≈ 0.05;
/// 9 raw units of |q| at 0.1) plus rounding, and it does not accumulate:
/// repeated calls keep |q| within 2 raw units of 1 for |δ| ≤ 0.05 (asserted
/// over 1M steps by the tests). Use rot_normalize for pairs far from unit
/// length.
constexpr Rot integrate_rotation(Rot q, Q32 delta_angle) {
  const Rot r{q.c - delta_angle * q.s, q.s + delta_angle * q.c};
  return rot_normalize_fast(rot_normalize_fast(r));
}

// ---------------------------------------------------------------------------
// Transform
// ---------------------------------------------------------------------------

/// A rigid transform: rotate by q, then translate by p (metres).
struct Transform {
  Vec2 p;
  Rot q;
  friend constexpr bool operator==(Transform, Transform) = default;
};

/// The identity transform.
constexpr Transform transform_identity() { return {}; }
/// t applied to the point v: q·v + p.
constexpr Vec2 transform_point(Transform t, Vec2 v) { return rotate(t.q, v) + t.p; }
/// The inverse of t applied to the point v: qᵀ·(v − p).
constexpr Vec2 inv_transform_point(Transform t, Vec2 v) { return inv_rotate(t.q, v - t.p); }
/// a·b: apply b, then a.
constexpr Transform mul_transforms(Transform a, Transform b) { return {rotate(a.q, b.p) + a.p, mul_rot(a.q, b.q)}; }
/// a⁻¹·b: b expressed in a's frame. b.p − a.p is formed first (saturating),
/// then rotated, so nearby frames far from the origin lose nothing.
constexpr Transform inv_mul_transforms(Transform a, Transform b) {
  return {inv_rotate(a.q, b.p - a.p), inv_mul_rot(a.q, b.q)};
}
/// t⁻¹: rotation qᵀ, translation −qᵀ·p. Each component rounded once; exact
/// for the rotation.
constexpr Transform transform_inverse(Transform t) {
  const Rot qi = rot_inverse(t.q);
  return {rotate(qi, -t.p), qi};
}

// ---------------------------------------------------------------------------
// Mat22
// ---------------------------------------------------------------------------

/// A 2×2 matrix stored by columns: [cx cy].
struct Mat22 {
  Vec2 cx;
  Vec2 cy;
  friend constexpr bool operator==(Mat22, Mat22) = default;
};

/// m·v. Each component rounded once.
constexpr Vec2 mul(Mat22 m, Vec2 v) {
  return {detail::sum_products(m.cx.x.raw, v.x.raw, m.cy.x.raw, v.y.raw, "Mat22 multiply"),
          detail::sum_products(m.cx.y.raw, v.x.raw, m.cy.y.raw, v.y.raw, "Mat22 multiply")};
}
/// The determinant, exact product difference rounded once.
constexpr Q32 determinant(Mat22 m) {
  return detail::sum_products(m.cx.x.raw, m.cy.y.raw, detail::neg_raw(m.cy.x.raw), m.cx.y.raw, "Mat22 determinant");
}

/// Solves m·x = b for x by Cramer's rule: the determinant and both
/// numerators are formed exactly in 128 bits and each component is ONE
/// rounded quotient of the two: correctly rounded when |det| < 1, within
/// 1.5 raw units of exact (0.5 + |x|·2^-63 + 2^-31) otherwise. A singular
/// matrix (determinant exactly 0 at 128-bit precision) gives the zero vector
/// and writes false to *out_ok (if given); else *out_ok is true. A solution
/// outside the Q32.32 range saturates (overflow fault, *out_ok still true).
Vec2 solve(Mat22 m, Vec2 b, bool* out_ok = nullptr);
/// The inverse of m: each entry is one rounded quotient of the exact entry by
/// the exact 128-bit determinant, with solve's accuracy. A singular matrix
/// gives the zero matrix and false in *out_ok (if given); entries outside the
/// range saturate (overflow fault).
Mat22 inverse(Mat22 m, bool* out_ok = nullptr);

// ---------------------------------------------------------------------------
// AABB
// ---------------------------------------------------------------------------

/// An axis-aligned box, lower ≤ upper on both axes (metres).
struct AABB {
  Vec2 lower;
  Vec2 upper;
  friend constexpr bool operator==(AABB, AABB) = default;
};

/// True when lower ≤ upper on both axes.
constexpr bool aabb_is_valid(AABB a) { return a.lower.x <= a.upper.x && a.lower.y <= a.upper.y; }
/// The smallest box holding both.
constexpr AABB aabb_union(AABB a, AABB b) { return {min(a.lower, b.lower), max(a.upper, b.upper)}; }
/// True when the boxes overlap or touch (closed intervals).
constexpr bool aabb_overlaps(AABB a, AABB b) {
  return !(b.lower.x > a.upper.x || b.lower.y > a.upper.y || a.lower.x > b.upper.x || a.lower.y > b.upper.y);
}
/// True when `inner` lies entirely inside `outer` (closed).
constexpr bool aabb_contains(AABB outer, AABB inner) {
  return outer.lower.x <= inner.lower.x && outer.lower.y <= inner.lower.y && inner.upper.x <= outer.upper.x &&
         inner.upper.y <= outer.upper.y;
}
/// True when the point lies inside or on the box.
constexpr bool aabb_contains_point(AABB a, Vec2 p) {
  return a.lower.x <= p.x && p.x <= a.upper.x && a.lower.y <= p.y && p.y <= a.upper.y;
}
/// The centre, rounded to nearest (ties away from zero); never overflows.
constexpr Vec2 aabb_center(AABB a) {
  // (lo + hi)/2 without an intermediate overflow: lo + (hi − lo)/2 would
  // overflow for a box spanning the whole range, so halve first.
  const auto half_sum = [](Q32 lo, Q32 hi) {
    const int64_t l = lo.raw, h = hi.raw;
    const int64_t s = (l >> 1) + (h >> 1);  // floor halves: arithmetic shift
    const int64_t r = (l & 1) + (h & 1);    // lost low bits, 0..2
    // exact (l + h)/2 = s + r/2; round half away from zero.
    if (r == 2) return Q32::from_raw(s + 1);
    if (r == 1) return Q32::from_raw(s >= 0 ? s + 1 : s);
    return Q32::from_raw(s);
  };
  return {half_sum(a.lower.x, a.upper.x), half_sum(a.lower.y, a.upper.y)};
}
namespace detail {
/// (hi − lo)/2 rounded to nearest, ties away from zero, formed in unsigned
/// 64 bits: the difference of two in-range values always fits there, so a
/// box spanning the whole range has extents ≈ 2^31 with no overflow.
constexpr Q32 half_difference(Q32 lo, Q32 hi) {
  const bool negative = hi.raw < lo.raw;  // an invalid (inverted) box
  const uint64_t d = negative ? static_cast<uint64_t>(lo.raw) - static_cast<uint64_t>(hi.raw)
                              : static_cast<uint64_t>(hi.raw) - static_cast<uint64_t>(lo.raw);
  uint64_t h = (d >> 1) + (d & 1u);
  if (h > static_cast<uint64_t>(INT64_MAX)) h = static_cast<uint64_t>(INT64_MAX);  // only via raw INT64_MIN
  const int64_t m = static_cast<int64_t>(h);
  return Q32::from_raw(negative ? -m : m);
}
}  // namespace detail

/// Half the size on each axis, (upper − lower)/2, rounded to nearest (ties
/// away from zero). Never overflows, even for a box spanning the full range.
constexpr Vec2 aabb_extents(AABB a) {
  return {detail::half_difference(a.lower.x, a.upper.x), detail::half_difference(a.lower.y, a.upper.y)};
}
/// The perimeter 2·(width + height), exact; saturates (overflow fault) when
/// a side or the sum leaves the range (boxes wider than about 2^30).
constexpr Q32 aabb_perimeter(AABB a) { return ((a.upper.x - a.lower.x) + (a.upper.y - a.lower.y)) * 2; }
/// The box grown by `margin` on every side (a negative margin shrinks it);
/// saturating at the range limits.
constexpr AABB aabb_fatten(AABB a, Q32 margin) {
  return {{a.lower.x - margin, a.lower.y - margin}, {a.upper.x + margin, a.upper.y + margin}};
}

// ---------------------------------------------------------------------------
// Q16.16 vectors for the compact formats
// ---------------------------------------------------------------------------

/// A 2D vector in Q16.16: inputs, network messages, exported transforms.
struct Vec2Q16 {
  Q16 x;
  Q16 y;
  friend constexpr bool operator==(Vec2Q16, Vec2Q16) = default;
};

/// Exact widening to Q32.32.
constexpr Vec2 to_vec2(Vec2Q16 v) { return {to_q32(v.x), to_q32(v.y)}; }
/// Narrowing to Q16.16: rounded to nearest, ties away from zero; saturates
/// (and reports) outside ±32768.
constexpr Vec2Q16 to_vec2_q16(Vec2 v) { return {to_q16(v.x), to_q16(v.y)}; }

}  // namespace tandem

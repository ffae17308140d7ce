// vec2.cpp — the parts of vec2.h that need a square root, a division or the
// trigonometric functions.
#include "fixed/vec2.h"

namespace tandem {
namespace {

/// x_raw² + y_raw² exactly, as an unsigned 128-bit integer (< 2^127).
wide::U128 sum_of_squares(Vec2 v) {
  const uint64_t ax = detail::magnitude(v.x.raw), ay = detail::magnitude(v.y.raw);
  return wide::add(wide::mul_u64(ax, ax), wide::mul_u64(ay, ay));
}

/// The exact 128-bit Q64.64 value a·b − c·d rounded once to Q32.32.
Q32 product_difference(Q32 a, Q32 b, Q32 c, Q32 d, const char* op) {
  return detail::sum_products(a.raw, b.raw, detail::neg_raw(c.raw), d.raw, op);
}

}  // namespace

Q32 length(Vec2 v) {
  const uint64_t r = isqrt_round(sum_of_squares(v));
  if (r > static_cast<uint64_t>(INT64_MAX)) {
    TANDEM_FIXED_FAULT(FixedFault::overflow, "Vec2 length");
    return Q32::max();
  }
  return Q32::from_raw(static_cast<int64_t>(r));
}

Q32 distance(Vec2 a, Vec2 b) { return length(b - a); }

Vec2 length_and_normalize(Vec2 v, Q32* out_length) {
  const Q32 len = length(v);
  *out_length = len;
  if (len.raw == 0) return {};
  return {v.x / len, v.y / len};
}

Vec2 normalize(Vec2 v) {
  Q32 len;
  return length_and_normalize(v, &len);
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
  Q32 len;
  const Vec2 n = length_and_normalize({q.c, q.s}, &len);
  if (len.raw == 0) return rot_identity();
  return {n.x, n.y};
}

// Cramer's rule. The determinant and numerators are exact in 128 bits and
// rounded once to Q32.32; each quotient is then one rounded Q32.32 division.
// A determinant that rounds to zero (|det| < 2^-33) is treated as singular.
Vec2 solve(Mat22 m, Vec2 b, bool* out_ok) {
  const Q32 det = determinant(m);
  if (det.raw == 0) {
    if (out_ok) *out_ok = false;
    return {};
  }
  if (out_ok) *out_ok = true;
  const Q32 nx = product_difference(m.cy.y, b.x, m.cy.x, b.y, "Mat22 solve");
  const Q32 ny = product_difference(m.cx.x, b.y, m.cx.y, b.x, "Mat22 solve");
  return {nx / det, ny / det};
}

Mat22 inverse(Mat22 m, bool* out_ok) {
  const Q32 det = determinant(m);
  if (det.raw == 0) {
    if (out_ok) *out_ok = false;
    return {};
  }
  if (out_ok) *out_ok = true;
  return {{m.cy.y / det, -m.cx.y / det}, {-m.cy.x / det, m.cx.x / det}};
}

}  // namespace tandem

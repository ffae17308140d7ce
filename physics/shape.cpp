// shape.cpp — mass properties, bounding boxes, point tests and ray casts of
// the single shapes in collision.h. Integer (Q32.32) arithmetic only.
//
// Design notes
// ------------
// Mass. Densities are kg/m² (2D). Rotational inertia is about the centre of
// mass. All three shapes use exact closed forms (no approximation):
//   * circle:  m = ρπr², I = m·r²/2.
//   * capsule: a 2r × L rectangle plus two half discs that together make a
//     full disc; each half disc's polar moment about the capsule centre is
//     πr⁴/4 + 2h·(2r³/3) + (πr²/2)·h² with h = L/2 (its first moment about its
//     flat side's centre is 2r³/3 along the axis), so the two give
//     πr⁴/2 + (8/3)·h·r³ + πr²h²; the rectangle gives 2rL·(L² + 4r²)/12.
//   * polygon with rounding radius r: EXACT, not Box2D's approximation (which
//     pushes the vertices out by √2·r). The rounded polygon is the core
//     polygon, plus one L×r rectangle on each edge, plus one circular sector
//     at each vertex spanning the angle θ between the two edge normals (the
//     sectors sum to one full disc). All moments are taken about the core's
//     centroid c0: the core by a triangle fan from c0 (each triangle's
//     D·(|e1|² + e1·e2 + |e2|²)/12 rounded once from an exact 128-bit product);
//     a sector's first moment about its apex is (r³/3)·(n2.y − n1.y,
//     n1.x − n2.x) and its polar moment θr⁴/4, moved to c0 by the parallel
//     axis theorem. Then c = c0 + M/A and I = J − |M|²/A. θ comes from atan2
//     (±2 raw units), the only transcendental step.
// Range: every intermediate is a saturating Q32.32 value. For density ρ and a
// shape of diameter s, the inertia is about ρ·s⁴/12 (a square) — it saturates
// (and reports a fault) when ρ·s⁴ approaches 2.5·10^10, e.g. a 200 m square
// at density 1 or a 20 m square at density 10,000. limits.h keeps bodies far
// inside that (k_max_rotational_inertia = 10^6 kg·m²).
//
// Ray casts avoid squaring coordinates and dividing by small numbers:
//   * circle: the closest approach c of the (unit-direction) ray to the centre
//     gives the half chord h = √((r − |c|)(r + |c|)) — no r² or |p|² — and the
//     entry distance tc − h. Every fraction is compared as `s ≤ max·L` before
//     the one division s/L, so a quotient never exceeds max_fraction.
//   * polygon (radius 0): slab clipping against each edge with the same
//     multiply-before-divide comparisons.
//   * capsule and rounded polygon: the shape is the union of convex pieces
//     (the offset edges' slabs and the discs around the centres/vertices); a
//     ray starting outside enters the union at the earliest of its entries
//     into the pieces' outer boundaries: the offset edges (one-sided) and the
//     discs. Exact, with no iteration (Box2D instead runs a shape cast).
//   * a ray starting inside or ON a solid shape does not hit it.
//   * segments: the intersection parameters t and s are formed as rounded
//     cross products over a common denominator and compared before dividing.
// Chain segments (one-sided): the outward normal is right_perp(point2 −
// point1), as in Box2D; the solid side is on the left. A one-sided ray cast
// hits only rays whose origin is on the right (cross(origin − p1, p2 − p1) ≥ 0).
#include "physics/collision.h"

namespace tandem {
namespace {

using wide::U128;

constexpr Q32 k_third = Q32::from_raw(1431655765);  // round(2^32/3)

/// a·b / k rounded once (nearest, ties away from zero) from the exact
/// 128-bit product; saturates (with a fault) outside the Q32.32 range.
Q32 product_over(Q32 a, Q32 b, uint32_t k) {
  const U128 p = wide::mul_s64(a.raw, b.raw);
  const bool negative = wide::is_negative(p);
  const uint64_t d = uint64_t{k} << 32;
  bool overflow = false;
  const U128 m = wide::abs_u(p);
  uint64_t q = static_cast<uint64_t>(INT64_MAX);
  if (m.hi >= d) {
    overflow = true;
  } else {
    q = detail::div_round_mag(m, d, static_cast<uint64_t>(INT64_MAX), &overflow);
  }
  if (overflow) TANDEM_FIXED_FAULT(FixedFault::overflow, "polygon mass");
  const int64_t r = static_cast<int64_t>(q);
  return Q32::from_raw(negative ? -r : r);
}

CastOutput no_hit() { return CastOutput{}; }

/// max_fraction limited to [0, 1].
Q32 clamp_fraction(Q32 f) { return clamp(f, Q32::zero(), Q32::one()); }

/// Entry of a ray into the disc (centre, r) — see the notes. Misses when the
/// origin is inside or on the disc.
CastOutput ray_disc(const RayCastInput& in, Vec2 center, Q32 r) {
  Q32 len;
  const Vec2 u = length_and_normalize(in.translation, &len);
  if (len.raw == 0) return no_hit();
  const Vec2 p = in.origin - center;
  const Q32 tc = -dot(p, u);            // distance along the ray to the closest approach
  const Vec2 closest = mul_add(p, tc, u);
  const Q32 cl = length(closest);
  if (cl > r) return no_hit();
  const Q32 h = sqrt((r - cl) * (r + cl));
  const Q32 s = tc - h;  // entry distance, m
  if (s <= Q32::zero() || s > clamp_fraction(in.max_fraction) * len) return no_hit();
  CastOutput out;
  out.fraction = s / len;
  out.point = mul_add(in.origin, s, u);
  out.normal = normalize(out.point - center);
  out.hit = true;
  return out;
}

/// A ray against the edge a→b seen from the side its unit normal n points
/// to: hits only rays starting on that side (or on the line) moving against n,
/// at a point whose projection lies within the edge.
CastOutput ray_outer_edge(const RayCastInput& in, Vec2 a, Vec2 b, Vec2 n) {
  const Q32 gap = dot(in.origin - a, n);  // m, ≥ 0 outside
  if (gap < Q32::zero()) return no_hit();
  const Q32 closing = -dot(in.translation, n);  // m per unit fraction
  if (closing <= Q32::zero()) return no_hit();
  if (gap > clamp_fraction(in.max_fraction) * closing) return no_hit();
  const Q32 t = gap / closing;
  const Vec2 q = mul_add(in.origin, t, in.translation);
  Q32 len;
  const Vec2 u = length_and_normalize(b - a, &len);
  const Q32 along = dot(q - a, u);
  if (along < Q32::zero() || along > len) return no_hit();
  CastOutput out;
  out.fraction = t;
  out.point = q;
  out.normal = n;
  out.hit = true;
  return out;
}

/// Keeps the earlier of two hits (the first on a tie).
void keep_first(CastOutput* best, const CastOutput& candidate) {
  if (candidate.hit && (!best->hit || candidate.fraction < best->fraction)) *best = candidate;
}

}  // namespace

// ---------------------------------------------------------------------------
// Mass
// ---------------------------------------------------------------------------

MassData compute_circle_mass(const Circle& circle, Q32 density) {
  const Q32 rr = circle.radius * circle.radius;
  MassData m;
  m.mass = density * (k_pi * rr);
  m.center = circle.center;
  m.rotational_inertia = m.mass * (rr / 2);
  return m;
}

MassData compute_capsule_mass(const Capsule& capsule, Q32 density) {
  const Q32 r = capsule.radius;
  const Q32 rr = r * r;
  const Q32 len = distance(capsule.center1, capsule.center2);
  const Q32 h = len / 2;
  const Q32 disc_area = k_pi * rr;
  const Q32 box_area = (r * len) * 2;
  // Polar moments about the capsule centre (m⁴); see the notes.
  const Q32 disc_j = disc_area * (rr / 2 + h * h) + (h * r) * rr * 8 * k_third;
  const Q32 box_j = product_over(box_area, len * len + rr * 4, 12);
  MassData m;
  m.mass = density * (disc_area + box_area);
  m.center = {(capsule.center1.x + capsule.center2.x) / 2, (capsule.center1.y + capsule.center2.y) / 2};
  m.rotational_inertia = density * (disc_j + box_j);
  return m;
}

MassData compute_polygon_mass(const Polygon& polygon, Q32 density) {
  const int32_t n = polygon.count;
  const Vec2 c0 = polygon.centroid;
  const auto vertex = [&](int32_t i) { return polygon.vertices[static_cast<size_t>(i)] - c0; };
  // Core polygon, triangle fan from c0.
  Q32 area2;             // 2·area, m²
  Vec2 first6;           // 6·first moment about c0, m³
  Q32 polar;             // polar moment about c0, m⁴
  for (int32_t i = 0; i < n; ++i) {
    const Vec2 e1 = vertex(i), e2 = vertex(i + 1 < n ? i + 1 : 0);
    const Q32 d = cross(e1, e2);
    area2 += d;
    first6 += d * (e1 + e2);
    const Q32 s = dot(e1, e1) + dot(e1, e2) + dot(e2, e2);
    polar += product_over(d, s, 12);
  }
  Q32 area = area2 / 2;
  Vec2 first{first6.x / 6, first6.y / 6};
  const Q32 r = polygon.radius;
  if (r > Q32::zero()) {
    const Q32 rr = r * r;
    const Q32 half_r = r / 2;
    for (int32_t i = 0; i < n; ++i) {
      const int32_t i2 = i + 1 < n ? i + 1 : 0;
      const int32_t i0 = i > 0 ? i - 1 : n - 1;
      const Vec2 v1 = vertex(i), v2 = vertex(i2);
      const Vec2 n1 = polygon.normals[static_cast<size_t>(i0)], n2 = polygon.normals[static_cast<size_t>(i)];
      // Edge rectangle i: L × r, outside edge i.
      const Q32 len = distance(v1, v2);
      const Q32 a = len * r;
      const Vec2 mid = mul_add({(v1.x + v2.x) / 2, (v1.y + v2.y) / 2}, half_r, n2);
      area += a;
      first += a * mid;
      polar += a * (product_over(len, len, 12) + product_over(r, r, 12) + dot(mid, mid));
      // Vertex sector i: between normals n1 (edge i−1) and n2 (edge i).
      const Q32 theta = atan2(cross(n1, n2), dot(n1, n2));
      const Q32 sector_area = theta * rr / 2;
      const Vec2 f = (r * rr * k_third) * Vec2{n2.y - n1.y, n1.x - n2.x};  // first moment about the apex
      area += sector_area;
      first += f + sector_area * v1;
      polar += theta * rr * rr / 4 + dot(v1, f) * 2 + sector_area * dot(v1, v1);
    }
  }
  MassData m;
  m.mass = density * area;
  Vec2 shift;
  if (area > Q32::zero()) shift = first / area;
  m.center = c0 + shift;
  m.rotational_inertia = density * (polar - dot(first, shift));
  return m;
}

// ---------------------------------------------------------------------------
// Bounds
// ---------------------------------------------------------------------------

AABB compute_circle_aabb(const Circle& circle, Transform xf) {
  const Vec2 p = transform_point(xf, circle.center);
  const Vec2 r{circle.radius, circle.radius};
  return {p - r, p + r};
}

AABB compute_capsule_aabb(const Capsule& capsule, Transform xf) {
  const Vec2 a = transform_point(xf, capsule.center1), b = transform_point(xf, capsule.center2);
  const Vec2 r{capsule.radius, capsule.radius};
  return {min(a, b) - r, max(a, b) + r};
}

AABB compute_polygon_aabb(const Polygon& polygon, Transform xf) {
  Vec2 lo = transform_point(xf, polygon.vertices[0]);
  Vec2 hi = lo;
  for (int32_t i = 1; i < polygon.count; ++i) {
    const Vec2 v = transform_point(xf, polygon.vertices[static_cast<size_t>(i)]);
    lo = min(lo, v);
    hi = max(hi, v);
  }
  const Vec2 r{polygon.radius, polygon.radius};
  return {lo - r, hi + r};
}

AABB compute_segment_aabb(const Segment& segment, Transform xf) {
  const Vec2 a = transform_point(xf, segment.point1), b = transform_point(xf, segment.point2);
  return {min(a, b), max(a, b)};
}

AABB compute_chain_segment_aabb(const ChainSegment& segment, Transform xf) {
  return compute_segment_aabb(segment.segment, xf);
}

// ---------------------------------------------------------------------------
// Point tests
// ---------------------------------------------------------------------------

bool point_in_circle(Vec2 point, const Circle& circle) {
  // Exact: |p − c|² ≤ r² on raw integers (differences < 2^63 for points
  // within the world range).
  const uint64_t dx = detail::magnitude(point.x.raw - circle.center.x.raw);
  const uint64_t dy = detail::magnitude(point.y.raw - circle.center.y.raw);
  const uint64_t r = detail::magnitude(circle.radius.raw);
  const U128 d2 = wide::add(wide::mul_u64(dx, dx), wide::mul_u64(dy, dy));
  return !wide::less_u(wide::mul_u64(r, r), d2);
}

bool point_in_capsule(Vec2 point, const Capsule& capsule) {
  Q32 len;
  const Vec2 u = length_and_normalize(capsule.center2 - capsule.center1, &len);
  const Q32 along = clamp(dot(point - capsule.center1, u), Q32::zero(), len);
  const Vec2 closest = mul_add(capsule.center1, along, u);
  return length(point - closest) <= capsule.radius;
}

bool point_in_polygon(Vec2 point, const Polygon& polygon) {
  if (polygon.radius.raw == 0) {
    for (int32_t i = 0; i < polygon.count; ++i) {
      const size_t k = static_cast<size_t>(i);
      if (dot(polygon.normals[k], point - polygon.vertices[k]) > Q32::zero()) return false;
    }
    return true;
  }
  DistanceInput in;
  in.proxy_a = make_proxy(polygon);
  in.proxy_b = make_proxy(&point, 1, Q32::zero());
  in.use_radii = false;
  return shape_distance(in).distance <= polygon.radius;
}

// ---------------------------------------------------------------------------
// Ray casts
// ---------------------------------------------------------------------------

CastOutput ray_cast_circle(const RayCastInput& input, const Circle& circle) {
  if (point_in_circle(input.origin, circle)) return no_hit();
  return ray_disc(input, circle.center, circle.radius);
}

CastOutput ray_cast_capsule(const RayCastInput& input, const Capsule& capsule) {
  if (point_in_capsule(input.origin, capsule)) return no_hit();
  const Vec2 u = normalize(capsule.center2 - capsule.center1);
  CastOutput best;
  for (const Vec2 n : {right_perp(u), left_perp(u)}) {
    const Vec2 off = capsule.radius * n;
    // The side's edge direction does not matter for ray_outer_edge.
    keep_first(&best, ray_outer_edge(input, capsule.center1 + off, capsule.center2 + off, n));
  }
  keep_first(&best, ray_disc(input, capsule.center1, capsule.radius));
  keep_first(&best, ray_disc(input, capsule.center2, capsule.radius));
  return best;
}

CastOutput ray_cast_polygon(const RayCastInput& input, const Polygon& polygon) {
  if (polygon.radius.raw == 0) {
    // Slab clipping: the ray is inside edge i's half plane while
    // numerator − t·denominator ≥ 0.
    Q32 lower = Q32::zero(), upper = clamp_fraction(input.max_fraction);
    int32_t index = -1;
    for (int32_t i = 0; i < polygon.count; ++i) {
      const size_t k = static_cast<size_t>(i);
      const Q32 num = dot(polygon.normals[k], polygon.vertices[k] - input.origin);
      const Q32 den = dot(polygon.normals[k], input.translation);
      if (den.raw == 0) {
        if (num < Q32::zero()) return no_hit();  // parallel and outside
      } else if (den < Q32::zero()) {
        // Entering: t ≥ num/den. Compare before dividing (den < 0 flips).
        if (num < upper * den) return no_hit();  // num/den > upper
        if (num < lower * den) {
          lower = num / den;
          index = i;
        }
      } else {
        // Leaving: t ≤ num/den.
        if (num < lower * den) return no_hit();  // num/den < lower
        if (num < upper * den) upper = num / den;
      }
    }
    if (index < 0) return no_hit();  // starts inside (or on) the polygon
    CastOutput out;
    out.fraction = lower;
    out.point = mul_add(input.origin, lower, input.translation);
    out.normal = polygon.normals[static_cast<size_t>(index)];
    out.hit = true;
    return out;
  }
  if (point_in_polygon(input.origin, polygon)) return no_hit();
  CastOutput best;
  for (int32_t i = 0; i < polygon.count; ++i) {
    const size_t k = static_cast<size_t>(i), k2 = static_cast<size_t>(i + 1 < polygon.count ? i + 1 : 0);
    const Vec2 off = polygon.radius * polygon.normals[k];
    keep_first(&best, ray_outer_edge(input, polygon.vertices[k] + off, polygon.vertices[k2] + off, polygon.normals[k]));
  }
  for (int32_t i = 0; i < polygon.count; ++i) {
    keep_first(&best, ray_disc(input, polygon.vertices[static_cast<size_t>(i)], polygon.radius));
  }
  return best;
}

CastOutput ray_cast_segment(const RayCastInput& input, const Segment& segment, bool one_sided) {
  const Vec2 e = segment.point2 - segment.point1;
  const Vec2 d = input.translation;
  const Vec2 w = segment.point1 - input.origin;
  if (one_sided && cross(input.origin - segment.point1, e) < Q32::zero()) return no_hit();
  // origin + t·d = point1 + s·e  ⇒  t = (w × e)/(d × e), s = (w × d)/(d × e).
  Q32 den = cross(d, e);
  Q32 tn = cross(w, e);
  Q32 sn = cross(w, d);
  if (den.raw == 0) return no_hit();  // parallel (or degenerate)
  if (den < Q32::zero()) {
    den = -den;
    tn = -tn;
    sn = -sn;
  }
  if (tn < Q32::zero() || tn > clamp_fraction(input.max_fraction) * den) return no_hit();
  if (sn < Q32::zero() || sn > den) return no_hit();
  CastOutput out;
  out.fraction = tn / den;
  out.point = mul_add(input.origin, out.fraction, d);
  Vec2 n = normalize(left_perp(e));
  if (dot(n, d) > Q32::zero()) n = -n;
  out.normal = n;
  out.hit = true;
  return out;
}

}  // namespace tandem

// hull.cpp — building convex polygons: compute_hull, make_polygon,
// make_polygon_from_points, make_box, make_offset_box, and the shape
// validators (validate_circle/capsule/segment/polygon), which share the range
// checks and the message formatting.
//
// Design notes
// ------------
// Determinism and order independence. compute_hull first sorts the points by
// (x, y). Two points that compare equal are bit-identical, so the sorted
// sequence depends only on the multiset of points, never on the input order.
// Welding then walks the sorted sequence and keeps a point unless it is closer
// than k_weld_tolerance to a point already kept (so a cluster is represented
// by its smallest point in (x, y) order). The hull is built by gift wrapping
// from the lowest-then-leftmost point with an EXACT orientation test (the
// 128-bit sign of a cross product of raw coordinate differences): no rounding
// can make two equivalent inputs take different branches. Of collinear
// candidates the farthest wins, so exactly collinear points never become
// vertices. Rejected: quickhull (recursion order is data-defined too, but the
// exact-orientation gift wrap is simpler to reason about for ≤ 64 points),
// Andrew's monotone chain (equally good; gift wrapping needs no second pass).
//
// Near-collinear points. A vertex closer than k_linear_slop to the line
// through its two neighbours is dropped (as Box2D does, with half its
// tolerance): such a vertex makes two nearly parallel edges that the contact
// solver cannot tell apart. The scan restarts after each removal from the
// canonical start, so the result is again a function of the point set. The
// smallest features that survive are therefore about linear-slop sized, the
// same as limits.h's k_min_shape_size.
//
// More than k_max_polygon_vertices points. compute_hull accepts up to
// k_max_hull_input_points points (interior and duplicate points are common in
// authored data) and fails only if the HULL has more than
// k_max_polygon_vertices vertices. It never picks "the 8 most extreme" points
// silently: that choice is ill-defined and would change the shape.
//
// Range. Every coordinate must lie within ±k_max_shape_size (10,000 m), so
// raw coordinate differences are below 2^47 and the exact orientation
// products below 2^95. Areas up to (2·10^4 m)² fit Q32.32.
//
// Centroid. Area-weighted triangle fan from vertex 0: the doubled triangle
// areas D are rounded once each to Q32.32, Σ D·(e1 + e2) is summed exactly in
// 128 bits and divided once by Σ D, then by 3 (≤ 1 raw unit in total).
#include <algorithm>
#include <string>

#include "fixed/str_cat.h"
#include "physics/collision.h"
#include "physics/limits.h"

namespace tandem {
namespace {

using wide::U128;

/// Largest accepted raw coordinate magnitude (k_max_shape_size).
constexpr int64_t k_max_coordinate_raw = k_max_shape_size.raw;

/// A value as short decimal text for messages: rounded to 9 decimals
/// (nearest, ties away from zero), trailing zeros dropped: "0.001", "-2.5".
std::string decimal(Q32 v) {
  constexpr uint64_t k_scale = 1000000000u;
  const uint64_t mag = detail::magnitude(v.raw);
  // round(mag · 10^9 / 2^32): the product is < 2^93.
  const U128 scaled = wide::add(wide::mul_u64(mag, k_scale), U128{uint64_t{1} << 31, 0});
  const uint64_t units = wide::shr_u(scaled, 32).lo;  // < 2^61
  const uint64_t frac = units % k_scale;
  std::string s = (v.raw < 0 && units != 0) ? "-" : "";
  s += std::to_string(units / k_scale);
  if (frac != 0) {
    std::string digits = std::to_string(frac);
    digits.insert(0, 9 - digits.size(), '0');
    while (digits.back() == '0') digits.pop_back();
    s += '.';
    s += digits;
  }
  return s;
}

std::string point_text(Vec2 p) { return str_cat("(", decimal(p.x), ", ", decimal(p.y), ")"); }

/// A failed status whose message is the pieces concatenated.
template <typename... Parts>
Status fail(const Parts&... parts) {
  return Status{StatusCode::invalid_argument, str_cat(parts...)};
}

/// True when |x| + margin and |y| + margin are within k_max_shape_size
/// (margin ≥ 0 and ≤ k_max_shape_size; the sums cannot overflow).
bool in_range(Vec2 p, Q32 margin) {
  const int64_t lim = k_max_coordinate_raw - margin.raw;
  return detail::magnitude(p.x.raw) <= static_cast<uint64_t>(lim) &&
         detail::magnitude(p.y.raw) <= static_cast<uint64_t>(lim);
}

/// The exact sign (−1, 0, +1) of (b − a) × (c − a). Coordinates must be in
/// range (raw differences < 2^48, so each product is < 2^96: exact).
int orientation(Vec2 a, Vec2 b, Vec2 c) {
  const int64_t bx = b.x.raw - a.x.raw, by = b.y.raw - a.y.raw;
  const int64_t cx = c.x.raw - a.x.raw, cy = c.y.raw - a.y.raw;
  const U128 p = wide::sub(wide::mul_s64(bx, cy), wide::mul_s64(by, cx));
  if (p == U128{}) return 0;
  return wide::is_negative(p) ? -1 : 1;
}

/// |b − a|² in raw units squared, exact (coordinates in range).
U128 exact_distance_squared(Vec2 a, Vec2 b) {
  const uint64_t dx = detail::magnitude(b.x.raw - a.x.raw), dy = detail::magnitude(b.y.raw - a.y.raw);
  return wide::add(wide::mul_u64(dx, dx), wide::mul_u64(dy, dy));
}

/// True when a comes before b in (y, x) order: lower, then further left.
bool lower_left(Vec2 a, Vec2 b) { return a.y < b.y || (a.y == b.y && a.x < b.x); }

/// Area-weighted centroid of a convex CCW polygon (count ≥ 3, in range).
Vec2 polygon_centroid(const Vec2* v, int32_t count) {
  const Vec2 origin = v[0];
  U128 sum_x{}, sum_y{};
  int64_t sum_d = 0;  // Σ D raw: 2·area ≤ 8·10^8 m² → < 2^62
  for (int32_t i = 1; i + 1 < count; ++i) {
    const Vec2 e1 = v[i] - origin, e2 = v[i + 1] - origin;
    const Q32 d = cross(e1, e2);
    sum_d += d.raw;
    const Vec2 s = e1 + e2;
    sum_x = wide::add(sum_x, wide::mul_s64(d.raw, s.x.raw));
    sum_y = wide::add(sum_y, wide::mul_s64(d.raw, s.y.raw));
  }
  // (Σ D·s) / Σ D is a weighted mean of the s (|s| < 4·10^4 m): it fits.
  const auto mean = [sum_d](U128 n) {
    bool overflow = false;
    const uint64_t q = detail::div_round_mag(wide::abs_u(n), static_cast<uint64_t>(sum_d),
                                             static_cast<uint64_t>(INT64_MAX), &overflow);
    const int64_t m = static_cast<int64_t>(q);
    return Q32::from_raw(wide::is_negative(n) ? -m : m);
  };
  if (sum_d <= 0) return origin;  // not reached for validated input
  return {origin.x + mean(sum_x) / 3, origin.y + mean(sum_y) / 3};
}

/// Twice the area of a CCW polygon, Σ of the fan's cross products (Q32.32,
/// each rounded once).
Q32 doubled_area(const Vec2* v, int32_t count) {
  Q32 a2;
  for (int32_t i = 1; i + 1 < count; ++i) a2 += cross(v[i] - v[0], v[i + 1] - v[0]);
  return a2;
}

/// Checks vertex count, range, strict convexity, counter-clockwise order and
/// area of a vertex list (the shared part of make_polygon and
/// validate_polygon).
Status check_convex_vertices(const Vec2* v, int32_t count, Q32 radius) {
  if (count < 3 || count > k_max_polygon_vertices) {
    return fail("polygon: ", std::to_string(count), " vertices, need 3 to ",
                std::to_string(k_max_polygon_vertices));
  }
  if (radius < Q32::zero() || radius > k_max_shape_size) {
    return fail("polygon: radius ", decimal(radius), " m is outside [0, ", decimal(k_max_shape_size), "] m");
  }
  for (int32_t i = 0; i < count; ++i) {
    if (!in_range(v[i], radius)) {
      return fail("polygon: vertex ", std::to_string(i), " ", point_text(v[i]), " m plus radius ",
                  decimal(radius), " m reaches beyond ±", decimal(k_max_shape_size), " m");
    }
  }
  for (int32_t i = 0; i < count; ++i) {
    const int32_t i2 = i + 1 < count ? i + 1 : 0;
    for (int32_t j = 0; j < count; ++j) {
      if (j == i || j == i2) continue;
      if (orientation(v[i], v[i2], v[j]) <= 0) {
        return fail("polygon: vertex ", std::to_string(j), " ", point_text(v[j]), " is not strictly left of edge ",
                    std::to_string(i), "→", std::to_string(i2),
                    " (vertices must be strictly convex and counter-clockwise)");
      }
    }
  }
  const Q32 area = doubled_area(v, count) / 2;
  if (area < k_min_polygon_area) {
    return fail("polygon: area ", decimal(area), " m² is below the minimum ", decimal(k_min_polygon_area), " m²");
  }
  return {};
}

/// Fills a polygon from checked vertices (normals, centroid).
Polygon build_polygon(const Vec2* v, int32_t count, Q32 radius) {
  Polygon p{};
  for (int32_t i = 0; i < count; ++i) {
    const int32_t i2 = i + 1 < count ? i + 1 : 0;
    p.vertices[static_cast<size_t>(i)] = v[i];
    p.normals[static_cast<size_t>(i)] = normalize(right_perp(v[i2] - v[i]));
  }
  p.count = count;
  p.radius = radius;
  p.centroid = polygon_centroid(v, count);
  return p;
}

Status check_size(const char* shape, const char* what, Q32 value) {
  if (value < k_min_shape_size || value > k_max_shape_size) {
    return fail(std::string(shape), ": ", what, " ", decimal(value), " m is outside [",
                decimal(k_min_shape_size), ", ", decimal(k_max_shape_size), "] m");
  }
  return {};
}

}  // namespace

Status compute_hull(const Vec2* points, int32_t count, Hull* out_hull) {
  *out_hull = Hull{};
  if (points == nullptr || count < 3) {
    return fail("polygon: ", std::to_string(points == nullptr ? 0 : count), " points given, need at least 3");
  }
  if (count > k_max_hull_input_points) {
    return fail("polygon: ", std::to_string(count), " points given, at most ",
                std::to_string(k_max_hull_input_points), " are accepted");
  }
  std::array<Vec2, k_max_hull_input_points> sorted{};
  for (int32_t i = 0; i < count; ++i) {
    if (!in_range(points[i], Q32::zero())) {
      return fail("polygon: point ", std::to_string(i), " ", point_text(points[i]), " m is beyond ±",
                  decimal(k_max_shape_size), " m");
    }
    sorted[static_cast<size_t>(i)] = points[i];
  }
  // Equal keys are bit-identical points, so the order among them is moot.
  std::sort(sorted.begin(), sorted.begin() + count,
            [](Vec2 a, Vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });

  // Weld in sorted order.
  const uint64_t tol = static_cast<uint64_t>(k_weld_tolerance.raw);
  const U128 tol_sq = wide::mul_u64(tol, tol);
  std::array<Vec2, k_max_hull_input_points> ps{};
  int32_t n = 0;
  for (int32_t i = 0; i < count; ++i) {
    const Vec2 p = sorted[static_cast<size_t>(i)];
    bool weld = false;
    for (int32_t j = 0; j < n && !weld; ++j) weld = wide::less_u(exact_distance_squared(ps[static_cast<size_t>(j)], p), tol_sq);
    if (!weld) ps[static_cast<size_t>(n++)] = p;
  }
  if (n < 3) {
    return fail("polygon: only ", std::to_string(n), " distinct points of ", std::to_string(count),
                " after welding points closer than ", decimal(k_weld_tolerance), " m, need at least 3");
  }

  // Gift wrapping from the lowest-then-leftmost point, exact orientation.
  int32_t start = 0;
  for (int32_t i = 1; i < n; ++i) {
    if (lower_left(ps[static_cast<size_t>(i)], ps[static_cast<size_t>(start)])) start = i;
  }
  std::array<Vec2, k_max_hull_input_points> hull{};
  int32_t h = 0;
  int32_t current = start;
  for (;;) {
    if (h == n) break;  // cannot happen with exact orientation; bounds the loop regardless
    hull[static_cast<size_t>(h++)] = ps[static_cast<size_t>(current)];
    int32_t next = current == 0 ? 1 : 0;
    const Vec2 c = ps[static_cast<size_t>(current)];
    for (int32_t i = 0; i < n; ++i) {
      if (i == current || i == next) continue;
      const int o = orientation(c, ps[static_cast<size_t>(next)], ps[static_cast<size_t>(i)]);
      if (o < 0 || (o == 0 && wide::less_u(exact_distance_squared(c, ps[static_cast<size_t>(next)]),
                                           exact_distance_squared(c, ps[static_cast<size_t>(i)])))) {
        next = i;
      }
    }
    current = next;
    if (current == start) break;
  }
  if (h < 3) return fail("polygon: all ", std::to_string(count), " points are collinear");

  // Drop vertices within linear slop of the line through their neighbours.
  bool removed = true;
  while (removed && h >= 3) {
    removed = false;
    for (int32_t i = 0; i < h; ++i) {
      const Vec2 s1 = hull[static_cast<size_t>(i)];
      const int32_t i2 = (i + 1) % h, i3 = (i + 2) % h;
      const Vec2 s2 = hull[static_cast<size_t>(i2)], s3 = hull[static_cast<size_t>(i3)];
      // distance = cross(s2 − s1, s3 − s1) / |s3 − s1| (positive: convex CCW)
      const Q32 area2 = cross(s2 - s1, s3 - s1);
      if (area2 <= k_linear_slop * distance(s1, s3)) {
        for (int32_t k = i2; k + 1 < h; ++k) hull[static_cast<size_t>(k)] = hull[static_cast<size_t>(k + 1)];
        --h;
        removed = true;
        break;
      }
    }
  }
  if (h < 3) {
    return fail("polygon: all ", std::to_string(count), " points lie within ", decimal(k_linear_slop),
                " m of a line");
  }
  if (h > k_max_polygon_vertices) {
    return fail("polygon: the hull of the ", std::to_string(count), " points has ", std::to_string(h),
                " vertices, at most ", std::to_string(k_max_polygon_vertices), " are allowed");
  }
  const Q32 area = doubled_area(hull.data(), h) / 2;
  if (area < k_min_polygon_area) {
    return fail("polygon: area ", decimal(area), " m² is below the minimum ", decimal(k_min_polygon_area), " m²");
  }
  // Start at the lowest-then-leftmost vertex (removals may have moved it).
  int32_t first = 0;
  for (int32_t i = 1; i < h; ++i) {
    if (lower_left(hull[static_cast<size_t>(i)], hull[static_cast<size_t>(first)])) first = i;
  }
  for (int32_t i = 0; i < h; ++i) {
    out_hull->points[static_cast<size_t>(i)] = hull[static_cast<size_t>((first + i) % h)];
  }
  out_hull->count = h;
  return {};
}

Status make_polygon(const Hull& hull, Q32 radius, Polygon* out_polygon) {
  *out_polygon = Polygon{};
  Status s = check_convex_vertices(hull.points.data(), hull.count, radius);
  if (!s.ok()) return s;
  *out_polygon = build_polygon(hull.points.data(), hull.count, radius);
  return s;
}

Status make_polygon_from_points(const Vec2* points, int32_t count, Q32 radius, Polygon* out_polygon) {
  *out_polygon = Polygon{};
  Hull hull;
  Status s = compute_hull(points, count, &hull);
  if (!s.ok()) return s;
  return make_polygon(hull, radius, out_polygon);
}

Status make_box(Q32 half_width, Q32 half_height, Polygon* out_polygon) {
  *out_polygon = Polygon{};
  Status s = check_size("box", "half width", half_width);
  if (s.ok()) s = check_size("box", "half height", half_height);
  if (!s.ok()) return s;
  Polygon& p = *out_polygon;
  p.count = 4;
  p.vertices[0] = {-half_width, -half_height};
  p.vertices[1] = {half_width, -half_height};
  p.vertices[2] = {half_width, half_height};
  p.vertices[3] = {-half_width, half_height};
  p.normals[0] = {Q32::zero(), -Q32::one()};
  p.normals[1] = {Q32::one(), Q32::zero()};
  p.normals[2] = {Q32::zero(), Q32::one()};
  p.normals[3] = {-Q32::one(), Q32::zero()};
  return s;
}

Status make_offset_box(Q32 half_width, Q32 half_height, Vec2 center, Q32 angle, Q32 radius,
                               Polygon* out_polygon) {
  *out_polygon = Polygon{};
  Status s = check_size("box", "half width", half_width);
  if (s.ok()) s = check_size("box", "half height", half_height);
  if (!s.ok()) return s;
  if (radius < Q32::zero() || radius > k_max_shape_size) {
    return fail("box: radius ", decimal(radius), " m is outside [0, ", decimal(k_max_shape_size), "] m");
  }
  // |centre| + hw + hh + radius bounds every coordinate of the rounded box.
  const Q32 reach = half_width + half_height + radius;
  if (reach > k_max_shape_size || !in_range(center, reach)) {
    return fail("box: centre ", point_text(center), " m with half extents ", decimal(half_width), " × ",
                decimal(half_height), " m and radius ", decimal(radius), " m reaches beyond ±",
                decimal(k_max_shape_size), " m");
  }
  const Rot q = rot_normalize(rot_from_angle(angle));
  Polygon& p = *out_polygon;
  p.count = 4;
  p.vertices[0] = center + rotate(q, {-half_width, -half_height});
  p.vertices[1] = center + rotate(q, {half_width, -half_height});
  p.vertices[2] = center + rotate(q, {half_width, half_height});
  p.vertices[3] = center + rotate(q, {-half_width, half_height});
  // The box's axes rotated: exact functions of q (rotate by ±x, ±y axes).
  p.normals[0] = {q.s, -q.c};
  p.normals[1] = {q.c, q.s};
  p.normals[2] = {-q.s, q.c};
  p.normals[3] = {-q.c, -q.s};
  p.centroid = center;
  p.radius = radius;
  return s;
}

Status validate_circle(const Circle& circle) {
  Status s = check_size("circle", "radius", circle.radius);
  if (!s.ok()) return s;
  if (!in_range(circle.center, circle.radius)) {
    return fail("circle: centre ", point_text(circle.center), " m plus radius ", decimal(circle.radius),
                " m reaches beyond ±", decimal(k_max_shape_size), " m");
  }
  return s;
}

Status validate_capsule(const Capsule& capsule) {
  Status s = check_size("capsule", "radius", capsule.radius);
  if (!s.ok()) return s;
  for (const Vec2 c : {capsule.center1, capsule.center2}) {
    if (!in_range(c, capsule.radius)) {
      return fail("capsule: centre ", point_text(c), " m plus radius ", decimal(capsule.radius),
                  " m reaches beyond ±", decimal(k_max_shape_size), " m");
    }
  }
  const Q32 d = distance(capsule.center1, capsule.center2);
  if (d < k_linear_slop) {
    return fail("capsule: centres ", decimal(d), " m apart, need at least ", decimal(k_linear_slop), " m");
  }
  return s;
}

Status validate_segment(const Segment& segment) {
  for (const Vec2 p : {segment.point1, segment.point2}) {
    if (!in_range(p, Q32::zero())) {
      return fail("segment: end point ", point_text(p), " m is beyond ±", decimal(k_max_shape_size), " m");
    }
  }
  const Q32 d = distance(segment.point1, segment.point2);
  if (d < k_linear_slop) {
    return fail("segment: end points ", decimal(d), " m apart, need at least ", decimal(k_linear_slop), " m");
  }
  return {};
}

Status validate_polygon(const Polygon& polygon) {
  Status s = check_convex_vertices(polygon.vertices.data(), polygon.count, polygon.radius);
  if (!s.ok()) return s;
  const Polygon expected = build_polygon(polygon.vertices.data(), polygon.count, polygon.radius);
  for (int32_t i = 0; i < polygon.count; ++i) {
    const Vec2 n = polygon.normals[static_cast<size_t>(i)], e = expected.normals[static_cast<size_t>(i)];
    if (abs(n.x - e.x) > k_polygon_normal_tolerance || abs(n.y - e.y) > k_polygon_normal_tolerance) {
      return fail("polygon: normal ", std::to_string(i), " ", point_text(n),
                  " is not the unit outward normal of edge ", std::to_string(i), " ", point_text(e));
    }
  }
  const Vec2 c = polygon.centroid, e = expected.centroid;
  if (abs(c.x - e.x) > k_polygon_centroid_tolerance || abs(c.y - e.y) > k_polygon_centroid_tolerance) {
    return fail("polygon: centroid ", point_text(c), " m is not the vertices' centroid ", point_text(e), " m");
  }
  return s;
}

}  // namespace tandem

// test_shape_bounds.cpp — compute_shape_aabb (physics/shape_api.cpp) gives
// the same bits on its short path for make_box's boxes as on the general
// loop over the corners: the same corners listed from another start do not
// match the box pattern and take the loop. Rotations, half extents,
// positions and radii include raw extremes, where the products round to
// saturation. A second test compares every shape kind's bounds with the
// checked operators of vec2.h (the circle and in-range short paths).
#include <catch2/catch.hpp>

#include <cstdint>
#include <vector>

#include "fixed/splitmix64.h"
#include "ignore_fixed_faults.h"
#include "physics/shape.h"

namespace {

using namespace tandem;

/// A small deterministic generator (splitmix64).
struct Random {
  uint64_t state;
  uint64_t next() { return splitmix64_next(&state); }
  /// A raw value: mostly in the engine's ranges, sometimes anywhere.
  int64_t raw(int64_t typical) {
    switch (next() % 8) {
      case 0: return static_cast<int64_t>(next());
      case 1: {
        const int64_t extremes[] = {INT64_MAX, INT64_MIN + 1, 0, 1, -1, int64_t{1} << 32, -(int64_t{1} << 32)};
        return extremes[next() % 7];
      }
      default: return static_cast<int64_t>(next() % (2 * static_cast<uint64_t>(typical) + 1)) - typical;
    }
  }
};

ShapeGeometry box_geometry(int64_t a, int64_t b, int64_t radius, int32_t start) {
  const Vec2 corners[4] = {{Q32::from_raw(-a), Q32::from_raw(-b)},
                           {Q32::from_raw(a), Q32::from_raw(-b)},
                           {Q32::from_raw(a), Q32::from_raw(b)},
                           {Q32::from_raw(-a), Q32::from_raw(b)}};
  ShapeGeometry g;
  g.type = ShapeType::polygon;
  g.polygon.count = 4;
  g.polygon.radius = Q32::from_raw(radius);
  for (int32_t i = 0; i < 4; ++i) g.polygon.vertices[static_cast<size_t>(i)] = corners[(i + start) % 4];
  return g;
}

}  // namespace

TEST_CASE("compute_shape_aabb: a box's short path gives the corner loop's bits", "[shape][aabb]") {
  const test_support::IgnoreFixedFaults ignore;
  Random rng{0xB0C5};
  const int64_t one = int64_t{1} << 32;
  for (int32_t k = 0; k < 200000; ++k) {
    const int64_t a = rng.raw(100 * one);
    const int64_t b = rng.raw(100 * one);
    if (a == INT64_MIN || b == INT64_MIN) continue;
    const int64_t radius = rng.raw(one);
    Transform xf;
    xf.p = {Q32::from_raw(rng.raw(2000000 * one)), Q32::from_raw(rng.raw(2000000 * one))};
    xf.q = {Q32::from_raw(rng.raw(one + 1)), Q32::from_raw(rng.raw(one + 1))};
    const AABB box = compute_shape_aabb(box_geometry(a, b, radius, 0), xf);
    const AABB loop = compute_shape_aabb(box_geometry(a, b, radius, 1 + k % 3), xf);
    INFO("a " << a << " b " << b << " r " << radius << " c " << xf.q.c.raw << " s " << xf.q.s.raw << " p "
              << xf.p.x.raw << ", " << xf.p.y.raw);
    REQUIRE(box.lower.x.raw == loop.lower.x.raw);
    REQUIRE(box.lower.y.raw == loop.lower.y.raw);
    REQUIRE(box.upper.x.raw == loop.upper.x.raw);
    REQUIRE(box.upper.y.raw == loop.upper.y.raw);
  }
}

namespace {

/// The reference: every point through vec2.h's checked transform_point, the
/// least and greatest taken, then ∓ r with the checked operators.
AABB checked_bounds(const std::vector<Vec2>& points, Q32 r, Transform xf) {
  Vec2 lo = transform_point(xf, points[0]);
  Vec2 hi = lo;
  for (size_t i = 1; i < points.size(); ++i) {
    const Vec2 v = transform_point(xf, points[i]);
    lo = {min(lo.x, v.x), min(lo.y, v.y)};
    hi = {max(hi.x, v.x), max(hi.y, v.y)};
  }
  const Vec2 rr{r, r};
  return {lo - rr, hi + rr};
}

}  // namespace

TEST_CASE("compute_shape_aabb gives the checked operators' bits for circles, capsules, segments, boxes",
          "[shape][aabb]") {
  // Covers the short paths of shape_api.cpp: a circle at its body's origin
  // (no rotation), one elsewhere, and the in-range tail (plain adds when
  // every operand is below 2^61) against the saturating adds out of range.
  const test_support::IgnoreFixedFaults ignore;
  Random rng{0xB0C6};
  const int64_t one = int64_t{1} << 32;
  for (int32_t k = 0; k < 100000; ++k) {
    Transform xf;
    xf.p = {Q32::from_raw(rng.raw(2000000 * one)), Q32::from_raw(rng.raw(2000000 * one))};
    xf.q = {Q32::from_raw(rng.raw(one + 1)), Q32::from_raw(rng.raw(one + 1))};
    const Q32 radius = Q32::from_raw(rng.raw(one));
    const Vec2 p1{Q32::from_raw(rng.raw(100 * one)), Q32::from_raw(rng.raw(100 * one))};
    const Vec2 p2{Q32::from_raw(rng.raw(100 * one)), Q32::from_raw(rng.raw(100 * one))};
    ShapeGeometry g;
    std::vector<Vec2> points;
    Q32 r = Q32::zero();
    switch (k % 4) {
      case 0:
        g.type = ShapeType::circle;
        g.circle = Circle{k % 8 == 0 ? Vec2{} : p1, radius};
        points = {g.circle.center};
        r = radius;
        break;
      case 1:
        g.type = ShapeType::capsule;
        g.capsule = Capsule{p1, p2, radius};
        points = {p1, p2};
        r = radius;
        break;
      case 2:
        g.type = ShapeType::segment;
        g.segment = Segment{p1, p2};
        points = {p1, p2};
        break;
      default: {
        const int64_t a = rng.raw(100 * one);
        const int64_t b = rng.raw(100 * one);
        if (a == INT64_MIN || b == INT64_MIN) continue;
        g = box_geometry(a, b, radius.raw, 0);
        points.assign(g.polygon.vertices.begin(), g.polygon.vertices.begin() + 4);
        r = radius;
        break;
      }
    }
    const AABB got = compute_shape_aabb(g, xf);
    const AABB want = checked_bounds(points, r, xf);
    INFO("kind " << k % 4 << " r " << r.raw << " c " << xf.q.c.raw << " s " << xf.q.s.raw << " p " << xf.p.x.raw
                 << ", " << xf.p.y.raw << " p1 " << p1.x.raw << ", " << p1.y.raw);
    REQUIRE(got.lower.x.raw == want.lower.x.raw);
    REQUIRE(got.lower.y.raw == want.lower.y.raw);
    REQUIRE(got.upper.x.raw == want.upper.x.raw);
    REQUIRE(got.upper.y.raw == want.upper.y.raw);
  }
}

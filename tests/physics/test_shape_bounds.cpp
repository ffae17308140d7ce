// test_shape_bounds.cpp — compute_shape_aabb (physics/shape_api.cpp) gives
// the same bits on its short path for make_box's boxes as on the general
// loop over the corners: the same corners listed from another start do not
// match the box pattern and take the loop. Rotations, half extents,
// positions and radii include raw extremes, where the products round to
// saturation.
#include <catch2/catch.hpp>

#include <cstdint>
#include <vector>

#include "fixed/fault.h"
#include "fixed/splitmix64.h"
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

/// Builds that report range faults (debug, sanitizers) take the loop for
/// every box; the saturating cases must not abort them.
struct IgnoreFaults {
  FixedFaultHandler old = set_fixed_fault_handler([](FixedFault, const char*) {});
  ~IgnoreFaults() { set_fixed_fault_handler(old); }
  IgnoreFaults() = default;
  IgnoreFaults(const IgnoreFaults&) = delete;
  IgnoreFaults& operator=(const IgnoreFaults&) = delete;
};

}  // namespace

TEST_CASE("compute_shape_aabb: a box's short path gives the corner loop's bits", "[shape][aabb]") {
  const IgnoreFaults ignore;
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

// Tests for physics/query.cpp: ray casts (closest and all hits, order,
// filters, rays starting inside), AABB, point and shape overlap, sensors,
// and stale world handles. The scene is built so every answer is known in
// closed form.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

#include "physics/tandem.h"

using namespace tandem;

namespace {

constexpr long double k_two32 = 4294967296.0L;
long double ld(Q32 v) { return static_cast<long double>(v.raw) / k_two32; }

/// Within `raw` raw units of `expected` (metres or dimensionless).
bool near(Q32 v, long double expected, long double raw = 64) {
  return std::fabs(ld(v) - expected) <= raw / k_two32;
}

ShapeId add_static(WorldId w, Vec2 position, const ShapeDef& sd, const Polygon* box, const Circle* circle) {
  BodyDef def = default_body_def();
  def.position = position;
  Result<BodyId> b = create_body(w, def);
  REQUIRE(b.ok());
  Result<ShapeId> s = box != nullptr ? create_polygon_shape(b.value, sd, *box) : create_circle_shape(b.value, sd, *circle);
  REQUIRE(s.ok());
  return s.value;
}

/// Box A (2 × 2 at the origin, layer 1), circle B (radius 1 at (5, 0), layer
/// 1), box C (2 × 2 at (10, 0), layer 2), sensor D (2 × 2 at (0, 5)).
struct Scene {
  WorldId world;
  ShapeId a, b, c, d;
  Scene() {
    Result<WorldId> r = create_world(default_world_def());
    REQUIRE(r.ok());
    world = r.value;
    Polygon box;
    REQUIRE(make_box(1_q32, 1_q32, &box).ok());
    const Circle circle{{}, 1_q32};
    ShapeDef sd = default_shape_def();
    a = add_static(world, {0_q32, 0_q32}, sd, &box, nullptr);
    b = add_static(world, {5_q32, 0_q32}, sd, nullptr, &circle);
    sd.filter.category_bits = 2;
    c = add_static(world, {10_q32, 0_q32}, sd, &box, nullptr);
    sd = default_shape_def();
    sd.is_sensor = true;
    d = add_static(world, {0_q32, 5_q32}, sd, &box, nullptr);
  }
  ~Scene() { (void)destroy_world(world); }
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;
};

}  // namespace

TEST_CASE("ray casts: closest hit and all hits in order", "[physics][query]") {
  Scene s;
  const Vec2 origin{-5_q32, 0_q32};
  const Vec2 translation{20_q32, 0_q32};
  const Result<RayHit> closest = world_cast_ray_closest(s.world, origin, translation);
  REQUIRE(closest.ok());
  REQUIRE(closest.value.hit);
  CHECK(closest.value.shape == s.a);
  CHECK(near(closest.value.fraction, 0.2L));  // x = −1 of 20 m from −5
  CHECK(near(closest.value.point.x, -1.0L));
  CHECK(near(closest.value.point.y, 0.0L));
  CHECK(near(closest.value.normal.x, -1.0L));
  CHECK(near(closest.value.normal.y, 0.0L));

  std::vector<RayHit> hits;
  REQUIRE(world_cast_ray_all(s.world, origin, translation, QueryFilter{}, &hits).ok());
  REQUIRE(hits.size() == 3);
  CHECK(hits[0].shape == s.a);
  CHECK(hits[1].shape == s.b);
  CHECK(hits[2].shape == s.c);
  CHECK(near(hits[1].fraction, 0.45L));  // circle surface at x = 4
  CHECK(near(hits[1].point.x, 4.0L));
  CHECK(near(hits[1].normal.x, -1.0L));
  CHECK(near(hits[2].fraction, 0.7L));  // box C at x = 9
  CHECK(near(hits[2].point.x, 9.0L));

  // Reversed: C first. A diagonal ray hits the circle at 45°.
  REQUIRE(world_cast_ray_all(s.world, {15_q32, 0_q32}, {-20_q32, 0_q32}, QueryFilter{}, &hits).ok());
  REQUIRE(hits.size() == 3);
  CHECK(hits[0].shape == s.c);
  CHECK(hits[1].shape == s.b);
  CHECK(hits[2].shape == s.a);
  CHECK(near(hits[2].normal.x, 1.0L));
  const Result<RayHit> diag = world_cast_ray_closest(s.world, {7_q32, 2_q32}, {-2_q32, -2_q32});
  REQUIRE(diag.value.hit);
  CHECK(diag.value.shape == s.b);
  const long double r = std::sqrt(0.5L);
  CHECK(near(diag.value.point.x, 5.0L + r, 4096));
  CHECK(near(diag.value.point.y, r, 4096));
  CHECK(near(diag.value.normal.x, r, 4096));
  CHECK(near(diag.value.fraction, (2.0L - r) / 2.0L, 4096));

  // Filters: a query that sees only layer 1 misses C; only layer 2 sees only C.
  QueryFilter layer1;
  layer1.mask_bits = 1;
  REQUIRE(world_cast_ray_all(s.world, origin, translation, layer1, &hits).ok());
  REQUIRE(hits.size() == 2);
  CHECK(hits[1].shape == s.b);
  QueryFilter layer2;
  layer2.mask_bits = 2;
  const Result<RayHit> only_c = world_cast_ray_closest(s.world, origin, translation, layer2);
  CHECK(only_c.value.shape == s.c);

  // A ray starting inside A does not hit A; a short ray misses everything.
  const Result<RayHit> inside = world_cast_ray_closest(s.world, {0_q32, 0_q32}, {10_q32, 0_q32});
  CHECK(inside.value.shape == s.b);
  CHECK(near(inside.value.fraction, 0.4L));
  const Result<RayHit> miss = world_cast_ray_closest(s.world, origin, {3_q32, 0_q32});
  REQUIRE(miss.ok());
  CHECK_FALSE(miss.value.hit);
  CHECK(is_null(miss.value.shape));

  // Sensors only when asked: a vertical ray through D.
  REQUIRE(world_cast_ray_all(s.world, {0_q32, 10_q32}, {0_q32, -20_q32}, QueryFilter{}, &hits).ok());
  REQUIRE(hits.size() == 1);
  CHECK(hits[0].shape == s.a);
  QueryFilter with_sensors;
  with_sensors.include_sensors = true;
  REQUIRE(world_cast_ray_all(s.world, {0_q32, 10_q32}, {0_q32, -20_q32}, with_sensors, &hits).ok());
  REQUIRE(hits.size() == 2);
  CHECK(hits[0].shape == s.d);
  CHECK(near(hits[0].fraction, 0.2L));  // top of D at y = 6
  CHECK(hits[1].shape == s.a);
  CHECK(near(hits[1].fraction, 0.45L));  // top of A at y = 1
}

TEST_CASE("equal-fraction ray hits are ordered by shape index", "[physics][query]") {
  Result<WorldId> r = create_world(default_world_def());
  REQUIRE(r.ok());
  Polygon box;
  REQUIRE(make_box(1_q32, 1_q32, &box).ok());
  // Two identical boxes at the same place: same fraction, index decides.
  const ShapeId first = add_static(r.value, {3_q32, 0_q32}, default_shape_def(), &box, nullptr);
  const ShapeId second = add_static(r.value, {3_q32, 0_q32}, default_shape_def(), &box, nullptr);
  std::vector<RayHit> hits;
  REQUIRE(world_cast_ray_all(r.value, {0_q32, 0_q32}, {10_q32, 0_q32}, QueryFilter{}, &hits).ok());
  REQUIRE(hits.size() == 2);
  CHECK(hits[0].fraction == hits[1].fraction);
  CHECK(hits[0].shape == first);
  CHECK(hits[1].shape == second);
  CHECK(world_cast_ray_closest(r.value, {0_q32, 0_q32}, {10_q32, 0_q32}).value.shape == first);
  REQUIRE(destroy_world(r.value).ok());
}

TEST_CASE("AABB, point and shape overlap queries", "[physics][query]") {
  Scene s;
  std::vector<ShapeId> out;
  // AABB: the circle's bounds are [4, 6] × [−1, 1].
  REQUIRE(world_overlap_aabb(s.world, {{3.5_q32, -0.5_q32}, {4.5_q32, 0.5_q32}}, QueryFilter{}, &out).ok());
  REQUIRE(out.size() == 1);
  CHECK(out[0] == s.b);
  REQUIRE(world_overlap_aabb(s.world, {{-2_q32, -2_q32}, {12_q32, 2_q32}}, QueryFilter{}, &out).ok());
  REQUIRE(out.size() == 3);
  CHECK(out[0] == s.a);
  CHECK(out[1] == s.b);
  CHECK(out[2] == s.c);
  QueryFilter layer1;
  layer1.mask_bits = 1;
  REQUIRE(world_overlap_aabb(s.world, {{-2_q32, -2_q32}, {12_q32, 2_q32}}, layer1, &out).ok());
  CHECK(out.size() == 2);
  QueryFilter with_sensors;
  with_sensors.include_sensors = true;
  REQUIRE(world_overlap_aabb(s.world, {{-2_q32, -2_q32}, {12_q32, 10_q32}}, with_sensors, &out).ok());
  REQUIRE(out.size() == 4);
  CHECK(out[3] == s.d);
  CHECK(world_overlap_aabb(s.world, {{1_q32, 1_q32}, {0_q32, 0_q32}}, QueryFilter{}, &out).code ==
        StatusCode::invalid_argument);

  // Points: inside A; inside the circle's box but outside the circle (distance
  // 1.204 from its centre); just inside the circle; on A's edge.
  REQUIRE(world_overlap_point(s.world, {0.5_q32, 0.5_q32}, QueryFilter{}, &out).ok());
  REQUIRE(out.size() == 1);
  CHECK(out[0] == s.a);
  REQUIRE(world_overlap_point(s.world, {4.2_q32, 0.9_q32}, QueryFilter{}, &out).ok());
  CHECK(out.empty());
  REQUIRE(world_overlap_point(s.world, {5_q32, 0.99_q32}, QueryFilter{}, &out).ok());
  REQUIRE(out.size() == 1);
  CHECK(out[0] == s.b);
  REQUIRE(world_overlap_point(s.world, {1_q32, 0_q32}, QueryFilter{}, &out).ok());
  CHECK(out.size() == 1);

  // Shapes: a circle of radius 0.5 at x = 1.4 overlaps A (gap −0.1); at 1.6
  // it does not (gap 0.1), though its bounds are near.
  REQUIRE(world_overlap_circle(s.world, Circle{{}, 0.5_q32}, {{1.4_q32, 0_q32}, rot_identity()}, QueryFilter{}, &out)
              .ok());
  REQUIRE(out.size() == 1);
  CHECK(out[0] == s.a);
  REQUIRE(world_overlap_circle(s.world, Circle{{}, 0.5_q32}, {{1.6_q32, 0_q32}, rot_identity()}, QueryFilter{}, &out)
              .ok());
  CHECK(out.empty());
  // A box of half-size 0.5 turned 45° at x = 3.5 reaches x = 4.207 and
  // overlaps the circle (surface at x = 4); at x = 3.2 it reaches 3.907 and
  // does not, though its bounds [2.49, 3.91] touch nothing either way but B's.
  Polygon small;
  REQUIRE(make_box(0.5_q32, 0.5_q32, &small).ok());
  const Rot turn = rot_from_angle(Q32::from_raw((k_pi.raw + 2) / 4));
  REQUIRE(world_overlap_polygon(s.world, small, {{3.5_q32, 0_q32}, turn}, QueryFilter{}, &out).ok());
  REQUIRE(out.size() == 1);
  CHECK(out[0] == s.b);
  REQUIRE(world_overlap_polygon(s.world, small, {{3.2_q32, 0_q32}, turn}, QueryFilter{}, &out).ok());
  CHECK(out.empty());
  // A capsule from x = −2 to 12 along y = 0 touches A, B and C; layer 1 only A, B.
  const Capsule long_capsule{{-7_q32, 0_q32}, {7_q32, 0_q32}, 0.1_q32};
  REQUIRE(world_overlap_capsule(s.world, long_capsule, {{5_q32, 0_q32}, rot_identity()}, QueryFilter{}, &out).ok());
  REQUIRE(out.size() == 3);
  CHECK(out[0] == s.a);
  CHECK(out[2] == s.c);
  REQUIRE(world_overlap_capsule(s.world, long_capsule, {{5_q32, 0_q32}, rot_identity()}, layer1, &out).ok());
  CHECK(out.size() == 2);
  CHECK(world_overlap_circle(s.world, Circle{{}, -1_q32}, transform_identity(), QueryFilter{}, &out).code ==
        StatusCode::invalid_argument);
}

TEST_CASE("queries on a stale world handle give an error Status", "[physics][query]") {
  Result<WorldId> r = create_world(default_world_def());
  REQUIRE(r.ok());
  const WorldId w = r.value;
  REQUIRE(destroy_world(w).ok());
  std::vector<ShapeId> out{ShapeId{}};
  std::vector<RayHit> hits{RayHit{}};
  const Result<RayHit> closest = world_cast_ray_closest(w, {}, {1_q32, 0_q32});
  CHECK(closest.status.code == StatusCode::invalid_handle);
  CHECK_FALSE(closest.value.hit);
  CHECK(world_cast_ray_all(w, {}, {1_q32, 0_q32}, QueryFilter{}, &hits).code == StatusCode::invalid_handle);
  CHECK(hits.empty());
  CHECK(world_overlap_aabb(w, {{0_q32, 0_q32}, {1_q32, 1_q32}}, QueryFilter{}, &out).code ==
        StatusCode::invalid_handle);
  CHECK(out.empty());
  CHECK(world_overlap_point(w, {}, QueryFilter{}, &out).code == StatusCode::invalid_handle);
  CHECK(world_overlap_circle(w, Circle{{}, 1_q32}, transform_identity(), QueryFilter{}, &out).code ==
        StatusCode::invalid_handle);
  CHECK(world_cast_ray_closest(WorldId{}, {}, {1_q32, 0_q32}).status.code == StatusCode::null_handle);
}

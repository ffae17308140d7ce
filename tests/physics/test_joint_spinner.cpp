// A small version of the bench's `spinner` (tools/bench/scenes.cpp, Box2D v3's
// spinner rebuilt): a ring of 360 two-sided segments (radius 40 m about
// (0, 32)) around a 0.8 × 40 m bar rounded by 0.2 m, driven by a revolute
// motor at 5 rad/s, with capsules, circles and squares on the bench's
// lattice (the bar starts upright through the lattice and sweeps the pile
// round). The test counts the bodies whose centre ends outside the ring
// (docs/benchmarks.md, spinner footnote) and asserts a ceiling on it.
// Doubles appear only as test oracles (never fed back into the world).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

#include "fixed/fixed_math.h"
#include "physics/tandem.h"
#include "physics_test_support.h"

using namespace tandem;
using namespace tandem::test_support;

namespace {

double d(Q32 v) { return static_cast<double>(ld(v)); }

struct SpinnerRun {
  int32_t outside = 0;  ///< bodies whose centre is more than 40 m from (0, 32)
  int32_t bodies = 0;
};

/// Builds the spinner with `count` small bodies, steps it `steps` times at
/// 60 Hz and counts the bodies outside the ring.
SpinnerRun run_spinner(int32_t count, int32_t steps) {
  Result<UniqueWorld> world = make_unique_world(default_world_def());
  REQUIRE(world.ok());
  const WorldId w = world.value.id;
  constexpr int32_t k_points = 360;
  const Q32 q40 = Q32::from_int(40), q32 = Q32::from_int(32);
  std::vector<Vec2> points;
  for (int32_t i = 0; i < k_points; ++i) {
    const auto sc = sincos(-k_two_pi * Q32::from_int(i) / Q32::from_int(k_points));
    points.push_back(Vec2{q40 * sc.cos, q40 * sc.sin + q32});
  }
  BodyDef rd = default_body_def();
  const Result<BodyId> ring = create_body(w, rd);
  REQUIRE(ring.ok());
  ShapeDef sd = default_shape_def();
  sd.friction = Q32::from_ratio(1, 10);
  for (int32_t i = 0; i < k_points; ++i) {
    const Segment seg{points[static_cast<size_t>(i)], points[static_cast<size_t>((i + 1) % k_points)]};
    REQUIRE(create_segment_shape(ring.value, sd, seg).ok());
  }
  BodyDef bd = default_body_def();
  bd.type = BodyType::dynamic_body;
  bd.position = {Q32{}, Q32::from_int(12)};
  const Result<BodyId> bar = create_body(w, bd);
  REQUIRE(bar.ok());
  Polygon bar_box;
  REQUIRE(make_offset_box(Q32::from_ratio(2, 5), Q32::from_int(20), Vec2{}, Q32{}, Q32::from_ratio(1, 5), &bar_box)
              .ok());
  ShapeDef bar_sd = default_shape_def();
  bar_sd.friction = Q32{};
  REQUIRE(create_polygon_shape(bar.value, bar_sd, bar_box).ok());
  RevoluteJointDef jd = default_revolute_joint_def();
  jd.base.body_a = ring.value;
  jd.base.body_b = bar.value;
  jd.base.local_anchor_a = Vec2{Q32{}, Q32::from_int(12)};
  jd.base.local_anchor_b = Vec2{};
  jd.enable_motor = true;
  jd.motor_speed = Q32::from_int(5);
  jd.max_motor_torque = Q32::from_int(100000000);
  REQUIRE(create_revolute_joint(w, jd).ok());

  std::vector<BodyId> bodies;
  Q32 x = Q32::from_int(-23), y = Q32::from_int(2);
  for (int32_t i = 0; i < count; ++i) {
    BodyDef def = default_body_def();
    def.type = BodyType::dynamic_body;
    def.position = {x, y};
    const Result<BodyId> b = create_body(w, def);
    REQUIRE(b.ok());
    ShapeDef s = default_shape_def();
    s.friction = Q32::from_ratio(1, 10);
    s.restitution = Q32::from_ratio(1, 10);
    s.density = Q32::from_ratio(1, 4);
    const Q32 r = Q32::from_ratio(1, 4);
    switch (i % 3) {
      case 0:
        REQUIRE(create_capsule_shape(b.value, s, Capsule{{-r, Q32{}}, {r, Q32{}}, r}).ok());
        break;
      case 1:
        REQUIRE(create_circle_shape(b.value, s, Circle{Vec2{}, Q32::from_ratio(7, 20)}).ok());
        break;
      default: {
        Polygon box;
        REQUIRE(make_box(Q32::from_ratio(7, 20), Q32::from_ratio(7, 20), &box).ok());
        REQUIRE(create_polygon_shape(b.value, s, box).ok());
        break;
      }
    }
    bodies.push_back(b.value);
    x += Q32::from_ratio(1, 2);
    if (x >= Q32::from_int(23)) {
      x = Q32::from_int(-23);
      y += Q32::from_ratio(1, 2);
    }
  }
  for (int32_t i = 0; i < steps; ++i) REQUIRE(world_step(w, k_dt).ok());
  SpinnerRun run;
  run.bodies = count;
  for (const BodyId b : bodies) {
    const Vec2 p = body_position(b);
    if (std::hypot(d(p.x), d(p.y) - 32.0) > 40.0) ++run.outside;
  }
  return run;
}

}  // namespace

// Known issue (docs/benchmarks.md, spinner): the bar sweeps the pile against
// the ring; a body pressed between the pile and the wall sinks into the soft
// static contact over several steps (about 0.27 m for a 0.35 m circle) until
// its centre crosses the two-sided segment, which then pushes it out. Not
// tunnelling: the bodies move below 25 m/s. With restitution 0 only 1 body
// escapes (the latched-bounce path of contact_solver.cpp carries no soft
// push; see the doc). With 2,000 bodies the first escapes come at steps
// 16-30, so 60 steps show them. The count is a ceiling: a fix must lower it
// (and update the figure here and in the doc).
TEST_CASE("joint: spinner-2000 loses at most 12 bodies through the ring in 60 steps", "[physics][joint][spinner]") {
  const SpinnerRun run = run_spinner(2000, 60);
  WARN("spinner-2000, 60 steps: " << run.outside << " of " << run.bodies << " bodies outside the ring");
  CHECK(run.outside <= 12);
}

// The README's physics example, compiled and checked, so the README cannot
// drift from the API. Keep the block between the markers identical to the
// README's "Physics" example.
#include <catch2/catch.hpp>

#include <cstdio>

#include "physics/tandem.h"

using namespace tandem;
using namespace tandem::literals;

namespace {
Q32 readme_example() {
  // --- README example begins ---
  auto check = [](const Status& s) { if (!s.ok()) std::printf("%s\n", s.message.c_str()); };  // [[nodiscard]]
  WorldDef world_def = default_world_def();          // gravity (0, -10), 4 sub-steps, ...
  WorldId world = create_world(world_def).value;

  BodyDef ground_def = default_body_def();           // static by default
  BodyId ground = create_body(world, ground_def).value;
  Polygon ground_box;
  check(make_offset_box(20_q32, 1_q32, Vec2{0_q32, -1_q32}, 0_q32, 0_q32, &ground_box));  // top face at y = 0
  check(create_polygon_shape(ground, default_shape_def(), ground_box).status);

  BodyDef ball_def = default_body_def();
  ball_def.type = BodyType::dynamic_body;
  ball_def.position = Vec2{0_q32, 10_q32};
  BodyId ball = create_body(world, ball_def).value;
  ShapeDef ball_shape = default_shape_def();
  ball_shape.restitution = 1_q32;                    // a perfectly elastic bounce
  ball_shape.friction = 0_q32;
  check(create_circle_shape(ball, ball_shape, Circle{Vec2{}, 0.5_q32}).status);

  const Q32 dt = Q32::from_ratio(1, 60);             // exact: the raw value nearest 1/60 s
  for (int tick = 0; tick < 600; ++tick) {
    StepResult r = world_step(world, dt);
    if (!r.ok()) std::printf("step %d: %s\n", tick, r.status.message.c_str());
  }
  Vec2 p = body_position(ball);                      // the same bits on every machine
  std::printf("ball at (%s, %s)\n", to_string(p.x).c_str(), to_string(p.y).c_str());

  Status bad = body_set_linear_velocity(ball, Vec2{5000_q32, 0_q32});
  // bad.message: "body_set_linear_velocity: ... is above the world's maximum linear speed ..."
  check(destroy_world(world));
  // --- README example ends ---
  CHECK_FALSE(bad.ok());
  CHECK(bad.message.find("body_set_linear_velocity") == 0);
  return p.y;
}
}  // namespace

TEST_CASE("README physics example runs and the ball keeps bouncing", "[physics][readme]") {
  const Q32 y = readme_example();
  // After 10 s an elastic ball dropped from 10 m is somewhere between the
  // ground (centre at 0.5 m) and its starting height.
  CHECK(y >= 0.45_q32);
  CHECK(y <= 10.1_q32);
  CHECK(readme_example() == y);  // and the same bits twice
}

namespace {
void readme_events_example() {
  WorldId world = create_world(default_world_def()).value;
  BodyId ground = create_body(world, default_body_def()).value;
  Polygon ground_box;
  REQUIRE(make_offset_box(20_q32, 1_q32, Vec2{0_q32, -1_q32}, 0_q32, 0_q32, &ground_box).ok());
  REQUIRE(create_polygon_shape(ground, default_shape_def(), ground_box).ok());
  BodyDef ball_def = default_body_def();
  ball_def.type = BodyType::dynamic_body;
  ball_def.position = Vec2{0_q32, 3_q32};
  BodyId ball = create_body(world, ball_def).value;
  ShapeDef ball_shape = default_shape_def();
  ball_shape.enable_hit_events = true;
  const ShapeId ball_shape_id = create_circle_shape(ball, ball_shape, Circle{Vec2{}, 0.5_q32}).value;
  int begins = 0, hits = 0, slept = 0;
  // --- README events example begins ---
  for (int tick = 0; tick < 240; ++tick) {
    world_step(world, Q32::from_ratio(1, 60));
    ContactEvents contacts = world_contact_events(world).value;    // valid until the next step
    for (const ContactBeginEvent& e : contacts.begin) { ++begins; (void)e.shape_a; }
    for (const ContactHitEvent& e : contacts.hit)                   // approach speed above 1 m/s
      std::printf("tick %d: hit at %s m/s\n", tick, to_string(e.approach_speed).substr(0, 6).c_str()), ++hits;
    for (const BodyMoveEvent& e : world_body_events(world).value.move)
      if (e.fell_asleep) ++slept;                                   // sleeping: 0.5 s below 0.05 m/s
  }
  RayHit hit = world_cast_ray_closest(world, Vec2{0_q32, 10_q32}, Vec2{0_q32, -20_q32}).value;
  // hit.shape is the ball's shape; hit.point, hit.normal, hit.fraction
  std::vector<ShapeId> found;
  Status query = world_overlap_aabb(world, AABB{{Q32(-1), Q32(-1)}, {1_q32, 1_q32}}, QueryFilter{}, &found);  // id order
  // --- README events example ends ---
  CHECK(begins == 1);
  CHECK(hits == 1);
  CHECK(slept == 1);
  CHECK(hit.hit);
  CHECK(hit.shape == ball_shape_id);
  CHECK(body_is_awake(ball) == false);
  CHECK(query.ok());
  CHECK(found.size() == 2);
  CHECK(destroy_world(world).ok());
}
}  // namespace

TEST_CASE("README events and queries example", "[physics][readme]") { readme_events_example(); }

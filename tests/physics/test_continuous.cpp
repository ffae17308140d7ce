// Tests for physics/continuous.cpp: fast bodies stop at thin static walls
// instead of tunnelling, bullets also stop at thin dynamic bodies, sensors
// and filters are honoured, and turning continuous collision off brings the
// tunnelling back (so each test can fail).
#include <catch2/catch.hpp>

#include <algorithm>
#include <thread>
#include <vector>

#include "physics/tandem.h"
#include "physics_test_support.h"

using namespace tandem;
using namespace tandem::test_support;

namespace {

/// A box body of half extents hw × hh at `center`.
BodyId add_box_body(WorldId w, BodyType type, Vec2 center, Q32 hw, Q32 hh, ShapeDef sd = default_shape_def()) {
  BodyDef def = default_body_def();
  def.type = type;
  def.position = center;
  const Result<BodyId> b = create_body(w, def);
  REQUIRE(b.ok());
  Polygon box;
  REQUIRE(make_box(hw, hh, &box).ok());
  REQUIRE(create_polygon_shape(b.value, sd, box).ok());
  return b.value;
}

/// A dynamic ball of radius r at `center` moving at `velocity`.
BodyId add_fast_ball(WorldId w, Vec2 center, Q32 radius, Vec2 velocity, bool bullet = false) {
  BodyDef def = default_body_def();
  def.type = BodyType::dynamic_body;
  def.position = center;
  def.linear_velocity = velocity;
  def.is_bullet = bullet;
  const Result<BodyId> b = create_body(w, def);
  REQUIRE(b.ok());
  REQUIRE(create_circle_shape(b.value, default_shape_def(), Circle{{}, radius}).ok());
  return b.value;
}

WorldDef zero_gravity_def(bool continuous) {
  WorldDef def = default_world_def();
  def.gravity = {};
  def.enable_continuous = continuous;
  return def;
}

/// Fires a 0.1 m ball at 290 m/s (4.83 m per step) at a 0.1 m thick wall 10 m
/// away and returns the ball's x after 30 steps.
long double shoot_at_wall(bool continuous, BodyType wall_type, bool bullet, bool wall_is_sensor = false) {
  ScopedWorld w(zero_gravity_def(continuous));
  ShapeDef wall_shape = default_shape_def();
  wall_shape.is_sensor = wall_is_sensor;
  wall_shape.density = 1000_q32;  // a heavy plate when dynamic
  add_box_body(w.id, wall_type, {10_q32, 0_q32}, 0.05_q32, 2_q32, wall_shape);
  const BodyId ball = add_fast_ball(w.id, {0_q32, 0_q32}, 0.1_q32, {290_q32, 0_q32}, bullet);
  for (int i = 0; i < 30; ++i) REQUIRE(world_step(w.id, k_dt).ok());
  return ld(body_position(ball).x);
}

/// A volley for the worker tests: 48 balls of 0.1 m at 280–327 m/s (every
/// third a bullet) towards a row of thin heavy dynamic plates at x = 6 and a
/// thin static wall at x = 10: 48 fast bodies in a step, so the sweeps run
/// in 12 blocks, and both passes (non-bullets, then bullets against the
/// plates' final poses) have work.
std::vector<BodyId> build_volley(WorldId w) {
  ShapeDef heavy = default_shape_def();
  heavy.density = 1000_q32;
  add_box_body(w, BodyType::static_body, {10_q32, 0_q32}, 0.05_q32, 20_q32);
  std::vector<BodyId> bodies;
  for (int k = 0; k < 12; ++k) {
    bodies.push_back(add_box_body(w, BodyType::dynamic_body, {6_q32, Q32::from_int(3 * k - 17)}, 0.05_q32, 1_q32,
                                  heavy));
  }
  for (int k = 0; k < 48; ++k) {
    const Vec2 at{Q32::from_ratio(k % 5, 10), Q32::from_ratio(3 * k, 4) - 18_q32};
    const Vec2 v{Q32::from_int(280 + k), Q32::from_ratio(k % 7 - 3, 2)};
    bodies.push_back(add_fast_ball(w, at, 0.1_q32, v, k % 3 == 0));
  }
  return bodies;
}

/// Every body's pose and velocity, raw, after each of `steps` steps.
std::vector<int64_t> run_volley(WorldDef def, int steps, CustomFilterFn filter = nullptr, void* filter_context = nullptr) {
  ScopedWorld w(def);
  const std::vector<BodyId> bodies = build_volley(w.id);
  if (filter != nullptr) REQUIRE(world_set_custom_filter(w.id, filter, filter_context).ok());
  std::vector<int64_t> trail;
  for (int i = 0; i < steps; ++i) {
    const StepResult r = world_step(w.id, k_dt);
    REQUIRE(r.ok());
    REQUIRE(r.flags == 0);
    for (BodyId b : bodies) {
      const Vec2 p = body_position(b), v = body_linear_velocity(b);
      const Rot q = body_rotation(b);
      trail.insert(trail.end(), {p.x.raw, p.y.raw, q.c.raw, q.s.raw, v.x.raw, v.y.raw, body_angular_velocity(b).raw});
    }
  }
  return trail;
}

/// A custom filter that accepts every pair and records whether it was ever
/// called from a thread other than `owner`.
struct ThreadCheckingFilter {
  std::thread::id owner;
  int64_t calls = 0;
  bool foreign_thread = false;
};

bool thread_checking_filter(ShapeId, ShapeId, void* context) {
  auto* f = static_cast<ThreadCheckingFilter*>(context);
  ++f->calls;
  if (std::this_thread::get_id() != f->owner) f->foreign_thread = true;
  return true;
}

}  // namespace

TEST_CASE("continuous collision gives one worker's bits for every worker count and task order",
          "[physics][continuous][workers]") {
  constexpr int k_steps = 8;
  const std::vector<int64_t> reference = run_volley(zero_gravity_def(true), k_steps);
  // The scene needs continuous collision: without it the trail differs.
  CHECK(run_volley(zero_gravity_def(false), k_steps) != reference);
  for (const int32_t workers : {2, 3, 16}) {
    WorldDef def = zero_gravity_def(true);
    def.worker_count = workers;
    INFO(workers << " workers");
    CHECK(run_volley(def, k_steps) == reference);
  }
  ReversingTasks tasks;
  WorldDef def = zero_gravity_def(true);
  def.worker_count = 4;
  def.enqueue_task = &reversing_enqueue;
  def.finish_task = &reversing_finish;
  def.user_task_context = &tasks;
  CHECK(run_volley(def, k_steps) == reference);
}

TEST_CASE("continuous collision calls a custom filter on the stepping thread only", "[physics][continuous][workers]") {
  constexpr int k_steps = 8;
  ThreadCheckingFilter one;
  one.owner = std::this_thread::get_id();
  const std::vector<int64_t> reference = run_volley(zero_gravity_def(true), k_steps, &thread_checking_filter, &one);
  ThreadCheckingFilter many;
  many.owner = std::this_thread::get_id();
  WorldDef def = zero_gravity_def(true);
  def.worker_count = 4;
  CHECK(run_volley(def, k_steps, &thread_checking_filter, &many) == reference);
  CHECK(many.calls == one.calls);
  CHECK(many.calls > 0);
  CHECK_FALSE(many.foreign_thread);
}

TEST_CASE("a fast ball stops at a thin static wall only with continuous collision", "[physics][continuous]") {
  const long double with = shoot_at_wall(true, BodyType::static_body, false);
  const long double without = shoot_at_wall(false, BodyType::static_body, false);
  INFO("with continuous: x = " << with << ", without: x = " << without);
  CHECK(with < 9.95L);      // stayed on the near side of the wall's face (x = 9.95)
  CHECK(without > 10.05L);  // tunnelled: the test scene does need continuous collision
}

TEST_CASE("a fast ball passes through a thin sensor wall", "[physics][continuous]") {
  CHECK(shoot_at_wall(true, BodyType::static_body, false, true) > 10.05L);
}

TEST_CASE("a bullet stops at a thin dynamic plate; an ordinary fast body does not", "[physics][continuous]") {
  const long double bullet = shoot_at_wall(true, BodyType::dynamic_body, true);
  const long double ordinary = shoot_at_wall(true, BodyType::dynamic_body, false);
  INFO("bullet x = " << bullet << ", ordinary x = " << ordinary);
  CHECK(bullet < 10.0L);
  CHECK(ordinary > 10.05L);
}

TEST_CASE("a fast ball respects collision filters in continuous collision", "[physics][continuous]") {
  ScopedWorld w(zero_gravity_def(true));
  ShapeDef wall_shape = default_shape_def();
  wall_shape.filter.category_bits = 2;
  wall_shape.filter.mask_bits = ~uint64_t{1};  // ignores the ball's layer 1
  add_box_body(w.id, BodyType::static_body, {10_q32, 0_q32}, 0.05_q32, 2_q32, wall_shape);
  const BodyId ball = add_fast_ball(w.id, {0_q32, 0_q32}, 0.1_q32, {290_q32, 0_q32});
  for (int i = 0; i < 30; ++i) REQUIRE(world_step(w.id, k_dt).ok());
  CHECK(ld(body_position(ball).x) > 10.05L);
}

TEST_CASE("a thin stick falling flat at 200 m/s does not pass through the ground", "[physics][continuous]") {
  WorldDef def = default_world_def();
  def.gravity = {0_q32, -10_q32};
  ScopedWorld w(def);
  add_box_body(w.id, BodyType::static_body, {0_q32, -0.05_q32}, 50_q32, 0.05_q32);  // 0.1 m thick floor
  BodyDef stick_def = default_body_def();
  stick_def.type = BodyType::dynamic_body;
  stick_def.position = {0_q32, 3_q32};
  stick_def.linear_velocity = {0_q32, -200_q32};
  const Result<BodyId> stick = create_body(w.id, stick_def);
  REQUIRE(stick.ok());
  Polygon box;
  REQUIRE(make_box(0.5_q32, 0.02_q32, &box).ok());
  REQUIRE(create_polygon_shape(stick.value, default_shape_def(), box).ok());
  long double lowest = 10;
  for (int i = 0; i < 120; ++i) {
    REQUIRE(world_step(w.id, k_dt).ok());
    lowest = std::min(lowest, ld(body_position(stick.value).y));
  }
  INFO("lowest centre y = " << lowest);
  CHECK(lowest > -0.05L);  // the centre never went below the floor's top face by more than its own half-height
  CHECK(ld(body_position(stick.value).y) > 0L);
}

TEST_CASE("continuous collision is switchable and deterministic", "[physics][continuous]") {
  const long double a = shoot_at_wall(true, BodyType::static_body, false);
  const long double b = shoot_at_wall(true, BodyType::static_body, false);
  CHECK(a == b);
  ScopedWorld w;
  CHECK(world_enable_continuous(w.id, false).ok());
  CHECK_FALSE(world_enable_continuous(WorldId{}, true).ok());
}

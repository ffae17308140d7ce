// Tests for physics/world.h and the world half of physics/tandem.h: world
// definitions and settings, handle validity (null, stale, foreign, destroyed
// world), the locked flag, the step (free fall against the exact sub-stepped
// symplectic Euler formula and the analytic law), determinism (two worlds
// side by side, id sequences), and zero heap allocations per warmed-up step.
//
// The allocation tests count operator new calls (tests/counting_allocator.h,
// included here once for the physics test binary) only around world_step().
#include <catch2/catch.hpp>

#include "../counting_allocator.h"  // this binary's counting operator new/delete

#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <random>
#include <string>
#include <vector>

#include "physics/tandem.h"
#include "physics_test_support.h"
#include "physics/world.h"

using namespace tandem;
using namespace tandem::test_support;


namespace {

BodyId make_dynamic(WorldId world, Vec2 position) {
  BodyDef def = default_body_def();
  def.type = BodyType::dynamic_body;
  def.position = position;
  Result<BodyId> r = create_body(world, def);
  REQUIRE(r.ok());
  return r.value;
}

ShapeId add_circle(BodyId body, Q32 radius, Vec2 center = {}) {
  Result<ShapeId> r = create_circle_shape(body, default_shape_def(), Circle{center, radius});
  REQUIRE(r.status.message == "");
  return r.value;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }


}  // namespace

// ---------------------------------------------------------------------------
// Definitions and settings
// ---------------------------------------------------------------------------

TEST_CASE("default world def has the documented values", "[physics][world]") {
  const WorldDef def = default_world_def();
  CHECK(def.gravity == Vec2{0_q32, -10_q32});
  CHECK(def.sub_step_count == 4);
  CHECK(def.contact_hertz == 30_q32);
  CHECK(def.contact_damping_ratio == 10_q32);
  CHECK(def.joint_hertz == 60_q32);
  CHECK(def.restitution_threshold == 1_q32);
  CHECK(def.max_linear_speed <= k_max_linear_speed);
  CHECK(def.max_linear_speed == 400_q32);
  CHECK(def.bounds.lower == Vec2{-k_max_world_coordinate, -k_max_world_coordinate});
  CHECK(def.bounds.upper == Vec2{k_max_world_coordinate, k_max_world_coordinate});
  CHECK(def.enable_sleep);
  CHECK(def.broad_phase == BroadPhaseKind::naive);
  CHECK(def.internal_cookie == k_def_cookie);
}

TEST_CASE("create_world refuses bad definitions with the field named", "[physics][world]") {
  WorldDef no_cookie{};
  Result<WorldId> r = create_world(no_cookie);
  CHECK(r.status.code == StatusCode::invalid_definition);
  CHECK(contains(r.status.message, "default_world_def"));
  CHECK(is_null(r.value));

  WorldDef def = default_world_def();
  def.sub_step_count = 0;
  r = create_world(def);
  CHECK(r.status.code == StatusCode::invalid_argument);
  CHECK(contains(r.status.message, "sub_step_count 0"));

  def = default_world_def();
  def.max_linear_speed = k_max_linear_speed + Q32::epsilon();
  r = create_world(def);
  CHECK(contains(r.status.message, "max_linear_speed"));

  def = default_world_def();
  def.bounds.upper.x = k_max_world_coordinate * 2;
  r = create_world(def);
  CHECK(contains(r.status.message, "bounds"));

  def = default_world_def();
  def.gravity.y = -k_max_gravity - 1_q32;
  r = create_world(def);
  CHECK(contains(r.status.message, "gravity.y"));
}

TEST_CASE("world setters validate and a refused call changes nothing", "[physics][world]") {
  ScopedWorld w;
  CHECK(world_set_gravity(w.id, Vec2{1_q32, -5_q32}).ok());
  CHECK(world_gravity(w.id) == Vec2{1_q32, -5_q32});
  CHECK(world_set_sub_step_count(w.id, 8).ok());
  CHECK(world_def(w.id).sub_step_count == 8);
  const Status s = world_set_sub_step_count(w.id, k_max_sub_steps + 1);
  CHECK(s.code == StatusCode::invalid_argument);
  CHECK(world_def(w.id).sub_step_count == 8);
  // Cross-field: the push speed may not exceed the maximum speed.
  CHECK_FALSE(world_set_contact_tuning(w.id, 30_q32, 10_q32, 500_q32).ok());
  CHECK(world_def(w.id).max_contact_push_speed == 3_q32);
  CHECK_FALSE(world_set_max_linear_speed(w.id, 0.5_q32).ok());  // below the restitution threshold (1 m/s)
  CHECK(world_set_max_linear_speed(w.id, 100_q32).ok());
  CHECK(world_def(w.id).max_linear_speed == 100_q32);
  CHECK(world_set_user_data(w.id, 0xfeedu).ok());
  CHECK(world_user_data(w.id) == 0xfeedu);
  // world_def() of a live world can create a copy.
  Result<WorldId> copy = create_world(world_def(w.id));
  REQUIRE(copy.ok());
  CHECK(world_def(copy.value).max_linear_speed == 100_q32);
  CHECK(destroy_world(copy.value).ok());
}

// ---------------------------------------------------------------------------
// Handles
// ---------------------------------------------------------------------------

TEST_CASE("world handles: null, destroyed, slot reuse gives a new generation", "[physics][world]") {
  CHECK(world_check(WorldId{}).code == StatusCode::null_handle);
  Result<WorldId> a = create_world(default_world_def());
  REQUIRE(a.ok());
  const WorldId first = a.value;
  CHECK(world_is_valid(first));
  CHECK(destroy_world(first).ok());
  CHECK_FALSE(world_is_valid(first));
  const Status gone = world_check(first);
  CHECK(gone.code == StatusCode::invalid_handle);
  CHECK(contains(gone.message, describe(first) + " was destroyed"));
  CHECK(destroy_world(first).code == StatusCode::invalid_handle);  // twice: an error, not a crash
  Result<WorldId> b = create_world(default_world_def());
  REQUIRE(b.ok());
  CHECK(b.value.index1 == first.index1);  // the lowest free slot again
  CHECK(b.value.generation != first.generation);
  CHECK_FALSE(world_is_valid(first));
  CHECK(destroy_world(b.value).ok());
  // A step or a body on a dead world is refused.
  CHECK(world_step(first, k_dt).status.code == StatusCode::invalid_handle);
  CHECK(create_body(first, default_body_def()).status.code == StatusCode::invalid_handle);
}

TEST_CASE("body handles: stale, reused, foreign, null, never created", "[physics][world]") {
  ScopedWorld w;
  ScopedWorld other;
  const BodyId a = make_dynamic(w.id, vec2(0, 0));
  const BodyId b = make_dynamic(w.id, vec2(1, 0));
  CHECK(a.index1 == 1u);
  CHECK(b.index1 == 2u);
  CHECK(a.generation == 1u);
  CHECK(a.world == w.id);

  // Null.
  const Status null_status = body_set_linear_velocity(BodyId{}, vec2(1, 0));
  CHECK(null_status.code == StatusCode::null_handle);
  CHECK(contains(null_status.message, "body_set_linear_velocity: the body handle is null"));

  // Stale after destroy; getters give defaults.
  REQUIRE(body_set_linear_velocity(a, vec2(3, 0)).ok());
  CHECK(destroy_body(a).ok());
  CHECK_FALSE(body_is_valid(a));
  const Status stale = body_set_linear_velocity(a, vec2(1, 0));
  CHECK(stale.code == StatusCode::invalid_handle);
  CHECK(stale.message == "body_set_linear_velocity: body {index 0, generation 1} was destroyed");
  CHECK(body_linear_velocity(a) == Vec2{});
  CHECK(body_position(b) == vec2(1, 0));
  CHECK(destroy_body(a).code == StatusCode::invalid_handle);

  // Reuse: the same slot with the next generation; the old handle stays dead.
  const BodyId c = make_dynamic(w.id, vec2(2, 0));
  CHECK(c.index1 == a.index1);
  CHECK(c.generation == a.generation + 1u);
  CHECK(body_is_valid(c));
  CHECK_FALSE(body_is_valid(a));
  CHECK(body_position(a) == Vec2{});
  CHECK(body_position(c) == vec2(2, 0));

  // Foreign: a body of w where `other` was expected.
  const Status foreign = body_check(b, other.id);
  CHECK(foreign.code == StatusCode::foreign_handle);
  CHECK(contains(foreign.message, describe(b) + " belongs to " + describe(w.id) + ", not " + describe(other.id)));
  CHECK(body_check(b, w.id).ok());
  CHECK(body_check(b).ok());

  // Never created: an index beyond the pool, a generation from the future.
  BodyId forged = b;
  forged.index1 = 99;
  CHECK(contains(body_check(forged).message, "was never created"));
  forged = b;
  forged.generation = 7;
  CHECK(contains(body_check(forged).message, "does not name a live body"));
  CHECK(body_mass(forged) == Q32::zero());
}

TEST_CASE("handles of a destroyed world fail clearly", "[physics][world]") {
  Result<WorldId> r = create_world(default_world_def());
  REQUIRE(r.ok());
  const BodyId body = make_dynamic(r.value, vec2(0, 0));
  const ShapeId shape = add_circle(body, 0.5_q32);
  REQUIRE(destroy_world(r.value).ok());
  // A new world in the same slot with its own body 0 does not revive them.
  ScopedWorld again;
  REQUIRE(again.id.index1 == r.value.index1);
  const BodyId fresh = make_dynamic(again.id, vec2(0, 0));
  CHECK(fresh.index1 == body.index1);
  CHECK(fresh.generation == body.generation);
  CHECK_FALSE(body_is_valid(body));
  const Status s = body_check(body);
  CHECK(s.code == StatusCode::invalid_handle);
  CHECK(contains(s.message, "which was destroyed or never existed"));
  CHECK_FALSE(shape_is_valid(shape));
  CHECK(shape_check(shape).code == StatusCode::invalid_handle);
}

TEST_CASE("shape handles: stale after destroy, foreign world", "[physics][world]") {
  ScopedWorld w;
  ScopedWorld other;
  const BodyId body = make_dynamic(w.id, vec2(0, 0));
  const ShapeId s1 = add_circle(body, 0.5_q32);
  const ShapeId s2 = add_circle(body, 0.25_q32, vec2(1, 0));
  CHECK(shape_body(s1) == body);
  CHECK(shape_check(s1, other.id).code == StatusCode::foreign_handle);
  CHECK(destroy_shape(s1).ok());
  CHECK(shape_check(s1).message == "shape_check: shape {index 0, generation 1} was destroyed");
  CHECK(shape_friction(s1) == Q32::zero());
  CHECK(shape_set_friction(s1, 0.1_q32).code == StatusCode::invalid_handle);
  CHECK(body_shape_count(body) == 1);
  const ShapeId s3 = add_circle(body, 0.5_q32);
  CHECK(s3.index1 == s1.index1);
  CHECK(s3.generation == 2u);
  // The body's list stays in ascending shape index although s3 came last.
  ShapeId listed[4];
  REQUIRE(body_shapes(body, listed, 4) == 2);
  CHECK(listed[0] == s3);
  CHECK(listed[1] == s2);
  // Destroying the body destroys its shapes.
  CHECK(destroy_body(body).ok());
  CHECK_FALSE(shape_is_valid(s2));
  CHECK_FALSE(shape_is_valid(s3));
  CHECK(world_counters(w.id).shape_count == 0);
}

TEST_CASE("a locked world refuses changes but answers getters", "[physics][world]") {
  ScopedWorld w;
  const BodyId body = make_dynamic(w.id, vec2(0, 5));
  World* world = find_world(w.id);
  REQUIRE(world != nullptr);
  world->locked = true;  // as inside world_step()
  CHECK(world_is_locked(w.id));
  const Result<BodyId> r = create_body(w.id, default_body_def());
  CHECK(r.status.code == StatusCode::world_locked);
  CHECK(contains(r.status.message, "locked"));
  CHECK(destroy_body(body).code == StatusCode::world_locked);
  CHECK(body_set_linear_velocity(body, vec2(1, 0)).code == StatusCode::world_locked);
  CHECK(create_circle_shape(body, default_shape_def(), Circle{{}, 0.5_q32}).status.code == StatusCode::world_locked);
  CHECK(world_step(w.id, k_dt).status.code == StatusCode::world_locked);
  CHECK(destroy_world(w.id).code == StatusCode::world_locked);
  CHECK(body_position(body) == vec2(0, 5));
  world->locked = false;
  CHECK(body_is_valid(body));
  CHECK(world_counters(w.id).body_count == 1);
}

// ---------------------------------------------------------------------------
// The step
// ---------------------------------------------------------------------------

TEST_CASE("world_step validates the time step", "[physics][world]") {
  ScopedWorld w;
  const BodyId body = make_dynamic(w.id, vec2(0, 0));
  CHECK(world_step(w.id, -k_dt).status.code == StatusCode::invalid_argument);
  CHECK(contains(world_step(w.id, 2_q32).status.message, "time_step 2 s is outside"));
  CHECK(contains(world_step(w.id, Q32::epsilon()).status.message, "too small"));
  CHECK(world_step(w.id, Q32::zero()).ok());
  CHECK(body_position(body) == vec2(0, 0));
  CHECK(world_counters(w.id).step_count == 0u);
}

TEST_CASE("free fall matches sub-stepped symplectic Euler exactly and v = g t", "[physics][world]") {
  ScopedWorld w;
  const Vec2 start{3_q32, 100_q32};
  const BodyId body = make_dynamic(w.id, start);
  add_circle(body, 0.5_q32);
  const int steps = 120;
  for (int k = 0; k < steps; ++k) REQUIRE(world_step(w.id, k_dt).ok());

  // The same arithmetic as solver.cpp, by hand: h = dt/4 (rounded),
  // Δv = h·(1·g), per sub-step v ← v·1 + Δv, y ← y + h·v.
  const Q32 h = k_dt / 4;
  const Q32 dv = h * (Q32::one() * -10_q32);
  Q32 v, y = start.y;
  for (int k = 0; k < steps * 4; ++k) {
    v = v * Q32::one() + dv;
    y = y + h * v;
  }
  CHECK(body_linear_velocity(body).y.raw == v.raw);
  CHECK(body_position(body).y.raw == y.raw);
  CHECK(body_position(body).x == start.x);
  CHECK(body_linear_velocity(body).x == Q32::zero());
  CHECK(body_rotation(body) == rot_identity());

  // Against the laws: v = g·t, and the discrete position
  // y0 + g·h²·K(K+1)/2 for K sub-steps (symplectic Euler), which differs from
  // y0 + ½gt² by ½·g·h·t.
  const long double t = steps / 60.0L;
  const long double hh = ld(h);
  const long double kk = steps * 4.0L;
  CHECK(std::fabs(ld(body_linear_velocity(body).y) - (-10.0L * t)) < 1e-6L);
  const long double discrete = 100.0L - 10.0L * hh * hh * kk * (kk + 1.0L) / 2.0L;
  CHECK(std::fabs(ld(body_position(body).y) - discrete) < 1e-6L);
  const long double analytic = 100.0L - 5.0L * t * t;
  CHECK(std::fabs(ld(body_position(body).y) - analytic) < 5.0L * hh * t + 1e-6L);
  CHECK(world_counters(w.id).step_count == static_cast<uint64_t>(steps));
  CHECK(world_counters(w.id).solver_body_count == 1);
}

TEST_CASE("shape bounds follow the body after a step", "[physics][world]") {
  ScopedWorld w;
  const BodyId body = make_dynamic(w.id, vec2(0, 10));
  REQUIRE(body_set_angular_velocity(body, 2_q32).ok());
  const ShapeId circle = add_circle(body, 0.5_q32, vec2(1, 0));
  Polygon box;
  REQUIRE(make_box(0.5_q32, 0.25_q32, &box).ok());
  const Result<ShapeId> boxed = create_polygon_shape(body, default_shape_def(), box);
  REQUIRE(boxed.ok());
  for (int k = 0; k < 5; ++k) REQUIRE(world_step(w.id, k_dt).ok());
  const Transform xf = body_transform(body);
  CHECK(shape_aabb(circle) == compute_circle_aabb(Circle{vec2(1, 0), 0.5_q32}, xf));
  CHECK(shape_aabb(boxed.value) == compute_polygon_aabb(box, xf));
}

TEST_CASE("a body that leaves the world bounds is disabled and flagged", "[physics][world]") {
  WorldDef def = default_world_def();
  def.bounds = {vec2(-10, -10), vec2(10, 10)};
  ScopedWorld w(def);
  const BodyId body = make_dynamic(w.id, vec2(0, -9));
  add_circle(body, 0.5_q32);
  uint32_t flags = 0;
  int steps = 0;
  while (body_is_enabled(body) && steps < 600) {
    const StepResult r = world_step(w.id, k_dt);
    REQUIRE(r.ok());
    flags |= r.flags;
    ++steps;
  }
  CHECK_FALSE(body_is_enabled(body));
  CHECK((flags & k_step_flag_body_left_bounds) != 0u);
  // Free fall from −9 m crosses −10 m after about √(2/10) s ≈ 27 steps.
  CHECK(steps >= 26);
  CHECK(steps <= 28);
  const Vec2 p = body_position(body);
  CHECK(world_step(w.id, k_dt).flags == 0u);  // disabled: not simulated any more
  CHECK(body_position(body) == p);
}

namespace {

/// A random scene of dynamic bodies with random shapes, velocities and
/// settings; identical for the same seed.
std::vector<BodyId> build_random_scene(WorldId world, uint64_t seed) {
  std::mt19937_64 rng(seed);
  const auto raw_in = [&](int64_t lo, int64_t hi) {  // a raw value in [lo, hi] (Q32 raw units)
    return Q32::from_raw(lo + static_cast<int64_t>(rng() % static_cast<uint64_t>(hi - lo + 1)));
  };
  const int64_t one = int64_t{1} << 32;
  std::vector<BodyId> bodies;
  for (int k = 0; k < 40; ++k) {
    BodyDef def = default_body_def();
    def.type = (k % 7 == 3) ? BodyType::kinematic_body : BodyType::dynamic_body;
    def.position = {raw_in(-100 * one, 100 * one), raw_in(-100 * one, 100 * one)};
    def.rotation = rot_from_angle(raw_in(-3 * one, 3 * one));
    def.linear_velocity = {raw_in(-20 * one, 20 * one), raw_in(-20 * one, 20 * one)};
    def.angular_velocity = raw_in(-5 * one, 5 * one);
    def.linear_damping = raw_in(0, one);
    def.angular_damping = raw_in(0, one / 2);
    def.gravity_scale = raw_in(-one, 2 * one);
    Result<BodyId> r = create_body(world, def);
    REQUIRE(r.ok());
    const ShapeDef sd = default_shape_def();
    switch (rng() % 3) {
      case 0: REQUIRE(create_circle_shape(r.value, sd, Circle{{raw_in(-one, one), 0_q32}, raw_in(one / 10, one)}).ok()); break;
      case 1: {
        Polygon box;
        REQUIRE(make_box(raw_in(one / 10, one), raw_in(one / 10, one), &box).ok());
        REQUIRE(create_polygon_shape(r.value, sd, box).ok());
        break;
      }
      default:
        REQUIRE(create_capsule_shape(r.value, sd, Capsule{vec2(-1, 0), vec2(1, 0), raw_in(one / 10, one / 2)}).ok());
        break;
    }
    bodies.push_back(r.value);
  }
  return bodies;
}

/// Applies the same random forces and impulses to the same bodies.
void push_randomly(const std::vector<BodyId>& bodies, std::mt19937_64* rng) {
  const int64_t one = int64_t{1} << 32;
  for (const BodyId b : bodies) {
    const uint64_t r = (*rng)();
    // Forces within ±2 N, impulses within ±0.2 N·s: the lightest body here
    // (a 0.1 m circle, 0.031 kg) stays far below the maximum speed.
    const Q32 fx = Q32::from_raw(static_cast<int64_t>(r % static_cast<uint64_t>(4 * one)) - 2 * one);
    const Q32 fy = Q32::from_raw(static_cast<int64_t>((r >> 7) % static_cast<uint64_t>(4 * one)) - 2 * one);
    REQUIRE(body_apply_force(b, {fx, fy}, body_world_point(b, vec2(0, 1)), true).ok());
    if ((r & 0xF) == 0) REQUIRE(body_apply_linear_impulse_to_center(b, {fy / 10, fx / 10}, true).ok());
    if ((r & 0xF) == 1) REQUIRE(body_apply_torque(b, fx, true).ok());
  }
}

}  // namespace

TEST_CASE("two worlds stepped side by side stay bit-identical", "[physics][world]") {
  ScopedWorld a;
  ScopedWorld b;
  const std::vector<BodyId> ba = build_random_scene(a.id, 0x7a4d'e400'0000'0001ull);
  const std::vector<BodyId> bb = build_random_scene(b.id, 0x7a4d'e400'0000'0001ull);
  std::mt19937_64 ra(99), rb(99);
  int mismatches = 0;
  for (int step = 0; step < 200; ++step) {
    push_randomly(ba, &ra);
    push_randomly(bb, &rb);
    REQUIRE(world_step(a.id, k_dt).ok());
    REQUIRE(world_step(b.id, k_dt).ok());
    for (size_t k = 0; k < ba.size(); ++k) {
      REQUIRE(ba[k].index1 == bb[k].index1);
      if (!(body_transform(ba[k]) == body_transform(bb[k])) ||
          !(body_linear_velocity(ba[k]) == body_linear_velocity(bb[k])) ||
          body_angular_velocity(ba[k]) != body_angular_velocity(bb[k])) {
        ++mismatches;
      }
    }
  }
  CHECK(mismatches == 0);
  // The scene really moved (so the comparison compared something).
  CHECK(body_position(ba[0]) != Vec2{});
}

TEST_CASE("create/destroy through the API gives the same ids in every run", "[physics][world]") {
  const auto run = [](uint64_t seed) {
    ScopedWorld w;
    std::mt19937_64 rng(seed);
    std::vector<BodyId> live;
    std::vector<BodyId> trace;
    for (int k = 0; k < 600; ++k) {
      const uint64_t r = rng();
      if ((r & 1u) == 0u && !live.empty()) {
        const size_t pick = static_cast<size_t>((r >> 1) % live.size());
        REQUIRE(destroy_body(live[pick]).ok());
        live.erase(live.begin() + static_cast<std::ptrdiff_t>(pick));
      } else {
        const BodyId b = make_dynamic(w.id, vec2(static_cast<int64_t>(r % 100), 0));
        add_circle(b, 0.5_q32);
        live.push_back(b);
        trace.push_back(b);
      }
      if (k % 50 == 0) REQUIRE(world_step(w.id, k_dt).ok());
    }
    std::vector<uint64_t> ids;
    for (const BodyId b : trace) ids.push_back((uint64_t{b.generation} << 32) | b.index1);
    // world_bodies lists live bodies in ascending index.
    std::vector<BodyId> listed(live.size());
    REQUIRE(world_bodies(w.id, listed.data(), static_cast<int32_t>(listed.size())) ==
            static_cast<int32_t>(live.size()));
    for (size_t k = 1; k < listed.size(); ++k) REQUIRE(listed[k - 1].index1 < listed[k].index1);
    return ids;
  };
  const std::vector<uint64_t> first = run(42);
  const std::vector<uint64_t> second = run(42);
  CHECK(first == second);
  CHECK(first.size() > 200u);
  // Some slot was reused with a later generation.
  bool reused = false;
  for (const uint64_t id : first) reused = reused || (id >> 32) > 1u;
  CHECK(reused);
}

TEST_CASE("world_step makes no heap allocation once warmed up", "[physics][world]") {
  TANDEM_REQUIRE_ALLOCATION_COUNTING();
  ScopedWorld w;
  const std::vector<BodyId> bodies = build_random_scene(w.id, 12345);
  std::mt19937_64 rng(7);
  push_randomly(bodies, &rng);

  g_allocation_count = 0;
  g_count_allocations = true;
  StepResult first = world_step(w.id, k_dt);
  g_count_allocations = false;
  REQUIRE(first.ok());
  const int64_t first_step = g_allocation_count.load();
  // The first step found an empty arena and borrowed from the heap (which
  // shows that the counter sees allocations made inside world_step).
  CHECK(first_step > 0);
  CHECK(world_counters(w.id).arena_capacity > 0);

  int64_t later = 0;
  for (int k = 0; k < 20; ++k) {
    push_randomly(bodies, &rng);  // outside the counted region
    g_allocation_count = 0;
    g_count_allocations = true;
    const StepResult r = world_step(w.id, k_dt);
    g_count_allocations = false;
    REQUIRE(r.ok());
    later += g_allocation_count.load();
  }
  CHECK(later == 0);
}

TEST_CASE("world_step makes no heap allocation once warmed up, with contacts", "[physics][world]") {
  TANDEM_REQUIRE_ALLOCATION_COUNTING();
  // A pile of boxes and circles falling onto the ground: contacts appear,
  // persist and vanish while the count is measured.
  ScopedWorld w;
  {
    BodyDef gd = default_body_def();
    gd.position = {0_q32, -1_q32};
    Result<BodyId> g = create_body(w.id, gd);
    REQUIRE(g.ok());
    Polygon ground;
    REQUIRE(make_box(30_q32, 1_q32, &ground).ok());
    REQUIRE(create_polygon_shape(g.value, default_shape_def(), ground).ok());
  }
  for (int k = 0; k < 30; ++k) {
    const BodyId b = make_dynamic(w.id, {Q32::from_int(k % 6) - 3_q32, Q32::from_int(1 + k / 3)});
    if (k % 2 == 0) {
      add_circle(b, 0.4_q32);
    } else {
      Polygon box;
      REQUIRE(make_box(0.4_q32, 0.3_q32, &box).ok());
      REQUIRE(create_polygon_shape(b, default_shape_def(), box).ok());
    }
  }
  for (int k = 0; k < 360; ++k) REQUIRE(world_step(w.id, k_dt).ok());  // warm-up: the pile forms (6 s: it still gains contacts at 3 s)
  int64_t later = 0;
  for (int k = 0; k < 120; ++k) {
    g_allocation_count = 0;
    g_count_allocations = true;
    const StepResult r = world_step(w.id, k_dt);
    g_count_allocations = false;
    REQUIRE(r.ok());
    later += g_allocation_count.load();
  }
  CHECK(find_world(w.id)->contacts.size() > 20u);
  CHECK(later == 0);
}

TEST_CASE("world_step makes no heap allocation when joints break", "[physics][world][joint]") {
  TANDEM_REQUIRE_ALLOCATION_COUNTING();
  // A row of balls hanging from a ceiling on breakable revolute joints: once
  // warmed up, a pull breaks them inside counted steps (joint events, the
  // freed slots and the collide-connected filter all use room made when the
  // joints were created).
  ScopedWorld w;
  BodyDef cd = default_body_def();
  cd.position = {0_q32, 10_q32};
  const BodyId ceiling = create_body(w.id, cd).value;
  std::vector<BodyId> balls;
  std::vector<JointId> joints;
  for (int k = 0; k < 8; ++k) {
    const BodyId b = make_dynamic(w.id, {Q32::from_int(k), 9_q32});
    add_circle(b, 0.25_q32);
    RevoluteJointDef rd = default_revolute_joint_def();
    rd.base.body_a = ceiling;
    rd.base.body_b = b;
    rd.base.local_anchor_a = body_local_point(ceiling, {Q32::from_int(k), 10_q32});
    rd.base.local_anchor_b = body_local_point(b, {Q32::from_int(k), 10_q32});
    rd.base.break_force = 200_q32;
    const Result<JointId> j = create_revolute_joint(w.id, rd);
    REQUIRE(j.ok());
    joints.push_back(j.value);
    balls.push_back(b);
  }
  for (int k = 0; k < 30; ++k) REQUIRE(world_step(w.id, k_dt).ok());
  REQUIRE(world_counters(w.id).joint_count == 8);
  int64_t allocations = 0;
  int events = 0;
  for (int k = 0; k < 8; ++k) {
    REQUIRE(body_apply_force_to_center(balls[static_cast<size_t>(k)], {0_q32, -100000_q32}, true).ok());
    g_allocation_count = 0;
    g_count_allocations = true;
    const StepResult r = world_step(w.id, k_dt);
    g_count_allocations = false;
    REQUIRE(r.ok());
    allocations += g_allocation_count.load();
    events += static_cast<int>(world_joint_events(w.id).value.size());
  }
  CHECK(world_counters(w.id).joint_count == 0);
  CHECK(events == 8);
  CHECK(allocations == 0);
}

namespace {
// A task system for the allocation test: runs each task at finish, in one
// call, on the stepping thread.
void* inline_enqueue(TaskFunction task, int32_t items, int32_t, void* task_context, void* user_context) {
  task(0, items, task_context);
  return user_context;
}
void inline_finish(void*, void*) {}
}  // namespace

TEST_CASE("world_step makes no heap allocation once warmed up, with workers or a task system", "[physics][world]") {
  TANDEM_REQUIRE_ALLOCATION_COUNTING();
  // The pool's threads start at create_world; the user path keeps its block
  // states in the arena. 120 boxes so that stages split into blocks.
  for (const bool task_system : {false, true}) {
    int dummy = 0;
    WorldDef def = default_world_def();
    def.worker_count = 2;
    if (task_system) {
      def.enqueue_task = &inline_enqueue;
      def.finish_task = &inline_finish;
      def.user_task_context = &dummy;
    }
    ScopedWorld w(def);
    BodyDef gd = default_body_def();
    gd.position = {0_q32, -1_q32};
    Result<BodyId> g = create_body(w.id, gd);
    REQUIRE(g.ok());
    Polygon box;
    REQUIRE(make_box(30_q32, 1_q32, &box).ok());
    REQUIRE(create_polygon_shape(g.value, default_shape_def(), box).ok());
    REQUIRE(make_box(0.4_q32, 0.3_q32, &box).ok());
    for (int k = 0; k < 120; ++k) {
      const BodyId b = make_dynamic(w.id, {Q32::from_int(k % 20) - 10_q32, Q32::from_int(1 + k / 10)});
      REQUIRE(create_polygon_shape(b, default_shape_def(), box).ok());
    }
    for (int k = 0; k < 240; ++k) REQUIRE(world_step(w.id, k_dt).ok());
    int64_t later = 0;
    for (int k = 0; k < 60; ++k) {
      g_allocation_count = 0;
      g_count_allocations = true;
      const StepResult r = world_step(w.id, k_dt);
      g_count_allocations = false;
      REQUIRE(r.ok());
      CHECK(r.flags == 0);
      later += g_allocation_count.load();
    }
    INFO((task_system ? "task system" : "built-in pool"));
    CHECK(later == 0);
  }
}

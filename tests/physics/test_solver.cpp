// Tests for physics/contact_solver.cpp through the public API: resting,
// stacking, bouncing, sliding, containment and determinism, each with a
// number asserted. Heavy scenes are scaled down when NDEBUG is not defined
// (Debug and sanitizer builds), keeping each physical assertion meaningful.
// Measured values are printed with WARN so the report can quote them.
#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "physics/tandem.h"
#include "physics_test_support.h"
#include "tests/readme_quote.h"

using namespace tandem;
using namespace tandem::test_support;

namespace {

ShapeDef material(Q32 friction, Q32 restitution) {
  ShapeDef sd = default_shape_def();
  sd.friction = friction;
  sd.restitution = restitution;
  return sd;
}

/// A static box (half extents hw × hh) centred at `center`, rotated by angle.
BodyId add_static_box(WorldId w, Vec2 center, Q32 hw, Q32 hh, Q32 angle = {}, ShapeDef sd = default_shape_def()) {
  BodyDef def = default_body_def();
  def.position = center;
  def.rotation = rot_from_angle(angle);
  Result<BodyId> b = create_body(w, def);
  REQUIRE(b.ok());
  Polygon box;
  REQUIRE(make_box(hw, hh, &box).ok());
  REQUIRE(create_polygon_shape(b.value, sd, box).ok());
  return b.value;
}

/// The ground: a static box whose top face is y = 0, 200 m wide.
BodyId add_ground(WorldId w, ShapeDef sd = default_shape_def()) {
  return add_static_box(w, {0_q32, -1_q32}, 100_q32, 1_q32, {}, sd);
}

BodyId add_dynamic_box(WorldId w, Vec2 center, Q32 hw, Q32 hh, ShapeDef sd = default_shape_def(), Q32 angle = {}) {
  BodyDef def = default_body_def();
  def.type = BodyType::dynamic_body;
  def.position = center;
  def.rotation = rot_from_angle(angle);
  Result<BodyId> b = create_body(w, def);
  REQUIRE(b.ok());
  Polygon box;
  REQUIRE(make_box(hw, hh, &box).ok());
  REQUIRE(create_polygon_shape(b.value, sd, box).ok());
  return b.value;
}

BodyId add_ball(WorldId w, Vec2 center, Q32 radius, ShapeDef sd = default_shape_def(), Vec2 velocity = {}) {
  BodyDef def = default_body_def();
  def.type = BodyType::dynamic_body;
  def.position = center;
  def.linear_velocity = velocity;
  Result<BodyId> b = create_body(w, def);
  REQUIRE(b.ok());
  REQUIRE(create_circle_shape(b.value, sd, Circle{{}, radius}).ok());
  return b.value;
}

long double distance_ld(Vec2 a, Vec2 b) {
  const long double dx = ld(a.x) - ld(b.x), dy = ld(a.y) - ld(b.y);
  return std::sqrt(dx * dx + dy * dy);
}

long double kinetic_energy(BodyId b) {
  const Vec2 v = body_linear_velocity(b);
  const long double w = ld(body_angular_velocity(b));
  return 0.5L * ld(body_mass(b)) * (ld(v.x) * ld(v.x) + ld(v.y) * ld(v.y)) +
         0.5L * ld(body_rotational_inertia(b)) * w * w;
}

#ifdef NDEBUG
constexpr int k_scale = 1;  // full length
#else
constexpr int k_scale = 4;  // Debug / sanitizers: shorter runs
#endif

}  // namespace

TEST_CASE("a box resting on the ground stays put", "[physics][solver]") {
  ScopedWorld w;
  add_ground(w.id);
  const BodyId box = add_dynamic_box(w.id, {0_q32, 0.5_q32}, 0.5_q32, 0.5_q32);
  const Vec2 start = body_position(box);
  long double worst = 0;
  for (int i = 0; i < 300; ++i) {
    REQUIRE(world_step(w.id, k_dt).ok());
    worst = std::max(worst, distance_ld(body_position(box), start));
  }
  WARN("box resting 5 s: largest displacement " << worst * 1000 << " mm");
  CHECK(worst < 0.001L);
  CHECK(std::fabs(ld(body_angle(box))) < 0.001L);
}

TEST_CASE("a ball with restitution 0 does not bounce", "[physics][solver]") {
  ScopedWorld w;
  add_ground(w.id);
  const BodyId ball = add_ball(w.id, {0_q32, 3_q32}, 0.5_q32, material(0.6_q32, 0_q32));
  bool contacted = false;
  long double max_height = 0;  // of the bottom above the ground after first contact
  for (int i = 0; i < 240; ++i) {
    REQUIRE(world_step(w.id, k_dt).ok());
    const long double bottom = ld(body_position(ball).y) - 0.5L;
    if (!contacted && bottom < 0.01L) contacted = true;
    if (contacted) max_height = std::max(max_height, bottom);
  }
  WARN("restitution 0: highest bottom after first contact " << max_height * 1000 << " mm");
  CHECK(contacted);
  CHECK(max_height < 0.01L);
  CHECK(std::fabs(ld(body_position(ball).y) - 0.5L) < 0.01L);
}

TEST_CASE("a ball with restitution 1 keeps its energy for 5 minutes", "[physics][solver]") {
  // The report's accuracy test: r = 0.5 m, bottom dropped from 10 m, e = 1,
  // friction 0, static ground, 60 Hz, 18000 steps.
  ScopedWorld w;
  add_ground(w.id, material(0_q32, 1_q32));
  const BodyId ball = add_ball(w.id, {0_q32, 10.5_q32}, 0.5_q32, material(0_q32, 1_q32));
  const long double m = ld(body_mass(ball)), g = 10.0L;
  const auto energy = [&] { return m * g * (ld(body_position(ball).y) - 0.5L) + kinetic_energy(ball); };
  const long double e0 = energy();
  long double lo = 1, hi = 1;
  int bounces = 0;
  long double previous_vy = 0;
  for (int i = 0; i < 18000; ++i) {
    REQUIRE(world_step(w.id, k_dt).ok());
    const long double r = energy() / e0;
    lo = std::min(lo, r);
    hi = std::max(hi, r);
    const long double vy = ld(body_linear_velocity(ball).y);
    if (previous_vy < 0 && vy > 0) ++bounces;
    previous_vy = vy;
  }
  const long double end = energy() / e0;
  WARN("dropped ball, 18000 steps: E_end/E0 = " << end << ", range [" << lo << ", " << hi << "], bounces "
                                               << bounces);
  CHECK(std::fabs(end - 1) < 0.01L);
  CHECK(lo > 0.98L);
  CHECK(hi < 1.02L);
  CHECK(bounces > 100);
  // The README quotes the end ratio to 4 decimals and the range to 3.
  readme::check_quotes("ends at " + readme::fixed(end, 4) + " of its starting energy (range " + readme::fixed(lo, 3) +
                       "–" + readme::fixed(hi, 3) + ")");
}

TEST_CASE("head-on elastic collision of equal circles", "[physics][solver]") {
  WorldDef def = default_world_def();
  def.gravity = {};
  ScopedWorld w(def);
  const ShapeDef sd = material(0_q32, 1_q32);
  const BodyId a = add_ball(w.id, {-2_q32, 0_q32}, 0.5_q32, sd, {5_q32, 0_q32});
  const BodyId b = add_ball(w.id, {2_q32, 0_q32}, 0.5_q32, sd, {-5_q32, 0_q32});
  const long double ke0 = kinetic_energy(a) + kinetic_energy(b);
  int64_t momentum = body_linear_velocity(a).x.raw + body_linear_velocity(b).x.raw;  // equal masses: Σv
  int64_t worst_step = 0, worst_y = 0;
  for (int i = 0; i < 60; ++i) {
    REQUIRE(world_step(w.id, k_dt).ok());
    const int64_t now = body_linear_velocity(a).x.raw + body_linear_velocity(b).x.raw;
    worst_step = std::max<int64_t>(worst_step, now > momentum ? now - momentum : momentum - now);
    momentum = now;
    const int64_t y = body_linear_velocity(a).y.raw + body_linear_velocity(b).y.raw;
    worst_y = std::max<int64_t>(worst_y, y < 0 ? -y : y);
  }
  const long double ke1 = kinetic_energy(a) + kinetic_energy(b);
  WARN("elastic pair: largest momentum change per step " << worst_step << " raw units of velocity; KE ratio "
                                                           << ke1 / ke0 << "; v_a " << ld(body_linear_velocity(a).x));
  // The README quotes momentum and kinetic energy as conserved exactly: the
  // two velocities are swapped to the raw unit, nothing spins, and no step
  // changes the total momentum by even one raw unit.
  CHECK(worst_step == 0);
  CHECK(worst_y == 0);
  CHECK(body_linear_velocity(a).x == -5_q32);
  CHECK(body_linear_velocity(b).x == 5_q32);
  CHECK(body_linear_velocity(a).y == 0_q32);
  CHECK(body_linear_velocity(b).y == 0_q32);
  CHECK(body_angular_velocity(a) == 0_q32);
  CHECK(body_angular_velocity(b) == 0_q32);
  readme::check_quotes("a head-on elastic collision of two equal circles conserves momentum and kinetic energy "
                       "exactly (the velocities are swapped to the raw unit)");
  CHECK(std::fabs(ke1 / ke0 - 1) < 0.001L);
  CHECK(ld(body_linear_velocity(a).x) < -4.99L);  // they swapped velocities
  CHECK(ld(body_linear_velocity(b).x) > 4.99L);
}

TEST_CASE("a vertical stack of 10 boxes stands", "[physics][solver]") {
  // Soft contacts are springs (30 Hz): the stack first settles by the
  // compression its weight gives them (3 cm for 10 boxes) and sways once
  // (about 1 cm at the top, the two-point manifolds being solved one point
  // after the other), then must stand still. Asserted: the top box's
  // movement over 10 s after 2 s of settling (< 1 cm), and the settling
  // itself (< 5 cm).
  ScopedWorld w;
  add_ground(w.id);
  std::vector<BodyId> boxes;
  for (int i = 0; i < 10; ++i) {
    boxes.push_back(add_dynamic_box(w.id, {0_q32, Q32::from_int(i) + 0.5_q32}, 0.5_q32, 0.5_q32));
  }
  const Vec2 placed = body_position(boxes.back());
  long double worst_total = 0;
  for (int i = 0; i < 120; ++i) {
    REQUIRE(world_step(w.id, k_dt).ok());
    worst_total = std::max(worst_total, distance_ld(body_position(boxes.back()), placed));
  }
  const Vec2 settled = body_position(boxes.back());
  long double worst = 0;
  const int steps = 600 / k_scale;
  for (int i = 0; i < steps; ++i) {
    REQUIRE(world_step(w.id, k_dt).ok());
    worst = std::max(worst, distance_ld(body_position(boxes.back()), settled));
    worst_total = std::max(worst_total, distance_ld(body_position(boxes.back()), placed));
  }
  WARN("stack of 10: settled by " << distance_ld(settled, placed) * 1000 << " mm in 2 s, then top moved at most "
                                  << worst * 1000 << " mm over " << steps << " steps (from placement at most "
                                  << worst_total * 1000 << " mm)");
  CHECK(worst < 0.01L);
  CHECK(worst_total < 0.05L);
}

TEST_CASE("a pyramid stands", "[physics][solver]") {
#ifdef NDEBUG
  const int base = 20;  // 210 boxes
  const int steps = 600;
#else
  const int base = 6;  // 21 boxes in Debug / sanitizer builds
  const int steps = 150;
#endif
  WorldDef awake_def = default_world_def();
  awake_def.enable_sleep = false;  // measure the solver, not a sleeping pyramid (test_sleep.cpp covers sleep)
  ScopedWorld w(awake_def);
  add_ground(w.id);
  std::vector<BodyId> boxes;
  const Q32 half = 0.5_q32;
  for (int row = 0; row < base; ++row) {
    for (int k = 0; k < base - row; ++k) {
      const Q32 x = Q32::from_int(k) - Q32::from_ratio(base - row - 1, 2);
      const Q32 y = Q32::from_int(row) + half;
      boxes.push_back(add_dynamic_box(w.id, {x, y}, half, half));
    }
  }
  const Vec2 placed = body_position(boxes.back());
  for (int i = 0; i < 60; ++i) REQUIRE(world_step(w.id, k_dt).ok());
  const Vec2 settled = body_position(boxes.back());
  long double worst = 0, worst_total = distance_ld(settled, placed);
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < steps; ++i) {
    REQUIRE(world_step(w.id, k_dt).ok());
    worst = std::max(worst, distance_ld(body_position(boxes.back()), settled));
    worst_total = std::max(worst_total, distance_ld(body_position(boxes.back()), placed));
  }
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() / steps;
  WARN("pyramid base " << base << " (" << boxes.size() << " boxes): settled by " << distance_ld(settled, placed) * 1000
                       << " mm in 1 s, then top moved at most " << worst * 1000 << " mm over " << steps
                       << " steps (from placement " << worst_total * 1000 << " mm); " << ms << " ms/step");
  CHECK(worst_total < 0.1L);
  CHECK(worst < 0.01L);
}

TEST_CASE("a box on a 30 degree slope sticks with friction 0.7 and slides with 0.3", "[physics][solver]") {
  const auto run = [](Q32 friction) {
    ScopedWorld w;
    const Q32 angle = k_pi / 6;
    add_static_box(w.id, {0_q32, 0_q32}, 20_q32, 0.5_q32, angle, material(friction, 0_q32));
    // A box resting on the slope's top face, rotated with it.
    const Rot q = rot_from_angle(angle);
    const Vec2 up = rotate(q, Vec2{0_q32, 1_q32});
    const Vec2 centre = up * 1_q32;  // slope half thickness 0.5 + box half 0.5
    const BodyId box = add_dynamic_box(w.id, centre, 0.5_q32, 0.5_q32, material(friction, 0_q32), angle);
    const Vec2 start = body_position(box);
    for (int i = 0; i < 120; ++i) REQUIRE(world_step(w.id, k_dt).ok());
    return distance_ld(body_position(box), start);
  };
  const long double sticky = run(0.7_q32);
  const long double slippery = run(0.3_q32);
  // Sliding: a = g (sin 30° − 0.3 cos 30°) = 2.40 m/s²; 2 s → 4.80 m.
  WARN("slope: friction 0.7 moved " << sticky * 1000 << " mm in 2 s; friction 0.3 slid " << slippery << " m (4.80 m expected)");
  CHECK(sticky < 0.01L);
  CHECK(slippery > 4.5L);
  CHECK(slippery < 5.1L);
}

TEST_CASE("no body leaves a closed box of static walls", "[physics][solver]") {
  ScopedWorld w;
  const Q32 half = 10_q32;  // interior ±10 m, walls 1 m thick
  const ShapeDef wall = material(0.2_q32, 0.5_q32);
  add_static_box(w.id, {0_q32, -half - 0.5_q32}, half + 1_q32, 0.5_q32, {}, wall);
  add_static_box(w.id, {0_q32, half + 0.5_q32}, half + 1_q32, 0.5_q32, {}, wall);
  add_static_box(w.id, {-half - 0.5_q32, 0_q32}, 0.5_q32, half + 1_q32, {}, wall);
  add_static_box(w.id, {half + 0.5_q32, 0_q32}, 0.5_q32, half + 1_q32, {}, wall);
  std::mt19937_64 rng(2024);
  const int64_t one = int64_t{1} << 32;
  const auto raw_in = [&](int64_t lo, int64_t hi) {
    return Q32::from_raw(lo + static_cast<int64_t>(rng() % static_cast<uint64_t>(hi - lo + 1)));
  };
  std::vector<BodyId> bodies;
  const int count = 60 / k_scale + 10;
  for (int k = 0; k < count; ++k) {
    const Vec2 p{Q32::from_int(-8 + (k % 9) * 2), Q32::from_int(-8 + (k / 9) * 2)};
    // |v| ≤ 40·√2 m/s → 0.94 m per step, below the 1 m wall thickness.
    const Vec2 v{raw_in(-40 * one, 40 * one), raw_in(-40 * one, 40 * one)};
    const ShapeDef sd = material(0.2_q32, raw_in(0, one));
    BodyId b;
    if (k % 2 == 0) {
      b = add_ball(w.id, p, raw_in(one / 5, one / 2), sd, v);
    } else {
      b = add_dynamic_box(w.id, p, raw_in(one / 5, one / 2), raw_in(one / 5, one / 2), sd);
      REQUIRE(body_set_linear_velocity(b, v).ok());
    }
    bodies.push_back(b);
  }
  int escaped = 0, inside_wall = 0;
  long double deepest = 0;  // of a centre beyond the inner wall face, m
  const int steps = 1200 / k_scale;
  for (int i = 0; i < steps; ++i) {
    REQUIRE(world_step(w.id, k_dt).ok());
    for (const BodyId b : bodies) {
      const Vec2 c = body_world_center(b);
      const long double beyond = std::max(std::fabs(ld(c.x)), std::fabs(ld(c.y))) - ld(half);
      deepest = std::max(deepest, beyond);
      if (beyond > 0) ++inside_wall;
      if (beyond > 1) ++escaped;  // past the wall's outer face
    }
  }
  int outside_at_end = 0;
  for (const BodyId b : bodies) {
    const Vec2 c = body_world_center(b);
    if (abs(c.x) > half || abs(c.y) > half) ++outside_at_end;
  }
  WARN("closed box: " << bodies.size() << " bodies, " << steps << " steps: body-steps with the centre inside a wall "
                      << inside_wall << " (deepest " << deepest << " m), escaped " << escaped << ", outside at end "
                      << outside_at_end);
  CHECK(escaped == 0);
  CHECK(outside_at_end == 0);
}

TEST_CASE("two worlds with contacts stay bit-identical step by step", "[physics][solver]") {
  const auto build = [](WorldId w) {
    add_ground(w, material(0.6_q32, 0.3_q32));
    std::vector<BodyId> bodies;
    std::mt19937_64 rng(77);
    for (int k = 0; k < 40; ++k) {
      const Vec2 p{Q32::from_raw(static_cast<int64_t>(rng() % (int64_t{8} << 32)) - (int64_t{4} << 32)),
                   Q32::from_int(1 + k / 2)};
      const ShapeDef sd = material(0.5_q32, Q32::from_raw(static_cast<int64_t>(rng() % (int64_t{1} << 32))));
      bodies.push_back(k % 3 == 0 ? add_ball(w, p, 0.4_q32, sd) : add_dynamic_box(w, p, 0.4_q32, 0.3_q32, sd));
    }
    return bodies;
  };
  ScopedWorld a, b;
  const std::vector<BodyId> ba = build(a.id), bb = build(b.id);
  int mismatches = 0;
  for (int i = 0; i < 300 / k_scale; ++i) {
    REQUIRE(world_step(a.id, k_dt).ok());
    REQUIRE(world_step(b.id, k_dt).ok());
    for (size_t k = 0; k < ba.size(); ++k) {
      if (!(body_transform(ba[k]) == body_transform(bb[k])) ||
          !(body_linear_velocity(ba[k]) == body_linear_velocity(bb[k])) ||
          body_angular_velocity(ba[k]) != body_angular_velocity(bb[k])) {
        ++mismatches;
      }
    }
  }
  CHECK(mismatches == 0);
  // Something happened: the bodies fell and piled up.
  long double lowest = 1e9L;
  for (const BodyId body : ba) lowest = std::min(lowest, ld(body_position(body).y));
  CHECK(lowest < 1.0L);
}

// Tests for physics/body.h and the body and shape halves of physics/tandem.h:
// body definitions, refused input, mass data from shapes, forces and
// impulses (Δv = J·(1/m) exactly), damping, gravity scale, fixed rotation,
// kinematic and static bodies, speed clamps, flags, frame conversions, and
// the record sizes the issue asks to report.
//
// Where the step is involved, the expected values are recomputed here with
// the same Q32 operations solver.cpp documents (bit-exact), and compared
// with the continuous law in long double within a stated tolerance.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <string>

#include "physics/body.h"
#include "physics/shape.h"
#include "physics/tandem.h"
#include "physics_test_support.h"
#include "physics/world.h"

using namespace tandem;
using namespace tandem::test_support;

namespace {

BodyId make_body(WorldId world, BodyType type, Vec2 position) {
  BodyDef def = default_body_def();
  def.type = type;
  def.position = position;
  Result<BodyId> r = create_body(world, def);
  REQUIRE(r.status.message == "");
  return r.value;
}

ShapeId add_circle(BodyId body, Q32 radius, Vec2 center = {}, Q32 density = Q32::one()) {
  ShapeDef sd = default_shape_def();
  sd.density = density;
  Result<ShapeId> r = create_circle_shape(body, sd, Circle{center, radius});
  REQUIRE(r.status.message == "");
  return r.value;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

/// Steps the world `steps` times, requiring success.
void run(WorldId world, int steps) {
  for (int k = 0; k < steps; ++k) REQUIRE(world_step(world, k_dt).ok());
}

}  // namespace

TEST_CASE("record sizes (bytes per body and per shape)", "[physics][body]") {
  // Reported for the memory question; upper bounds are asserted in
  // the headers. Printed with -s.
  INFO("Body " << sizeof(Body) << ", BodySim " << sizeof(BodySim) << ", BodyState " << sizeof(BodyState)
               << ", SolverBodyParams " << sizeof(SolverBodyParams) << ", Shape " << sizeof(Shape)
               << ", ShapeGeometry " << sizeof(ShapeGeometry));
  const size_t per_body = sizeof(Body) + sizeof(BodySim) + sizeof(uint32_t) + sizeof(uint8_t);  // + pool entry
  const size_t per_shape = sizeof(Shape) + sizeof(ShapeGeometry) + sizeof(uint32_t) + sizeof(uint8_t);
  const size_t per_simulated_body_per_step = sizeof(BodyState) + sizeof(SolverBodyParams) + 2 * sizeof(int32_t);
  WARN("bytes: Body " << sizeof(Body) << " + BodySim " << sizeof(BodySim) << " = " << per_body
                      << " per body (with id pool); Shape " << sizeof(Shape) << " + ShapeGeometry "
                      << sizeof(ShapeGeometry) << " = " << per_shape << " per shape; step scratch "
                      << per_simulated_body_per_step << " per simulated body");
  CHECK(sizeof(BodyState) <= 56);
  CHECK(per_body <= 240);
}

// ---------------------------------------------------------------------------
// Definitions and refused input
// ---------------------------------------------------------------------------

TEST_CASE("default body and shape defs have the documented values", "[physics][body]") {
  const BodyDef b = default_body_def();
  CHECK(b.type == BodyType::static_body);
  CHECK(b.position == Vec2{});
  CHECK(b.rotation == rot_identity());
  CHECK(b.gravity_scale == 1_q32);
  CHECK(b.linear_damping == 0_q32);
  CHECK(b.is_awake);
  CHECK(b.is_enabled);
  CHECK_FALSE(b.fixed_rotation);
  CHECK_FALSE(b.is_bullet);
  CHECK(b.internal_cookie == k_def_cookie);
  const ShapeDef s = default_shape_def();
  CHECK(s.friction == 0.6_q32);
  CHECK(s.restitution == 0_q32);
  CHECK(s.density == 1_q32);
  CHECK(s.filter.category_bits == 1u);
  CHECK(s.filter.mask_bits == UINT64_MAX);
  CHECK(s.filter.group_index == 0);
  CHECK_FALSE(s.is_sensor);
  CHECK(s.internal_cookie == k_def_cookie);
}

TEST_CASE("create_body refuses bad input and leaves the world unchanged", "[physics][body]") {
  ScopedWorld w;
  const auto refuse = [&](const BodyDef& def, const std::string& part) {
    const Result<BodyId> r = create_body(w.id, def);
    CHECK_FALSE(r.ok());
    CHECK(is_null(r.value));
    INFO(r.status.message);
    CHECK(contains(r.status.message, part));
  };
  BodyDef def{};
  refuse(def, "default_body_def");

  def = default_body_def();
  def.position = {2000000_q32, 0_q32};
  refuse(def, "create_body: position (2000000, 0) m is outside the world bounds [(-1000000, -1000000), (1000000, "
              "1000000)] m");

  def = default_body_def();
  def.rotation = {0_q32, 0_q32};
  refuse(def, "(0, 0) is not a rotation");

  def = default_body_def();
  def.linear_velocity = vec2(1, 0);
  refuse(def, "must be zero for a static body");

  def = default_body_def();
  def.type = BodyType::dynamic_body;
  def.linear_velocity = vec2(300, 300);  // 424 m/s > 400 m/s
  refuse(def, "faster than the world's maximum linear speed 400 m/s");

  def = default_body_def();
  def.type = BodyType::dynamic_body;
  def.angular_velocity = k_max_angular_speed + Q32::epsilon();
  refuse(def, "angular_velocity");

  def = default_body_def();
  def.type = BodyType::dynamic_body;
  def.linear_damping = -1_q32;
  refuse(def, "linear_damping -1 1/s is outside");

  def = default_body_def();
  def.type = BodyType::dynamic_body;
  def.gravity_scale = 1000_q32;
  refuse(def, "gravity_scale 1000");

  CHECK(world_counters(w.id).body_count == 0);
  // The world is still fine.
  const BodyId ok = make_body(w.id, BodyType::dynamic_body, vec2(0, 0));
  CHECK(ok.index1 == 1u);
}

TEST_CASE("shape creation refuses bad input and leaves the body unchanged", "[physics][body]") {
  ScopedWorld w;
  const BodyId body = make_body(w.id, BodyType::dynamic_body, vec2(0, 0));
  add_circle(body, 0.5_q32);
  const MassData before = body_mass_data(body);

  ShapeDef sd = default_shape_def();
  sd.density = 0_q32;
  Result<ShapeId> r = create_circle_shape(body, sd, Circle{{}, 0.5_q32});
  CHECK(contains(r.status.message, "create_circle_shape: density 0 kg/m² is outside (0, 100000] kg/m²"));
  sd.density = -2_q32;
  CHECK(contains(create_circle_shape(body, sd, Circle{{}, 0.5_q32}).status.message, "density -2"));

  CHECK(create_circle_shape(body, ShapeDef{}, Circle{{}, 0.5_q32}).status.code == StatusCode::invalid_definition);

  sd = default_shape_def();
  sd.restitution = 1.5_q32;
  CHECK(contains(create_circle_shape(body, sd, Circle{{}, 0.5_q32}).status.message, "restitution 1.5"));

  sd = default_shape_def();
  CHECK_FALSE(create_circle_shape(body, sd, Circle{{}, 0_q32}).ok());             // validate_circle
  CHECK_FALSE(create_circle_shape(body, sd, Circle{vec2(20000, 0), 1_q32}).ok());  // reach
  Polygon bad{};
  bad.count = 12;
  CHECK(contains(create_polygon_shape(body, sd, bad).status.message, "vertex count 12"));

  // Too light for a dynamic body (0.01 m circle of density 1: 0.000314 kg).
  CHECK(contains(create_circle_shape(body, sd, Circle{{}, 0.01_q32}).status.message, "below k_min_body_mass"));
  // Too heavy: a 2 m circle of density 100000 is 1.26e6 kg.
  sd.density = 100000_q32;
  CHECK(contains(create_circle_shape(body, sd, Circle{{}, 2_q32}).status.message, "mass"));

  CHECK(body_shape_count(body) == 1);
  CHECK(body_mass_data(body).mass == before.mass);
  CHECK(world_counters(w.id).shape_count == 1);
  // The same light circle is fine on a static body (static bodies have no mass).
  const BodyId ground = make_body(w.id, BodyType::static_body, vec2(0, -5));
  CHECK(create_circle_shape(ground, default_shape_def(), Circle{{}, 0.01_q32}).ok());
  // ...but the body can then not become dynamic.
  const Status s = body_set_type(ground, BodyType::dynamic_body);
  CHECK(contains(s.message, "below k_min_body_mass"));
  CHECK(body_type(ground) == BodyType::static_body);
}

// ---------------------------------------------------------------------------
// Mass
// ---------------------------------------------------------------------------

TEST_CASE("mass data comes from the shapes", "[physics][body]") {
  ScopedWorld w;
  const BodyId body = make_body(w.id, BodyType::dynamic_body, vec2(0, 0));
  // No shapes: 1 kg, no rotational inertia.
  CHECK(body_mass(body) == 1_q32);
  CHECK(body_rotational_inertia(body) == 0_q32);

  const Circle c1{vec2(-1, 0), 0.5_q32};
  const ShapeId s1 = add_circle(body, 0.5_q32, vec2(-1, 0));
  const MassData m1 = compute_circle_mass(c1, 1_q32);
  CHECK(body_mass(body) == m1.mass);
  CHECK(body_local_center(body) == vec2(-1, 0));
  CHECK(body_rotational_inertia(body) == m1.rotational_inertia);
  CHECK(shape_mass_data(s1).mass == m1.mass);

  // A second circle three times as dense at (+1, 0): centre at the weighted
  // mean, inertia by the parallel axis rule.
  const Circle c2{vec2(1, 0), 0.5_q32};
  add_circle(body, 0.5_q32, vec2(1, 0), 3_q32);
  const MassData m2 = compute_circle_mass(c2, 3_q32);
  const Q32 total = m1.mass + m2.mass;
  CHECK(body_mass(body) == total);
  const long double cx = (ld(m1.mass) * -1.0L + ld(m2.mass) * 1.0L) / ld(total);
  CHECK(std::fabs(ld(body_local_center(body).x) - cx) <= 1.0L / k_two32);
  CHECK(body_local_center(body).y == 0_q32);
  const long double inertia = ld(m1.rotational_inertia) + ld(m2.rotational_inertia) +
                              ld(m1.mass) * (cx + 1) * (cx + 1) + ld(m2.mass) * (1 - cx) * (1 - cx);
  CHECK(std::fabs(ld(body_rotational_inertia(body)) - inertia) < 1e-8L);
  CHECK(body_world_center(body) == body_local_center(body));  // body at the origin, unrotated

  // Removing a shape recomputes; changing density recomputes.
  REQUIRE(destroy_shape(s1).ok());
  CHECK(body_mass(body) == m2.mass);
  CHECK(body_local_center(body) == vec2(1, 0));
  ShapeId only;
  REQUIRE(body_shapes(body, &only, 1) == 1);
  REQUIRE(shape_set_density(only, 1_q32).ok());
  CHECK(body_mass(body) == compute_circle_mass(c2, 1_q32).mass);
  CHECK_FALSE(shape_set_density(only, 0_q32).ok());
  CHECK(shape_density(only) == 1_q32);

  // Static and kinematic bodies have no mass.
  REQUIRE(body_set_type(body, BodyType::kinematic_body).ok());
  CHECK(body_mass(body) == 0_q32);
  REQUIRE(body_set_type(body, BodyType::dynamic_body).ok());
  CHECK(body_mass(body) == compute_circle_mass(c2, 1_q32).mass);
}

TEST_CASE("moving the centre of mass keeps the body's motion", "[physics][body]") {
  ScopedWorld w;
  BodyDef def = default_body_def();
  def.type = BodyType::dynamic_body;
  def.angular_velocity = 2_q32;
  def.linear_velocity = vec2(1, 0);
  const BodyId body = create_body(w.id, def).value;
  add_circle(body, 0.5_q32);
  // A second equal circle at (0, 2) moves the centre to (0, 1): the new
  // centre's velocity is v + ω × Δc = (1, 0) + 2 × (0, 1) = (−1, 0).
  add_circle(body, 0.5_q32, vec2(0, 2));
  CHECK(body_local_center(body) == vec2(0, 1));
  CHECK(body_linear_velocity(body) == vec2(-1, 0));
  CHECK(body_point_velocity(body, vec2(0, 0)) == vec2(1, 0));  // the origin still moves at (1, 0)
}

// ---------------------------------------------------------------------------
// Forces and impulses
// ---------------------------------------------------------------------------

TEST_CASE("a linear impulse changes velocity by J/m", "[physics][body]") {
  ScopedWorld w;
  const BodyId body = make_body(w.id, BodyType::dynamic_body, vec2(0, 0));
  add_circle(body, 0.5_q32);
  const Q32 m = body_mass(body);
  const Vec2 j{3_q32, -1.25_q32};
  REQUIRE(body_apply_linear_impulse_to_center(body, j, true).ok());
  const Vec2 v = body_linear_velocity(body);
  const Q32 inv_m = Q32::one() / m;
  CHECK(v == Vec2{j.x * inv_m, j.y * inv_m});  // the documented formula, bit for bit
  CHECK(std::fabs(ld(v.x) - ld(j.x) / ld(m)) < 1e-9L);
  CHECK(std::fabs(ld(v.y) - ld(j.y) / ld(m)) < 1e-9L);
  CHECK(body_angular_velocity(body) == 0_q32);

  // At a point: also ω += (1/I)·(r × J).
  const Vec2 point = vec2(0, 1);
  const Q32 inv_i = Q32::one() / body_rotational_inertia(body);
  REQUIRE(body_apply_linear_impulse(body, j, point, true).ok());
  CHECK(body_angular_velocity(body) == inv_i * cross(point - body_world_center(body), j));
  CHECK(std::fabs(ld(body_angular_velocity(body)) - (-3.0L) / ld(body_rotational_inertia(body))) < 1e-8L);

  // Angular impulse: ω += L/I.
  const Q32 omega = body_angular_velocity(body);
  REQUIRE(body_apply_angular_impulse(body, 0.5_q32, true).ok());
  CHECK(body_angular_velocity(body) == omega + inv_i * 0.5_q32);

  // An impulse that would exceed the maximum speed is refused; nothing changes.
  const Vec2 before = body_linear_velocity(body);
  const Status s = body_apply_linear_impulse_to_center(body, vec2(1000, 0), true);
  CHECK(s.code == StatusCode::invalid_argument);
  CHECK(contains(s.message, "faster than the world's maximum linear speed"));
  CHECK(body_linear_velocity(body) == before);
  CHECK_FALSE(body_apply_angular_impulse(body, 1000_q32, true).ok());
}

TEST_CASE("forces and torques act for one step", "[physics][body]") {
  ScopedWorld w;
  REQUIRE(world_set_gravity(w.id, Vec2{}).ok());
  const BodyId body = make_body(w.id, BodyType::dynamic_body, vec2(0, 0));
  add_circle(body, 0.5_q32);
  const Vec2 f{2_q32, 1_q32};
  REQUIRE(body_apply_force_to_center(body, f, true).ok());
  REQUIRE(body_apply_torque(body, 0.25_q32, true).ok());
  run(w.id, 1);
  // Per sub-step: Δv = h·(0·g + F·(1/m)), Δω = h·(τ·(1/I)); four sub-steps.
  const Q32 h = k_dt / 4;
  const Q32 inv_m = Q32::one() / body_mass(body);
  const Q32 inv_i = Q32::one() / body_rotational_inertia(body);
  const Vec2 dv{h * (f.x * inv_m), h * (f.y * inv_m)};  // note: inv_m·F, the same product
  const Q32 dw = h * (0.25_q32 * inv_i);
  CHECK(body_linear_velocity(body) == Vec2{dv.x * 4, dv.y * 4});
  CHECK(body_angular_velocity(body) == dw * 4);
  CHECK(std::fabs(ld(body_linear_velocity(body).x) - 2.0L / ld(body_mass(body)) / 60.0L) < 1e-8L);
  // Forces are cleared after the step.
  run(w.id, 1);
  CHECK(body_linear_velocity(body) == Vec2{dv.x * 4, dv.y * 4});

  // Refused: more than k_max_force, more than the acceleration limit.
  CHECK(contains(body_apply_force_to_center(body, {k_max_force + 1_q32, 0_q32}, true).message, "force x"));
  CHECK(contains(body_apply_force_to_center(body, {0_q32, 10000000_q32}, true).message, "acceleration y"));
  CHECK(contains(body_apply_force(body, vec2(1, 0), vec2(0, 2000000), true).message, "outside the world bounds"));
}

TEST_CASE("linear damping follows v/(1 + h c) per sub-step", "[physics][body]") {
  ScopedWorld w;
  BodyDef def = default_body_def();
  def.type = BodyType::dynamic_body;
  def.gravity_scale = 0_q32;
  def.linear_velocity = vec2(10, -4);
  def.linear_damping = 0.5_q32;
  def.angular_velocity = 3_q32;
  def.angular_damping = 2_q32;
  const BodyId body = create_body(w.id, def).value;
  add_circle(body, 0.5_q32);
  const int steps = 60;
  run(w.id, steps);
  const Q32 h = k_dt / 4;
  const Q32 f = Q32::one() / (Q32::one() + h * 0.5_q32);
  const Q32 fw = Q32::one() / (Q32::one() + h * 2_q32);
  Vec2 v = vec2(10, -4);
  Q32 omega = 3_q32;
  for (int k = 0; k < steps * 4; ++k) {
    v = Vec2{v.x * f, v.y * f};
    omega = omega * fw;
  }
  CHECK(body_linear_velocity(body) == v);
  CHECK(body_angular_velocity(body) == omega);
  // The discrete law v0/(1 + h c)^K, and close to v0·e^(−c t) for small h·c.
  const long double hh = ld(h);
  // 240 factors, each within 2^-33 of 1/(1 + h·c), each product rounded: ≲ 2e-7.
  CHECK(std::fabs(ld(v.x) - 10.0L / std::pow(1.0L + hh * 0.5L, 240.0L)) < 1e-6L);
  CHECK(std::fabs(ld(v.x) - 10.0L * std::exp(-0.5L)) < 10.0L * 0.5L * 0.5L * hh);
}

TEST_CASE("gravity scale 0 floats, fixed rotation never turns", "[physics][body]") {
  ScopedWorld w;
  BodyDef def = default_body_def();
  def.type = BodyType::dynamic_body;
  def.position = vec2(0, 7);
  def.gravity_scale = 0_q32;
  const BodyId floating = create_body(w.id, def).value;
  add_circle(floating, 0.5_q32);

  def = default_body_def();
  def.type = BodyType::dynamic_body;
  def.fixed_rotation = true;
  const BodyId fixed = create_body(w.id, def).value;
  Polygon box;
  REQUIRE(make_box(1_q32, 0.5_q32, &box).ok());
  REQUIRE(create_polygon_shape(fixed, default_shape_def(), box).ok());
  CHECK(body_is_fixed_rotation(fixed));
  CHECK(body_rotational_inertia(fixed) > 0_q32);  // reported, but not used
  REQUIRE(body_apply_torque(fixed, 5_q32, true).ok());
  REQUIRE(body_apply_angular_impulse(fixed, 5_q32, true).ok());
  REQUIRE(body_apply_linear_impulse(fixed, vec2(0, 1), vec2(1, 0), true).ok());
  CHECK(body_set_angular_velocity(fixed, 1_q32).code == StatusCode::invalid_argument);
  run(w.id, 30);
  CHECK(body_position(floating) == vec2(0, 7));
  CHECK(body_linear_velocity(floating) == Vec2{});
  CHECK(body_rotation(fixed) == rot_identity());
  CHECK(body_angular_velocity(fixed) == 0_q32);
  // Freeing the rotation lets torque act again.
  REQUIRE(body_set_fixed_rotation(fixed, false).ok());
  REQUIRE(body_apply_angular_impulse(fixed, 1_q32, true).ok());
  CHECK(body_angular_velocity(fixed) > 0_q32);
}

TEST_CASE("a kinematic body moves at its set velocity and ignores gravity", "[physics][body]") {
  ScopedWorld w;
  const BodyId body = make_body(w.id, BodyType::kinematic_body, vec2(1, 2));
  add_circle(body, 0.5_q32);
  REQUIRE(body_set_linear_velocity(body, vec2(2, -1)).ok());
  REQUIRE(body_set_angular_velocity(body, 0.5_q32).ok());
  REQUIRE(body_apply_force_to_center(body, vec2(100, 100), true).ok());       // no effect
  REQUIRE(body_apply_linear_impulse_to_center(body, vec2(100, 100), true).ok());  // no effect
  const int steps = 90;
  run(w.id, steps);
  const Q32 h = k_dt / 4;
  Vec2 c = vec2(1, 2);
  for (int k = 0; k < steps * 4; ++k) c = mul_add(c, h, vec2(2, -1));
  CHECK(body_linear_velocity(body) == vec2(2, -1));
  CHECK(body_angular_velocity(body) == 0.5_q32);
  CHECK(body_position(body) == c);
  CHECK(std::fabs(ld(body_position(body).x) - (1.0L + 2.0L * 1.5L)) < 1e-6L);
  CHECK(std::fabs(ld(body_angle(body)) - 0.75L) < 1e-4L);  // first-order rotation: atan(hω) per sub-step
  CHECK(body_mass(body) == 0_q32);
}

TEST_CASE("a static body never moves", "[physics][body]") {
  ScopedWorld w;
  const BodyId ground = make_body(w.id, BodyType::static_body, vec2(0, -1));
  Polygon box;
  REQUIRE(make_box(10_q32, 1_q32, &box).ok());
  REQUIRE(create_polygon_shape(ground, default_shape_def(), box).ok());
  const Status s = body_set_linear_velocity(ground, vec2(1, 0));
  CHECK(contains(s.message, "is static"));
  CHECK(body_set_linear_velocity(ground, Vec2{}).ok());
  CHECK(body_apply_force_to_center(ground, vec2(5, 5), true).ok());
  CHECK(body_apply_linear_impulse_to_center(ground, vec2(5, 5), true).ok());
  CHECK_FALSE(body_is_awake(ground));
  run(w.id, 60);
  CHECK(body_position(ground) == vec2(0, -1));
  CHECK(body_linear_velocity(ground) == Vec2{});
  CHECK(body_mass(ground) == 0_q32);
  CHECK(world_counters(w.id).solver_body_count == 0);
}

TEST_CASE("speeds are clamped by the step and refused at the API", "[physics][body]") {
  ScopedWorld w;
  REQUIRE(world_set_max_linear_speed(w.id, 50_q32).ok());
  const BodyId body = make_body(w.id, BodyType::dynamic_body, vec2(0, 0));
  add_circle(body, 0.5_q32);
  CHECK(contains(body_set_linear_velocity(body, vec2(60, 0)).message, "faster than the world's maximum"));
  REQUIRE(body_set_linear_velocity(body, vec2(30, -40)).ok());  // exactly 50 m/s, downwards
  REQUIRE(body_set_angular_velocity(body, k_max_angular_speed).ok());
  run(w.id, 10);
  const long double speed = std::hypot(ld(body_linear_velocity(body).x), ld(body_linear_velocity(body).y));
  // v·(max/|v|): the ratio is rounded to 2^-33 absolute, so the speed may
  // exceed 50 m/s by 50·2^-33 m/s (25 raw units) plus the products' rounding.
  CHECK(speed <= 50.0L + 32.0L / k_two32);
  CHECK(speed >= 50.0L - 1e-6L);
  CHECK(body_linear_velocity(body).y < -40_q32);  // gravity turned it, the clamp kept the speed
  CHECK(body_linear_velocity(body).x < 30_q32);
  // |ω| is clamped to (π/16)/h = 47.1 rad/s at 60 Hz and 4 sub-steps.
  const Q32 max_w = k_max_rotation_per_sub_step / (k_dt / 4);
  CHECK(body_angular_velocity(body) == max_w);
  CHECK(std::fabs(ld(max_w) - 3.14159265358979L / 16.0L * 240.0L) < 1e-6L);
}

TEST_CASE("teleport, frames and conversions", "[physics][body]") {
  ScopedWorld w;
  const BodyId body = make_body(w.id, BodyType::dynamic_body, vec2(1, 2));
  const ShapeId circle = add_circle(body, 0.5_q32, vec2(1, 0));
  CHECK(contains(body_set_transform(body, vec2(0, 3000000), rot_identity()).message, "outside the world bounds"));
  CHECK(body_position(body) == vec2(1, 2));
  const Rot quarter{0_q32, 1_q32};  // 90°
  REQUIRE(body_set_transform(body, vec2(5, 6), quarter).ok());
  CHECK(body_position(body) == vec2(5, 6));
  CHECK(body_world_point(body, vec2(1, 0)) == vec2(5, 7));
  CHECK(body_local_point(body, vec2(5, 7)) == vec2(1, 0));
  CHECK(body_world_vector(body, vec2(1, 0)) == vec2(0, 1));
  CHECK(body_local_vector(body, vec2(0, 1)) == vec2(1, 0));
  CHECK(body_world_center(body) == vec2(5, 7));  // the circle's centre
  CHECK(std::fabs(ld(body_angle(body)) - 3.14159265358979L / 2) < 1e-9L);
  // Bounds follow at once.
  CHECK(shape_aabb(circle) == AABB{{4.5_q32, 6.5_q32}, {5.5_q32, 7.5_q32}});
  // A non-unit rotation is normalised.
  REQUIRE(body_set_transform(body, vec2(5, 6), Rot{0_q32, 3_q32}).ok());
  CHECK(body_rotation(body) == quarter);
}

TEST_CASE("flags: user data, bullet, enable, awake, sleep", "[physics][body]") {
  ScopedWorld w;
  const BodyId body = make_body(w.id, BodyType::dynamic_body, vec2(0, 0));
  add_circle(body, 0.5_q32);
  REQUIRE(body_set_user_data(body, 0xdead'beef'0000'0001ull).ok());
  CHECK(body_user_data(body) == 0xdead'beef'0000'0001ull);
  REQUIRE(body_set_bullet(body, true).ok());
  CHECK(body_is_bullet(body));
  REQUIRE(body_enable_sleep(body, false).ok());
  CHECK_FALSE(body_is_sleep_enabled(body));

  // Disabled: does not move; enabled again: falls.
  REQUIRE(body_set_enabled(body, false).ok());
  CHECK_FALSE(body_is_enabled(body));
  run(w.id, 10);
  CHECK(body_position(body) == vec2(0, 0));
  REQUIRE(body_set_enabled(body, true).ok());
  run(w.id, 1);
  CHECK(body_position(body).y < 0_q32);

  // Asleep: does not move, velocity zeroed; an impulse without wake is
  // ignored, with wake it wakes the body.
  REQUIRE(body_set_awake(body, false).ok());
  CHECK_FALSE(body_is_awake(body));
  CHECK(body_linear_velocity(body) == Vec2{});
  const Vec2 p = body_position(body);
  run(w.id, 10);
  CHECK(body_position(body) == p);
  REQUIRE(body_apply_linear_impulse_to_center(body, vec2(1, 0), false).ok());
  CHECK_FALSE(body_is_awake(body));
  CHECK(body_linear_velocity(body) == Vec2{});
  REQUIRE(body_apply_linear_impulse_to_center(body, vec2(1, 0), true).ok());
  CHECK(body_is_awake(body));
  CHECK(body_linear_velocity(body).x > 0_q32);

  // Shape material and filter round trips.
  ShapeId s;
  REQUIRE(body_shapes(body, &s, 1) == 1);
  REQUIRE(shape_set_friction(s, 0.25_q32).ok());
  CHECK(shape_friction(s) == 0.25_q32);
  CHECK_FALSE(shape_set_friction(s, -1_q32).ok());
  REQUIRE(shape_set_restitution(s, 1_q32).ok());
  CHECK(shape_restitution(s) == 1_q32);
  Filter f;
  f.category_bits = 4;
  f.mask_bits = 6;
  f.group_index = -3;
  REQUIRE(shape_set_filter(s, f).ok());
  CHECK(shape_filter(s).mask_bits == 6u);
  CHECK(shape_filter(s).group_index == -3);
  REQUIRE(shape_set_user_data(s, 77).ok());
  CHECK(shape_user_data(s) == 77u);
  CHECK(shape_type(s) == ShapeType::circle);
  CHECK(shape_geometry(s).circle.radius == 0.5_q32);
  CHECK_FALSE(shape_is_sensor(s));
  ShapeDef sensor_def = default_shape_def();
  sensor_def.is_sensor = true;
  const Result<ShapeId> sensor = create_circle_shape(body, sensor_def, Circle{{}, 1_q32});
  REQUIRE(sensor.ok());
  CHECK(shape_is_sensor(sensor.value));
}

TEST_CASE("rotation stays unit length and on angle at slow and fast spins", "[physics][body]") {
  ScopedWorld w;
  // 10 rad/s: h·ω = 1/24 per sub-step, the polynomial path (turns by
  // atan(h·ω)). 40 rad/s: h·ω = 1/6, the exact path (turns by h·ω).
  const Q32 speeds[2] = {10_q32, 40_q32};
  BodyId bodies[2];
  for (int k = 0; k < 2; ++k) {
    bodies[k] = make_body(w.id, BodyType::kinematic_body, vec2(0, 0));
    REQUIRE(body_set_angular_velocity(bodies[k], speeds[k]).ok());
  }
  const int steps = 600;
  run(w.id, steps);
  const long double h = ld(k_dt / 4);
  const long double pi = 3.14159265358979323846L;
  for (int k = 0; k < 2; ++k) {
    const Rot q = body_rotation(bodies[k]);
    const long double norm = ld(q.c) * ld(q.c) + ld(q.s) * ld(q.s);
    INFO("spin " << ld(speeds[k]) << " rad/s, |q|^2 - 1 = " << norm - 1.0L);
    CHECK(std::fabs(norm - 1.0L) < 8.0L / k_two32);
    const long double delta = h * ld(speeds[k]);
    const long double turn = k == 0 ? std::atan(delta) : delta;
    const long double expected = std::remainder(4.0L * steps * turn, 2.0L * pi);
    const long double got = ld(body_angle(bodies[k]));
    CHECK(std::fabs(std::remainder(got - expected, 2.0L * pi)) < 1e-5L);
  }
}

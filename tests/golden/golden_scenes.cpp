// golden_scenes.cpp — the golden scenes: small worlds built from the public
// API (physics/tandem.h) with integer and fixed-point inputs only (exact
// literals, Q32::from_ratio, raw integers from a seeded std::mt19937_64),
// each run for k_scene_ticks ticks by golden_support.cpp.
//
// Together they cover every pair of shape kinds the narrow phase collides
// (circle, capsule, polygon/box, segment and chain segment against the three
// solid kinds), friction and restitution, sleeping and waking, filtering
// (category, mask, positive and negative groups, a filter changed mid-run),
// sensors, bodies and shapes created and destroyed mid-run, and scripted
// impulses, forces, torques, velocity sets, teleports, type changes, gravity
// and damping changes at given ticks. A scene never expects an API call to
// fail: the first failure stops the run with a message naming it.
//
// Changing a scene changes its golden file: regenerate it in the same
// commit (docs/determinism.md).
#include <array>
#include <cstdint>
#include <iterator>
#include <random>
#include <vector>

#include "golden_support.h"

namespace tandem::golden {
namespace {

using namespace tandem::literals;

Q32 q(int64_t num, int64_t den = 1) { return Q32::from_ratio(num, den); }
Vec2 v(Q32 x, Q32 y) { return {x, y}; }

// (Default arguments avoid _q32 literals: clang 14 rejects a consteval call
// in a default argument.)
ShapeDef mat(Q32 friction = Q32::from_ratio(3, 5), Q32 restitution = Q32::zero(), Q32 density = Q32::one()) {
  ShapeDef sd = default_shape_def();
  sd.friction = friction;
  sd.restitution = restitution;
  sd.density = density;
  return sd;
}

BodyId body(SceneContext& c, BodyType type, Vec2 position, Q32 angle = Q32::zero(), Vec2 velocity = {}) {
  BodyDef def = default_body_def();
  def.type = type;
  def.position = position;
  def.rotation = rot_from_angle(angle);
  def.linear_velocity = velocity;
  return c.value(create_body(c.world, def), "create_body");
}
BodyId dyn(SceneContext& c, Vec2 position, Q32 angle = Q32::zero(), Vec2 velocity = {}) {
  return body(c, BodyType::dynamic_body, position, angle, velocity);
}

ShapeId add_box(SceneContext& c, BodyId b, Q32 hw, Q32 hh, const ShapeDef& sd = mat()) {
  Polygon p;
  const Status g = make_box(hw, hh, &p);
  if (!g.ok()) c.check({StatusCode::invalid_argument, g.message}, "make_box");
  return c.value(create_polygon_shape(b, sd, p), "create_polygon_shape(box)");
}
ShapeId add_offset_box(SceneContext& c, BodyId b, Q32 hw, Q32 hh, Vec2 center, Q32 angle, Q32 radius,
                       const ShapeDef& sd = mat()) {
  Polygon p;
  const Status g = make_offset_box(hw, hh, center, angle, radius, &p);
  if (!g.ok()) c.check({StatusCode::invalid_argument, g.message}, "make_offset_box");
  return c.value(create_polygon_shape(b, sd, p), "create_polygon_shape(offset box)");
}
/// A regular-ish polygon with `n` vertices on a circle of radius r (exact
/// fixed-point sines), rounded by `radius`.
ShapeId add_ngon(SceneContext& c, BodyId b, int32_t n, Q32 r, Q32 radius = Q32::zero(), const ShapeDef& sd = mat()) {
  std::array<Vec2, 8> pts{};
  for (int32_t i = 0; i < n; ++i) {
    const Rot rot = rot_from_angle(k_pi * int64_t{2 * i} / int64_t{n});
    pts[static_cast<size_t>(i)] = {r * rot.c, r * rot.s};
  }
  Polygon p;
  const Status g = make_polygon_from_points(pts.data(), n, radius, &p);
  if (!g.ok()) c.check({StatusCode::invalid_argument, g.message}, "make_polygon_from_points");
  return c.value(create_polygon_shape(b, sd, p), "create_polygon_shape(ngon)");
}
ShapeId add_circle(SceneContext& c, BodyId b, Q32 r, Vec2 center = {}, const ShapeDef& sd = mat()) {
  return c.value(create_circle_shape(b, sd, Circle{center, r}), "create_circle_shape");
}
ShapeId add_capsule(SceneContext& c, BodyId b, Vec2 p1, Vec2 p2, Q32 r, const ShapeDef& sd = mat()) {
  return c.value(create_capsule_shape(b, sd, Capsule{p1, p2, r}), "create_capsule_shape");
}
ShapeId add_segment(SceneContext& c, BodyId b, Vec2 p1, Vec2 p2, const ShapeDef& sd = mat()) {
  return c.value(create_segment_shape(b, sd, Segment{p1, p2}), "create_segment_shape");
}

/// A static box floor (top at y = 0, 40 m wide) with walls at x = ±half_width.
BodyId container(SceneContext& c, int64_t half_width = 10, const ShapeDef& sd = mat()) {
  const BodyId g = body(c, BodyType::static_body, {});
  add_offset_box(c, g, 20_q32, 1_q32, v(0_q32, -1_q32), 0_q32, 0_q32, sd);
  add_offset_box(c, g, 1_q32, 10_q32, v(q(-half_width - 1), 10_q32), 0_q32, 0_q32, sd);
  add_offset_box(c, g, 1_q32, 10_q32, v(q(half_width + 1), 10_q32), 0_q32, 0_q32, sd);
  return g;
}

/// One dynamic body of a kind chosen by k (0 circle, 1 capsule, 2 box,
/// 3 hexagon, 4 compound circle + box, 5 rounded triangle).
BodyId add_kind(SceneContext& c, int64_t k, Vec2 p, Q32 angle = Q32::zero(), const ShapeDef& sd = mat()) {
  const BodyId b = dyn(c, p, angle);
  switch (k % 6) {
    case 0: add_circle(c, b, q(2 + k % 3, 8), {}, sd); break;
    case 1: add_capsule(c, b, v(q(-3, 10), 0_q32), v(q(3, 10), 0_q32), q(1, 5), sd); break;
    case 2: add_box(c, b, q(3, 10), q(1 + k % 3, 5), sd); break;
    case 3: add_ngon(c, b, 6, q(2, 5), 0_q32, sd); break;
    case 4:
      add_circle(c, b, q(1, 4), v(q(-3, 10), 0_q32), sd);
      add_offset_box(c, b, q(1, 5), q(1, 5), v(q(3, 10), 0_q32), q(1, 4), 0_q32, sd);
      break;
    default: add_ngon(c, b, 3, q(2, 5), q(1, 20), sd); break;
  }
  return b;
}

// --- 1. circles ----------------------------------------------------------------
void build_circles(SceneContext& c) {
  container(c);
  for (int64_t i = 0; i < 36; ++i) {
    const BodyId b = dyn(c, v(q(-8) + q(3 * (i % 9), 2) + q(i % 2, 7), q(2) + q(6 * (i / 9), 5)));
    add_circle(c, b, q(4 + i % 5, 20), {}, mat(q(i % 3, 3), q(i % 4, 10)));
  }
}

// --- 2. capsules ---------------------------------------------------------------
void build_capsules(SceneContext& c) {
  container(c);
  for (int64_t i = 0; i < 30; ++i) {
    const Vec2 p = v(q(-8) + q(2 * (i % 8)) + q(i % 3, 5), q(2) + q(3 * (i / 8), 2));
    const BodyId b = dyn(c, p, q(i * 3, 10));
    if (i % 3 == 2) {
      add_circle(c, b, q(3, 10));
    } else {
      add_capsule(c, b, v(q(-1, 2), 0_q32), v(q(1, 2), q(i % 2, 5)), q(1 + i % 3, 10), mat(q(1, 2), q(1, 10)));
    }
  }
}

// --- 3. pyramid of boxes; sleeps, then a scripted impulse wakes it ------------
void build_pyramid(SceneContext& c) {
  const BodyId g = body(c, BodyType::static_body, {});
  add_offset_box(c, g, 30_q32, 1_q32, v(0_q32, -1_q32), 0_q32, 0_q32);
  const int64_t rows = 10;
  for (int64_t row = 0; row < rows; ++row) {
    for (int64_t i = 0; i < rows - row; ++i) {
      const BodyId b = dyn(c, v(q(-rows + 1 + row + 2 * i, 2) * 1_q32 + q(row, 100), q(1, 2) + q(row * 21, 20)));
      add_box(c, b, q(1, 2), q(1, 2));
      c.bodies.push_back(b);
    }
  }
}
void script_pyramid(SceneContext& c, int32_t tick) {
  if (tick == 2400) {  // bottom-left box, knocked sideways: wakes the island
    c.check(body_apply_linear_impulse_to_center(c.bodies[0], v(-6_q32, 2_q32), true), "impulse");
  }
  if (tick == 2700) {  // a rounded hexagon and a triangle dropped on top
    add_ngon(c, dyn(c, v(q(1, 3), 14_q32)), 6, q(1, 2), q(1, 20));
    add_ngon(c, dyn(c, v(-2_q32, 16_q32), q(1, 3)), 3, q(3, 5));
  }
}

// --- 4. static segments: ramps for circles, capsules and polygons ------------
void build_segments(SceneContext& c) {
  const BodyId g = body(c, BodyType::static_body, {});
  add_segment(c, g, v(-20_q32, 14_q32), v(2_q32, 8_q32), mat(q(2, 5)));
  add_segment(c, g, v(20_q32, 6_q32), v(-4_q32, 2_q32), mat(q(2, 5)));
  add_segment(c, g, v(-30_q32, 0_q32), v(30_q32, 0_q32));
  add_segment(c, g, v(-30_q32, 0_q32), v(-30_q32, 20_q32));
  add_segment(c, g, v(30_q32, 0_q32), v(30_q32, 20_q32));
}
void script_segments(SceneContext& c, int32_t tick) {
  if (tick <= 1200 && tick % 60 == 1) {
    const int64_t k = tick / 60;
    add_kind(c, k, v(q(-18) + q(k % 4, 3), 17_q32), q(k, 7), mat(q(k % 4, 5), q(k % 3, 10)));
  }
}

// --- 5. chains: an open wavy ground and a clockwise bowl ----------------------
void build_chains(SceneContext& c) {
  const BodyId g = body(c, BodyType::static_body, {});
  std::vector<Vec2> ground;  // right to left: collision side up
  for (int64_t x = 26; x >= -26; x -= 2) ground.push_back(v(q(x), q((x / 2) % 3 == 0 ? 0 : 1, 2) + q(x * x, 200)));
  std::vector<ShapeId> out;
  c.check(create_chain_shapes(g, mat(q(1, 2)), ground.data(), static_cast<int32_t>(ground.size()), false, &out),
          "create_chain_shapes(ground)");
  // A clockwise loop (holds bodies inside) around (0, 12).
  const std::array<Vec2, 6> bowl = {v(-6_q32, 18_q32), v(6_q32, 18_q32), v(6_q32, 9_q32),
                                    v(2_q32, 6_q32),   v(-2_q32, 6_q32), v(-6_q32, 9_q32)};
  c.check(create_chain_shapes(g, mat(q(3, 10), q(1, 5)), bowl.data(), 6, true, &out), "create_chain_shapes(bowl)");
  for (int64_t i = 0; i < 18; ++i) {
    c.bodies.push_back(add_kind(c, i, v(q(-5) + q(5 * (i % 6), 3), q(10) + q(i / 6, 1) * 2_q32), q(i, 5)));
  }
  for (int64_t i = 0; i < 12; ++i) add_kind(c, i + 3, v(q(-20) + q(7 * i, 2), q(24) + q(i % 3)), q(i, 3));
}
void script_chains(SceneContext& c, int32_t tick) {
  if (tick % 400 == 0) {  // shake the bowl's contents
    const BodyId b = c.bodies[static_cast<size_t>(tick / 400) % c.bodies.size()];
    c.check(body_apply_linear_impulse_to_center(b, v(q(tick % 3 - 1), 3_q32), true), "impulse");
  }
}

// --- 6. friction and restitution ------------------------------------------------
void build_friction_restitution(SceneContext& c) {
  c.check(world_set_restitution_threshold(c.world, q(1, 2)), "world_set_restitution_threshold");
  const BodyId g = body(c, BodyType::static_body, {});
  add_offset_box(c, g, 40_q32, 1_q32, v(0_q32, -1_q32), 0_q32, 0_q32, mat(q(1, 2)));
  const Q32 slope = q(3, 10);
  const BodyId ramp = body(c, BodyType::static_body, v(-20_q32, 8_q32), slope);
  add_box(c, ramp, 12_q32, q(1, 2), mat(1_q32));
  const Rot r = rot_from_angle(slope);
  for (int64_t i = 0; i < 6; ++i) {
    const Q32 along = q(-9) + q(3 * i);
    const Vec2 p = v(-20_q32 + along * r.c - 1_q32 * r.s, 8_q32 + along * r.s + 1_q32 * r.c);
    const BodyId b = dyn(c, p, slope);
    add_box(c, b, q(2, 5), q(2, 5), mat(q(i, 5)));
  }
  for (int64_t i = 0; i < 6; ++i) {
    const BodyId b = dyn(c, v(q(2 * i), q(8 + i)));
    add_circle(c, b, q(2, 5), {}, mat(q(1, 5), q(i, 5)));
  }
  for (int64_t i = 0; i < 4; ++i) {  // sliding boxes thrown along the floor
    const BodyId b = dyn(c, v(q(16), q(1, 2)), 0_q32, v(q(-4 - i), 0_q32));
    add_box(c, b, q(1, 2), q(3, 10), mat(q(i, 4), q(i, 8)));
  }
}

// --- 7. sleeping and waking ---------------------------------------------------------
void build_sleep_wake(SceneContext& c) {
  container(c, 16);
  for (int64_t s = 0; s < 4; ++s) {
    for (int64_t h = 0; h < 4; ++h) {
      const BodyId b = dyn(c, v(q(-12 + 8 * s), q(1, 2) + q(h, 1) * 1_q32 + q(h, 50)));
      add_box(c, b, q(1, 2), q(1, 2));
      c.bodies.push_back(b);
    }
  }
}
void script_sleep_wake(SceneContext& c, int32_t tick) {
  auto b = [&](size_t i) { return c.bodies[i]; };
  switch (tick) {
    case 600: c.check(body_set_awake(b(3), false), "body_set_awake(false)"); break;
    case 1200: {  // touch: a ball dropped on stack 1
      const BodyId ball = dyn(c, v(-4_q32, 8_q32));
      add_circle(c, ball, q(1, 2));
      break;
    }
    case 1500: c.check(destroy_body(b(8)), "destroy_body"); break;  // stack 2's bottom box
    case 1800: c.check(body_set_transform(b(15), v(14_q32, 3_q32), rot_from_angle(q(1, 2))), "body_set_transform"); break;
    case 2100: c.check(body_enable_sleep(b(12), false), "body_enable_sleep(false)"); break;
    case 2400: c.check(world_enable_sleep(c.world, false), "world_enable_sleep(false)"); break;
    case 2700: c.check(world_enable_sleep(c.world, true), "world_enable_sleep(true)"); break;
    case 3000: c.check(body_enable_sleep(b(12), true), "body_enable_sleep(true)"); break;
    case 3300: c.check(body_set_awake(b(0), true), "body_set_awake(true)"); break;
    case 3400: c.check(body_apply_angular_impulse(b(1), 1_q32, false), "angular impulse, no wake"); break;
    default: break;
  }
}

// --- 8. filtering ------------------------------------------------------------------
ShapeDef filtered(uint64_t category, uint64_t mask, int32_t group) {
  ShapeDef sd = mat();
  sd.filter.category_bits = category;
  sd.filter.mask_bits = mask;
  sd.filter.group_index = group;
  return sd;
}
void build_filtering(SceneContext& c) {
  container(c, 12);
  for (int64_t i = 0; i < 8; ++i) {  // layer 2 boxes and layer 4 circles at the same places
    add_box(c, dyn(c, v(q(-7 + 2 * i), q(3 + i % 3))), q(2, 5), q(2, 5), filtered(2, 1 | 2, 0));
    c.shapes.push_back(add_circle(c, dyn(c, v(q(-7 + 2 * i), q(4 + i % 3))), q(2, 5), {}, filtered(4, 1 | 4, 0)));
  }
  for (int64_t i = 0; i < 5; ++i) {  // a negative group: overlapping capsules that never collide
    add_capsule(c, dyn(c, v(q(-2 + i, 2), q(10 + i, 2)), q(i, 4)), v(q(-1), 0_q32), v(1_q32, 0_q32), q(1, 4),
                filtered(8, UINT64_MAX, -1));
  }
  for (int64_t i = 0; i < 4; ++i) {  // masks exclude each other, a shared positive group collides anyway
    add_box(c, dyn(c, v(q(4 + i, 2), q(12 + 2 * i))), q(1, 2), q(1, 4), filtered(16, 1, 3));
  }
}
void script_filtering(SceneContext& c, int32_t tick) {
  if (tick == 1500) {  // circles 0..3 move to layer 2: they now collide with the boxes
    for (size_t i = 0; i < 4; ++i) c.check(shape_set_filter(c.shapes[i], Filter{2, 1 | 2, 0}), "shape_set_filter");
  }
  if (tick == 2500) {  // circle 4 joins a never-collide group with nothing: no change expected
    c.check(shape_set_filter(c.shapes[4], Filter{4, 1 | 4, -2}), "shape_set_filter(group)");
    c.check(body_apply_linear_impulse_to_center(shape_body(c.shapes[5]), v(0_q32, 2_q32), true), "impulse");
  }
}

// --- 9. sensors ---------------------------------------------------------------------
void build_sensors(SceneContext& c) {
  container(c, 14);
  ShapeDef sensor = mat();
  sensor.is_sensor = true;
  const BodyId zone = body(c, BodyType::static_body, v(0_q32, 3_q32));
  add_box(c, zone, 4_q32, 2_q32, sensor);
  const BodyId mover = body(c, BodyType::kinematic_body, v(-10_q32, 1_q32), 0_q32, v(2_q32, 0_q32));
  add_circle(c, mover, 1_q32, {}, sensor);
  c.bodies.push_back(mover);
  const BodyId carrier = dyn(c, v(8_q32, 2_q32));  // a solid ball carrying a larger sensor capsule
  add_circle(c, carrier, q(1, 2));
  add_capsule(c, carrier, v(-1_q32, 0_q32), v(1_q32, 0_q32), q(3, 4), sensor);
  c.bodies.push_back(carrier);
  ShapeDef sensor_poly = sensor;
  sensor_poly.filter.mask_bits = 1;  // a sensor that only sees layer 1
  add_ngon(c, body(c, BodyType::static_body, v(-8_q32, 6_q32)), 5, 1_q32, 0_q32, sensor_poly);
}
void script_sensors(SceneContext& c, int32_t tick) {
  if (tick % 240 == 0) {  // the kinematic sensor turns around
    const Q32 speed = (tick / 240) % 2 == 1 ? -2_q32 : 2_q32;
    c.check(body_set_linear_velocity(c.bodies[0], v(speed, 0_q32)), "body_set_linear_velocity");
  }
  if (tick % 90 == 30 && tick < 2400) {  // visitors dropped through the zones
    const int64_t k = tick / 90;
    ShapeDef sd = mat(q(1, 2), q(3, 10));
    sd.filter.category_bits = k % 3 == 0 ? 2 : 1;
    add_kind(c, k, v(q(-9) + q(k % 7, 1) * 3_q32, 12_q32), q(k, 4), sd);
  }
  if (tick % 500 == 0) {
    c.check(body_apply_linear_impulse_to_center(c.bodies[1], v(q(tick % 1000 == 0 ? -3 : 3), 2_q32), true),
            "impulse");
  }
}

// --- 10. creating and destroying bodies and shapes mid-run ----------------------
void build_create_destroy(SceneContext& c) { container(c, 10); }
void script_create_destroy(SceneContext& c, int32_t tick) {
  if (tick % 20 == 1 && tick < 3000) {
    const int64_t k = c.counter++;
    c.bodies.push_back(add_kind(c, k, v(q(-6) + q(k % 5, 1) * 3_q32, 14_q32), q(k, 9)));
  }
  if (c.bodies.size() > 24) {  // the oldest goes (its slot is reused by the next spawn)
    c.check(destroy_body(c.bodies.front()), "destroy_body(oldest)");
    c.bodies.erase(c.bodies.begin());
  }
  if (tick % 250 == 0 && !c.bodies.empty()) {  // drop one shape of a multi-shape body
    for (const BodyId b : c.bodies) {
      if (body_shape_count(b) > 1) {
        ShapeId first;
        (void)body_shapes(b, &first, 1);
        c.check(destroy_shape(first), "destroy_shape");
        break;
      }
    }
  }
  if (tick == 2000) {  // destroy and recreate in one tick
    const BodyId b = c.bodies[3];
    c.check(destroy_body(b), "destroy_body");
    c.bodies[3] = add_kind(c, 2, v(0_q32, 16_q32));
  }
}

// --- 11. scripted forces, impulses, velocity sets and changes ---------------------
void build_scripted(SceneContext& c) {
  container(c, 14);
  for (int64_t i = 0; i < 8; ++i) c.bodies.push_back(add_kind(c, i, v(q(-10 + 3 * i), q(2 + i % 2)), q(i, 5)));
}
void script_scripted(SceneContext& c, int32_t tick) {
  auto b = [&](size_t i) { return c.bodies[i]; };
  if (tick % 120 == 0) {
    const size_t i = static_cast<size_t>(tick / 120) % 8;
    c.check(body_apply_linear_impulse_to_center(b(i), v(q(static_cast<int64_t>(i % 3) - 1, 2), 1_q32), true),
            "impulse to centre");
  }
  if (tick >= 300 && tick < 600) {
    c.check(body_apply_force_to_center(b(1), v(0_q32, q(15)), true), "force to centre");
  }
  if (tick >= 700 && tick < 760) c.check(body_apply_torque(b(2), q(3, 2), true), "torque");
  if (tick >= 800 && tick < 840) {
    const Vec2 p = body_world_point(b(3), v(q(1, 4), q(1, 8)));
    c.check(body_apply_force(b(3), v(q(3), q(20)), p, true), "force at point");
  }
  switch (tick) {
    case 900:
      c.check(body_set_linear_velocity(b(4), v(q(-3), q(5))), "set velocity");
      c.check(body_set_angular_velocity(b(4), q(4)), "set angular velocity");
      break;
    case 1100: {
      const Vec2 p = body_world_point(b(5), v(q(3, 10), 0_q32));
      c.check(body_apply_linear_impulse(b(5), v(0_q32, q(2)), p, true), "impulse at point");
      break;
    }
    case 1300: c.check(body_apply_angular_impulse(b(6), q(1, 2), true), "angular impulse"); break;
    case 1500: c.check(world_set_gravity(c.world, v(q(2), q(-5))), "gravity"); break;
    case 1700: c.check(body_set_gravity_scale(b(7), q(-1, 2)), "gravity scale"); break;
    case 1800: c.check(world_set_gravity(c.world, v(0_q32, q(-10))), "gravity"); break;
    case 1900:
      c.check(body_set_linear_damping(b(0), q(1, 2)), "linear damping");
      c.check(body_set_angular_damping(b(0), q(2)), "angular damping");
      c.check(body_set_gravity_scale(b(7), 1_q32), "gravity scale");
      break;
    case 2100:
      c.check(body_set_type(b(1), BodyType::kinematic_body), "to kinematic");
      c.check(body_set_linear_velocity(b(1), v(q(1), 0_q32)), "kinematic velocity");
      break;
    case 2400: c.check(body_set_type(b(1), BodyType::dynamic_body), "to dynamic"); break;
    case 2600: c.check(body_set_enabled(b(2), false), "disable"); break;
    case 2900: c.check(body_set_enabled(b(2), true), "enable"); break;
    case 3100: c.check(body_set_fixed_rotation(b(3), true), "fixed rotation"); break;
    case 3300: c.check(body_set_transform(b(4), v(q(0), q(10)), rot_from_angle(q(1))), "teleport"); break;
    case 3400: c.check(body_set_type(b(5), BodyType::static_body), "to static"); break;
    default: break;
  }
}

// --- 12. kinematic movers, compound and rounded bodies --------------------------
void build_kinematic(SceneContext& c) {
  container(c, 14);
  const BodyId paddle = body(c, BodyType::kinematic_body, v(0_q32, 4_q32));
  add_box(c, paddle, q(3), q(1, 5));
  c.check(body_set_angular_velocity(paddle, q(1)), "paddle spin");
  const BodyId platform = body(c, BodyType::kinematic_body, v(-8_q32, 8_q32), 0_q32, v(q(1), 0_q32));
  add_capsule(c, platform, v(-2_q32, 0_q32), v(2_q32, 0_q32), q(1, 4));
  c.bodies.push_back(platform);
  for (int64_t i = 0; i < 12; ++i) {
    const BodyId b = dyn(c, v(q(-10) + q(9 * i, 5), q(10) + q(i % 4, 1) * 2_q32), q(i, 6));
    add_offset_box(c, b, q(1, 2), q(1, 8), v(0_q32, 0_q32), 0_q32, q(i % 2, 20));
    add_offset_box(c, b, q(1, 8), q(1, 2), v(q(3, 8), 0_q32), 0_q32, 0_q32);
    if (i % 3 == 0) add_capsule(c, b, v(-1_q32 / 2, q(1, 2)), v(q(1, 2), q(1, 2)), q(1, 10));
  }
  BodyDef fixed = default_body_def();
  fixed.type = BodyType::dynamic_body;
  fixed.position = v(6_q32, 14_q32);
  fixed.fixed_rotation = true;
  const BodyId f = c.value(create_body(c.world, fixed), "create_body(fixed rotation)");
  add_ngon(c, f, 8, q(3, 5), q(1, 10));
}
void script_kinematic(SceneContext& c, int32_t tick) {
  if (tick % 300 == 0) {
    const Q32 speed = (tick / 300) % 2 == 1 ? -1_q32 : 1_q32;
    c.check(body_set_linear_velocity(c.bodies[0], v(speed, 0_q32)), "platform velocity");
  }
}

// --- 13. a seeded random mix inside a chain loop -------------------------------------
void build_random_mix(SceneContext& c) {
  const BodyId g = body(c, BodyType::static_body, {});
  // A clockwise octagon loop holds everything inside.
  const std::array<Vec2, 8> loop = {v(-6_q32, 26_q32), v(6_q32, 26_q32), v(14_q32, 18_q32), v(14_q32, 6_q32),
                                    v(6_q32, -2_q32),  v(-6_q32, -2_q32), v(-14_q32, 6_q32), v(-14_q32, 18_q32)};
  c.check(create_chain_shapes(g, mat(q(2, 5)), loop.data(), 8, true, nullptr), "create_chain_shapes(loop)");
  add_segment(c, g, v(-8_q32, 8_q32), v(-2_q32, 6_q32));
  add_capsule(c, g, v(3_q32, 9_q32), v(8_q32, 10_q32), q(1, 3));
  add_circle(c, g, 1_q32, v(0_q32, 2_q32));
  add_box(c, g, q(1, 2), q(1, 2));  // at the origin, under the circle
  std::mt19937_64 rng(0x601DE2);
  for (int64_t i = 0; i < 40; ++i) {
    const uint64_t r = rng();
    const Vec2 p = v(q(-10) + q(i % 8, 1) * 3_q32 - q(1), q(12) + q(i / 8, 1) * 2_q32);
    const BodyId b = dyn(c, p, Q32::from_raw(static_cast<int64_t>(r >> 34)));
    const ShapeDef sd = mat(q(static_cast<int64_t>(r % 5), 5), q(static_cast<int64_t>((r >> 8) % 4), 10));
    switch ((r >> 16) % 4) {
      case 0: add_circle(c, b, q(static_cast<int64_t>(3 + (r >> 20) % 5), 10), {}, sd); break;
      case 1: add_capsule(c, b, v(q(-1, 2), 0_q32), v(q(1, 2), 0_q32), q(static_cast<int64_t>(1 + (r >> 20) % 3), 10), sd); break;
      case 2: {
        std::array<Vec2, 8> pts{};
        const int32_t n = 3 + static_cast<int32_t>((r >> 24) % 6);
        for (int32_t k = 0; k < n; ++k) {  // random points on a 1 m box, hull taken by make_polygon_from_points
          const uint64_t s = rng();
          pts[static_cast<size_t>(k)] = v(Q32::from_raw(static_cast<int64_t>(s & 0xFFFFFFFFu) - (int64_t{1} << 31)),
                                          Q32::from_raw(static_cast<int64_t>(s >> 32) - (int64_t{1} << 31)));
        }
        Polygon poly;
        if (make_polygon_from_points(pts.data(), n, 0_q32, &poly).ok()) {
          c.check(create_polygon_shape(b, sd, poly).status, "create_polygon_shape(random)");
        } else {
          add_box(c, b, q(2, 5), q(1, 5), sd);  // degenerate hull: a box instead (same on every platform)
        }
        break;
      }
      default: add_box(c, b, q(static_cast<int64_t>(2 + (r >> 20) % 4), 10), q(3, 10), sd); break;
    }
  }
}
void script_random_mix(SceneContext& c, int32_t tick) {
  if (tick == 1800) {  // a heavy ball dropped into the settled pile
    add_circle(c, dyn(c, v(1_q32, 24_q32)), 1_q32, {}, mat(q(1, 2), 0_q32, 4_q32));
  }
}

constexpr Scene k_scenes[] = {
    {"circles", "circle-circle, circle-polygon; mixed friction and restitution", build_circles, nullptr},
    {"capsules", "capsule-capsule, capsule-circle, capsule-polygon", build_capsules, nullptr},
    {"pyramid", "polygon-polygon stacking, sleep, impulse wake at tick 2400, polygons dropped", build_pyramid,
     script_pyramid},
    {"segments", "segment vs circle, capsule and polygon; bodies created every second", build_segments,
     script_segments},
    {"chains", "chain segment vs circle, capsule and polygon; open chain and clockwise loop", build_chains,
     script_chains},
    {"friction_restitution", "friction 0..1 on a slope, restitution 0..1 bounces, sliding boxes",
     build_friction_restitution, nullptr},
    {"sleep_wake", "sleep; wake by touch, destroy, teleport, set_awake; enable_sleep per body and world",
     build_sleep_wake, script_sleep_wake},
    {"filtering", "category/mask layers, negative and positive groups, shape_set_filter mid-run", build_filtering,
     script_filtering},
    {"sensors", "static, kinematic and dynamic sensors, masked sensor, visitors created mid-run", build_sensors,
     script_sensors},
    {"create_destroy", "bodies created every 20 ticks, oldest destroyed, shapes destroyed, slot reuse",
     build_create_destroy, script_create_destroy},
    {"scripted", "forces, torques, impulses, velocity sets, gravity, damping, type changes, disable/enable",
     build_scripted, script_scripted},
    {"kinematic", "kinematic paddle and platform, compound and rounded bodies, fixed rotation", build_kinematic,
     script_kinematic},
    {"random_mix", "seeded random shapes in a chain loop with static segment, capsule, circle and box",
     build_random_mix, script_random_mix},
};

}  // namespace

extern const Scene k_joint_scenes[4];  // golden_joint_scenes.cpp

std::span<const Scene> scenes() {
  static const std::vector<Scene> all = [] {
    std::vector<Scene> v(std::begin(k_scenes), std::end(k_scenes));
    v.insert(v.end(), std::begin(k_joint_scenes), std::end(k_joint_scenes));
    return v;
  }();
  return all;
}

}  // namespace tandem::golden

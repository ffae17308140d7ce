// Tests for physics/events.cpp through the public API: contact begin/end
// (also on destroy), hit events and their approach speed, sensor begin/end,
// body move events, orders and stale handles. Every test asserts a number.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <iomanip>
#include <vector>

#include "physics/tandem.h"
#include "physics_test_support.h"

using namespace tandem;
using namespace tandem::test_support;

namespace {

ShapeDef material(Q32 friction, Q32 restitution, bool hit_events = false) {
  ShapeDef sd = default_shape_def();
  sd.friction = friction;
  sd.restitution = restitution;
  sd.enable_hit_events = hit_events;
  return sd;
}

/// A static box (half extents hw × hh) at `center`; returns its shape.
ShapeId add_static_box(WorldId w, Vec2 center, Q32 hw, Q32 hh, ShapeDef sd = default_shape_def()) {
  BodyDef def = default_body_def();
  def.position = center;
  Result<BodyId> b = create_body(w, def);
  REQUIRE(b.ok());
  Polygon box;
  REQUIRE(make_box(hw, hh, &box).ok());
  Result<ShapeId> s = create_polygon_shape(b.value, sd, box);
  REQUIRE(s.ok());
  return s.value;
}

/// The ground: a static box whose top face is y = 0, 200 m wide.
ShapeId add_ground(WorldId w, ShapeDef sd = default_shape_def()) {
  return add_static_box(w, {0_q32, -1_q32}, 100_q32, 1_q32, sd);
}

/// A dynamic ball; returns its shape.
ShapeId add_ball(WorldId w, Vec2 center, Q32 radius, ShapeDef sd = default_shape_def(), Vec2 velocity = {},
                 Q32 gravity_scale = Q32::one()) {
  BodyDef def = default_body_def();
  def.type = BodyType::dynamic_body;
  def.position = center;
  def.linear_velocity = velocity;
  def.gravity_scale = gravity_scale;
  Result<BodyId> b = create_body(w, def);
  REQUIRE(b.ok());
  Result<ShapeId> s = create_circle_shape(b.value, sd, Circle{{}, radius});
  REQUIRE(s.ok());
  return s.value;
}

}  // namespace

TEST_CASE("a bouncing ball gives one begin, then one end, with its shape ids", "[physics][events]") {
  ScopedWorld w;
  const ShapeId ground = add_ground(w.id, material(0_q32, 1_q32));
  const ShapeId ball = add_ball(w.id, {0_q32, 3.5_q32}, 0.5_q32, material(0_q32, 1_q32));
  int begins = 0, ends = 0, begin_step = -1, end_step = -1;
  for (int i = 0; i < 120 && ends == 0; ++i) {
    REQUIRE(world_step(w.id, k_dt).ok());
    const Result<ContactEvents> ev = world_contact_events(w.id);
    REQUIRE(ev.ok());
    for (const ContactBeginEvent& b : ev.value.begin) {
      ++begins;
      begin_step = i;
      CHECK(b.shape_a == ground);
      CHECK(b.shape_b == ball);
      CHECK(b.manifold.point_count == 1);
      CHECK(std::fabs(ld(b.manifold.normal.y) - 1.0L) < 1e-9L);
    }
    for (const ContactEndEvent& e : ev.value.end) {
      ++ends;
      end_step = i;
      CHECK(e.shape_a == ground);
      CHECK(e.shape_b == ball);
      CHECK(body_linear_velocity(shape_body(ball)).y > 0_q32);  // bouncing away
    }
    CHECK(ev.value.hit.empty());  // hit events are off by default
  }
  CHECK(begins == 1);
  CHECK(ends == 1);
  // Dropped 3 m: lands after √(2·3/10) s ≈ 0.775 s ≈ step 46; touching lasts
  // a few steps (speculative margin on the way down and up).
  CHECK(begin_step >= 42);
  CHECK(begin_step <= 47);
  CHECK(end_step > begin_step);
  CHECK(end_step <= begin_step + 4);
}

TEST_CASE("destroying a touching body reports an end event at the next step", "[physics][events]") {
  ScopedWorld w;
  const ShapeId ground = add_ground(w.id);
  const ShapeId ball = add_ball(w.id, {0_q32, 0.5_q32}, 0.5_q32);
  REQUIRE(world_step(w.id, k_dt).ok());
  Result<ContactEvents> ev = world_contact_events(w.id);
  REQUIRE(ev.ok());
  REQUIRE(ev.value.begin.size() == 1);
  for (int i = 0; i < 10; ++i) REQUIRE(world_step(w.id, k_dt).ok());
  ev = world_contact_events(w.id);
  CHECK(ev.value.begin.empty());
  CHECK(ev.value.end.empty());

  REQUIRE(destroy_body(shape_body(ball)).ok());
  ev = world_contact_events(w.id);
  CHECK(ev.value.end.empty());  // reported at the next step, not on destroy
  REQUIRE(world_step(w.id, k_dt).ok());
  ev = world_contact_events(w.id);
  REQUIRE(ev.value.end.size() == 1);
  CHECK(ev.value.end[0].shape_a == ground);
  CHECK(ev.value.end[0].shape_b == ball);  // the stale handle the shape had
  CHECK_FALSE(shape_is_valid(ev.value.end[0].shape_b));
  REQUIRE(world_step(w.id, k_dt).ok());
  CHECK(world_contact_events(w.id).value.end.empty());
}

TEST_CASE("hit events: approach speed matches sqrt(2gh) and the threshold applies", "[physics][events]") {
  for (const int height : {5, 20}) {
    ScopedWorld w;
    const ShapeId ground = add_ground(w.id, material(0_q32, 1_q32));
    const ShapeId ball =
        add_ball(w.id, {0_q32, Q32::from_int(height) + 0.5_q32}, 0.5_q32, material(0_q32, 1_q32, true));
    int hits = 0;
    long double speed = 0;
    Vec2 point, normal;
    for (int i = 0; i < 200; ++i) {
      REQUIRE(world_step(w.id, k_dt).ok());
      for (const ContactHitEvent& h : world_contact_events(w.id).value.hit) {
        ++hits;
        CHECK(h.shape_a == ground);
        CHECK(h.shape_b == ball);
        speed = ld(h.approach_speed);
        point = h.point;
        normal = h.normal;
      }
      if (hits > 0) break;
    }
    const long double expected = std::sqrt(2.0L * 10.0L * height);
    INFO("height " << height << " m: approach " << speed << " m/s, sqrt(2gh) " << expected);
    REQUIRE(hits == 1);
    WARN(std::setprecision(10) << "hit event from " << height << " m: approach " << static_cast<double>(speed) << " m/s, sqrt(2gh) "
                           << static_cast<double>(expected) << ", point y " << static_cast<double>(ld(point.y)));
    CHECK(std::fabs(speed / expected - 1.0L) < 0.01L);
    CHECK(std::fabs(ld(point.x)) < 1e-6L);
    // Midway between the surfaces at the step start, less than one step's
    // travel from touching: |y| < v·dt / 2.
    CHECK(std::fabs(ld(point.y)) < speed / 120.0L);
    CHECK(std::fabs(ld(normal.y) - 1.0L) < 1e-9L);
  }

  // Below the threshold: a ball resting on the ground, and a threshold
  // raised above the impact speed, give no hits.
  ScopedWorld w;
  add_ground(w.id, material(0_q32, 1_q32));
  add_ball(w.id, {0_q32, 5.5_q32}, 0.5_q32, material(0_q32, 1_q32, true));
  REQUIRE(world_set_hit_event_threshold(w.id, 10.5_q32).ok());  // impact ≈ 10 m/s
  CHECK(world_set_hit_event_threshold(w.id, -1_q32).code == StatusCode::invalid_argument);
  int hits = 0, begins = 0;
  for (int i = 0; i < 100; ++i) {
    REQUIRE(world_step(w.id, k_dt).ok());
    hits += static_cast<int>(world_contact_events(w.id).value.hit.size());
    begins += static_cast<int>(world_contact_events(w.id).value.begin.size());
  }
  CHECK(begins >= 1);
  CHECK(hits == 0);
}

TEST_CASE("sensor begin and end as a ball passes through a sensor box", "[physics][events]") {
  ScopedWorld w;
  ShapeDef sensor_def = default_shape_def();
  sensor_def.is_sensor = true;
  const ShapeId sensor = add_static_box(w.id, {0_q32, 5_q32}, 1_q32, 1_q32, sensor_def);
  // A ball at 5 m/s without gravity from x = −5: its edge reaches the box
  // (x = −1) when its centre is at −1.5 and leaves it at +1.5.
  const ShapeId ball = add_ball(w.id, {-5_q32, 5_q32}, 0.5_q32, default_shape_def(), {5_q32, 0_q32}, 0_q32);
  const BodyId body = shape_body(ball);
  int begins = 0, ends = 0;
  long double x_previous = -5;
  for (int i = 0; i < 180; ++i) {
    REQUIRE(world_step(w.id, k_dt).ok());
    const long double x = ld(body_position(body).x);
    const Result<SensorEvents> ev = world_sensor_events(w.id);
    REQUIRE(ev.ok());
    for (const SensorEvent& e : ev.value.begin) {
      ++begins;
      CHECK(e.sensor == sensor);
      CHECK(e.visitor == ball);
      CHECK(x >= -1.5L);
      CHECK(x_previous < -1.5L);
    }
    for (const SensorEvent& e : ev.value.end) {
      ++ends;
      CHECK(e.sensor == sensor);
      CHECK(e.visitor == ball);
      CHECK(x > 1.5L);
      CHECK(x_previous <= 1.5L);
    }
    x_previous = x;
  }
  CHECK(begins == 1);
  CHECK(ends == 1);
  CHECK(x_previous > 5.0L);  // the sensor did not push the ball
  // Sensors form no contacts.
  CHECK(world_contact_events(w.id).value.begin.empty());
}

TEST_CASE("move events only for bodies that moved, in body order", "[physics][events]") {
  ScopedWorld w;
  add_ground(w.id);                                                         // body 0, static
  const BodyId falling = shape_body(add_ball(w.id, {0_q32, 5_q32}, 0.5_q32));  // body 1
  const BodyId floating =
      shape_body(add_ball(w.id, {3_q32, 5_q32}, 0.5_q32, default_shape_def(), {}, 0_q32));  // body 2, at rest
  BodyDef kd = default_body_def();
  kd.type = BodyType::kinematic_body;
  kd.position = {-3_q32, 5_q32};
  kd.linear_velocity = {1_q32, 0_q32};
  const Result<BodyId> kinematic = create_body(w.id, kd);  // body 3
  REQUIRE(kinematic.ok());
  REQUIRE(world_step(w.id, k_dt).ok());
  const Result<BodyEvents> ev = world_body_events(w.id);
  REQUIRE(ev.ok());
  REQUIRE(ev.value.move.size() == 2);
  CHECK(ev.value.move[0].body == falling);
  CHECK(ev.value.move[1].body == kinematic.value);
  CHECK(ev.value.move[0].transform.p.y == body_position(falling).y);
  CHECK_FALSE(ev.value.move[0].fell_asleep);
  CHECK(body_position(floating).y == 5_q32);

  // A zero step changes nothing, events included.
  REQUIRE(world_step(w.id, 0_q32).ok());
  CHECK(world_body_events(w.id).value.move.size() == 2);
}

TEST_CASE("event getters refuse a stale world handle", "[physics][events]") {
  Result<WorldId> r = create_world(default_world_def());
  REQUIRE(r.ok());
  add_ground(r.value);
  add_ball(r.value, {0_q32, 0.5_q32}, 0.5_q32);
  REQUIRE(world_step(r.value, k_dt).ok());
  CHECK(world_contact_events(r.value).value.begin.size() == 1);
  REQUIRE(destroy_world(r.value).ok());
  const Result<ContactEvents> c = world_contact_events(r.value);
  CHECK(c.status.code == StatusCode::invalid_handle);
  CHECK(c.value.begin.empty());
  CHECK(world_sensor_events(r.value).status.code == StatusCode::invalid_handle);
  CHECK(world_body_events(r.value).status.code == StatusCode::invalid_handle);
  CHECK(world_contact_events(WorldId{}).status.code == StatusCode::null_handle);
}

namespace {

uint64_t pair_key(ShapeId a, ShapeId b) { return (uint64_t{a.index1} << 32) | b.index1; }

/// A pile of balls and a sensor strip on the ground, all shapes with hit
/// events; returns the number of balls.
int build_pile(WorldId w) {
  add_ground(w, material(0.6_q32, 0.5_q32, true));
  ShapeDef sensor_def = default_shape_def();
  sensor_def.is_sensor = true;
  add_static_box(w, {0_q32, 1_q32}, 20_q32, 0.5_q32, sensor_def);
  int n = 0;
  for (int row = 0; row < 6; ++row) {
    for (int col = 0; col < 8; ++col) {
      const Vec2 p{Q32::from_int(col - 4) + Q32::from_ratio(row % 2, 2), Q32::from_int(2 + 2 * row)};
      add_ball(w, p, 0.45_q32, material(0.6_q32, 0.5_q32, true));
      ++n;
    }
  }
  return n;
}

}  // namespace

TEST_CASE("event lists are sorted by their keys and identical in identical worlds", "[physics][events]") {
  ScopedWorld w1, w2;
  build_pile(w1.id);
  build_pile(w2.id);
  int begins = 0, ends = 0, hits = 0, sensor_begins = 0, sensor_ends = 0, moves = 0;
  for (int i = 0; i < 240; ++i) {
    REQUIRE(world_step(w1.id, k_dt).ok());
    REQUIRE(world_step(w2.id, k_dt).ok());
    const ContactEvents c1 = world_contact_events(w1.id).value, c2 = world_contact_events(w2.id).value;
    const SensorEvents s1 = world_sensor_events(w1.id).value, s2 = world_sensor_events(w2.id).value;
    const BodyEvents b1 = world_body_events(w1.id).value, b2 = world_body_events(w2.id).value;
    REQUIRE(c1.begin.size() == c2.begin.size());
    REQUIRE(c1.end.size() == c2.end.size());
    REQUIRE(c1.hit.size() == c2.hit.size());
    REQUIRE(s1.begin.size() == s2.begin.size());
    REQUIRE(s1.end.size() == s2.end.size());
    REQUIRE(b1.move.size() == b2.move.size());
    for (size_t k = 0; k < c1.begin.size(); ++k) {
      CHECK(c1.begin[k].shape_a.index1 < c1.begin[k].shape_b.index1);
      CHECK(c1.begin[k].shape_b.index1 == c2.begin[k].shape_b.index1);
      if (k > 0) CHECK(pair_key(c1.begin[k - 1].shape_a, c1.begin[k - 1].shape_b) <
                       pair_key(c1.begin[k].shape_a, c1.begin[k].shape_b));
    }
    for (size_t k = 1; k < c1.end.size(); ++k) {
      CHECK(pair_key(c1.end[k - 1].shape_a, c1.end[k - 1].shape_b) < pair_key(c1.end[k].shape_a, c1.end[k].shape_b));
    }
    for (size_t k = 0; k < c1.hit.size(); ++k) {
      CHECK(c1.hit[k].approach_speed.raw == c2.hit[k].approach_speed.raw);
      CHECK(c1.hit[k].approach_speed > 1_q32);
      if (k > 0) CHECK(pair_key(c1.hit[k - 1].shape_a, c1.hit[k - 1].shape_b) <
                       pair_key(c1.hit[k].shape_a, c1.hit[k].shape_b));
    }
    for (size_t k = 1; k < s1.begin.size(); ++k) {
      CHECK(pair_key(s1.begin[k - 1].sensor, s1.begin[k - 1].visitor) <
            pair_key(s1.begin[k].sensor, s1.begin[k].visitor));
    }
    for (size_t k = 0; k < b1.move.size(); ++k) {
      CHECK(b1.move[k].transform.p.y.raw == b2.move[k].transform.p.y.raw);
      if (k > 0) CHECK(b1.move[k - 1].body.index1 < b1.move[k].body.index1);
    }
    begins += static_cast<int>(c1.begin.size());
    ends += static_cast<int>(c1.end.size());
    hits += static_cast<int>(c1.hit.size());
    sensor_begins += static_cast<int>(s1.begin.size());
    sensor_ends += static_cast<int>(s1.end.size());
    moves += static_cast<int>(b1.move.size());
  }
  WARN("pile of 48 balls, 240 steps: contact begin " << begins << ", end " << ends << ", hit " << hits
                                                     << ", sensor begin " << sensor_begins << ", end " << sensor_ends
                                                     << ", moves " << moves);
  CHECK(begins > 48);         // every ball lands, and balls touch each other
  CHECK(hits >= 48);          // every ball lands faster than 1 m/s
  CHECK(sensor_begins >= 48); // every ball reaches the strip (top at y = 1.5)
  CHECK(moves > 48);
}

TEST_CASE("a visitor destroyed inside a sensor ends its overlap at the next step", "[physics][events]") {
  ScopedWorld w;
  ShapeDef sensor_def = default_shape_def();
  sensor_def.is_sensor = true;
  const ShapeId sensor = add_static_box(w.id, {0_q32, 5_q32}, 2_q32, 2_q32, sensor_def);
  const ShapeId inside = add_ball(w.id, {0_q32, 5_q32}, 0.5_q32, default_shape_def(), {}, 0_q32);
  const ShapeId outside = add_ball(w.id, {5_q32, 5_q32}, 0.5_q32, default_shape_def(), {}, 0_q32);
  REQUIRE(world_step(w.id, k_dt).ok());
  SensorEvents ev = world_sensor_events(w.id).value;
  REQUIRE(ev.begin.size() == 1);
  CHECK(ev.begin[0].sensor == sensor);
  CHECK(ev.begin[0].visitor == inside);
  REQUIRE(world_step(w.id, k_dt).ok());
  CHECK(world_sensor_events(w.id).value.begin.empty());
  REQUIRE(destroy_shape(inside).ok());
  REQUIRE(world_step(w.id, k_dt).ok());
  ev = world_sensor_events(w.id).value;
  REQUIRE(ev.end.size() == 1);
  CHECK(ev.end[0].sensor == sensor);
  CHECK(ev.end[0].visitor == inside);
  CHECK_FALSE(shape_is_valid(ev.end[0].visitor));
  CHECK(ev.begin.empty());
  // Teleporting the other ball into the sensor begins an overlap at the next step.
  REQUIRE(body_set_transform(shape_body(outside), {1_q32, 5_q32}, rot_identity()).ok());
  REQUIRE(world_step(w.id, k_dt).ok());
  ev = world_sensor_events(w.id).value;
  REQUIRE(ev.begin.size() == 1);
  CHECK(ev.begin[0].visitor == outside);
}

TEST_CASE("move events say when a body fell asleep", "[physics][events][sleep]") {
  ScopedWorld w;
  BodyId ground = create_body(w.id, default_body_def()).value;
  Polygon ground_box;
  REQUIRE(make_offset_box(10_q32, 1_q32, Vec2{0_q32, -1_q32}, 0_q32, 0_q32, &ground_box).ok());
  REQUIRE(create_polygon_shape(ground, default_shape_def(), ground_box).ok());
  BodyDef bd = default_body_def();
  bd.type = BodyType::dynamic_body;
  bd.position = {0_q32, 1_q32};
  const BodyId box = create_body(w.id, bd).value;
  Polygon square;
  REQUIRE(make_box(0.5_q32, 0.5_q32, &square).ok());
  REQUIRE(create_polygon_shape(box, default_shape_def(), square).ok());
  int slept_at = -1, reported_at = -1;
  for (int tick = 1; tick <= 300 && slept_at < 0; ++tick) {
    REQUIRE(world_step(w.id, k_dt).ok());
    for (const BodyMoveEvent& m : world_body_events(w.id).value.move) {
      if (m.body == box && m.fell_asleep) reported_at = tick;
    }
    if (!body_is_awake(box)) slept_at = tick;
  }
  INFO("slept at tick " << slept_at << ", reported at tick " << reported_at);
  REQUIRE(slept_at > 0);
  CHECK(reported_at == slept_at);
  // Asleep: no more move events for it.
  REQUIRE(world_step(w.id, k_dt).ok());
  CHECK(world_body_events(w.id).value.move.empty());
}

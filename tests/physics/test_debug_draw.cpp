// Tests for world_draw (physics/debug_draw.h): which callbacks run, in what
// order, with which world coordinates; AABB and contact switches; refusals.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "physics/debug_draw.h"
#include "physics/tandem.h"

using namespace tandem;
using namespace tandem::literals;

namespace {

struct Log {
  std::vector<std::string> calls;
  std::vector<Vec2> points;    // circle centres, rims, polygon vertices in call order
  std::vector<DrawShape> shapes;
  int contacts = 0;
  int touching = 0;
  int aabbs = 0;
  int joints = 0;
};

Log& L(void* c) { return *static_cast<Log*>(c); }

DebugDraw recorder(Log* log) {
  DebugDraw dd;
  dd.context = log;
  dd.draw_polygon = [](const Vec2* v, int32_t n, Q32, const DrawShape& s, void* c) {
    L(c).calls.push_back("polygon" + std::to_string(n));
    L(c).shapes.push_back(s);
    for (int32_t i = 0; i < n; ++i) L(c).points.push_back(v[i]);
  };
  dd.draw_circle = [](Vec2 center, Q32, Vec2 rim, const DrawShape& s, void* c) {
    L(c).calls.push_back("circle");
    L(c).shapes.push_back(s);
    L(c).points.push_back(center);
    L(c).points.push_back(rim);
  };
  dd.draw_capsule = [](Vec2, Vec2, Q32, const DrawShape& s, void* c) {
    L(c).calls.push_back("capsule");
    L(c).shapes.push_back(s);
  };
  dd.draw_segment = [](Vec2, Vec2, const DrawShape& s, void* c) {
    L(c).calls.push_back(s.type == ShapeType::chain_segment ? "chain" : "segment");
    L(c).shapes.push_back(s);
  };
  dd.draw_aabb = [](const AABB&, const DrawShape&, void* c) { ++L(c).aabbs; };
  dd.draw_joint = [](JointId, JointType type, Vec2, Vec2 a, Vec2 b, Vec2, void* c) {
    ++L(c).joints;
    L(c).calls.push_back("joint" + std::to_string(static_cast<int>(type)));
    L(c).points.push_back(a);
    L(c).points.push_back(b);
  };
  dd.draw_contact = [](Vec2, Vec2, Q32 separation, void* c) {
    ++L(c).contacts;
    if (separation <= Q32{}) ++L(c).touching;
  };
  return dd;
}

}  // namespace

TEST_CASE("world_draw calls one callback per shape, in body order, in world metres", "[physics][debug_draw]") {
  const WorldId w = create_world(default_world_def()).value;
  // Body 0: static ground box 10 × 1, its top at y = 0, plus a segment and a chain loop.
  BodyDef ground_def = default_body_def();
  ground_def.position = Vec2{0_q32, -1_q32};
  const BodyId ground = create_body(w, ground_def).value;
  Polygon box;
  REQUIRE(make_box(5_q32, 1_q32, &box).ok());
  REQUIRE(create_polygon_shape(ground, default_shape_def(), box).ok());
  REQUIRE(create_segment_shape(ground, default_shape_def(), Segment{{-5_q32, 3_q32}, {5_q32, 3_q32}}).ok());
  const Vec2 loop[4] = {{-6_q32, 0_q32}, {-6_q32, 8_q32}, {6_q32, 8_q32}, {6_q32, 0_q32}};
  REQUIRE(create_chain_shapes(ground, default_shape_def(), loop, 4, true, nullptr).ok());
  // Body 1: a dynamic ball at (1, 0.5) resting on the ground, rotated a quarter turn.
  BodyDef ball_def = default_body_def();
  ball_def.type = BodyType::dynamic_body;
  ball_def.position = Vec2{1_q32, 0.5_q32};
  ball_def.rotation = Rot{0_q32, 1_q32};
  const BodyId ball = create_body(w, ball_def).value;
  REQUIRE(create_circle_shape(ball, default_shape_def(), Circle{{0_q32, 0_q32}, 0.5_q32}).ok());
  // Body 2: a dynamic capsule with a sensor circle, jointed to the ball.
  BodyDef cap_def = default_body_def();
  cap_def.type = BodyType::dynamic_body;
  cap_def.position = Vec2{-2_q32, 2_q32};
  const BodyId cap = create_body(w, cap_def).value;
  REQUIRE(create_capsule_shape(cap, default_shape_def(), Capsule{{-0.5_q32, 0_q32}, {0.5_q32, 0_q32}, 0.25_q32}).ok());
  ShapeDef sensor = default_shape_def();
  sensor.is_sensor = true;
  REQUIRE(create_circle_shape(cap, sensor, Circle{{0_q32, 1_q32}, 0.25_q32}).ok());
  RevoluteJointDef jd = default_revolute_joint_def();
  jd.base.body_a = ball;
  jd.base.body_b = cap;
  jd.base.local_anchor_a = Vec2{0_q32, 1_q32};
  jd.base.local_anchor_b = Vec2{2_q32, -1.5_q32};  // the same world point: no gap for the position pass to close
  REQUIRE(create_revolute_joint(w, jd).ok());

  Log log;
  DebugDraw dd = recorder(&log);
  REQUIRE(world_draw(w, dd).ok());
  const std::vector<std::string> expected = {"polygon4", "segment", "chain", "chain", "chain", "chain",
                                             "circle",   "capsule", "circle", "joint0"};
  CHECK(log.calls == expected);
  REQUIRE(log.shapes.size() == 9);
  CHECK(log.shapes[0].state == DrawBodyState::static_body);
  CHECK(log.shapes[6].state == DrawBodyState::awake);
  CHECK(log.shapes[6].body == ball);
  CHECK_FALSE(log.shapes[7].sensor);
  CHECK(log.shapes[8].sensor);
  // Ground box vertices in world metres: body at y = −1, half height 1.
  CHECK(log.points[0] == Vec2{-5_q32, -2_q32});
  CHECK(log.points[2] == Vec2{5_q32, 0_q32});
  // Ball: centre at its body position; rim a radius along its local x, which a quarter turn points up.
  CHECK(log.points[4] == Vec2{1_q32, 0.5_q32});
  CHECK(log.points[5] == Vec2{1_q32, 1_q32});
  // Joint anchors: A's local (0, 1) rotated a quarter turn is (−1, 0) from the ball; B's local (2, −1.5)
  // from the capsule at (−2, 2): the same world point.
  CHECK(log.points[log.points.size() - 2] == Vec2{0_q32, 0.5_q32});
  CHECK(log.points[log.points.size() - 1] == Vec2{0_q32, 0.5_q32});
  CHECK(log.aabbs == 0);
  CHECK(log.contacts == 0);

  // AABBs: one per shape; joints off; contacts after a few steps (the ball touches the ground).
  for (int i = 0; i < 10; ++i) REQUIRE(world_step(w, Q32::from_ratio(1, 60)).ok());
  Log log2;
  DebugDraw dd2 = recorder(&log2);
  dd2.draw_aabbs = true;
  dd2.draw_joints = false;
  dd2.draw_contacts = true;
  REQUIRE(world_draw(w, dd2).ok());
  CHECK(log2.aabbs == 9);
  CHECK(log2.joints == 0);
  CHECK(log2.contacts >= 1);
  CHECK(log2.touching >= 1);

  // Shapes off, null callbacks: nothing but what is asked.
  Log log3;
  DebugDraw dd3;
  dd3.context = &log3;
  dd3.draw_shapes = false;
  REQUIRE(world_draw(w, dd3).ok());
  CHECK(log3.calls.empty());

  REQUIRE(destroy_world(w).ok());
  const Status gone = world_draw(w, dd);
  CHECK(gone.code == StatusCode::invalid_handle);
  CHECK(world_draw(WorldId{}, dd).code == StatusCode::null_handle);
}

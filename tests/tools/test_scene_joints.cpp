// Scene files with a "joints" array (tools/scene, docs/scene-format.md):
// bodies by name or index, world anchors turned into body frames, errors
// with JSON pointers, refusals by the joint API carrying the joint's
// pointer, and the scene's create commands (bodies then joints) building the
// same world as build_world.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "replay/state.h"
#include "scene/scene.h"

using namespace tandem;
using namespace tandem::scene;

namespace {

const char* const k_scene = R"({
  "bodies": [
    {"name": "ground", "shapes": [{"type": "box", "half_width": 20, "half_height": 0.5, "center": [0, -0.5]}]},
    {"name": "arm", "type": "dynamic", "position": [1, 5], "shapes": [{"type": "box", "half_width": 1, "half_height": 0.1}]},
    {"name": "ball", "type": "dynamic", "position": [3, 6], "shapes": [{"type": "circle", "radius": 0.25}]},
    {"type": "dynamic", "position": [-5, 2], "shapes": [{"type": "box", "half_width": 0.3, "half_height": 0.3}]}
  ],
  "joints": [
    {"type": "revolute", "body_a": "ground", "body_b": "arm", "anchor": [0, 5], "limit": [-0.5, 0.5],
     "motor_speed": 1, "max_motor_force": 50},
    {"type": "rope", "body_a": "arm", "body_b": "ball", "anchor_a": [2, 5], "anchor_b": [3, 6]},
    {"type": "prismatic", "body_a": 0, "body_b": 3, "axis": [0, 1], "limit": [-1, 1], "hertz": 2, "damping_ratio": 0.1}
  ]
})";

}  // namespace

TEST_CASE("scene joints: loaded, built and stepped; the create commands build the same world", "[scene][joint]") {
  Result<Scene> s = load_scene_text(k_scene, "joints.json");
  INFO(s.status.message);
  REQUIRE(s.ok());
  REQUIRE(s.value.joints.size() == 3);
  CHECK(s.value.joints[0].spec.local_anchor_b == Vec2{Q32::from_int(-1), Q32::zero()});  // (0, 5) in the arm's frame
  CHECK(s.value.joints[1].spec.length == distance(Vec2{Q32::from_int(2), Q32::from_int(5)},
                                                  Vec2{Q32::from_int(3), Q32::from_int(6)}));
  Result<BuiltScene> built = build_world(s.value);
  INFO(built.status.message);
  REQUIRE(built.ok());
  CHECK(world_counters(built.value.world).joint_count == 3);
  for (int t = 0; t < 120; ++t) REQUIRE(world_step(built.value.world, s.value.time_step).ok());

  WorldId again = create_world(s.value.world).value;
  for (const Command& c : scene_create_commands(s.value)) REQUIRE(apply_command(again, c).ok());
  for (int t = 0; t < 120; ++t) REQUIRE(world_step(again, s.value.time_step).ok());
  CHECK(world_state_hash(again) == world_state_hash(built.value.world));
  CHECK(destroy_world(again).ok());
  CHECK(destroy_world(built.value.world).ok());
}

TEST_CASE("scene joints: errors carry the JSON pointer", "[scene][joint]") {
  const auto error = [](const std::string& joints) {
    const std::string text = R"({"bodies": [{"name": "a"}, {"name": "b", "type": "dynamic"}], "joints": [)" + joints + "]}";
    Result<Scene> s = load_scene_text(text, "j.json");
    if (!s.ok()) return s.status.message;
    Result<BuiltScene> b = build_world(s.value);
    if (b.ok()) CHECK(destroy_world(b.value.world).ok());
    return b.status.message;
  };
  CHECK(error(R"({"type": "hinge", "body_a": 0, "body_b": 1})").find("j.json: /joints/0/type: unknown value \"hinge\"; expected one of") == 0);
  CHECK(error(R"({"type": "weld", "body_a": "nobody", "body_b": 1})") ==
        "j.json: /joints/0/body_a: no body is named \"nobody\"");
  CHECK(error(R"({"type": "weld", "body_a": 0, "body_b": 1, "stiffness": 3})").find("/joints/0/stiffness: unknown key") !=
        std::string::npos);
  CHECK(error(R"({"type": "weld", "body_a": 1, "body_b": 1})")
            .find("j.json: /joints/0: create_joint: create_weld_joint: WeldJointDef.base.body_a and base.body_b are "
                  "the same") == 0);
  CHECK(error(R"({"type": "distance", "body_a": 0, "body_b": 1, "length": 0})")
            .find("/joints/0: create_joint: create_distance_joint: DistanceJointDef.length 0 m is outside") !=
        std::string::npos);
  CHECK(error(R"({"type": "revolute", "body_a": 0, "body_b": 1, "limit": [1, -1]})")
            .find("RevoluteJointDef.lower_angle 1 is above RevoluteJointDef.upper_angle -1") != std::string::npos);
}

namespace {

double to_d(Q32 v) { return static_cast<double>(v.raw) / 4294967296.0; }

/// |world anchor B − world anchor A| of every live revolute or wheel joint of
/// a scene world (those whose anchors coincide), the worst, m.
double worst_pin_separation(WorldId world, size_t joints) {
  double worst = 0;
  for (size_t i = 0; i < joints; ++i) {
    const JointId j = joint_id(world, JointRef{static_cast<uint32_t>(i), 1});
    if (!joint_is_valid(j) || joint_type(j) != JointType::revolute) continue;
    const Vec2 a = joint_world_anchor_a(j), b = joint_world_anchor_b(j);
    worst = std::max(worst, std::hypot(to_d(b.x - a.x), to_d(b.y - a.y)));
  }
  return worst;
}

struct SceneRun {
  Scene scene;
  BuiltScene built;
};

SceneRun load_bundled(const std::string& name) {
  Result<Scene> s = load_scene_file(std::string(TANDEM_SOURCE_DIR) + "/scenes/" + name + ".json");
  INFO(s.status.message);
  REQUIRE(s.ok());
  Result<BuiltScene> b = build_world(s.value);
  INFO(b.status.message);
  REQUIRE(b.ok());
  return SceneRun{s.value, b.value};
}

void step(SceneRun& r, int64_t tick) {
  REQUIRE(apply_scene_inputs(r.built, r.scene, tick).ok());
  REQUIRE(world_step(r.built.world, r.scene.time_step).ok());
}

}  // namespace

// The bundled joint scenes (scenes/*.json) do what their descriptions say,
// with the figures asserted (measured in every build; the values printed by
// WARN are the ones docs and the report quote).
TEST_CASE("bundled joint scenes: pendulum, chain, ragdolls, car and grappling hook", "[scene][joint]") {
  SECTION("pendulum: the 1 m bob keeps its 0.2 rad amplitude; the chaotic double pendulum stays pinned") {
    SceneRun r = load_bundled("pendulum");
    const BodyId bob = r.built.bodies[1];
    double amplitude = 0, worst = 0;
    for (int64_t t = 0; t < r.scene.ticks; ++t) {
      step(r, t);
      const Vec2 p = body_position(bob);
      amplitude = std::max(amplitude, std::abs(std::atan2(to_d(p.x), 4.0 - to_d(p.y))));
      worst = std::max(worst, worst_pin_separation(r.built.world, r.scene.joints.size()));
    }
    WARN("pendulum.json: amplitude " << amplitude << " rad (released at 0.2), worst pin separation "
                                     << 1000 * worst << " mm over " << r.scene.ticks << " ticks");
    CHECK(amplitude < 0.2 * 1.01);
    CHECK(amplitude > 0.2 * 0.97);
    CHECK(worst < 0.01);
    CHECK(destroy_world(r.built.world).ok());
  }
  SECTION("chain50: 51 joints hold the swinging chain and its weight together") {
    SceneRun r = load_bundled("chain50");
    double worst = 0;
    for (int64_t t = 0; t < r.scene.ticks; ++t) {
      step(r, t);
      worst = std::max(worst, worst_pin_separation(r.built.world, r.scene.joints.size()));
    }
    const Vec2 weight = body_position(r.built.bodies[51]);
    WARN("chain50.json: worst joint separation " << 1000 * worst << " mm; weight at (" << to_d(weight.x) << ", "
                                                 << to_d(weight.y) << ")");
    CHECK(world_counters(r.built.world).joint_count == 51);
    CHECK(worst < 0.04);  // measured 28 mm: a 50-link chain stretches like the bridge
    CHECK(to_d(weight.y) > 0.0);  // above the ground, hanging
    CHECK(destroy_world(r.built.world).ok());
  }
  SECTION("ragdolls: down the stairs, joints within the stated stretch, nothing escapes") {
    SceneRun r = load_bundled("ragdolls");
    double worst = 0, resting = 0;
    bool escaped = false;
    for (int64_t t = 0; t < r.scene.ticks; ++t) {
      step(r, t);
      const double now = worst_pin_separation(r.built.world, r.scene.joints.size());
      worst = std::max(worst, now);
      if (t >= r.scene.ticks - 120) resting = std::max(resting, now);
      for (size_t i = 1; i < r.built.bodies.size(); ++i) {
        const Vec2 p = body_position(r.built.bodies[i]);
        if (to_d(p.x) < -12.5 || to_d(p.x) > 19.5 || to_d(p.y) < 0.0) escaped = true;
      }
    }
    double lowest = 1e9;  // the lowest torso: at least one ragdoll reached the floor
    for (size_t k = 0; k < 6; ++k) lowest = std::min(lowest, to_d(body_position(r.built.bodies[1 + 10 * k]).y));
    WARN("ragdolls.json: worst joint separation " << 1000 * worst << " mm, " << 1000 * resting
                                                  << " mm over the last 2 s; lowest torso at y " << lowest);
    CHECK(worst < 0.01);      // measured 7.3 mm (110 mm without the rigid position pass)
    CHECK(resting < 0.004);   // the pass's 3 mm slop
    CHECK(lowest < 1.0);
    CHECK_FALSE(escaped);
    CHECK(destroy_world(r.built.world).ok());
  }
  SECTION("car: the wheel motors drive it over the chain ground, stop it, and back it up") {
    SceneRun r = load_bundled("car");
    const BodyId chassis = r.built.bodies[1];
    const double x0 = to_d(body_position(chassis).x);
    double x600 = 0, x720 = 0, min_y = 1e9, max_tilt = 0;
    for (int64_t t = 0; t < r.scene.ticks; ++t) {
      step(r, t);
      const double x = to_d(body_position(chassis).x);
      if (t + 1 == 600) x600 = x;
      if (t + 1 == 720) x720 = x;
      min_y = std::min(min_y, to_d(body_position(chassis).y));
      max_tilt = std::max(max_tilt, std::abs(to_d(body_angle(chassis))));
    }
    const double x900 = to_d(body_position(chassis).x);
    WARN("car.json: chassis x " << x0 << " -> " << x600 << " m at tick 600 (motors stop), " << x720
                                << " at 720 (reverse), " << x900 << " at 900; lowest y " << min_y << ", max tilt "
                                << max_tilt << " rad");
    CHECK(x600 - x0 > 20.0);
    CHECK(x900 < x720 - 1.0);
    CHECK(min_y > -2.0);     // on the ground, never through it
    CHECK(max_tilt < 1.0);   // never rolled over
    CHECK(destroy_world(r.built.world).ok());
  }
  SECTION("grappling_hook: the rope never stretches past its reel, pulls only, and releases at tick 470") {
    SceneRun r = load_bundled("grappling_hook");
    const BodyId player = r.built.bodies[2];
    const JointId rope = joint_id(r.built.world, JointRef{0, 1});
    Q32 reel = r.scene.joints[0].spec.upper;
    double worst_over = -1e9, shortest = 1e9;
    double x_release = 0;
    for (int64_t t = 0; t < r.scene.ticks; ++t) {
      for (const SceneInput& in : r.scene.inputs)
        if (in.tick == t && in.command.type == CommandType::set_joint_limits) reel = in.command.scalar2;
      step(r, t);
      if (t + 1 < 470) {
        REQUIRE(joint_is_valid(rope));
        const Vec2 a = joint_world_anchor_a(rope), b = joint_world_anchor_b(rope);
        const double len = std::hypot(to_d(b.x - a.x), to_d(b.y - a.y));
        worst_over = std::max(worst_over, len - to_d(reel));
        shortest = std::min(shortest, to_d(reel));
      }
      if (t + 1 == 470) x_release = to_d(body_position(player).x);
    }
    WARN("grappling_hook.json: rope at most " << 1000 * worst_over << " mm past its reel (reeled to " << shortest
                                              << " m); player x " << x_release << " at release, "
                                              << to_d(body_position(player).x) << " at the end");
    CHECK(worst_over < 0.05);
    CHECK(shortest < 7.0);
    CHECK_FALSE(joint_is_valid(rope));
    CHECK(world_counters(r.built.world).joint_count == 0);
    CHECK(destroy_world(r.built.world).ok());
  }
}

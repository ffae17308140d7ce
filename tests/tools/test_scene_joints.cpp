// Scene files with a "joints" array (tools/scene, docs/scene-format.md):
// bodies by name or index, world anchors turned into body frames, errors
// with JSON pointers, refusals by the joint API carrying the joint's
// pointer, and the scene's create commands (bodies then joints) building the
// same world as build_world.
#include <catch2/catch.hpp>

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

// Joint commands (replay/joint_commands.cpp): encode/decode round trips with
// every field set, malformed input refused with offsets, application through
// the joint API with errors naming the command and the joint, and a recorded
// command stream replayed into a fresh world bit-identically.
#include <catch2/catch.hpp>

#include <functional>
#include <utility>
#include <vector>

#include "replay/commands.h"
#include "replay/state.h"

using namespace tandem;
using namespace tandem::literals;

namespace {

std::vector<Command> joint_commands() {
  std::vector<Command> out;
  JointSpec s;
  s.type = JointType::wheel;
  s.body_a = {1, 1};
  s.body_b = {2, 3};
  s.local_anchor_a = {0.5_q32, -0.25_q32};
  s.local_anchor_b = {Q32::from_raw(-7), 1_q32};
  s.collide_connected = true;
  s.break_force = 100_q32;
  s.break_torque = 50_q32;
  s.user_data = 0x0123456789ABCDEFull;
  s.local_axis = {0_q32, 1_q32};
  s.reference_angle = 0.5_q32;
  s.enable_spring = true;
  s.enable_limit = true;
  s.enable_motor = true;
  s.hertz = 4_q32;
  s.damping_ratio = 0.7_q32;
  s.angular_hertz = 3_q32;
  s.angular_damping_ratio = 0.2_q32;
  s.length = 2_q32;
  s.lower = -1_q32;
  s.upper = 1_q32;
  s.motor_speed = 3_q32;
  s.motor_force = 20_q32;
  s.target = {4_q32, 5_q32};
  s.angular_offset = 0.25_q32;
  s.max_force = 300_q32;
  s.max_torque = 30_q32;
  s.correction_factor = 0.5_q32;
  out.push_back(make_create_joint(s));
  out.push_back(make_destroy_joint({3, 2}));
  out.push_back(make_set_joint_motor_speed({0, 1}, -2_q32));
  out.push_back(make_set_joint_target({1, 1}, {Q32::from_raw(5), -3_q32}));
  out.push_back(make_set_joint_length({2, 7}, 1.5_q32));
  out.push_back(make_set_joint_limits({4, 1}, 0_q32, 6_q32));
  out.push_back(make_enable_joint_motor({5, 1}, true));
  out.push_back(make_set_joint_max_motor_force({5, 2}, 40_q32));
  out.push_back(make_enable_joint_limit({6, 1}, false));
  out.push_back(make_enable_joint_spring({6, 3}, true));
  out.push_back(make_set_joint_spring({7, 1}, 2.5_q32, 0.3_q32));
  out.push_back(make_set_joint_offsets({8, 1}, {1_q32, Q32::from_raw(-9)}, 0.75_q32));
  out.push_back(make_set_joint_break_thresholds({9, 4}, 500_q32, 60_q32));
  return out;
}

}  // namespace

TEST_CASE("joint commands: every type round-trips through its encoding", "[replay][commands][joint]") {
  const std::vector<Command> all = joint_commands();
  std::vector<uint8_t> bytes;
  ByteWriter w(&bytes);
  encode_commands(w, all);
  ByteReader r(bytes);
  std::vector<Command> back;
  REQUIRE(decode_commands(&r, &back).ok());
  CHECK(r.at_end());
  REQUIRE(back.size() == all.size());
  for (size_t i = 0; i < all.size(); ++i) {
    INFO(describe(all[i]));
    CHECK(back[i] == all[i]);
  }
  CHECK(describe(all[2]) == "set_joint_motor_speed joint {index 0, generation 1}");
  // Every truncation is refused, never a crash.
  for (size_t cut = 0; cut < bytes.size(); ++cut) {
    ByteReader t(std::span<const uint8_t>(bytes.data(), cut));
    std::vector<Command> partial;
    CHECK_FALSE(decode_commands(&t, &partial).ok());
  }
  // An unknown joint type names its offset.
  std::vector<uint8_t> one;
  ByteWriter w1(&one);
  encode_command(w1, all[0]);
  one[1] = 9;
  ByteReader r1(one);
  Command c;
  CHECK_FALSE(decode_command(&r1, &c).ok());
  CHECK(r1.error().find("offset 1: expected joint type 0..6, got 9") != std::string::npos);
}

TEST_CASE("joint commands: every setter changes the world as the joint API call does", "[replay][commands][joint]") {
  // Two worlds with a motorised revolute joint and a motor joint: one is
  // changed through the commands, the other through the API; their state
  // hashes agree after each change and after stepping, and each change
  // changes the hash.
  const auto make = [](WorldId* world, JointId* hinge, JointId* motor) {
    *world = create_world(default_world_def()).value;
    const BodyId ground = create_body(*world, default_body_def()).value;
    BodyDef dd = default_body_def();
    dd.type = BodyType::dynamic_body;
    dd.position = {1_q32, 0_q32};
    const BodyId arm = create_body(*world, dd).value;
    REQUIRE(create_circle_shape(arm, default_shape_def(), Circle{{}, 0.25_q32}).ok());
    dd.position = {3_q32, 0_q32};
    const BodyId box = create_body(*world, dd).value;
    REQUIRE(create_circle_shape(box, default_shape_def(), Circle{{}, 0.25_q32}).ok());
    RevoluteJointDef rd = default_revolute_joint_def();
    rd.base.body_a = ground;
    rd.base.body_b = arm;
    rd.base.local_anchor_b = {-1_q32, 0_q32};
    rd.motor_speed = 2_q32;
    *hinge = create_revolute_joint(*world, rd).value;
    MotorJointDef md = default_motor_joint_def();
    md.base.body_a = ground;
    md.base.body_b = box;
    *motor = create_motor_joint(*world, md).value;
  };
  WorldId by_command, by_api;
  JointId hc, mc, ha, ma;
  make(&by_command, &hc, &mc);
  make(&by_api, &ha, &ma);
  const JointRef h = joint_ref(hc), m = joint_ref(mc);
  const std::vector<std::pair<Command, std::function<Status()>>> steps = {
      {make_enable_joint_motor(h, true), [&] { return joint_enable_motor(ha, true); }},
      {make_set_joint_max_motor_force(h, 40_q32), [&] { return joint_set_max_motor_force(ha, 40_q32); }},
      {make_set_joint_limits(h, -0.5_q32, 0.5_q32), [&] { return joint_set_limits(ha, -0.5_q32, 0.5_q32); }},
      {make_enable_joint_limit(h, true), [&] { return joint_enable_limit(ha, true); }},
      {make_set_joint_spring(h, 2.5_q32, 0.3_q32), [&] { return joint_set_spring(ha, 2.5_q32, 0.3_q32); }},
      {make_enable_joint_spring(h, true), [&] { return joint_enable_spring(ha, true); }},
      {make_set_joint_offsets(m, {0.5_q32, 1_q32}, 0.25_q32), [&] { return joint_set_offsets(ma, {0.5_q32, 1_q32}, 0.25_q32); }},
      {make_set_joint_break_thresholds(h, 500_q32, 60_q32), [&] { return joint_set_break_thresholds(ha, 500_q32, 60_q32); }},
  };
  for (const auto& [command, call] : steps) {
    INFO(describe(command));
    const uint64_t before = world_state_hash(by_command);
    REQUIRE(apply_command(by_command, command).ok());
    REQUIRE(call().ok());
    CHECK(world_state_hash(by_command) != before);
    CHECK(world_state_hash(by_command) == world_state_hash(by_api));
    REQUIRE(world_step(by_command, Q32::from_ratio(1, 60)).ok());
    REQUIRE(world_step(by_api, Q32::from_ratio(1, 60)).ok());
    CHECK(world_state_hash(by_command) == world_state_hash(by_api));
  }
  // A refusal names the command, the joint and the field, and changes nothing.
  const uint64_t before = world_state_hash(by_command);
  const Status bad = apply_command(by_command, make_set_joint_spring(h, -1_q32, 0_q32));
  CHECK_FALSE(bad.ok());
  CHECK(bad.message.find("set_joint_spring joint {index 0, generation 1}") != std::string::npos);
  CHECK(bad.message.find("hertz") != std::string::npos);
  CHECK(world_state_hash(by_command) == before);
  CHECK(destroy_world(by_command).ok());
  CHECK(destroy_world(by_api).ok());
}

TEST_CASE("joint commands: applied through the joint API, errors name the command and the field",
          "[replay][commands][joint]") {
  WorldId world = create_world(default_world_def()).value;
  std::vector<Command> script;
  BodyDef ground = default_body_def();
  script.push_back(make_create_body(ground, {}));
  BodyDef bob = default_body_def();
  bob.type = BodyType::dynamic_body;
  bob.position = {3_q32, 0_q32};
  ShapeSpec ball;
  ball.kind = ShapeKind::circle;
  ball.circle = {Vec2{}, 0.25_q32};
  script.push_back(make_create_body(bob, {ball}));
  JointSpec rope;
  rope.type = JointType::distance;
  rope.body_a = {0, 1};
  rope.body_b = {1, 1};
  rope.local_anchor_b = {};
  rope.length = 3_q32;
  rope.enable_spring = true;
  rope.enable_limit = true;
  rope.upper = 3_q32;
  script.push_back(make_create_joint(rope));
  for (const Command& c : script) REQUIRE(apply_command(world, c).ok());
  REQUIRE(world_counters(world).joint_count == 1);

  const JointRef j{0, 1};
  std::vector<Command> during;
  for (int t = 0; t < 120; ++t) {
    std::vector<Command> tick;
    if (t > 30 && t < 60) tick.push_back(make_set_joint_limits(j, 0_q32, 3_q32 - Q32::from_ratio(t - 30, 20)));
    if (t == 90) tick.push_back(make_destroy_joint(j));
    for (const Command& c : tick) REQUIRE(apply_command(world, c).ok());
    during.insert(during.end(), tick.begin(), tick.end());
    REQUIRE(world_step(world, Q32::from_ratio(1, 60)).ok());
  }
  const uint64_t hash = world_state_hash(world);

  // Errors.
  Status bad = apply_command(world, make_set_joint_length(j, 1_q32));
  CHECK(bad.message.find("set_joint_length joint {index 0, generation 1}: joint_set_length: joint {index 0, "
                         "generation 1} was destroyed") == 0);
  JointSpec self = rope;
  self.body_b = {0, 1};
  bad = apply_command(world, make_create_joint(self));
  CHECK(bad.message.find("create_joint: create_distance_joint: DistanceJointDef.base.body_a and base.body_b") == 0);
  rope.length = -1_q32;
  bad = apply_command(world, make_create_joint(rope));
  CHECK(bad.message.find("DistanceJointDef.length -1 m is outside") != std::string::npos);
  CHECK(world_state_hash(world) == hash);  // nothing changed

  // The same commands in a fresh world give the same bits.
  WorldId again = create_world(default_world_def()).value;
  for (const Command& c : script) REQUIRE(apply_command(again, c).ok());
  size_t next = 0;
  for (int t = 0; t < 120; ++t) {
    const size_t end = next + ((t > 30 && t < 60) || t == 90 ? 1 : 0);
    for (; next < end; ++next) REQUIRE(apply_command(again, during[next]).ok());
    REQUIRE(world_step(again, Q32::from_ratio(1, 60)).ok());
  }
  CHECK(world_state_hash(again) == hash);
  CHECK(destroy_world(again).ok());
  CHECK(destroy_world(world).ok());
}

// Joints in the canonical state (replay/state.h, versions 2 and 3): a world with
// joints snapshots and restores mid-run (into itself and into a fresh world)
// and then steps bit-identically to the original; the hash covers joint
// settings and impulses; a world that never had a joint still writes
// version 1; a corrupt joint record is refused with its byte offset and the
// world is left untouched; the diff names the joint field; joint events
// pending at snapshot time survive a restore (portable and compact); joint
// settings outside the joint limits are refused with offset and field.
#include <catch2/catch.hpp>

#include <cstring>
#include <vector>

#include "replay/bytes.h"
#include "replay/rollback.h"
#include "replay/state.h"

namespace tandem {
namespace {

using namespace tandem::literals;

const Q32 k_tick = Q32::from_ratio(1, 60);

struct Owned {
  WorldId id;
  explicit Owned(WorldId w) : id(w) {}
  ~Owned() {
    if (world_is_valid(id)) (void)destroy_world(id);
  }
  Owned(const Owned&) = delete;
  Owned& operator=(const Owned&) = delete;
};

/// A chain of 6 boxes on revolute joints (one with a motor and limits), a
/// rope to a ball, and a prismatic slider with a spring.
WorldId make_joint_world(std::vector<JointId>* out_joints) {
  WorldId w = create_world(default_world_def()).value;
  BodyId ground = create_body(w, default_body_def()).value;
  Polygon floor;
  REQUIRE(make_offset_box(20_q32, 0.5_q32, Vec2{0_q32, -8_q32}, 0_q32, 0_q32, &floor).ok());
  REQUIRE(create_polygon_shape(ground, default_shape_def(), floor).ok());
  BodyId prev = ground;
  for (int i = 0; i < 6; ++i) {
    BodyDef bd = default_body_def();
    bd.type = BodyType::dynamic_body;
    bd.position = Vec2{Q32::from_int(i) + 0.5_q32, 0_q32};
    BodyId b = create_body(w, bd).value;
    Polygon box;
    REQUIRE(make_box(0.5_q32, 0.1_q32, &box).ok());
    REQUIRE(create_polygon_shape(b, default_shape_def(), box).ok());
    RevoluteJointDef rd = default_revolute_joint_def();
    rd.base.body_a = prev;
    rd.base.body_b = b;
    rd.base.local_anchor_a = body_local_point(prev, Vec2{Q32::from_int(i), 0_q32});
    rd.base.local_anchor_b = {-0.5_q32, 0_q32};
    if (i == 0) {
      rd.enable_motor = true;
      rd.motor_speed = 1_q32;
      rd.max_motor_torque = 20_q32;
      rd.enable_limit = true;
      rd.lower_angle = -1_q32;
      rd.upper_angle = 1_q32;
    }
    Result<JointId> j = create_revolute_joint(w, rd);
    REQUIRE(j.ok());
    out_joints->push_back(j.value);
    prev = b;
  }
  BodyDef bd = default_body_def();
  bd.type = BodyType::dynamic_body;
  bd.position = Vec2{8_q32, 0_q32};
  BodyId ball = create_body(w, bd).value;
  REQUIRE(create_circle_shape(ball, default_shape_def(), Circle{Vec2{}, 0.3_q32}).ok());
  DistanceJointDef dd = default_distance_joint_def();
  dd.base.body_a = prev;
  dd.base.body_b = ball;
  dd.base.local_anchor_a = {0.5_q32, 0_q32};
  dd.length = 2_q32;
  dd.enable_spring = true;
  dd.enable_limit = true;
  dd.max_length = 2_q32;
  Result<JointId> rope = create_distance_joint(w, dd);
  REQUIRE(rope.ok());
  out_joints->push_back(rope.value);
  bd.position = Vec2{-5_q32, 0_q32};
  BodyId slider = create_body(w, bd).value;
  Polygon box;
  REQUIRE(make_box(0.3_q32, 0.3_q32, &box).ok());
  REQUIRE(create_polygon_shape(slider, default_shape_def(), box).ok());
  PrismaticJointDef pd = default_prismatic_joint_def();
  pd.base.body_a = ground;
  pd.base.body_b = slider;
  pd.base.local_anchor_a = {-5_q32, 0_q32};
  pd.local_axis_a = {0_q32, 1_q32};
  pd.enable_spring = true;
  pd.hertz = 2_q32;
  pd.damping_ratio = 0.1_q32;
  Result<JointId> pj = create_prismatic_joint(w, pd);
  REQUIRE(pj.ok());
  out_joints->push_back(pj.value);
  return w;
}

}  // namespace

TEST_CASE("state: a world with joints restores mid-run and steps bit-identically", "[replay][state][joint]") {
  std::vector<JointId> joints;
  Owned original(make_joint_world(&joints));
  std::vector<uint64_t> hashes;
  std::vector<std::vector<uint8_t>> snaps;
  for (int t = 0; t < 240; ++t) {
    std::vector<uint8_t> snap;
    REQUIRE(encode_world_state(original.id, &snap).ok());
    CHECK(snap.size() == world_snapshot_size(original.id));
    snaps.push_back(std::move(snap));
    if (t == 100) REQUIRE(destroy_joint(joints[3]).ok());  // a joint destroyed mid-run
    if (t == 150) REQUIRE(joint_set_motor_speed(joints[0], -2_q32).ok());
    REQUIRE(world_step(original.id, k_tick).ok());
    hashes.push_back(world_state_hash(original.id));
  }
  CHECK(snaps[10][4] == k_state_format_version_joints);  // u32 little-endian: the low byte first
  for (const int start : {0, 37, 120, 200}) {
    Result<WorldId> fresh = create_world_from_snapshot(snaps[static_cast<size_t>(start)].data(),
                                                       snaps[static_cast<size_t>(start)].size());
    REQUIRE(fresh.ok());
    Owned copy(fresh.value);
    CHECK(world_counters(copy.id).joint_count == world_joints(copy.id, nullptr, 0));
    for (int t = start; t < 240; ++t) {
      const JointId j3{joints[3].index1, joints[3].generation, copy.id};
      const JointId j0{joints[0].index1, joints[0].generation, copy.id};
      if (t == 100) REQUIRE(destroy_joint(j3).ok());
      if (t == 150) REQUIRE(joint_set_motor_speed(j0, -2_q32).ok());
      REQUIRE(world_step(copy.id, k_tick).ok());
      INFO("restored at tick " << start << ", tick " << t);
      REQUIRE(world_state_hash(copy.id) == hashes[static_cast<size_t>(t)]);
    }
  }
}

TEST_CASE("state: joint settings and impulses are in the hash; joint-free worlds write version 1",
          "[replay][state][joint]") {
  std::vector<JointId> joints;
  Owned w(make_joint_world(&joints));
  for (int t = 0; t < 30; ++t) REQUIRE(world_step(w.id, k_tick).ok());
  const uint64_t before = world_state_hash(w.id);
  REQUIRE(joint_set_motor_speed(joints[0], 3_q32).ok());
  CHECK(world_state_hash(w.id) != before);

  Owned plain(create_world(default_world_def()).value);
  std::vector<uint8_t> image;
  REQUIRE(encode_world_state(plain.id, &image).ok());
  CHECK(image[4] == k_state_format_version);
}

TEST_CASE("state: a corrupt joint record is refused and the diff names the joint field", "[replay][state][joint]") {
  std::vector<JointId> joints;
  Owned w(make_joint_world(&joints));
  for (int t = 0; t < 30; ++t) REQUIRE(world_step(w.id, k_tick).ok());
  std::vector<uint8_t> a;
  REQUIRE(encode_world_state(w.id, &a).ok());

  // Find the "JOIN" section; the first joint's body_a follows its type byte.
  size_t join = 0;
  for (size_t i = 0; i + 4 <= a.size(); ++i) {
    if (std::memcmp(a.data() + i, "JOIN", 4) == 0) join = i;
  }
  REQUIRE(join > 0);
  std::vector<uint8_t> bad = a;
  bad[join + 4 + 1] = 0x7F;  // body_a = a huge index
  const uint64_t hash = world_state_hash(w.id);
  Status s = world_restore(w.id, bad.data(), bad.size());
  INFO(s.message);
  CHECK_FALSE(s.ok());
  CHECK(s.message.find("joint 0 joins bodies") != std::string::npos);
  CHECK(s.message.find("offset " + std::to_string(join + 4)) != std::string::npos);
  CHECK(world_state_hash(w.id) == hash);  // untouched

  REQUIRE(joint_set_motor_speed(joints[0], 3_q32).ok());
  std::vector<uint8_t> b;
  REQUIRE(encode_world_state(w.id, &b).ok());
  DecodedState da, db;
  REQUIRE(decode_world_state(a.data(), a.size(), &da).ok());
  REQUIRE(decode_world_state(b.data(), b.size(), &db).ok());
  const StateDifference diff = diff_world_states(da, db);
  INFO(diff.describe());
  CHECK(diff.differs);
  CHECK(diff.kind == "joint");
  CHECK(diff.index == 0);
  CHECK(diff.field == "motor_speed");
  CHECK(diff.describe().find("joint 0 motor_speed: a = 1") == 0);
}

TEST_CASE("state: the diff names a record's generation only when the two sides differ", "[replay][state][joint]") {
  StateDifference d;
  d.differs = true;
  d.kind = "joint";
  d.index = 3;
  d.generation = 1;
  d.generation_b = 1;
  d.field = "motor_impulse";
  d.value_a = 1;
  d.value_b = 2;
  CHECK(d.describe() == "joint 3 motor_impulse: a = 1, b = 2");
  d.kind = "body";
  d.index = 4;
  d.generation_b = 2;
  CHECK(d.describe() == "body 4 (generation 1 in a, 2 in b) motor_impulse: a = 1, b = 2");
  d.field = "generation";  // the field already names both generations
  CHECK(d.describe() == "body 4 generation: a = 1, b = 2");
  d.missing_in_b = true;  // one side only: nothing to compare
  CHECK(d.describe() == "body 4: only in a");
}

namespace {

/// Offset of the first occurrence of an 8-byte little-endian value.
size_t find_raw(const std::vector<uint8_t>& bytes, int64_t value) {
  uint8_t le[8];
  for (int i = 0; i < 8; ++i) le[i] = static_cast<uint8_t>(static_cast<uint64_t>(value) >> (8 * i));
  for (size_t i = 0; i + 8 <= bytes.size(); ++i) {
    if (std::memcmp(bytes.data() + i, le, 8) == 0) return i;
  }
  return SIZE_MAX;
}

void put_raw(std::vector<uint8_t>* bytes, size_t at, int64_t value) {
  for (int i = 0; i < 8; ++i) {
    (*bytes)[at + static_cast<size_t>(i)] = static_cast<uint8_t>(static_cast<uint64_t>(value) >> (8 * i));
  }
}

/// The joint events of the world's last step.
std::vector<JointEvent> last_joint_events(WorldId w) {
  Result<std::span<const JointEvent>> r = world_joint_events(w);
  REQUIRE(r.ok());
  return std::vector<JointEvent>(r.value.begin(), r.value.end());
}

}  // namespace

TEST_CASE("state: joint events pending at snapshot time are saved (version 3) and reported after a restore",
          "[replay][state][joint]") {
  std::vector<JointId> joints;
  Owned w(make_joint_world(&joints));
  for (int t = 0; t < 20; ++t) REQUIRE(world_step(w.id, k_tick).ok());
  // Destroying the third chain box destroys its two joints: both wait for
  // the next step's events.
  const BodyId box = joint_body_b(joints[2]);
  REQUIRE(destroy_body(box).ok());
  std::vector<uint8_t> image;
  REQUIRE(encode_world_state(w.id, &image).ok());
  CHECK(image[4] == k_state_format_version_joint_events);
  RollbackBuffer compact;
  REQUIRE(rollback_save(w.id, &compact).ok());
  DecodedState decoded;
  REQUIRE(decode_world_state(image.data(), image.size(), &decoded).ok());
  CHECK(decoded.version == k_state_format_version_joint_events);
  int32_t event_records = 0;
  for (const DecodedRecord& r : decoded.records) event_records += r.kind == "joint_event" ? 1 : 0;
  CHECK(event_records == 2);

  Result<WorldId> a = create_world_from_snapshot(image.data(), image.size());
  REQUIRE(a.ok());
  Owned portable(a.value);
  Result<WorldId> b = create_world(default_world_def());
  REQUIRE(b.ok());
  Owned restored(b.value);
  REQUIRE(rollback_restore(restored.id, compact).ok());
  REQUIRE(world_step(w.id, k_tick).ok());
  REQUIRE(world_step(portable.id, k_tick).ok());
  REQUIRE(world_step(restored.id, k_tick).ok());
  const std::vector<JointEvent> expected = last_joint_events(w.id);
  REQUIRE(expected.size() == 2);
  for (const WorldId other : {portable.id, restored.id}) {
    const std::vector<JointEvent> got = last_joint_events(other);
    REQUIRE(got.size() == expected.size());
    for (size_t i = 0; i < got.size(); ++i) {
      CHECK(got[i].kind == JointEventKind::destroyed_with_body);
      CHECK(got[i].kind == expected[i].kind);
      CHECK(got[i].joint.index1 == expected[i].joint.index1);
      CHECK(got[i].joint.generation == expected[i].joint.generation);
      CHECK(got[i].body_a.index1 == expected[i].body_a.index1);
      CHECK(got[i].body_b.generation == expected[i].body_b.generation);
      CHECK(got[i].user_data == expected[i].user_data);
      CHECK(got[i].joint.world == other);
    }
    CHECK(world_state_hash(other) == world_state_hash(w.id));
  }
  // After the step nothing is pending: version 2 again.
  REQUIRE(encode_world_state(w.id, &image).ok());
  CHECK(image[4] == k_state_format_version_joints);
}

TEST_CASE("state: joint records outside the joint limits are refused with offset, joint and field",
          "[replay][state][joint]") {
  std::vector<JointId> joints;
  Owned w(make_joint_world(&joints));
  REQUIRE(joint_set_motor_speed(joints[0], 3.25_q32).ok());
  for (int t = 0; t < 10; ++t) REQUIRE(world_step(w.id, k_tick).ok());
  const uint64_t hash = world_state_hash(w.id);
  std::vector<uint8_t> image;
  REQUIRE(encode_world_state(w.id, &image).ok());
  const size_t at = find_raw(image, (3.25_q32).raw);
  REQUIRE(at != SIZE_MAX);
  std::vector<uint8_t> bad = image;
  put_raw(&bad, at, (5000_q32).raw);
  Status s = world_restore(w.id, bad.data(), bad.size());
  INFO(s.message);
  CHECK_FALSE(s.ok());
  CHECK(s.message ==
        "world_restore: offset " + std::to_string(at) +
            ": joint 0 motor_speed 5000 rad/s or m/s is outside [-1000, 1000] rad/s or m/s");
  CHECK(world_state_hash(w.id) == hash);

  // A negative break force and a lower limit above the upper one.
  const size_t join = [&] {
    size_t j = 0;
    for (size_t i = 0; i + 4 <= image.size(); ++i) {
      if (std::memcmp(image.data() + i, "JOIN", 4) == 0) j = i;
    }
    return j;
  }();
  REQUIRE(join > 0);
  const size_t break_force = join + 4 + 69;  // type, bodies, anchors, axis, reference angle, four flags
  bad = image;
  put_raw(&bad, break_force, (-1_q32).raw);
  s = world_restore(w.id, bad.data(), bad.size());
  CHECK(s.message == "world_restore: offset " + std::to_string(break_force) +
                         ": joint 0 break_force -1 N is outside [0, 100000000] N");
  const size_t lower = join + 4 + 133;
  bad = image;
  put_raw(&bad, lower, (2_q32).raw);  // upper is 1 rad
  s = world_restore(w.id, bad.data(), bad.size());
  CHECK(s.message == "world_restore: offset " + std::to_string(lower) + ": joint 0 lower 2 is above upper 1");
  CHECK(world_state_hash(w.id) == hash);

  // The compact snapshot refuses the same way.
  RollbackBuffer compact;
  REQUIRE(rollback_save(w.id, &compact).ok());
  const size_t cat = find_raw(compact.image, (3.25_q32).raw);
  REQUIRE(cat != SIZE_MAX);
  RollbackBuffer cbad = compact;
  put_raw(&cbad.image, cat, (5000_q32).raw);
  s = rollback_restore(w.id, cbad);
  CHECK(s.message == "rollback_restore: offset " + std::to_string(cat) +
                         ": joint 0 motor_speed 5000 rad/s or m/s is outside [-1000, 1000] rad/s or m/s");
  CHECK(world_state_hash(w.id) == hash);
  REQUIRE(world_step(w.id, k_tick).ok());
}

}  // namespace tandem

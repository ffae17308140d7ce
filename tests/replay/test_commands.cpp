// Engine commands: encode/decode round trips of every type, malformed input
// refused with offsets, application through the public API, and errors that
// name the command and the body.
#include <catch2/catch.hpp>

#include <random>

#include "replay_file_test_support.h"

using namespace tandem;
using namespace tandem::literals;
using namespace tandem::replay_file_test;

namespace {

ShapeSpec odd_shape_def(ShapeSpec s) {
  s.def.friction = 0.25_q32;
  s.def.restitution = 0.5_q32;
  s.def.density = 3_q32;
  s.def.filter.category_bits = 0x8000000000000001ull;
  s.def.filter.mask_bits = 0x00FF00FF00FF00FFull;
  s.def.filter.group_index = -7;
  s.def.user_data = 0xDEADBEEFCAFEF00Dull;
  s.def.is_sensor = true;
  s.def.enable_hit_events = true;
  return s;
}

// One command of every type, with non-default values in every encoded field.
std::vector<Command> every_command() {
  std::vector<Command> out;
  BodyDef d = default_body_def();
  d.type = BodyType::dynamic_body;
  d.position = {Q32::from_raw(-123456789), 7.25_q32};
  d.rotation = rot_from_angle(0.5_q32);
  d.linear_velocity = {1.5_q32, -2_q32};
  d.angular_velocity = Q32::from_raw(-3);
  d.linear_damping = 0.125_q32;
  d.angular_damping = 0.0625_q32;
  d.gravity_scale = -1_q32;
  d.user_data = UINT64_MAX;
  d.enable_sleep = false;
  d.is_awake = false;
  d.fixed_rotation = true;
  d.is_bullet = true;
  d.is_enabled = false;
  std::vector<ShapeSpec> shapes;
  shapes.push_back(odd_shape_def(circle_spec(0.3_q32)));
  shapes.back().circle.center = {0.1_q32, -0.2_q32};
  ShapeSpec capsule;
  capsule.kind = ShapeKind::capsule;
  capsule.capsule = {{-0.5_q32, 0_q32}, {0.5_q32, 0.25_q32}, 0.2_q32};
  shapes.push_back(capsule);
  ShapeSpec segment;
  segment.kind = ShapeKind::segment;
  segment.segment = {{-1_q32, 0_q32}, {1_q32, Q32::from_raw(1)}};
  shapes.push_back(segment);
  Polygon poly;
  REQUIRE(make_offset_box(0.5_q32, 0.25_q32, {0.1_q32, 0.2_q32}, 0.3_q32, 0.05_q32, &poly).ok());
  ShapeSpec polygon;
  polygon.kind = ShapeKind::polygon;
  polygon.polygon = poly;
  shapes.push_back(odd_shape_def(polygon));
  ShapeSpec chain;
  chain.kind = ShapeKind::chain;
  chain.chain_points = {{-2_q32, 0_q32}, {-1_q32, 0_q32}, {0_q32, 0.5_q32}, {1_q32, 0_q32}, {2_q32, 0_q32}};
  chain.chain_loop = true;
  shapes.push_back(chain);
  out.push_back(make_create_body(d, shapes));
  out.push_back(make_create_body(default_body_def(), {}));
  const BodyRef b{41, 0xFFFFFFFEu};
  out.push_back(make_destroy_body(b));
  out.push_back(make_apply_force(b, {3_q32, -4_q32}, {Q32::from_raw(5), 6_q32}, false));
  out.push_back(make_apply_force_to_center(b, {Q32::from_raw(-1), 0_q32}, true));
  out.push_back(make_apply_torque(b, -12.5_q32, false));
  out.push_back(make_apply_linear_impulse(b, {1_q32, 2_q32}, {3_q32, 4_q32}, true));
  out.push_back(make_apply_linear_impulse_to_center(b, {Q32::from_raw(INT64_MIN), Q32::max()}, false));
  out.push_back(make_apply_angular_impulse(b, 0.001_q32, true));
  out.push_back(make_set_linear_velocity(b, {-7_q32, 8_q32}));
  out.push_back(make_set_angular_velocity(b, Q32::from_raw(99)));
  out.push_back(make_set_transform(b, {9_q32, 10_q32}, rot_from_angle(-1_q32)));
  out.push_back(make_set_awake(b, false));
  out.push_back(make_set_enabled(b, false));
  out.push_back(make_set_enabled(b, true));
  out.push_back(make_set_gravity({Q32::from_raw(1), -10_q32}));
  out.push_back(make_user_input({}));
  out.push_back(make_user_input({0, 1, 2, 0xFF, 0x80}));
  return out;
}

std::vector<uint8_t> encode_all(const std::vector<Command>& commands) {
  std::vector<uint8_t> bytes;
  ByteWriter w(&bytes);
  encode_commands(w, commands);
  return bytes;
}

}  // namespace

TEST_CASE("every command round-trips through its encoding", "[replay][commands]") {
  const std::vector<Command> all = every_command();
  REQUIRE(all.size() == 18);
  for (const Command& c : all) {
    INFO(describe(c));
    std::vector<uint8_t> bytes;
    ByteWriter w(&bytes);
    encode_command(w, c);
    ByteReader r(bytes);
    Command back;
    REQUIRE(decode_command(&r, &back).ok());
    CHECK(r.at_end());
    CHECK(back == c);
    // Encoding the decoded command gives the same bytes.
    std::vector<uint8_t> again;
    ByteWriter w2(&again);
    encode_command(w2, back);
    CHECK(again == bytes);
  }
  // The equality is not trivially true: one raw unit anywhere breaks it.
  Command changed = all[9];
  changed.vector.y.raw += 1;
  CHECK_FALSE(changed == all[9]);
  Command shape_changed = all[0];
  shape_changed.shapes[3].polygon.normals[2].x.raw -= 1;
  CHECK_FALSE(shape_changed == all[0]);

  const std::vector<uint8_t> list = encode_all(all);
  ByteReader r(list);
  std::vector<Command> back;
  REQUIRE(decode_commands(&r, &back).ok());
  CHECK(r.at_end());
  REQUIRE(back.size() == all.size());
  for (size_t i = 0; i < all.size(); ++i) CHECK(back[i] == all[i]);
}

TEST_CASE("every truncation of a command list fails cleanly with an offset", "[replay][commands]") {
  const std::vector<uint8_t> list = encode_all(every_command());
  for (size_t n = 0; n < list.size(); ++n) {
    ByteReader r(list.data(), n);
    std::vector<Command> back;
    CHECK_FALSE(decode_commands(&r, &back).ok());
    CHECK_FALSE(r.ok());
    CHECK(r.error().rfind("offset ", 0) == 0);
    CHECK(r.error_offset() <= n);
  }
}

TEST_CASE("random bytes never crash the command decoder", "[replay][commands]") {
  std::mt19937_64 rng(0x5EED0001);
  const std::vector<uint8_t> valid = encode_all(every_command());
  for (int iter = 0; iter < 2000; ++iter) {
    std::vector<uint8_t> bytes = valid;
    const int flips = 1 + static_cast<int>(rng() % 4);
    for (int f = 0; f < flips; ++f) bytes[static_cast<size_t>(rng() % bytes.size())] = static_cast<uint8_t>(rng());
    ByteReader r(bytes);
    std::vector<Command> back;
    if (decode_commands(&r, &back).ok()) {
      CHECK(r.ok());
    } else {
      CHECK(!r.error().empty());
    }
  }
}

TEST_CASE("malformed commands are refused naming what was expected", "[replay][commands]") {
  SECTION("unknown command type") {
    const std::vector<uint8_t> bytes{1, 0, 0, 0, 99, 0, 0, 0, 0};
    ByteReader r(bytes);
    std::vector<Command> out;
    REQUIRE_FALSE(decode_commands(&r, &out).ok());
    CHECK(r.error() == "offset 4: expected command type 1..26, got 99");
  }
  SECTION("a 4 GB payload length is refused before allocating") {
    const std::vector<uint8_t> bytes{13, 0xFF, 0xFF, 0xFF, 0xFF, 1, 2, 3};
    ByteReader r(bytes);
    Command c;
    REQUIRE_FALSE(decode_command(&r, &c).ok());
    CHECK(r.error_offset() == 1);
    CHECK(r.error().find("payload byte count") != std::string::npos);
    CHECK(c.payload.empty());
  }
  SECTION("a 4 G command count is refused before allocating") {
    const std::vector<uint8_t> bytes{0xFF, 0xFF, 0xFF, 0xFF, 12};
    ByteReader r(bytes);
    std::vector<Command> out;
    REQUIRE_FALSE(decode_commands(&r, &out).ok());
    CHECK(r.error_offset() == 0);
    CHECK(r.error().find("command count") != std::string::npos);
    CHECK(out.capacity() == 0);
  }
  SECTION("shape count and polygon count are checked") {
    std::vector<uint8_t> bytes;
    ByteWriter w(&bytes);
    encode_command(w, make_create_body(default_body_def(), {box_spec(1_q32, 1_q32)}));
    // The shape count sits right after the type byte and the 94-byte body def.
    const size_t count_at = 1 + 94;
    std::vector<uint8_t> huge = bytes;
    huge[count_at] = huge[count_at + 1] = huge[count_at + 2] = huge[count_at + 3] = 0xFF;
    ByteReader r(huge);
    Command c;
    REQUIRE_FALSE(decode_command(&r, &c).ok());
    CHECK(r.error_offset() == count_at);
    CHECK(r.error().find("shape count") != std::string::npos);
    // polygon.count is after the kind byte and the 54-byte shape def.
    std::vector<uint8_t> bad_poly = bytes;
    const size_t poly_count_at = count_at + 4 + 1 + 54;
    REQUIRE(bad_poly[poly_count_at] == 4);
    bad_poly[poly_count_at] = 9;
    ByteReader r2(bad_poly);
    REQUIRE_FALSE(decode_command(&r2, &c).ok());
    CHECK(r2.error() == "offset " + std::to_string(poly_count_at) + ": expected shape 0 polygon.count 3..8, got 9");
  }
  SECTION("bools other than 0 or 1") {
    std::vector<uint8_t> bytes;
    ByteWriter w(&bytes);
    encode_command(w, make_set_awake(BodyRef{1, 1}, true));
    bytes.back() = 2;
    ByteReader r(bytes);
    Command c;
    REQUIRE_FALSE(decode_command(&r, &c).ok());
    CHECK(r.error_offset() == 9);
  }
}

TEST_CASE("apply_command drives the public API", "[replay][commands]") {
  OwnedWorld world;
  BodyId ground;
  REQUIRE(apply_command(world.id, create_at(BodyType::static_body, {0_q32, -1_q32}, box_spec(10_q32, 1_q32)), &ground).ok());
  CHECK(body_ref(ground) == BodyRef{0, 1});
  std::vector<ShapeSpec> shapes = {box_spec(0.5_q32, 0.5_q32), circle_spec(0.25_q32)};
  ShapeSpec capsule;
  capsule.kind = ShapeKind::capsule;
  capsule.capsule = {{-0.5_q32, 0_q32}, {0.5_q32, 0_q32}, 0.1_q32};
  shapes.push_back(capsule);
  ShapeSpec segment;
  segment.kind = ShapeKind::segment;
  segment.segment = {{-0.5_q32, 0.5_q32}, {0.5_q32, 0.5_q32}};
  shapes.push_back(segment);
  BodyDef d = default_body_def();
  d.type = BodyType::dynamic_body;
  d.position = {0_q32, 3_q32};
  BodyId body;
  REQUIRE(apply_command(world.id, make_create_body(d, shapes), &body).ok());
  CHECK(body_shape_count(body) == 4);
  CHECK(body_mass(body) > 1_q32);
  const BodyRef ref = body_ref(body);

  ShapeSpec chain;
  chain.kind = ShapeKind::chain;
  chain.chain_points = {{-3_q32, 1_q32}, {-2_q32, 0_q32}, {2_q32, 0_q32}, {3_q32, 1_q32}};
  BodyId chain_body;
  REQUIRE(apply_command(world.id, create_at(BodyType::static_body, {0_q32, 10_q32}, chain), &chain_body).ok());
  CHECK(body_shape_count(chain_body) == 1);

  REQUIRE(apply_command(world.id, make_set_linear_velocity(ref, {1_q32, 2_q32})).ok());
  CHECK(body_linear_velocity(body) == Vec2{1_q32, 2_q32});
  REQUIRE(apply_command(world.id, make_set_angular_velocity(ref, 0.5_q32)).ok());
  CHECK(body_angular_velocity(body) == 0.5_q32);
  REQUIRE(apply_command(world.id, make_set_transform(ref, {2_q32, 4_q32}, Rot{})).ok());
  CHECK(body_position(body) == Vec2{2_q32, 4_q32});
  REQUIRE(apply_command(world.id, make_set_gravity({0_q32, -5_q32})).ok());
  CHECK(world_gravity(world.id) == Vec2{0_q32, -5_q32});
  const Vec2 v0 = body_linear_velocity(body);
  REQUIRE(apply_command(world.id, make_apply_linear_impulse_to_center(ref, {body_mass(body), 0_q32})).ok());
  CHECK(body_linear_velocity(body).x > v0.x);
  const Q32 w0 = body_angular_velocity(body);
  REQUIRE(apply_command(world.id, make_apply_angular_impulse(ref, 0.01_q32)).ok());
  CHECK(body_angular_velocity(body) > w0);
  REQUIRE(apply_command(world.id, make_apply_linear_impulse(ref, {0_q32, 0.1_q32}, {2.25_q32, 4_q32})).ok());
  REQUIRE(apply_command(world.id, make_apply_force(ref, {0_q32, 10_q32}, {2_q32, 4_q32})).ok());
  REQUIRE(apply_command(world.id, make_apply_force_to_center(ref, {0_q32, 10_q32})).ok());
  REQUIRE(apply_command(world.id, make_apply_torque(ref, 1_q32)).ok());
  REQUIRE(apply_command(world.id, make_set_enabled(ref, false)).ok());
  CHECK_FALSE(body_is_enabled(body));
  REQUIRE(apply_command(world.id, make_set_enabled(ref, true)).ok());
  CHECK(body_is_enabled(body));
  REQUIRE(apply_command(world.id, make_set_awake(ref, false)).ok());
  CHECK_FALSE(body_is_awake(body));
  REQUIRE(apply_command(world.id, make_user_input({1, 2, 3})).ok());
  REQUIRE(apply_command(world.id, make_destroy_body(ref)).ok());
  CHECK_FALSE(body_is_valid(body));

  SECTION("errors name the command and the body") {
    const Status s = apply_command(world.id, make_set_linear_velocity(ref, {1_q32, 0_q32}));
    REQUIRE_FALSE(s.ok());
    CHECK(s.message.rfind("set_linear_velocity body {index 1, generation 1}: ", 0) == 0);
    const Status never = apply_command(world.id, make_apply_torque(BodyRef{500, 1}, 1_q32));
    REQUIRE_FALSE(never.ok());
    CHECK(never.message.rfind("apply_torque body {index 500, generation 1}: ", 0) == 0);
    const Status gen0 = apply_command(world.id, make_destroy_body(BodyRef{0, 0}));
    CHECK(gen0.code == StatusCode::invalid_handle);
    const Status gravity = apply_command(world.id, make_set_gravity({0_q32, 20000_q32}));
    REQUIRE_FALSE(gravity.ok());
    CHECK(gravity.message.rfind("set_gravity: ", 0) == 0);
  }
  SECTION("a refused shape names its position and leaves no body behind") {
    ShapeSpec bad = circle_spec(0_q32);
    const int32_t before = world_counters(world.id).body_count;
    const Status s = apply_command(world.id, make_create_body(d, {circle_spec(0.5_q32), bad}));
    REQUIRE_FALSE(s.ok());
    CHECK(s.message.find("create_body (2 shapes): shape 1 (circle): ") == 0);
    CHECK(world_counters(world.id).body_count == before);
  }
}

TEST_CASE("the same commands give the same bits in two worlds", "[replay][commands]") {
  OwnedWorld a, b;
  for (int64_t t = 1; t <= 30; ++t) {
    for (const Command& c : scene_commands(t)) {
      REQUIRE(apply_command(a.id, c).ok());
      // Through the encoding, as a peer would receive them.
      std::vector<uint8_t> bytes;
      ByteWriter w(&bytes);
      encode_command(w, c);
      ByteReader r(bytes);
      Command received;
      REQUIRE(decode_command(&r, &received).ok());
      REQUIRE(apply_command(b.id, received).ok());
    }
    REQUIRE(world_step(a.id, Q32::from_ratio(1, 60)).ok());
    REQUIRE(world_step(b.id, Q32::from_ratio(1, 60)).ok());
    REQUIRE(world_state_hash(a.id) == world_state_hash(b.id));
  }
  CHECK(world_counters(a.id).body_count == 4);
}

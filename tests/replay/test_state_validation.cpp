// test_state_validation.cpp — restore refuses out-of-range and inconsistent
// state (replay/state.h, "RESTORE"): a crafted image with an inverted shape
// bound (the outside fuzzing run's crash), one mutated field at a time
// across the world, body, shape and contact records, and a world at the
// limits that is accepted and steps without a fixed-point fault.
//
// Images are patched at the offset locate_state_field() reports. The state
// format has no checksum (a replay file's keyframe carries one; restore
// sees the same bytes once it is verified), so a patched image is exactly
// what a crafted file with valid checksums delivers to restore.
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include "fixed/fault.h"
#include "physics/tandem.h"
#include "replay/replay_file.h"
#include "replay/state.h"
#include "replay/verify.h"
#include "replay_file_test_support.h"
#include "replay_test_scenes.h"

using namespace tandem;
using namespace tandem::literals;
using namespace tandem::replay_test;
using tandem::replay_file_test::OwnedWorld;

namespace {

void put_le(std::vector<uint8_t>* image, size_t offset, uint64_t value, int bytes) {
  REQUIRE(offset + static_cast<size_t>(bytes) <= image->size());
  for (int k = 0; k < bytes; ++k) (*image)[offset + static_cast<size_t>(k)] = static_cast<uint8_t>(value >> (8 * k));
}

int64_t get_q32(const std::vector<uint8_t>& image, size_t offset) {
  uint64_t v = 0;
  for (int k = 0; k < 8; ++k) v |= static_cast<uint64_t>(image[offset + static_cast<size_t>(k)]) << (8 * k);
  return static_cast<int64_t>(v);
}

size_t locate(const std::vector<uint8_t>& image, const char* kind, int64_t index, const char* field) {
  size_t at = 0;
  const Status s = locate_state_field(image.data(), image.size(), kind, index, field, &at);
  INFO(s.message);
  REQUIRE(s.ok());
  return at;
}

/// The first record of a kind in a decoded image that satisfies `pred`; its
/// index (bodies, shapes) or position among the kind's records (contacts).
template <typename P>
int64_t first_record(const std::vector<uint8_t>& image, const char* kind, P&& pred) {
  DecodedState d;
  REQUIRE(decode_world_state(image.data(), image.size(), &d).ok());
  int64_t position = 0;
  for (const DecodedRecord& r : d.records) {
    if (r.kind != kind) continue;
    if (pred(r)) return std::string(kind) == "contact" ? position : r.index;
    ++position;
  }
  FAIL("no matching " << kind);
  return -1;
}

int64_t field_value(const DecodedRecord& r, const char* name) {
  for (const DecodedField& f : r.fields) {
    if (f.name == name) return f.value;
  }
  return INT64_MIN;
}

/// A pile stepped 60 ticks: dynamic bodies resting on each other, contacts
/// with points and warm-start impulses.
std::vector<uint8_t> pile_image(BroadPhaseKind kind) {
  OwnedWorld w(make_scene_world(Scene::pile));
  REQUIRE(world_set_broad_phase(w.id, kind).ok());
  for (int64_t t = 0; t < 60; ++t) step_scene(Scene::pile, w.id, t);
  std::vector<uint8_t> image;
  REQUIRE(encode_world_state(w.id, &image).ok());
  return image;
}

/// Restores `image` into a stepped pyramid world, expects a refusal naming
/// `offset` and every `needles`, checks the world unchanged, then steps it.
Status expect_refused(const std::vector<uint8_t>& image, size_t offset, const std::vector<std::string>& needles,
                      BroadPhaseKind kind = BroadPhaseKind::naive) {
  OwnedWorld target(make_scene_world(Scene::pyramid));
  REQUIRE(world_set_broad_phase(target.id, kind).ok());
  for (int64_t t = 0; t < 10; ++t) step_scene(Scene::pyramid, target.id, t);
  const uint64_t before = world_state_hash(target.id);
  const Status s = world_restore(target.id, image.data(), image.size());
  INFO(s.message);
  CHECK(!s.ok());
  CHECK(s.message.find("offset " + std::to_string(offset) + ":") != std::string::npos);
  for (const std::string& n : needles) CHECK(s.message.find(n) != std::string::npos);
  CHECK(world_state_hash(target.id) == before);
  // Nothing half-applied: the world goes on exactly like an untouched twin.
  OwnedWorld twin(make_scene_world(Scene::pyramid));
  REQUIRE(world_set_broad_phase(twin.id, kind).ok());
  for (int64_t t = 0; t < 10; ++t) step_scene(Scene::pyramid, twin.id, t);
  for (int64_t t = 10; t < 40; ++t) {
    step_scene(Scene::pyramid, target.id, t);
    step_scene(Scene::pyramid, twin.id, t);
  }
  CHECK(world_state_hash(target.id) == world_state_hash(twin.id));
  return s;
}

constexpr BroadPhaseKind k_kinds[] = {BroadPhaseKind::naive, BroadPhaseKind::sweep_and_prune, BroadPhaseKind::grid,
                                      BroadPhaseKind::tree};

}  // namespace

TEST_CASE("state validation: an image with an inverted shape bound is refused with every broad phase",
          "[replay][state][validation]") {
  for (const BroadPhaseKind kind : k_kinds) {
    INFO("broad phase " << static_cast<int32_t>(kind));
    std::vector<uint8_t> image = pile_image(kind);
    // A dynamic shape (on a body whose type byte is 2), lower.x above upper.x.
    DecodedState d;
    REQUIRE(decode_world_state(image.data(), image.size(), &d).ok());
    std::vector<int64_t> dynamic_bodies;
    for (const DecodedRecord& r : d.records) {
      if (r.kind == "body" && field_value(r, "type") == 2) dynamic_bodies.push_back(r.index);
    }
    REQUIRE(!dynamic_bodies.empty());
    const int64_t shape = first_record(image, "shape", [&](const DecodedRecord& r) {
      return field_value(r, "body") == dynamic_bodies.back();
    });
    const size_t lx = locate(image, "shape", shape, "aabb.lower.x");
    const size_t ux = locate(image, "shape", shape, "aabb.upper.x");
    const int64_t lower = get_q32(image, lx);
    const int64_t upper = get_q32(image, ux);
    REQUIRE(lower < upper);
    put_le(&image, lx, static_cast<uint64_t>(upper + (int64_t{5} << 32)), 8);
    put_le(&image, ux, static_cast<uint64_t>(lower - (int64_t{5} << 32)), 8);
    const Status s = expect_refused(image, lx, {"shape " + std::to_string(shape), "aabb.lower.x", "does not match"},
                                    kind);
    if (kind == BroadPhaseKind::sweep_and_prune) WARN("example refusal: " << s.message);
  }
}

TEST_CASE("state validation: every restored field is held to its limit (one field mutated at a time)",
          "[replay][state][validation]") {
  const std::vector<uint8_t> good = pile_image(BroadPhaseKind::naive);
  {
    // The unmutated image is accepted.
    OwnedWorld w;
    REQUIRE(world_restore(w.id, good.data(), good.size()).ok());
  }
  // A circle on a dynamic body.
  DecodedState decoded;
  REQUIRE(decode_world_state(good.data(), good.size(), &decoded).ok());
  std::vector<int64_t> dynamic;
  for (const DecodedRecord& r : decoded.records) {
    if (r.kind == "body" && field_value(r, "type") == 2) dynamic.push_back(r.index);
  }
  const int64_t shape = first_record(good, "shape", [&](const DecodedRecord& r) {
    return field_value(r, "type") == 0 &&
           std::find(dynamic.begin(), dynamic.end(), field_value(r, "body")) != dynamic.end();
  });
  const int64_t body = first_record(good, "shape", [&](const DecodedRecord& r) { return r.index == shape; }) >= 0
                           ? [&] {
                               for (const DecodedRecord& r : decoded.records) {
                                 if (r.kind == "shape" && r.index == shape) return field_value(r, "body");
                               }
                               return int64_t{-1};
                             }()
                           : -1;
  REQUIRE(body >= 0);
  const int64_t contact =
      first_record(good, "contact", [](const DecodedRecord& r) { return field_value(r, "point_count") > 0; });
  const auto q = [](int64_t units) { return static_cast<uint64_t>(units) << 32; };  // whole units, raw
  const auto raw = [](int64_t r) { return static_cast<uint64_t>(r); };
  struct Row {
    const char* kind;
    int64_t index;
    const char* field;
    uint64_t value;  // raw Q32 (or i32 for 4-byte fields)
    int bytes;
    std::vector<std::string> needles;
  };
  const std::vector<Row> rows = {
      {"world", 0, "max_linear_speed", q(2000), 8, {"world max_linear_speed 2000 m/s is outside (0, 1000] m/s"}},
      {"world", 0, "gravity.y", q(-20000), 8, {"world gravity.y", "[-10000, 10000]"}},
      {"world", 0, "contact_hertz", q(0), 8, {"world contact_hertz 0 Hz is outside (0, 10000] Hz"}},
      {"world", 0, "max_contact_push_speed", q(500), 8, {"world max_contact_push_speed", "[0, 400]"}},
      {"world", 0, "restitution_threshold", q(-1), 8, {"world restitution_threshold"}},
      {"world", 0, "bounds.lower.x", q(-2000000), 8, {"world bounds.lower.x", "[-1000000, 1000000]"}},
      {"body", body, "position.x", q(3000000), 8, {"position.x", "[-2000000, 2000000] m"}},
      {"body", body, "rotation.c", q(1) / 2, 8, {"rotation.c", "unit vector"}},
      {"body", body, "linear_velocity.x", q(100000), 8, {"linear_velocity.x 100000 m/s is outside [-4000, 4000] m/s"}},
      {"body", body, "angular_velocity", q(1000000), 8, {"angular_velocity 1000000 rad/s", "rim speed"}},
      {"body", body, "mass", q(5), 8, {"mass 5 kg does not match"}},
      {"body", body, "inv_mass", q(1) / 2, 8, {"inv_mass", "does not match"}},
      {"body", body, "rotational_inertia", q(7), 8, {"rotational_inertia", "does not match"}},
      {"body", body, "inv_inertia", q(9), 8, {"inv_inertia", "does not match"}},
      {"body", body, "local_center.x", q(1), 8, {"local_center.x", "does not match"}},
      {"body", body, "center.y", q(123), 8, {"center.y", "does not match"}},
      {"body", body, "min_extent", raw(1), 8, {"min_extent", "does not match"}},
      {"body", body, "max_extent", q(99), 8, {"max_extent", "does not match"}},
      {"body", body, "sleep_time", q(100), 8, {"sleep_time 100 s is outside [0, 0.5] s"}},
      {"body", body, "linear_damping", q(-1), 8, {"linear_damping -1 1/s is outside [0, 10000] 1/s"}},
      {"body", body, "angular_damping", q(20000), 8, {"angular_damping"}},
      {"body", body, "gravity_scale", q(1000), 8, {"gravity_scale 1000 is outside [-100, 100]"}},
      {"body", body, "force.x", q(1000000000), 8, {"force.x", "N is outside"}},
      {"body", body, "torque", q(-1000000000), 8, {"torque", "N·m is outside"}},
      {"shape", shape, "friction", q(1000), 8, {"shape " + std::to_string(shape) + " friction 1000 is outside [0, 100]"}},
      {"shape", shape, "restitution", q(2), 8, {"restitution 2 is outside [0, 1]"}},
      {"shape", shape, "density", q(1000000), 8, {"density 1000000 kg/m² is outside [0, 100000] kg/m²"}},
      {"shape", shape, "aabb.upper.y", q(-900000), 8, {"aabb.upper.y", "does not match"}},
      {"shape", shape, "circle.radius", q(20000), 8, {"circle.radius 20000 m is outside [0, 10000] m"}},
      {"shape", shape, "circle.center.x", q(10000), 8, {"circle.center.x 10000 m is outside [-9999.649"}},
      {"contact", contact, "points[0].normal_impulse", q(1000000000), 8, {"points[0].normal_impulse", "N·s is outside"}},
      {"contact", contact, "points[0].tangent_impulse", q(-100000000), 8, {"points[0].tangent_impulse", "warm-start"}},
      {"contact", contact, "friction", q(1000), 8, {"friction 1000 is outside [0, 100]"}},
      {"contact", contact, "normal.x", q(2), 8, {"normal.x 2 is outside"}},
      {"contact", contact, "points[0].anchor_a.x", q(1000000), 8, {"points[0].anchor_a.x", "[-40000, 40000] m"}},
      {"contact", contact, "points[0].separation", q(-100000), 8, {"points[0].separation"}},
      {"contact", contact, "flags", raw(6), 4, {"flags 6"}},
  };
  for (const Row& row : rows) {
    INFO(row.kind << " " << row.index << " " << row.field);
    std::vector<uint8_t> bad = good;
    const size_t at = locate(good, row.kind, row.index, row.field);
    put_le(&bad, at, row.value, row.bytes);
    std::vector<std::string> needles = row.needles;
    needles.push_back(row.field);
    if (std::string(row.kind) != "world") needles.push_back(std::string(row.kind) + " " + std::to_string(row.index));
    const Status s = expect_refused(bad, at, needles);
    if (std::string(row.field) == "max_linear_speed") WARN("example refusal: " << s.message);
    // decode_world_state (diffs, tools) applies the same checks.
    DecodedState d;
    CHECK(!decode_world_state(bad.data(), bad.size(), &d).ok());
  }
}

TEST_CASE("state validation: a count larger than the bytes left is refused before allocation",
          "[replay][state][validation]") {
  const std::vector<uint8_t> good = pile_image(BroadPhaseKind::naive);
  for (const char* tag : {"BPOL", "SPOL", "CONT", "TUCH", "SENS"}) {
    INFO(tag);
    const uint8_t* t = reinterpret_cast<const uint8_t*>(tag);
    const auto it = std::search(good.begin(), good.end(), t, t + 4);
    REQUIRE(it != good.end());
    const size_t at = static_cast<size_t>(it - good.begin()) + 4;
    std::vector<uint8_t> bad = good;
    put_le(&bad, at, 0xFFFFFFF0u, 4);
    OwnedWorld w;
    const Status s = world_restore(w.id, bad.data(), bad.size());
    INFO(s.message);
    CHECK(!s.ok());
    CHECK(s.message.find("offset " + std::to_string(at)) != std::string::npos);
  }
}

namespace {
std::atomic<int32_t> g_faults{0};
void count_fault(FixedFault, const char*) { g_faults.fetch_add(1); }
}  // namespace

TEST_CASE("state validation: a world at the limits is accepted and steps without a fixed-point fault",
          "[replay][state][validation]") {
  // Heaviest and lightest bodies, fastest speeds, largest shapes, the world's
  // own speed limit raised to the engine's: everything at the edge of what
  // the API accepts (and therefore restore). Checked builds report any
  // saturation as a fault; none may occur, so the release build's unchecked
  // in-range arithmetic and the portable 128-bit path compute the same bits
  // (the golden chains compare those builds; this world is their edge case).
  const FixedFaultHandler old = set_fixed_fault_handler(&count_fault);
  g_faults = 0;
  WorldDef def = default_world_def();
  def.max_linear_speed = k_max_linear_speed;
  def.gravity = {Q32::zero(), -k_max_gravity / 1000};
  OwnedWorld w(def);
  add_ground(w.id, 2000_q32, true);
  ShapeDef heavy = default_shape_def();
  heavy.density = k_max_density;
  heavy.restitution = 1_q32;
  for (int32_t i = 0; i < 6; ++i) {
    const BodyId big = add_body(w.id, BodyType::dynamic_body, {Q32::from_int(-30 + 12 * i), 3_q32});
    Circle c;
    c.radius = 0.56_q32;  // ≈ 98,500 kg at k_max_density
    REQUIRE(create_circle_shape(big, heavy, c).ok());
    REQUIRE(body_set_linear_velocity(big, {Q32::from_int(i % 2 == 0 ? 900 : -900), Q32::zero()}).ok());
    const BodyId tiny = add_body(w.id, BodyType::dynamic_body, {Q32::from_int(-30 + 12 * i), 4_q32});
    ShapeDef light = default_shape_def();
    light.density = 0.0128_q32;  // ≈ 0.001 kg at r = 0.16 m
    Circle t;
    t.radius = 0.16_q32;
    REQUIRE(create_circle_shape(tiny, light, t).ok());
    REQUIRE(body_set_angular_velocity(tiny, k_max_angular_speed).ok());
  }
  for (int32_t tick = 0; tick < 240; ++tick) {
    REQUIRE(world_step(w.id, k_dt).ok());
    if (tick % 20 != 19) continue;
    std::vector<uint8_t> image;
    REQUIRE(encode_world_state(w.id, &image).ok());
    OwnedWorld copy;
    const Status s = world_restore(copy.id, image.data(), image.size());
    INFO("tick " << tick << ": " << s.message);
    REQUIRE(s.ok());
    REQUIRE(world_step(copy.id, k_dt).ok());
    REQUIRE(world_step(w.id, k_dt).ok());
    ++tick;
    CHECK(world_state_hash(copy.id) == world_state_hash(w.id));
  }
  CHECK(g_faults.load() == 0);
  set_fixed_fault_handler(old);
  // Golden: the same bits on every build. Measured equal on gcc-release
  // (native __int128, unchecked in-range solver arithmetic) and
  // portable-int128 (wide.h limbs); debug and sanitizer builds check the
  // same value with fault reports on. Regenerate only in a commit that says
  // why the simulation changed. 2026-11-29: the speed clamps before
  // positions are integrated and when a step stores its velocities
  // (solver.cpp, known issue 8): a 900 m/s ball hitting a 1 g body leaves it
  // above the 1,000 m/s limit in the solve.
  const uint64_t hash = world_state_hash(w.id);
  INFO("at-the-limits world after 240 ticks: hash " << hash);
  CHECK(hash == 1917204718635169861ull);
}

TEST_CASE("state validation: a replay whose keyframe has valid checksums and an inverted bound fails verify cleanly",
          "[replay][state][validation]") {
  // The outside fuzzing run's case end to end: the writer computes every
  // checksum, so only restore stands between the crafted keyframe and the
  // broad phase (sweep and prune, which crashed).
  std::vector<uint8_t> image = pile_image(BroadPhaseKind::sweep_and_prune);
  const int64_t shape = first_record(image, "shape", [](const DecodedRecord& r) { return r.index >= 4; });
  const size_t lx = locate(image, "shape", shape, "aabb.lower.x");
  const size_t ux = locate(image, "shape", shape, "aabb.upper.x");
  const int64_t lower = get_q32(image, lx);
  const int64_t upper = get_q32(image, ux);
  put_le(&image, lx, static_cast<uint64_t>(upper), 8);
  put_le(&image, ux, static_cast<uint64_t>(lower), 8);

  ReplayWriter writer;
  writer.open_memory(ReplayWriterOptions{1});
  ReplayHeader header;
  header.tick_hashes = false;
  header.keyframe_interval = 0;
  REQUIRE(writer.write_header(header, image).ok());
  for (int64_t t = 1; t <= 30; ++t) {
    TickRecord rec;
    rec.tick = t;
    REQUIRE(writer.append_tick(rec).ok());
  }
  REQUIRE(writer.finish().ok());
  // read_replay already decodes (and so validates) keyframe images; either
  // it or verify must refuse, naming the keyframe's field.
  Replay replay;
  const Status read = read_replay(writer.memory(), &replay);
  Status refusal = read;
  if (read.ok()) {
    const VerifyReport report = verify_replay(replay, VerifyOptions{});
    CHECK(report.ticks_run == 0);
    refusal = report.error;
  }
  INFO(refusal.message);
  CHECK(!refusal.ok());
  CHECK(refusal.message.find("offset " + std::to_string(lx) + ": shape " + std::to_string(shape) + " aabb.lower.x") !=
        std::string::npos);
  WARN("replay refusal: " << refusal.message);
}

// Replay format versions: version 2 (game states, the header naming the
// tick-0 image's state format) is written; version 1 files still read and
// verify. tests/replay/data/test_scene_v1.tnr is a committed version-1 file (the
// test scene of replay_file_test_support.h, 20 ticks, keyframes every 5);
// with TANDEM_GOLDEN_REGENERATE=1 set (docs/determinism.md) this test
// rewrites it from the current engine, in format 1, as the golden chains are.
#include <catch2/catch.hpp>

#include <cstdio>
#include <cstdlib>
#include <string>

#define XXH_INLINE_ALL
#include <xxhash.h>

#include "replay/verify.h"
#include "replay_file_test_support.h"

using namespace tandem;
using namespace tandem::replay_file_test;

namespace {

const std::string k_v1_file = std::string(TANDEM_SESSION_SOURCE_DIR) + "/tests/replay/data/test_scene_v1.tnr";

Replay read_ok(std::span<const uint8_t> bytes, ReplayReadInfo* info = nullptr) {
  Replay r;
  const Status s = read_replay(bytes, &r, info);
  INFO(s.message);
  REQUIRE(s.ok());
  return r;
}

// A joint world (a pendulum: a revolute joint to a static anchor), whose
// state images are format 2.
WorldId joint_world() {
  const WorldId w = create_world(default_world_def()).value;
  const BodyId anchor = create_body(w, default_body_def()).value;
  BodyDef bd = default_body_def();
  bd.type = BodyType::dynamic_body;
  bd.position = Vec2{2_q32, 0_q32};
  const BodyId bob = create_body(w, bd).value;
  Circle c;
  c.radius = 0.25_q32;
  REQUIRE(create_circle_shape(bob, default_shape_def(), c).ok());
  RevoluteJointDef rd = default_revolute_joint_def();
  rd.base.body_a = anchor;
  rd.base.body_b = bob;
  rd.base.local_anchor_b = Vec2{-2_q32, 0_q32};
  REQUIRE(create_revolute_joint(w, rd).ok());
  return w;
}

}  // namespace

TEST_CASE("replay format 1: the committed file reads and verifies", "[replay][file][version]") {
  if (const char* regen = std::getenv("TANDEM_GOLDEN_REGENERATE"); regen != nullptr && std::string(regen) == "1") {
    RecordSpec spec;
    spec.ticks = 20;
    spec.keyframe_interval = 5;
    const std::vector<uint8_t> v1 = encode_replay(read_ok(record_scene(spec)), 1, 1);
    std::FILE* f = std::fopen(k_v1_file.c_str(), "wb");
    REQUIRE(f != nullptr);
    REQUIRE(std::fwrite(v1.data(), 1, v1.size(), f) == v1.size());
    REQUIRE(std::fclose(f) == 0);
    WARN("rewrote " << k_v1_file);
  }
  std::vector<uint8_t> bytes;
  const Status rs = read_file_bytes(k_v1_file, &bytes);
  INFO(rs.message);
  REQUIRE(rs.ok());
  REQUIRE(bytes.size() > 12);
  CHECK(bytes[8] == 1);  // format version, little-endian
  ReplayReadInfo info;
  const Replay r = read_ok(bytes, &info);
  CHECK(info.closed);
  CHECK(r.header.format_version == 1);
  CHECK(r.header.state_format_version == 1);
  CHECK(r.tick_count() == 20);
  CHECK(r.keyframes.size() == 5);
  for (const TickRecord& t : r.ticks) CHECK_FALSE(t.has_game_state);
  const VerifyReport v = verify_replay(r);
  INFO(format_verify_report(v));
  CHECK(v.ok());
  CHECK(v.hashes_checked == 20);
  CHECK(v.keyframes_checked == 5);
  CHECK(v.game_states_recorded == 0);
  // The same recording made now, written as format 1, is the committed file to the byte.
  RecordSpec spec;
  spec.ticks = 20;
  spec.keyframe_interval = 5;
  CHECK(encode_replay(read_ok(record_scene(spec)), 1, 1) == bytes);
}

TEST_CASE("replay format 2: game states per tick and per keyframe round-trip, and format 1 leaves them out",
          "[replay][file][version]") {
  Replay r = read_ok(record_scene(RecordSpec{}));
  REQUIRE(r.header.format_version == 2);
  for (TickRecord& t : r.ticks) {
    t.has_game_state = t.tick % 3 != 0;  // not every tick
    if (t.has_game_state) t.game_state = {static_cast<uint8_t>(t.tick), 0xAB, static_cast<uint8_t>(t.tick * 7)};
  }
  r.keyframes[0].game_state = {1, 2, 3, 4};
  for (uint32_t chunk : {1u, 4u}) {
    const Replay back = read_ok(encode_replay(r, chunk));
    REQUIRE(back.tick_count() == r.tick_count());
    for (int64_t t = 1; t <= r.tick_count(); ++t) {
      CHECK(back.tick_record(t).has_game_state == r.tick_record(t).has_game_state);
      CHECK(back.tick_record(t).game_state == r.tick_record(t).game_state);
    }
    CHECK(back.keyframes[0].game_state == r.keyframes[0].game_state);
    CHECK(back.keyframes[1].game_state.empty());
  }
  const Replay v1 = read_ok(encode_replay(r, 1, 1));
  CHECK(v1.header.format_version == 1);
  for (const TickRecord& t : v1.ticks) CHECK_FALSE(t.has_game_state);
  CHECK(v1.keyframes[0].game_state.empty());
}

TEST_CASE("replay header: the state format version is the tick-0 image's (2 with joints)", "[replay][file][version]") {
  const WorldId w = joint_world();
  std::vector<uint8_t> image;
  REQUIRE(encode_world_state(w, &image).ok());
  REQUIRE(image[4] == k_state_format_version_joints);
  ReplayWriter writer;
  writer.open_memory();
  REQUIRE(writer.write_header(ReplayHeader{}, image).ok());
  REQUIRE(writer.finish().ok());
  Replay r = read_ok(writer.memory());
  CHECK(r.header.state_format_version == k_state_format_version_joints);
  // Format 1 said 1 whatever the images were; such files still read.
  const Replay v1 = read_ok(encode_replay(r, 1, 1));
  CHECK(v1.header.state_format_version == k_state_format_version);
  CHECK(v1.keyframes[0].state == image);
  // A format 2 header that contradicts its image is refused, naming both.
  std::vector<uint8_t> bad = writer.memory();
  // HEAD payload starts at 12 + 12; the state format version is its third u32.
  bad[24 + 8] = 1;
  // Re-seal the HEAD chunk's checksum (u64 after the payload).
  const uint32_t head_len = static_cast<uint32_t>(bad[16]) | static_cast<uint32_t>(bad[17]) << 8;
  const uint64_t sum = XXH3_64bits(bad.data() + 24, head_len);
  for (size_t i = 0; i < 8; ++i) bad[24 + head_len + i] = static_cast<uint8_t>(sum >> (8 * i));
  Replay out;
  const Status s = read_replay(bad, &out);
  CHECK(s.message == "offset " + std::to_string(24 + head_len + 8 + 12) +
                         ": KEYF chunk at tick 0: the state image is format 2, the HEAD chunk says 1");
  (void)destroy_world(w);
}

TEST_CASE("verify checks recorded game states with the game's logic", "[replay][verify][version]") {
  Replay r = read_ok(record_scene(RecordSpec{}));
  // The "game": a counter of ticks, as 8 bytes, recorded after every tick.
  auto counter = [](int64_t n) {
    std::vector<uint8_t> b(8);
    for (size_t i = 0; i < 8; ++i) b[i] = static_cast<uint8_t>(n >> (8 * i));
    return b;
  };
  r.keyframes[0].game_state = counter(100);
  for (TickRecord& t : r.ticks) {
    t.has_game_state = true;
    t.game_state = counter(100 + t.tick);
  }
  VerifyOptions options;
  options.game = [](int64_t, WorldId, std::span<const uint8_t> before, std::vector<uint8_t>* after) {
    if (before.size() != 8) return Status{StatusCode::invalid_argument, "expected 8 bytes"};
    uint64_t n = 0;
    for (size_t i = 0; i < 8; ++i) n |= uint64_t{before[i]} << (8 * i);
    ++n;
    after->resize(8);
    for (size_t i = 0; i < 8; ++i) (*after)[i] = static_cast<uint8_t>(n >> (8 * i));
    return Status{};
  };
  const Replay back = read_ok(encode_replay(r));
  VerifyReport v = verify_replay(back, options);
  INFO(format_verify_report(v));
  CHECK(v.ok());
  CHECK(static_cast<int64_t>(v.game_states_recorded) == back.tick_count());
  CHECK(static_cast<int64_t>(v.game_states_checked) == back.tick_count());
  // Without the logic they are counted, not checked.
  v = verify_replay(back);
  CHECK(v.ok());
  CHECK(v.game_states_checked == 0);
  CHECK(format_verify_report(v).find("game states recorded: 20 (not checked") != std::string::npos);
  // One score changed at tick 7: a game state mismatch there, the world matching.
  r.ticks[6].game_state[1] = 9;
  v = verify_replay(read_ok(encode_replay(r)), options);
  CHECK(v.mismatch);
  CHECK(v.game_state_mismatch);
  CHECK(v.mismatch_tick == 7);
  CHECK(v.hashes_checked == 7);
  CHECK(v.game_states_checked == 6);
  CHECK(v.note == "the world matches; the game state after tick 7 (8 bytes recorded, 8 recomputed) differs from the first byte 1");
  CHECK(verify_exit_code(v) == 1);
}

TEST_CASE("replay format 1: files the command line wrote before format 2 read and re-encode to the byte",
          "[replay][file][version]") {
  // The fuzz seeds were recorded by `tandem record` in format 1 (scripts/fuzz.sh
  // --make-seeds), by an engine whose results have changed since, so they are
  // read, not verified (test_scene_v1.tnr is verified above).
  for (const char* name : {"stack.tdr", "dominoes.tdr", "impulses.tdr"}) {
    INFO(name);
    std::vector<uint8_t> bytes;
    REQUIRE(read_file_bytes(std::string(TANDEM_SESSION_SOURCE_DIR) + "/tests/fuzz/corpus/replay_file/" + name, &bytes).ok());
    const Replay r = read_ok(bytes);
    CHECK(r.tick_count() > 0);
    if (r.header.format_version == 1) CHECK(encode_replay(r, 1, 1) == bytes);
  }
}

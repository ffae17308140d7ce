// The names deprecated in this release (README "Naming and deprecations")
// still work for one release and do exactly what their replacements do. The
// deprecation warnings are silenced in this file only; every other in-tree
// user calls the new names (the build is -Werror).
#include <catch2/catch.hpp>

#include "replay_file_test_support.h"
#include "replay/session_packet.h"
#include "replay/verify.h"

using namespace tandem;
using namespace tandem::literals;
using namespace tandem::replay_file_test;

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"

TEST_CASE("deprecated physics names forward to their replacements", "[replay][deprecated]") {
  OwnedWorld world;
  CHECK(world_get_broad_phase(world.id) == world_broad_phase(world.id));
  REQUIRE(world_set_broad_phase(world.id, BroadPhaseKind::grid).ok());
  CHECK(world_get_broad_phase(world.id) == BroadPhaseKind::grid);
  REQUIRE(world_step(world.id, Q32::from_ratio(1, 60)).ok());
  CHECK(world_get_broad_phase_stats(world.id).pairs == world_broad_phase_stats(world.id).pairs);

  const BodyId body = create_body(world.id, default_body_def()).value;
  REQUIRE(body_disable(body).ok());
  CHECK_FALSE(body_is_enabled(body));
  REQUIRE(body_enable(body).ok());
  CHECK(body_is_enabled(body));
  // The replacement names itself in its messages.
  REQUIRE(destroy_body(body).ok());
  const Status stale = body_set_enabled(body, true);
  CHECK(stale.message.rfind("body_set_enabled: ", 0) == 0);
  CHECK(body_enable(body).message == stale.message);
}

TEST_CASE("deprecated bool decoders agree with the Status ones", "[replay][deprecated]") {
  std::vector<uint8_t> bytes;
  ByteWriter w(&bytes);
  const std::vector<Command> commands{make_set_gravity({0_q32, -10_q32}), make_user_input({1, 2, 3})};
  encode_commands(w, commands);

  ByteReader old_reader(bytes.data(), bytes.size());
  std::vector<Command> old_out;
  CHECK(decode_commands(old_reader, &old_out));
  ByteReader reader(bytes.data(), bytes.size());
  std::vector<Command> out;
  CHECK(decode_commands(&reader, &out).ok());
  CHECK(out == old_out);
  CHECK(out == commands);

  // A truncated command: false, and a Status naming the offset.
  ByteReader cut_old(bytes.data(), 6);
  Command c;
  (void)cut_old.u32("command count");
  CHECK_FALSE(decode_command(cut_old, &c));
  ByteReader cut(bytes.data(), 6);
  (void)cut.u32("command count");
  const Status s = decode_command(&cut, &c);
  CHECK(s.code == StatusCode::invalid_argument);
  CHECK(s.message.rfind("offset ", 0) == 0);
  CHECK(s.message == cut.error());
}

TEST_CASE("the deprecated size_t encode_session_packet returns the size, 0 on a refusal", "[replay][deprecated]") {
  SessionPacket p;
  p.type = SessionPacketType::desync;
  p.tick = 12;
  uint8_t buffer[k_packet_max_bytes];
  size_t size = 0;
  REQUIRE(encode_session_packet(p, buffer, sizeof buffer, &size).ok());
  CHECK(encode_session_packet(p, buffer, sizeof buffer) == size);
  p.tick = -1;
  CHECK(encode_session_packet(p, buffer, sizeof buffer) == 0);
}

#pragma GCC diagnostic pop

TEST_CASE("ReplayRecorder::submit_payload returns a Status", "[replay][recorder]") {
  OwnedWorld world;
  ReplayRecorder rec;
  rec.open_memory();
  CHECK(rec.submit_payload({1}).message == "ReplayRecorder::submit_payload: begin() first");
  REQUIRE(rec.begin(world.id, {}).ok());
  REQUIRE(rec.submit_payload({1, 2}).ok());
  const Status big = rec.submit_payload(std::vector<uint8_t>(k_max_user_payload_bytes + 1));
  CHECK(big.code == StatusCode::invalid_argument);
  CHECK(big.message.find(std::to_string(k_max_user_payload_bytes + 1) + " bytes") != std::string::npos);
  REQUIRE(rec.step().ok());
  REQUIRE(rec.finish().ok());
  Replay r;
  REQUIRE(read_replay(rec.memory(), &r).ok());
  REQUIRE(r.tick_count() == 1);
  REQUIRE(r.tick_record(1).commands.size() == 1);  // the refused payload was not recorded
  CHECK(r.tick_record(1).commands[0].payload == std::vector<uint8_t>{1, 2});
}

TEST_CASE("replay ticks are int64_t: negative ticks are refused by name", "[replay][ticks]") {
  const Replay r = read_ok(record_scene(RecordSpec{}));
  OwnedWorld world;
  const Status s = r.seek(world.id, -1);
  CHECK(s.code == StatusCode::invalid_argument);
  CHECK(s.message.rfind("seek: tick -1 is negative", 0) == 0);
  CHECK_FALSE(r.create_world_at(-2).ok());
  VerifyOptions options;
  options.max_ticks = -1;
  CHECK(verify_replay(r, options).error.message == "verify: max_ticks -1 is negative");
  const DiffReport d = diff_replay_live(r, world.id, [](int64_t) { return Status{}; }, -3);
  CHECK(d.error.message == "diff: tick count -3 is negative");
}

TEST_CASE("a replay tick above INT64_MAX in the file is refused with its offset", "[replay][ticks]") {
  std::vector<uint8_t> bytes = record_scene(RecordSpec{});
  Replay r;
  REQUIRE(read_replay(bytes, &r).ok());
  // Re-encode with the first TICK record's tick set to 2^63 and read back.
  Replay bad = r;
  bad.ticks[0].tick = INT64_MIN;  // written as its u64 bits: 2^63
  const std::vector<uint8_t> image = encode_replay(bad);
  Replay back;
  const Status s = read_replay(image, &back);
  CHECK_FALSE(s.ok());
  CHECK(s.message.find("expected tick 0…9223372036854775807, got 9223372036854775808") != std::string::npos);
  CHECK(s.message.rfind("offset ", 0) == 0);
}

// Helpers shared by the replay-file, verify and command tests: a tiny scene
// built from commands (so the recording carries its own creation), a
// recording loop that can perturb one body out of band (a simulated desync),
// and a walk over a file's chunk framing.
#pragma once

#include <catch2/catch.hpp>

#include <cstdint>
#include <vector>

#include "physics/tandem.h"
#include "replay/commands.h"
#include "replay/replay_file.h"
#include "replay/state.h"
#include "../test_world.h"

namespace tandem::replay_file_test {

using namespace tandem::literals;

/// A world destroyed at the end of the scope.
struct OwnedWorld : UniqueWorld {
  explicit OwnedWorld(const WorldDef& def = default_world_def()) : UniqueWorld(test_world::require_world(def).release()) {}
  explicit OwnedWorld(WorldId w) : UniqueWorld(w) {}
};

inline ShapeSpec box_spec(Q32 hw, Q32 hh) {
  ShapeSpec s;
  s.kind = ShapeKind::polygon;
  REQUIRE(make_box(hw, hh, &s.polygon).ok());
  return s;
}

inline ShapeSpec circle_spec(Q32 r) {
  ShapeSpec s;
  s.kind = ShapeKind::circle;
  s.circle.radius = r;
  return s;
}

inline Command create_at(BodyType type, Vec2 p, ShapeSpec shape) {
  BodyDef d = default_body_def();
  d.type = type;
  d.position = p;
  return make_create_body(d, {std::move(shape)});
}

/// Commands of tick `tick` (1-based) of the small test scene: tick 1 creates
/// a ground (body 0), two boxes that fall onto it (bodies 1, 2) and a
/// floating ball far away (body 3, gravity scale 0, drifting); later ticks
/// push bodies around. Body 3 never touches anything, so a perturbation of it
/// stays in its own record.
inline std::vector<Command> scene_commands(int64_t tick) {
  std::vector<Command> out;
  if (tick == 1) {
    out.push_back(create_at(BodyType::static_body, {0_q32, -1_q32}, box_spec(10_q32, 1_q32)));
    out.push_back(create_at(BodyType::dynamic_body, {-1_q32, 1_q32}, box_spec(0.5_q32, 0.5_q32)));
    out.push_back(create_at(BodyType::dynamic_body, {0.2_q32, 2.5_q32}, circle_spec(0.4_q32)));
    BodyDef d = default_body_def();
    d.type = BodyType::dynamic_body;
    d.position = {50_q32, 50_q32};
    d.gravity_scale = 0_q32;
    d.linear_velocity = {0.25_q32, -0.125_q32};
    d.enable_sleep = false;
    out.push_back(make_create_body(d, {circle_spec(0.5_q32)}));
  }
  if (tick % 7 == 3) out.push_back(make_apply_linear_impulse_to_center(BodyRef{1, 1}, {0.5_q32, 1_q32}));
  if (tick % 11 == 5) out.push_back(make_apply_torque(BodyRef{2, 1}, 2_q32));
  if (tick == 9) out.push_back(make_set_gravity({0_q32, -9_q32}));
  return out;
}

/// How a recording is made.
struct RecordSpec {
  int64_t ticks = 20;
  uint32_t keyframe_interval = 5;
  bool hashes = true;
  uint32_t flush_every = 1;
  int64_t perturb_tick = 0;      ///< 0: none; else after this tick's step, before its hash
  uint32_t perturb_body = 3;     ///< body index perturbed
  bool with_payloads = false;    ///< also record a payload each tick (the game applies its meaning itself)
  BroadPhaseKind broad_phase = BroadPhaseKind::naive;
};

/// What the test game makes of a payload: byte 0 = body index, byte 1 =
/// impulse in 1/8 N·s upwards.
inline Status payload_to_commands(int64_t, std::span<const uint8_t> p, std::vector<Command>* out) {
  if (p.size() != 2) return Status{StatusCode::invalid_argument, "payload of " + std::to_string(p.size()) + " bytes"};
  out->push_back(make_apply_linear_impulse_to_center(BodyRef{p[0], 1}, {0_q32, Q32::from_ratio(p[1], 8)}));
  return Status{};
}

/// Records the test scene with a ReplayWriter in memory and returns the file
/// image. The loop is written out (rather than ReplayRecorder) so that it can
/// perturb the state after a step, as a desync would.
inline std::vector<uint8_t> record_scene(const RecordSpec& spec) {
  WorldDef def = default_world_def();
  def.broad_phase = spec.broad_phase;
  OwnedWorld world(def);
  ReplayWriter writer;
  writer.open_memory(ReplayWriterOptions{spec.flush_every});
  ReplayHeader header;
  header.keyframe_interval = spec.keyframe_interval;
  header.tick_hashes = spec.hashes;
  const char scene[] = "{\"scene\": \"test\"}";
  header.has_scene_bytes = true;
  header.scene_bytes.assign(scene, scene + sizeof scene - 1);
  header.has_scene_hash = true;
  header.scene_hash = 0x1234;
  std::vector<uint8_t> state;
  REQUIRE(encode_world_state(world.id, &state).ok());
  REQUIRE(writer.write_header(header, state).ok());
  for (int64_t t = 1; t <= spec.ticks; ++t) {
    TickRecord rec;
    rec.tick = t;
    rec.commands = scene_commands(t);
    for (const Command& c : rec.commands) REQUIRE(apply_command(world.id, c).ok());
    if (spec.with_payloads && t >= 2) {
      const std::vector<uint8_t> payload{static_cast<uint8_t>(1 + t % 2), static_cast<uint8_t>(t % 5)};
      std::vector<Command> derived;
      REQUIRE(payload_to_commands(t, payload, &derived).ok());
      for (const Command& c : derived) REQUIRE(apply_command(world.id, c).ok());
      rec.commands.push_back(make_user_input(payload));
    }
    REQUIRE(world_step(world.id, header.time_step).ok());
    if (t == spec.perturb_tick) {
      const BodyId b = body_id(world.id, BodyRef{spec.perturb_body, 1});
      Vec2 v = body_linear_velocity(b);
      v.x.raw += 1;
      REQUIRE(body_set_linear_velocity(b, v).ok());
    }
    rec.has_hash = spec.hashes;
    if (spec.hashes) rec.hash = world_state_hash(world.id);
    REQUIRE(writer.append_tick(rec).ok());
    if (spec.keyframe_interval != 0 && t % spec.keyframe_interval == 0) {
      REQUIRE(encode_world_state(world.id, &state).ok());
      REQUIRE(writer.append_keyframe(t, state).ok());
    }
  }
  REQUIRE(writer.finish().ok());
  return writer.memory();
}

inline Replay read_ok(const std::vector<uint8_t>& bytes) {
  Replay r;
  ReplayReadInfo info;
  const Status s = read_replay(bytes, &r, &info);
  INFO(s.message);
  REQUIRE(s.ok());
  REQUIRE(info.warning.empty());
  return r;
}

/// One chunk's framing as found in a file image.
struct ChunkSpan {
  size_t offset = 0;   ///< of the chunk header
  uint32_t type = 0;
  size_t length = 0;   ///< payload bytes
  size_t end = 0;      ///< one past the checksum
  uint64_t ticks_in = 0;  ///< TICK: records in it
};

inline uint32_t le32(const std::vector<uint8_t>& b, size_t at) {
  return static_cast<uint32_t>(b[at]) | static_cast<uint32_t>(b[at + 1]) << 8 | static_cast<uint32_t>(b[at + 2]) << 16 |
         static_cast<uint32_t>(b[at + 3]) << 24;
}

/// The chunks of a well-formed image (trusting its framing).
inline std::vector<ChunkSpan> chunks_of(const std::vector<uint8_t>& b) {
  std::vector<ChunkSpan> out;
  size_t at = k_replay_prelude_bytes;
  while (at < b.size()) {
    ChunkSpan c;
    c.offset = at;
    c.type = le32(b, at);
    c.length = le32(b, at + 4);
    c.end = at + k_chunk_header_bytes + c.length + k_chunk_trailer_bytes;
    if (c.type == k_chunk_tick) c.ticks_in = le32(b, at + k_chunk_header_bytes);
    out.push_back(c);
    at = c.end;
  }
  REQUIRE(at == b.size());
  return out;
}

}  // namespace tandem::replay_file_test

// fuzz_targets.cpp — see fuzz_targets.h.
#include "fuzz_targets.h"

#include <array>
#include <cstdio>
#include <cstdlib>
#include <string_view>
#include <vector>

#include "fixed/fault.h"
#include "fixed/fixed.h"
#include "physics/tandem.h"
#include "replay/bytes.h"
#include "replay/commands.h"
#include "replay/replay_file.h"
#include "replay/session.h"
#include "replay/session_packet.h"
#include "replay/state.h"
#include "scene/scene.h"

#define XXH_INLINE_ALL
#include <xxhash.h>

namespace tandem::fuzz {
namespace {

constexpr Q32 k_dt = Q32::from_ratio(1, 60);

// A fixed-point fault saturates to a defined value in every build; debug
// builds abort on it by default. The targets look for crashes, UB and hangs
// in the parsers and what they accept, so faults are ignored unless
// TANDEM_FUZZ_FAULTS=abort (then a fault after an accepted input is a
// finding: state outside the limits got in).
void ignore_fault(FixedFault, const char*) {}
void setup_faults() {
  static const bool done = [] {
    const char* mode = std::getenv("TANDEM_FUZZ_FAULTS");
    if (mode == nullptr || std::string_view(mode) != "abort") set_fixed_fault_handler(ignore_fault);
    return true;
  }();
  (void)done;
}

[[noreturn]] void broken(const char* what) {
  std::fprintf(stderr, "fuzz invariant broken: %s\n", what);
  std::abort();
}

Outcome refused(std::string message) {
  if (message.empty()) broken("a refusal without a message");
  return Outcome{false, std::move(message)};
}

// Steps a world `n` times; a refused step is a finding only if the world is
// valid and unlocked (nothing else refuses a step).
void step(WorldId world, int n) {
  for (int i = 0; i < n; ++i) (void)world_step(world, k_dt);
}

uint32_t get_u32(const std::vector<uint8_t>& b, size_t at) {
  uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | b[at + static_cast<size_t>(i)];
  return v;
}
void put_u32(std::vector<uint8_t>* b, size_t at, uint32_t v) {
  for (size_t i = 0; i < 4; ++i) (*b)[at + i] = static_cast<uint8_t>(v >> (8 * i));
}
void put_u64(std::vector<uint8_t>* b, size_t at, uint64_t v) {
  for (size_t i = 0; i < 8; ++i) (*b)[at + i] = static_cast<uint8_t>(v >> (8 * i));
}

// Rewrites every checksum of a replay image to match its bytes: each chunk's
// header check (XXH3 of type and length) and payload checksum, and each KEYF
// chunk's state image hash (layout: replay/replay_file.h). So mutations reach
// the decoders behind the checksums instead of stopping at them; stops at the
// first chunk that does not fit.
std::vector<uint8_t> with_valid_checksums(std::span<const uint8_t> data) {
  std::vector<uint8_t> b(data.begin(), data.end());
  size_t at = 12;  // magic, format version
  while (at + k_chunk_header_bytes <= b.size()) {
    const uint32_t type = get_u32(b, at), length = get_u32(b, at + 4);
    uint8_t tl[8];
    for (size_t i = 0; i < 4; ++i) tl[i] = static_cast<uint8_t>(type >> (8 * i)), tl[4 + i] = static_cast<uint8_t>(length >> (8 * i));
    put_u32(&b, at + 8, static_cast<uint32_t>(XXH3_64bits(tl, 8)));
    const size_t payload = at + k_chunk_header_bytes;
    if (length > b.size() - payload || b.size() - payload - length < 8) break;
    if (type == k_chunk_keyframe && length >= 20) {
      const uint32_t n = get_u32(b, payload + 16);
      if (n <= length - 20) put_u64(&b, payload + 8, XXH3_64bits(b.data() + payload + 20, n));
    }
    put_u64(&b, payload + length, XXH3_64bits(b.data() + payload, length));
    at = payload + length + 8;
  }
  return b;
}

}  // namespace

Outcome run_replay_file(std::span<const uint8_t> data) {
  setup_faults();
  // The bytes as given (so the checksum refusals are exercised), then with
  // every checksum made to match (so the decoders behind them are).
  Replay raw;
  const Status raw_status = read_replay(data, &raw);
  if (!raw_status.ok() && raw_status.message.empty()) broken("a refusal without a message");
  const std::vector<uint8_t> fixed = with_valid_checksums(data);
  Replay replay;
  ReplayReadInfo info;
  const Status st = read_replay(fixed, &replay, &info);
  if (!st.ok()) return refused(st.message);
  // TANDEM_FUZZ_REPLAY_READ_ONLY=1: the reader alone (restore, which the
  // snapshot target covers, is skipped).
  static const bool read_only = std::getenv("TANDEM_FUZZ_REPLAY_READ_ONLY") != nullptr;
  if (replay.keyframes.empty() || read_only) return Outcome{true, {}};
  const int64_t tick = replay.tick_count() < 30 ? replay.tick_count() : 30;
  Result<WorldId> w = replay.create_world_at(tick);
  if (w.ok()) {
    step(w.value, 2);
    (void)destroy_world(w.value);
  }
  return Outcome{true, {}};
}

Outcome run_snapshot(std::span<const uint8_t> data) {
  setup_faults();
  Result<WorldId> w = create_world_from_snapshot(data.data(), data.size());
  if (!w.ok()) return refused(w.status.message);
  step(w.value, 30);
  (void)world_state_hash(w.value);
  (void)destroy_world(w.value);
  return Outcome{true, {}};
}

Outcome run_commands(std::span<const uint8_t> data) {
  setup_faults();
  ByteReader reader(data);
  std::vector<Command> commands;
  if (!decode_commands(&reader, &commands).ok() || !reader.ok()) return refused(reader.error());
  // Round trip: the accepted prefix re-encodes to the same bytes.
  std::vector<uint8_t> again;
  ByteWriter writer(&again);
  encode_commands(writer, commands);
  if (again.size() != reader.offset() || !std::equal(again.begin(), again.end(), data.begin()))
    broken("decode_commands then encode_commands changed the bytes");
  // Apply them to a small world: a floor and two boxes (body indices 0..2,
  // generation 1), so body refs in the input can hit real bodies.
  Result<WorldId> w = create_world(default_world_def());
  if (!w.ok()) broken("create_world failed");
  BodyDef floor_def = default_body_def();
  const BodyId floor = create_body(w.value, floor_def).value;
  Polygon box{};
  (void)make_box(Q32::from_int(20), Q32::from_int(1), &box);
  (void)create_polygon_shape(floor, default_shape_def(), box);
  for (int i = 0; i < 2; ++i) {
    BodyDef d = default_body_def();
    d.type = BodyType::dynamic_body;
    d.position = Vec2{Q32::from_int(i * 2), Q32::from_int(2)};
    const BodyId b = create_body(w.value, d).value;
    Polygon small{};
    (void)make_box(Q32::from_ratio(1, 2), Q32::from_ratio(1, 2), &small);
    (void)create_polygon_shape(b, default_shape_def(), small);
  }
  for (const Command& c : commands) (void)apply_command(w.value, c);
  step(w.value, 3);
  (void)destroy_world(w.value);
  return Outcome{true, {}};
}

Outcome run_scene(std::span<const uint8_t> data) {
  setup_faults();
  const std::string_view text(reinterpret_cast<const char*>(data.data()), data.size());
  scene::SceneLimits limits;
  limits.max_bodies = 300;
  limits.max_shapes = 1200;
  Result<scene::Scene> loaded = scene::load_scene_text(text, "fuzz.json", limits);
  if (!loaded.ok()) return refused(loaded.status.message);
  Result<scene::BuiltScene> built = scene::build_world(loaded.value);
  if (!built.ok()) return Outcome{true, built.status.message};
  for (int64_t tick = 0; tick < 5; ++tick) {
    (void)scene::apply_scene_inputs(built.value, loaded.value, tick);
    (void)world_step(built.value.world, loaded.value.time_step);
  }
  (void)destroy_world(built.value.world);
  return Outcome{true, {}};
}

Outcome run_decimal(std::span<const uint8_t> data) {
  setup_faults();
  const std::string_view text(reinterpret_cast<const char*>(data.data()), data.size());
  const FixedParse<Q32> a = parse_q32(text);
  const FixedParse<Q16> b = parse_q16(text);
  auto check_refusal = [&](bool ok, const char* error, size_t offset) {
    if (!ok && error == nullptr) broken("a failed parse without a message");
    if (!ok && offset > text.size()) broken("a parse error offset past the end of the text");
  };
  check_refusal(a.ok(), a.error, a.error_offset);
  check_refusal(b.ok(), b.error, b.error_offset);
  if (a.ok()) {
    const FixedParse<Q32> again = parse_q32(to_string(a.value));
    if (!again.ok() || again.value.raw != a.value.raw) broken("Q32 to_string does not parse back to the same value");
  }
  if (b.ok()) {
    const FixedParse<Q16> again = parse_q16(to_string(b.value));
    if (!again.ok() || again.value.raw != b.value.raw) broken("Q16 to_string does not parse back to the same value");
  }
  if (!a.ok()) return refused(describe_parse_error(text, a.error, a.error_offset));
  return Outcome{true, {}};
}

Outcome run_session_packet(std::span<const uint8_t> data) {
  setup_faults();
  SessionPacket packet;
  const Status st = decode_session_packet(data.data(), data.size(), SessionPacketLimits{}, &packet);
  if (st.ok()) {
    // Round trip: an accepted packet re-encodes to exactly its bytes.
    std::array<uint8_t, k_packet_max_bytes> again{};
    size_t n = 0;
    const Status encoded = encode_session_packet(packet, again.data(), again.size(), &n);
    if (!encoded.ok() || n != data.size() || !std::equal(data.begin(), data.end(), again.begin()))
      broken("decode_session_packet then encode_session_packet changed the bytes");
  } else if (st.message.empty()) {
    broken("a refusal without a message");
  }
  // The session that would receive it: endpoint 0 of 2, a floor and a box.
  Result<WorldId> w = create_world(default_world_def());
  if (!w.ok()) broken("create_world failed");
  const BodyId floor = create_body(w.value, default_body_def()).value;
  Polygon box{};
  (void)make_box(Q32::from_int(20), Q32::from_int(1), &box);
  (void)create_polygon_shape(floor, default_shape_def(), box);
  BodyDef d = default_body_def();
  d.type = BodyType::dynamic_body;
  d.position = Vec2{Q32{}, Q32::from_int(3)};
  const BodyId b = create_body(w.value, d).value;
  (void)make_box(Q32::from_ratio(1, 2), Q32::from_ratio(1, 2), &box);
  (void)create_polygon_shape(b, default_shape_def(), box);
  SessionConfig config;
  config.player_count = 2;
  config.local_endpoint = 0;
  config.input_bytes = 4;
  config.history_ticks = 16;
  SessionCallbacks callbacks;
  callbacks.send = [](uint32_t, std::span<const uint8_t>) {};
  callbacks.make_commands = [b](int64_t, const SessionTickInputs& in, WorldId, std::vector<Command>* out) {
    const Q32 push = Q32::from_int(static_cast<int8_t>(in.input(1)[0]));
    out->push_back(make_apply_force_to_center(body_ref(b), Vec2{push, Q32{}}));
    return Status{};
  };
  Session session;
  if (!session.start(w.value, config, std::move(callbacks)).ok()) broken("Session::start refused a valid config");
  const uint8_t input[4] = {1, 2, 3, 4};
  for (int frame = 0; frame < 3; ++frame) {
    session.receive(1, data);
    (void)session.advance_frame(input);
  }
  if (!st.ok() && session.stats().packets_rejected == 0) broken("the session accepted a packet the decoder refuses");
  (void)destroy_world(w.value);
  return st.ok() ? Outcome{true, {}} : refused(st.message);
}

std::span<const Target> all_targets() {
  static const std::array<Target, 6> targets = {{
      {"replay_file", run_replay_file},
      {"snapshot", run_snapshot},
      {"commands", run_commands},
      {"scene", run_scene},
      {"decimal", run_decimal},
      {"session_packet", run_session_packet},
  }};
  return targets;
}

}  // namespace tandem::fuzz

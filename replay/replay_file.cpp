// replay_file.cpp — writing, reading and seeking replay files (the format is
// documented byte by byte in replay_file.h).
//
// The reader works on the whole file in memory and walks the chunks with a
// ByteReader per level: the file reader checks framing and checksums, a
// payload reader (offset-shifted into file offsets in messages) decodes the
// payload. A payload error is reported at its file offset, so
// "offset 1234: expected 8 bytes of body index" points into the file.
#define XXH_INLINE_ALL
#include <xxhash.h>

#include "replay/replay_file.h"

#include <cerrno>
#include <cinttypes>
#include <cstring>
#include <utility>

#include "replay/state.h"

namespace tandem {

namespace {

uint64_t xxh64(std::span<const uint8_t> bytes) { return XXH3_64bits(bytes.data(), bytes.size()); }

std::string hex64(uint64_t v) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "0x%016" PRIx64, v);
  return buf;
}

std::string chunk_name(uint32_t type) {
  std::string s;
  for (int i = 0; i < 4; ++i) {
    const auto c = static_cast<char>((type >> (8 * i)) & 0xFFu);
    if (c >= 0x20 && c < 0x7F)
      s += c;
    else
      s += '?';
  }
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

uint32_t chunk_header_check(uint32_t type, uint32_t length) {
  uint8_t b[8];
  for (int i = 0; i < 4; ++i) {
    b[i] = static_cast<uint8_t>(type >> (8 * i));
    b[4 + i] = static_cast<uint8_t>(length >> (8 * i));
  }
  return static_cast<uint32_t>(XXH3_64bits(b, 8));
}

Status error(const std::string& message) { return Status{StatusCode::invalid_argument, message}; }

// A tick field: u64 in the file, int64_t in the API; above INT64_MAX is refused.
int64_t read_tick(ByteReader& r, const char* what) {
  const size_t at = r.offset();
  const uint64_t v = r.u64(what);
  if (r.ok() && v > static_cast<uint64_t>(INT64_MAX)) {
    r.fail_at(at, std::string("expected ") + what + " 0…" + std::to_string(INT64_MAX) + ", got " + std::to_string(v));
    return 0;
  }
  return static_cast<int64_t>(v);
}

// Re-bases a payload reader's message ("offset N: ...") onto file offsets.
Status payload_error(const ByteReader& r, size_t payload_offset, const char* chunk) {
  const size_t at = payload_offset + r.error_offset();
  std::string msg = r.error();
  const size_t colon = msg.find(": ");
  if (colon != std::string::npos) msg = msg.substr(colon + 2);
  return error("offset " + std::to_string(at) + ": " + chunk + " chunk: " + msg);
}

void encode_header_payload(ByteWriter& w, const ReplayHeader& h) {
  w.u32(h.engine_version);
  w.u32(h.fixed_format);
  w.u32(h.state_format_version);
  w.q32(h.time_step);
  w.u32(h.keyframe_interval);
  w.u8(h.tick_hashes ? 1 : 0);
  w.u8(static_cast<uint8_t>((h.has_scene_bytes ? 1 : 0) | (h.has_scene_hash ? 2 : 0)));
  w.u64(h.has_scene_hash ? h.scene_hash : 0);
  const size_t n = h.has_scene_bytes ? h.scene_bytes.size() : 0;
  w.u32(static_cast<uint32_t>(n));
  w.bytes(h.scene_bytes.data(), n);
}

void encode_keyframe_payload(ByteWriter& w, int64_t tick, std::span<const uint8_t> state,
                             std::span<const uint8_t> game_state, uint32_t version) {
  w.u64(static_cast<uint64_t>(tick));  // ≥ 0: the writer and the reader check it
  w.u64(xxh64(state));
  w.u32(static_cast<uint32_t>(state.size()));
  w.bytes(state.data(), state.size());
  if (version >= 2) {
    w.u32(static_cast<uint32_t>(game_state.size()));
    w.bytes(game_state.data(), game_state.size());
  }
}

void encode_tick_records(ByteWriter& w, std::span<const TickRecord> records, uint32_t version) {
  w.u32(static_cast<uint32_t>(records.size()));
  for (const TickRecord& t : records) {
    const bool game = version >= 2 && t.has_game_state;
    w.u64(static_cast<uint64_t>(t.tick));
    w.u8(static_cast<uint8_t>((t.has_hash ? 1 : 0) | (game ? 2 : 0)));
    encode_commands(w, t.commands);
    if (t.has_hash) w.u64(t.hash);
    if (game) {
      w.u32(static_cast<uint32_t>(t.game_state.size()));
      w.bytes(t.game_state.data(), t.game_state.size());
    }
  }
}

// The format version a state image names (bytes 4..7, little-endian; 0 when
// the image is too short to say).
uint32_t image_state_version(std::span<const uint8_t> image) {
  if (image.size() < 8) return 0;
  return static_cast<uint32_t>(image[4]) | static_cast<uint32_t>(image[5]) << 8 | static_cast<uint32_t>(image[6]) << 16 |
         static_cast<uint32_t>(image[7]) << 24;
}

void append_chunk(std::vector<uint8_t>* out, uint32_t type, const std::vector<uint8_t>& payload) {
  ByteWriter w(out);
  const auto length = static_cast<uint32_t>(payload.size());
  w.u32(type);
  w.u32(length);
  w.u32(chunk_header_check(type, length));
  w.bytes(payload.data(), payload.size());
  w.u64(xxh64(payload));
}

// The END payload. Written through a fixed buffer: appending 8 bytes to an
// empty vector makes g++ 12 at -O3 on i686 report a false -Wstringop-overflow.
std::vector<uint8_t> end_payload(uint64_t tick_count) {
  uint8_t buf[8];
  ByteWriter w(buf, sizeof buf);
  w.u64(tick_count);
  return std::vector<uint8_t>(buf, buf + sizeof buf);
}

// The 12 prelude bytes (through a fixed buffer, as end_payload).
std::vector<uint8_t> prelude_bytes(uint32_t version) {
  uint8_t buf[k_replay_prelude_bytes];
  ByteWriter w(buf, sizeof buf);
  w.bytes(k_replay_magic, sizeof k_replay_magic);
  w.u32(version);
  return std::vector<uint8_t>(buf, buf + sizeof buf);
}

}  // namespace

// --- running ------------------------------------------------------------------

Status run_tick(WorldId world, const TickRecord& record, Q32 time_step, const PayloadHandler& payloads,
                uint32_t* out_refused, uint32_t* out_skipped) {
  std::vector<Command> derived;
  for (const Command& c : record.commands) {
    if (c.type == CommandType::user_input) {
      if (!payloads) {
        if (out_skipped != nullptr) ++*out_skipped;
        continue;
      }
      derived.clear();
      Status s = payloads(record.tick, c.payload, &derived);
      if (!s.ok()) {
        s.message = "tick " + std::to_string(record.tick) + ": payload handler: " + s.message;
        return s;
      }
      for (const Command& d : derived)
        if (!apply_command(world, d).ok() && out_refused != nullptr) ++*out_refused;
      continue;
    }
    if (!apply_command(world, c).ok() && out_refused != nullptr) ++*out_refused;
  }
  StepResult r = world_step(world, time_step);
  if (!r.ok()) {
    r.status.message = "tick " + std::to_string(record.tick) + ": world_step: " + r.status.message;
    return r.status;
  }
  return Status{};
}

const Keyframe& Replay::keyframe_at_or_before(int64_t tick) const {
  static const Keyframe k_none{};
  if (keyframes.empty()) return k_none;
  size_t best = 0;
  for (size_t i = 0; i < keyframes.size(); ++i)
    if (keyframes[i].tick <= tick) best = i;
  return keyframes[best];
}

Status Replay::seek(WorldId world, int64_t tick, const PayloadHandler& payloads) const {
  if (keyframes.empty()) return error("seek: the replay has no keyframe");
  if (tick < 0) return error("seek: tick " + std::to_string(tick) + " is negative (ticks are 0…" + std::to_string(tick_count()) + ")");
  if (tick > tick_count())
    return error("seek: tick " + std::to_string(tick) + " is past the last recorded tick " +
                 std::to_string(tick_count()));
  const Keyframe& k = keyframe_at_or_before(tick);
  Status s = world_restore(world, k.state.data(), k.state.size());
  if (!s.ok()) {
    s.message = "seek: keyframe at tick " + std::to_string(k.tick) + ": " + s.message;
    return s;
  }
  for (int64_t t = k.tick + 1; t <= tick; ++t) {
    s = run_tick(world, tick_record(t), header.time_step, payloads);
    if (!s.ok()) return s;
  }
  return Status{};
}

Result<WorldId> Replay::create_world_at(int64_t tick, const PayloadHandler& payloads) const {
  Result<WorldId> r;
  if (keyframes.empty()) {
    r.status = error("create_world_at: the replay has no keyframe");
    return r;
  }
  r = create_world_from_snapshot(keyframes[0].state.data(), keyframes[0].state.size());
  if (!r.ok()) return r;
  Status s = seek(r.value, tick, payloads);
  if (!s.ok()) {
    (void)destroy_world(r.value);
    r.status = s;
    r.value = WorldId{};
  }
  return r;
}

// --- reading ------------------------------------------------------------------

bool is_replay_image(std::span<const uint8_t> data) {
  return data.size() >= sizeof k_replay_magic && std::memcmp(data.data(), k_replay_magic, sizeof k_replay_magic) == 0;
}

Status read_file_bytes(const std::string& path, std::vector<uint8_t>* out) {
  out->clear();
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) return error(path + ": cannot open: " + std::strerror(errno));
  uint8_t buf[65536];
  for (;;) {
    const size_t n = std::fread(buf, 1, sizeof buf, f);
    out->insert(out->end(), buf, buf + n);
    if (n < sizeof buf) break;
  }
  const bool failed = std::ferror(f) != 0;
  std::fclose(f);
  if (failed) return error(path + ": read error");
  return Status{};
}

namespace {

Status decode_header(std::span<const uint8_t> p, size_t base, uint32_t version, ReplayHeader* h) {
  ByteReader r(p);
  h->engine_version = r.u32("engine version");
  const size_t fixed_at = r.offset();
  h->fixed_format = r.u32("fixed-point format id");
  if (r.ok() && h->fixed_format != k_fixed_format_q32_32)
    r.fail_at(fixed_at, "expected fixed-point format id " + hex64(k_fixed_format_q32_32).substr(10) +
                            " (Q32.32), got 0x" + hex64(h->fixed_format).substr(10));
  const size_t state_at = r.offset();
  h->state_format_version = r.u32("state format version");
  // Version 1 writers always said 1; version 2 names the tick-0 image's
  // version (checked against the image when it is read).
  const uint32_t state_max = version >= 2 ? k_state_format_version_joints : k_state_format_version;
  if (r.ok() && (h->state_format_version < k_state_format_version || h->state_format_version > state_max))
    r.fail_at(state_at, "state format version " + std::to_string(h->state_format_version) +
                            " is not one this build reads in a version " + std::to_string(version) + " replay (" +
                            std::to_string(k_state_format_version) + "…" + std::to_string(state_max) + ")");
  const size_t step_at = r.offset();
  h->time_step = r.q32("time step");
  if (r.ok() && (h->time_step.raw <= 0 || h->time_step > k_max_time_step))
    r.fail_at(step_at, "expected time step in (0, " + std::to_string(k_max_time_step.raw) + "] raw, got " +
                           std::to_string(h->time_step.raw) + " raw");
  h->keyframe_interval = r.u32("keyframe interval");
  const size_t flags_at = r.offset();
  const uint8_t flags = r.u8("flags");
  const uint8_t scene_flags = r.u8("scene flags");
  if (r.ok() && (flags > 1 || scene_flags > 3))
    r.fail_at(flags_at, "expected flags 0..1 and scene flags 0..3, got " + std::to_string(flags) + " and " +
                            std::to_string(scene_flags));
  h->tick_hashes = (flags & 1) != 0;
  h->has_scene_bytes = (scene_flags & 1) != 0;
  h->has_scene_hash = (scene_flags & 2) != 0;
  h->scene_hash = r.u64("scene hash");
  const size_t scene_at = r.offset();
  const uint32_t n = r.read_count("scene byte count", 1);
  if (r.ok() && n != 0 && !h->has_scene_bytes)
    r.fail_at(scene_at, "scene byte count " + std::to_string(n) + " but the scene flags say no scene bytes");
  const std::span<const uint8_t> scene = r.bytes(n, "scene bytes");
  h->scene_bytes.assign(scene.begin(), scene.end());
  if (r.ok() && !r.at_end()) r.fail("expected the end of the HEAD chunk, " + std::to_string(r.remaining()) + " bytes left");
  if (!r.ok()) return payload_error(r, base, "HEAD");
  return Status{};
}

Status decode_keyframe(std::span<const uint8_t> p, size_t base, uint32_t version, Keyframe* k) {
  ByteReader r(p);
  k->tick = read_tick(r, "keyframe tick");
  k->hash = r.u64("keyframe state hash");
  const uint32_t n = r.read_count("state image byte count", 1);
  const size_t image_at = r.offset();
  const std::span<const uint8_t> image = r.bytes(n, "state image");
  if (version >= 2) {
    const uint32_t g = r.read_count("game state byte count", 1);
    const std::span<const uint8_t> game = r.bytes(g, "game state");
    if (r.ok()) k->game_state.assign(game.begin(), game.end());
  }
  if (r.ok() && !r.at_end()) r.fail("expected the end of the KEYF chunk, " + std::to_string(r.remaining()) + " bytes left");
  if (!r.ok()) return payload_error(r, base, "KEYF");
  const uint64_t actual = xxh64(image);
  if (actual != k->hash)
    return error("offset " + std::to_string(base + image_at) + ": KEYF chunk at tick " + std::to_string(k->tick) +
                 ": state image hash " + hex64(actual) + " differs from the recorded " + hex64(k->hash));
  DecodedState decoded;
  Status s = decode_world_state(image.data(), image.size(), &decoded);
  if (!s.ok())
    return error("offset " + std::to_string(base + image_at) + ": KEYF chunk at tick " + std::to_string(k->tick) +
                 ": state image: " + s.message);
  k->state.assign(image.begin(), image.end());
  return Status{};
}

Status decode_ticks(std::span<const uint8_t> p, size_t base, uint32_t version, int64_t first_tick,
                    std::vector<TickRecord>* out) {
  ByteReader r(p);
  // A record takes at least 8 (tick) + 1 (flags) + 4 (command count) bytes.
  const uint32_t n = r.read_count("tick record count", 13);
  for (uint32_t i = 0; i < n && r.ok(); ++i) {
    TickRecord t;
    const size_t tick_at = r.offset();
    t.tick = read_tick(r, "tick");
    if (r.ok() && t.tick != first_tick + i) {
      r.fail_at(tick_at, "expected tick " + std::to_string(first_tick + i) + ", got " + std::to_string(t.tick));
      break;
    }
    r.set_context("tick", t.tick);
    const size_t flags_at = r.offset();
    const uint8_t flags = r.u8("flags");
    const uint8_t flags_max = version >= 2 ? 3 : 1;
    if (r.ok() && flags > flags_max)
      r.fail_at(flags_at, "expected tick flags 0.." + std::to_string(flags_max) + ", got " + std::to_string(flags));
    t.has_hash = (flags & 1) != 0;
    t.has_game_state = (flags & 2) != 0;
    if (!decode_commands(&r, &t.commands).ok()) break;
    if (t.has_hash) t.hash = r.u64("world hash");
    if (t.has_game_state) {
      const uint32_t g = r.read_count("game state byte count", 1);
      const std::span<const uint8_t> game = r.bytes(g, "game state");
      if (r.ok()) t.game_state.assign(game.begin(), game.end());
    }
    r.set_context(nullptr);
    if (r.ok()) out->push_back(std::move(t));
  }
  if (r.ok() && !r.at_end()) r.fail("expected the end of the TICK chunk, " + std::to_string(r.remaining()) + " bytes left");
  if (!r.ok()) return payload_error(r, base, "TICK");
  return Status{};
}

}  // namespace

Status read_replay(std::span<const uint8_t> data, Replay* out, ReplayReadInfo* info_out) {
  *out = Replay{};
  ReplayReadInfo info;
  ByteReader r(data);
  const std::span<const uint8_t> magic = r.bytes(sizeof k_replay_magic, "magic");
  if (!r.ok()) return error("truncated header: " + r.error());
  if (std::memcmp(magic.data(), k_replay_magic, sizeof k_replay_magic) != 0) {
    std::string got;
    for (uint8_t b : magic) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "%02x", b);
      got += buf;
    }
    return error("offset 0: expected the replay magic \"TANDREPL\", got bytes " + got + " (not a Tandem replay)");
  }
  const uint32_t version = r.u32("format version");
  if (!r.ok()) return error("truncated header: " + r.error());
  if (version < k_replay_format_version_min || version > k_replay_format_version)
    return error("offset 8: unknown replay format version " + std::to_string(version) + " (this build reads versions " +
                 std::to_string(k_replay_format_version_min) + "…" + std::to_string(k_replay_format_version) + ")");
  out->header.format_version = version;

  // Chunks. The first two (HEAD, KEYF at tick 0) are the header: a cut or a
  // fault there is an error; after them a cut is a warning.
  int index = 0;
  int64_t last_tick = 0;
  auto cut = [&](size_t at, const std::string& why) {
    info.truncated = true;
    info.truncated_at = at;
    info.last_complete_tick = last_tick;
    info.warning = "file cut at byte " + std::to_string(at) + " after tick " + std::to_string(last_tick) + " (" + why +
                   "); read " + std::to_string(last_tick) + " complete ticks";
  };
  for (;; ++index) {
    const size_t at = r.offset();
    const bool in_header = index < 2;
    if (r.remaining() == 0) {
      if (in_header)
        return error("truncated header: offset " + std::to_string(at) + ": expected the " +
                     (index == 0 ? "HEAD" : "initial KEYF") + " chunk, the file ends");
      if (!info.closed) cut(at, "no END chunk: the recording was not closed");
      break;
    }
    if (info.closed)
      return error("offset " + std::to_string(at) + ": " + std::to_string(r.remaining()) +
                   " bytes after the END chunk");
    if (r.remaining() < k_chunk_header_bytes) {
      if (in_header)
        return error("truncated header: offset " + std::to_string(at) + ": expected a 12-byte chunk header, " +
                     std::to_string(r.remaining()) + " bytes left");
      cut(at, "mid chunk header: " + std::to_string(r.remaining()) + " of 12 bytes");
      break;
    }
    const uint32_t type = r.u32("chunk type");
    const uint32_t length = r.u32("chunk length");
    const uint32_t check = r.u32("chunk header check");
    if (check != chunk_header_check(type, length))
      return error("offset " + std::to_string(at) + ": corrupted chunk header (type bytes \"" + chunk_name(type) +
                   "\", length " + std::to_string(length) + "): header check mismatch");
    if (type != k_chunk_head && type != k_chunk_keyframe && type != k_chunk_tick && type != k_chunk_end)
      return error("offset " + std::to_string(at) + ": unknown chunk type \"" + chunk_name(type) + "\"");
    const std::string name = chunk_name(type);
    if (static_cast<uint64_t>(length) + k_chunk_trailer_bytes > r.remaining()) {
      if (in_header)
        return error("truncated header: offset " + std::to_string(at) + ": " + name + " chunk declares " +
                     std::to_string(length) + " payload bytes + 8 checksum bytes, " + std::to_string(r.remaining()) +
                     " left");
      cut(at, "mid " + name + " chunk: it declares " + std::to_string(length) + " + 8 bytes, " +
                  std::to_string(r.remaining()) + " left");
      break;
    }
    const size_t payload_at = r.offset();
    const std::span<const uint8_t> payload = r.bytes(length, "chunk payload");
    const uint64_t stored = r.u64("chunk checksum");
    const uint64_t actual = xxh64(payload);
    if (stored != actual)
      return error("offset " + std::to_string(at) + ": " + name + " chunk (payload at " + std::to_string(payload_at) +
                   ".." + std::to_string(payload_at + length) + ") is corrupted: checksum " + hex64(actual) +
                   ", recorded " + hex64(stored));
    info.chunk_count++;
    if (index == 0 && type != k_chunk_head)
      return error("offset " + std::to_string(at) + ": expected the HEAD chunk first, got " + name);
    if (index == 1 && type != k_chunk_keyframe)
      return error("offset " + std::to_string(at) + ": expected the initial KEYF chunk second, got " + name);
    if (type == k_chunk_head) {
      if (index != 0) return error("offset " + std::to_string(at) + ": a second HEAD chunk");
      Status s = decode_header(payload, payload_at, version, &out->header);
      if (!s.ok()) return s;
      out->header.format_version = version;
    } else if (type == k_chunk_keyframe) {
      Keyframe k;
      Status s = decode_keyframe(payload, payload_at, version, &k);
      if (!s.ok()) return s;
      if (index == 1 && version >= 2 && image_state_version(k.state) != out->header.state_format_version)
        return error("offset " + std::to_string(payload_at) + ": KEYF chunk at tick 0: the state image is format " +
                     std::to_string(image_state_version(k.state)) + ", the HEAD chunk says " +
                     std::to_string(out->header.state_format_version));
      if (k.tick != last_tick)
        return error("offset " + std::to_string(payload_at) + ": KEYF chunk: expected keyframe tick " +
                     std::to_string(last_tick) + " (ticks read so far), got " + std::to_string(k.tick));
      if (!out->keyframes.empty() && out->keyframes.back().tick == k.tick)
        return error("offset " + std::to_string(payload_at) + ": KEYF chunk: a second keyframe at tick " +
                     std::to_string(k.tick));
      out->keyframes.push_back(std::move(k));
    } else if (type == k_chunk_tick) {
      Status s = decode_ticks(payload, payload_at, version, last_tick + 1, &out->ticks);
      if (!s.ok()) return s;
      last_tick = static_cast<int64_t>(out->ticks.size());
    } else {  // END
      ByteReader e(payload);
      const uint64_t count = e.u64("tick count");
      if (e.ok() && !e.at_end()) e.fail("expected the end of the END chunk");
      if (!e.ok()) return payload_error(e, payload_at, "END");
      if (count != static_cast<uint64_t>(last_tick))
        return error("offset " + std::to_string(payload_at) + ": END chunk says " + std::to_string(count) +
                     " ticks, the file holds " + std::to_string(last_tick));
      info.closed = true;
    }
  }
  info.last_complete_tick = last_tick;
  if (info_out != nullptr) *info_out = info;
  return Status{};
}

Status read_replay_file(const std::string& path, Replay* out, ReplayReadInfo* info) {
  std::vector<uint8_t> bytes;
  Status s = read_file_bytes(path, &bytes);
  if (!s.ok()) return s;
  s = read_replay(bytes, out, info);
  if (!s.ok()) s.message = path + ": " + s.message;
  if (info != nullptr && !info->warning.empty()) info->warning = path + ": " + info->warning;
  return s;
}

std::vector<uint8_t> encode_replay(const Replay& replay, uint32_t ticks_per_chunk, uint32_t version) {
  if (ticks_per_chunk == 0) ticks_per_chunk = 1;
  if (version < k_replay_format_version_min || version > k_replay_format_version) version = k_replay_format_version;
  std::vector<uint8_t> out = prelude_bytes(version);
  std::vector<uint8_t> payload;
  {
    ReplayHeader h = replay.header;
    h.state_format_version = version >= 2 && !replay.keyframes.empty()
                                 ? image_state_version(replay.keyframes[0].state)
                                 : k_state_format_version;
    ByteWriter w(&payload);
    encode_header_payload(w, h);
  }
  append_chunk(&out, k_chunk_head, payload);
  size_t next_key = 0;
  size_t t = 0;
  auto keyframes_up_to = [&](size_t tick) {
    while (next_key < replay.keyframes.size() && replay.keyframes[next_key].tick <= static_cast<int64_t>(tick)) {
      payload.clear();
      ByteWriter w(&payload);
      encode_keyframe_payload(w, replay.keyframes[next_key].tick, replay.keyframes[next_key].state,
                              replay.keyframes[next_key].game_state, version);
      append_chunk(&out, k_chunk_keyframe, payload);
      ++next_key;
    }
  };
  keyframes_up_to(0);
  while (t < replay.ticks.size()) {
    size_t end = t + ticks_per_chunk;
    if (end > replay.ticks.size()) end = replay.ticks.size();
    // A chunk never spans a keyframe.
    for (size_t k = next_key; k < replay.keyframes.size(); ++k)
      if (replay.keyframes[k].tick > static_cast<int64_t>(t) && replay.keyframes[k].tick < static_cast<int64_t>(end)) {
        end = static_cast<size_t>(replay.keyframes[k].tick);
        break;
      }
    payload.clear();
    ByteWriter w(&payload);
    encode_tick_records(w, std::span<const TickRecord>(replay.ticks.data() + t, end - t), version);
    append_chunk(&out, k_chunk_tick, payload);
    t = end;
    keyframes_up_to(t);
  }
  append_chunk(&out, k_chunk_end, end_payload(replay.ticks.size()));
  return out;
}

// --- writer -------------------------------------------------------------------

ReplayWriter::~ReplayWriter() {
  if (file_ != nullptr) std::fclose(file_);
}

Status ReplayWriter::open_file(const std::string& path, const ReplayWriterOptions& options) {
  if (file_ != nullptr || memory_mode_) return error(path + ": the writer is already open");
  file_ = std::fopen(path.c_str(), "wb");
  if (file_ == nullptr) return error(path + ": cannot create: " + std::strerror(errno));
  path_ = path;
  options_ = options;
  if (options_.flush_every == 0) options_.flush_every = 1;
  return Status{};
}

void ReplayWriter::open_memory(const ReplayWriterOptions& options) {
  memory_mode_ = true;
  options_ = options;
  if (options_.flush_every == 0) options_.flush_every = 1;
}

Status ReplayWriter::emit(const std::vector<uint8_t>& bytes) {
  if (memory_mode_) {
    memory_.insert(memory_.end(), bytes.begin(), bytes.end());
    bytes_written_ += bytes.size();
    return Status{};
  }
  if (file_ == nullptr) return error("replay writer: not open");
  if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size())
    return error(path_ + ": write failed at byte " + std::to_string(bytes_written_) + ": " + std::strerror(errno));
  bytes_written_ += bytes.size();
  return Status{};
}

Status ReplayWriter::write_chunk(uint32_t type, const std::vector<uint8_t>& payload) {
  std::vector<uint8_t> bytes;
  bytes.reserve(payload.size() + k_chunk_header_bytes + k_chunk_trailer_bytes);
  append_chunk(&bytes, type, payload);
  return emit(bytes);
}

Status ReplayWriter::write_header(const ReplayHeader& header, std::span<const uint8_t> initial_state,
                                  std::span<const uint8_t> initial_game_state) {
  if (header_written_) return error("replay writer: the header is already written");
  if (!memory_mode_ && file_ == nullptr) return error("replay writer: not open");
  Status s = emit(prelude_bytes(k_replay_format_version));
  if (!s.ok()) return s;
  std::vector<uint8_t> payload;
  ReplayHeader h = header;
  h.state_format_version = image_state_version(initial_state);
  {
    ByteWriter w(&payload);
    encode_header_payload(w, h);
  }
  s = write_chunk(k_chunk_head, payload);
  if (!s.ok()) return s;
  payload.clear();
  {
    ByteWriter w(&payload);
    encode_keyframe_payload(w, 0, initial_state, initial_game_state, k_replay_format_version);
  }
  s = write_chunk(k_chunk_keyframe, payload);
  if (!s.ok()) return s;
  header_written_ = true;
  if (file_ != nullptr && std::fflush(file_) != 0) return error(path_ + ": flush failed: " + std::strerror(errno));
  return Status{};
}

Status ReplayWriter::append_tick(TickRecord record) {
  if (!header_written_ || finished_) return error("replay writer: append_tick before write_header or after finish");
  if (record.tick != ticks_ + 1)
    return error("replay writer: expected tick " + std::to_string(ticks_ + 1) + ", got " + std::to_string(record.tick));
  pending_.push_back(std::move(record));
  ++ticks_;
  if (pending_.size() >= options_.flush_every) return flush();
  return Status{};
}

Status ReplayWriter::flush() {
  if (!header_written_) return error("replay writer: flush before write_header");
  if (!pending_.empty()) {
    std::vector<uint8_t> payload;
    ByteWriter w(&payload);
    encode_tick_records(w, pending_, k_replay_format_version);
    pending_.clear();
    Status s = write_chunk(k_chunk_tick, payload);
    if (!s.ok()) return s;
  }
  if (file_ != nullptr && std::fflush(file_) != 0) return error(path_ + ": flush failed: " + std::strerror(errno));
  return Status{};
}

Status ReplayWriter::append_keyframe(int64_t tick, std::span<const uint8_t> state,
                                     std::span<const uint8_t> game_state) {
  if (!header_written_ || finished_) return error("replay writer: append_keyframe before write_header or after finish");
  if (tick != ticks_)
    return error("replay writer: keyframe tick " + std::to_string(tick) + " is not the ticks appended (" +
                 std::to_string(ticks_) + ")");
  Status s = flush();
  if (!s.ok()) return s;
  std::vector<uint8_t> payload;
  ByteWriter w(&payload);
  encode_keyframe_payload(w, tick, state, game_state, k_replay_format_version);
  s = write_chunk(k_chunk_keyframe, payload);
  if (!s.ok()) return s;
  if (file_ != nullptr && std::fflush(file_) != 0) return error(path_ + ": flush failed: " + std::strerror(errno));
  return Status{};
}

Status ReplayWriter::finish() {
  if (finished_) return Status{};
  if (!header_written_) return error("replay writer: finish before write_header");
  Status s = flush();
  if (!s.ok()) return s;
  s = write_chunk(k_chunk_end, end_payload(static_cast<uint64_t>(ticks_)));  // ≥ 0
  if (!s.ok()) return s;
  finished_ = true;
  if (file_ != nullptr) {
    const bool failed = std::fclose(file_) != 0;
    file_ = nullptr;
    if (failed) return error(path_ + ": close failed: " + std::strerror(errno));
  }
  return Status{};
}

// --- recorder -----------------------------------------------------------------

Status ReplayRecorder::open_file(const std::string& path, const RecorderOptions& options) {
  options_ = options;
  return writer_.open_file(path, ReplayWriterOptions{options.flush_every});
}

void ReplayRecorder::open_memory(const RecorderOptions& options) {
  options_ = options;
  writer_.open_memory(ReplayWriterOptions{options.flush_every});
}

Status ReplayRecorder::begin(WorldId world, std::span<const uint8_t> scene, std::optional<uint64_t> scene_hash,
                             bool embed_scene) {
  if (begun_) return error("ReplayRecorder::begin: already begun");
  std::vector<uint8_t> state;
  Status s = encode_world_state(world, &state);
  if (!s.ok()) {
    s.message = "ReplayRecorder::begin: " + s.message;
    return s;
  }
  ReplayHeader h;
  h.time_step = options_.time_step;
  h.keyframe_interval = options_.keyframe_interval;
  h.tick_hashes = options_.record_hashes;
  h.has_scene_bytes = embed_scene;
  if (embed_scene) h.scene_bytes.assign(scene.begin(), scene.end());
  h.has_scene_hash = true;
  h.scene_hash = scene_hash.has_value() ? *scene_hash : xxh64(scene);
  s = writer_.write_header(h, state);
  if (!s.ok()) return s;
  world_ = world;
  current_ = TickRecord{};
  current_.tick = 1;
  begun_ = true;
  return Status{};
}

Status ReplayRecorder::submit(const Command& command) {
  if (!begun_) return error("ReplayRecorder::submit: begin() first");
  current_.commands.push_back(command);
  return apply_command(world_, command);
}

Status ReplayRecorder::submit_payload(std::vector<uint8_t> payload) {
  if (!begun_) return error("ReplayRecorder::submit_payload: begin() first");
  if (payload.size() > k_max_user_payload_bytes) {
    return error("ReplayRecorder::submit_payload: payload of " + std::to_string(payload.size()) +
                 " bytes, expected at most " + std::to_string(k_max_user_payload_bytes));
  }
  current_.commands.push_back(make_user_input(std::move(payload)));
  return Status{};
}

StepResult ReplayRecorder::step() {
  StepResult r;
  if (!begun_) {
    r.status = error("ReplayRecorder::step: begin() first");
    return r;
  }
  r = world_step(world_, options_.time_step);
  if (!r.ok()) return r;
  if (options_.record_hashes) {
    current_.has_hash = true;
    current_.hash = world_state_hash(world_);
    last_hash_ = current_.hash;
  }
  const int64_t tick = current_.tick;
  Status s = writer_.append_tick(std::move(current_));
  current_ = TickRecord{};
  current_.tick = tick + 1;
  if (s.ok() && options_.keyframe_interval != 0 && tick % int64_t{options_.keyframe_interval} == 0) {
    std::vector<uint8_t> state;
    s = encode_world_state(world_, &state);
    if (s.ok()) s = writer_.append_keyframe(tick, state);
  }
  if (!s.ok()) r.status = s;
  return r;
}

Status ReplayRecorder::finish() {
  if (!begun_) return error("ReplayRecorder::finish: begin() first");
  return writer_.finish();
}

}  // namespace tandem

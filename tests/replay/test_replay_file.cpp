// Replay files: round trips, every truncation, every corrupted byte, wrong
// magic and version, absurd lengths, crash safety of the writer, and
// keyframe seeks.
#define XXH_INLINE_ALL
#include <xxhash.h>

#include <catch2/catch.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "replay_file_test_support.h"

using namespace tandem;
using namespace tandem::literals;
using namespace tandem::replay_file_test;

namespace {

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }
bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

void put32(std::vector<uint8_t>* b, uint32_t v) {
  for (int i = 0; i < 4; ++i) b->push_back(static_cast<uint8_t>(v >> (8 * i)));
}
void put64(std::vector<uint8_t>* b, uint64_t v) {
  for (int i = 0; i < 8; ++i) b->push_back(static_cast<uint8_t>(v >> (8 * i)));
}

// A chunk with correct framing and checksums around any payload; `length`
// overrides the declared payload length.
std::vector<uint8_t> framed(uint32_t type, const std::vector<uint8_t>& payload, int64_t length = -1) {
  const auto len = length < 0 ? static_cast<uint32_t>(payload.size()) : static_cast<uint32_t>(length);
  std::vector<uint8_t> head;
  put32(&head, type);
  put32(&head, len);
  std::vector<uint8_t> out = head;
  put32(&out, static_cast<uint32_t>(XXH3_64bits(head.data(), 8)));
  out.insert(out.end(), payload.begin(), payload.end());
  put64(&out, XXH3_64bits(payload.data(), payload.size()));
  return out;
}

// The image without its END chunk.
std::vector<uint8_t> without_end(const std::vector<uint8_t>& bytes) {
  const std::vector<ChunkSpan> chunks = chunks_of(bytes);
  REQUIRE(chunks.back().type == k_chunk_end);
  return std::vector<uint8_t>(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(chunks.back().offset));
}

// A fresh path in the temporary directory ($TMPDIR, %TEMP%, or /tmp); no
// <filesystem> (not in every standard library the cross builds use).
std::string temp_path(const char* name) {
  std::string dir = "/tmp";
  for (const char* var : {"TMPDIR", "TEMP", "TMP"}) {
    const char* v = std::getenv(var);
    if (v != nullptr && *v != 0) {
      dir = v;
      break;
    }
  }
  const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
  return dir + "/tandem_test_" + std::to_string(stamp) + "_" + name;
}

}  // namespace

TEST_CASE("a recorded replay reads back exactly", "[replay][file]") {
  const std::vector<uint8_t> bytes = record_scene(RecordSpec{});
  const Replay r = read_ok(bytes);
  CHECK(r.header.format_version == k_replay_format_version);
  CHECK(r.header.engine_version == k_engine_version);
  CHECK(r.header.fixed_format == k_fixed_format_q32_32);
  CHECK(r.header.state_format_version == k_state_format_version);
  CHECK(r.header.time_step == Q32::from_ratio(1, 60));
  CHECK(r.header.keyframe_interval == 5);
  CHECK(r.header.tick_hashes);
  CHECK(r.header.has_scene_bytes);
  CHECK(std::string(r.header.scene_bytes.begin(), r.header.scene_bytes.end()) == "{\"scene\": \"test\"}");
  CHECK(r.header.has_scene_hash);
  CHECK(r.header.scene_hash == 0x1234);
  REQUIRE(r.tick_count() == 20);
  REQUIRE(r.keyframes.size() == 5);
  for (size_t i = 0; i < r.keyframes.size(); ++i) CHECK(r.keyframes[i].tick == 5 * static_cast<int64_t>(i));
  for (int64_t t = 1; t <= 20; ++t) {
    const TickRecord& rec = r.tick_record(t);
    CHECK(rec.tick == t);
    CHECK(rec.has_hash);
    const std::vector<Command> expected = scene_commands(t);
    REQUIRE(rec.commands.size() == expected.size());
    for (size_t i = 0; i < expected.size(); ++i) CHECK(rec.commands[i] == expected[i]);
  }
  // Re-encoding gives the same bytes (one tick per chunk, as written).
  CHECK(encode_replay(r) == bytes);

  SECTION("batched flushes hold the same ticks in fewer chunks") {
    RecordSpec spec;
    spec.flush_every = 3;
    const std::vector<uint8_t> batched = record_scene(spec);
    CHECK(batched.size() < bytes.size());
    const Replay rb = read_ok(batched);
    REQUIRE(rb.tick_count() == r.tick_count());
    for (size_t i = 0; i < r.ticks.size(); ++i) CHECK(rb.ticks[i].hash == r.ticks[i].hash);
    CHECK(encode_replay(rb, 3) == batched);
  }
  SECTION("without hashes") {
    RecordSpec spec;
    spec.hashes = false;
    const Replay rn = read_ok(record_scene(spec));
    CHECK_FALSE(rn.header.tick_hashes);
    for (const TickRecord& t : rn.ticks) CHECK_FALSE(t.has_hash);
  }
}

TEST_CASE("a seek from the nearest keyframe equals running from tick 0", "[replay][file]") {
  RecordSpec spec;
  spec.ticks = 23;
  spec.keyframe_interval = 4;
  spec.with_payloads = true;
  const Replay r = read_ok(record_scene(spec));
  Replay only_first = r;
  only_first.keyframes.resize(1);
  const PayloadHandler handler = payload_to_commands;
  for (int64_t t = 0; t <= r.tick_count(); ++t) {
    INFO("tick " << t);
    Result<WorldId> a = r.create_world_at(t, handler);
    REQUIRE(a.ok());
    OwnedWorld wa(a.value);
    Result<WorldId> b = only_first.create_world_at(t, handler);
    REQUIRE(b.ok());
    OwnedWorld wb(b.value);
    std::vector<uint8_t> sa, sb;
    REQUIRE(encode_world_state(wa.id, &sa).ok());
    REQUIRE(encode_world_state(wb.id, &sb).ok());
    CHECK(sa == sb);
    if (t == 0)
      CHECK(sa == r.keyframes[0].state);
    else
      CHECK(world_state_hash(wa.id) == r.tick_record(t).hash);
    // seek() works on an existing world too, backwards as well.
    REQUIRE(r.seek(wb.id, t / 2, handler).ok());
    if (t / 2 > 0) CHECK(world_state_hash(wb.id) == r.tick_record(t / 2).hash);
    REQUIRE(encode_world_state(wb.id, &sb).ok());
    if (t / 2 == 0) CHECK(sb == r.keyframes[0].state);
  }
  OwnedWorld w;
  const Status past = r.seek(w.id, r.tick_count() + 1);
  CHECK_FALSE(past.ok());
  CHECK(contains(past.message, "past the last recorded tick 23"));
}

TEST_CASE("a cut at every byte reads up to the last complete tick or fails cleanly", "[replay][file]") {
  RecordSpec spec;
  spec.ticks = 9;
  spec.keyframe_interval = 4;
  spec.flush_every = 2;
  const std::vector<uint8_t> bytes = record_scene(spec);
  const std::vector<ChunkSpan> chunks = chunks_of(bytes);
  REQUIRE(chunks[0].type == k_chunk_head);
  REQUIRE(chunks[1].type == k_chunk_keyframe);
  const size_t header_end = chunks[1].end;
  for (size_t cut = 0; cut < bytes.size(); ++cut) {
    INFO("cut at " << cut);
    const std::vector<uint8_t> part(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(cut));
    Replay r;
    ReplayReadInfo info;
    const Status s = read_replay(part, &r, &info);
    if (cut < header_end) {
      REQUIRE_FALSE(s.ok());
      CHECK(starts_with(s.message, "truncated header: "));
      continue;
    }
    INFO(s.message);
    REQUIRE(s.ok());
    // The complete chunks before the cut.
    size_t boundary = 0;
    int64_t ticks = 0;
    size_t keyframes = 0;
    for (const ChunkSpan& c : chunks) {
      if (c.end > cut) break;
      boundary = c.end;
      ticks += static_cast<int64_t>(c.ticks_in);
      keyframes += c.type == k_chunk_keyframe ? 1 : 0;
    }
    CHECK(info.truncated);
    CHECK(info.truncated_at == boundary);
    CHECK(info.last_complete_tick == ticks);
    CHECK(r.tick_count() == ticks);
    CHECK(r.keyframes.size() == keyframes);
    CHECK(starts_with(info.warning, "file cut at byte " + std::to_string(boundary) + " after tick " +
                                        std::to_string(ticks) + " ("));
  }
}

TEST_CASE("a corrupted byte anywhere is an error naming its chunk's offset", "[replay][file]") {
  RecordSpec spec;
  spec.ticks = 8;
  spec.keyframe_interval = 4;
  const std::vector<uint8_t> bytes = record_scene(spec);
  const std::vector<ChunkSpan> chunks = chunks_of(bytes);
  std::vector<uint32_t> types_seen;
  for (const ChunkSpan& c : chunks) {
    for (size_t at = c.offset; at < c.end; ++at) {
      INFO("byte " << at << " of the " << c.type << " chunk at " << c.offset);
      std::vector<uint8_t> bad = bytes;
      bad[at] ^= static_cast<uint8_t>(1u << (at % 8));
      Replay r;
      const Status s = read_replay(bad, &r);
      REQUIRE_FALSE(s.ok());
      CHECK(starts_with(s.message, "offset " + std::to_string(c.offset) + ": "));
      if (at < c.offset + k_chunk_header_bytes)
        CHECK(contains(s.message, "corrupted chunk header"));
      else
        CHECK(contains(s.message, "is corrupted: checksum"));
    }
    if (std::find(types_seen.begin(), types_seen.end(), c.type) == types_seen.end()) types_seen.push_back(c.type);
  }
  CHECK(types_seen.size() == 4);  // HEAD, KEYF, TICK, END
}

TEST_CASE("wrong magic, unknown version and trailing data are refused", "[replay][file]") {
  const std::vector<uint8_t> bytes = record_scene(RecordSpec{});
  SECTION("wrong magic") {
    std::vector<uint8_t> bad = bytes;
    bad[3] = 'X';
    Replay r;
    const Status s = read_replay(bad, &r);
    CHECK(starts_with(s.message, "offset 0: expected the replay magic \"TANDREPL\", got bytes 54414e58"));
    const std::vector<uint8_t> text{'{', '"', 's', 'c', 'e', 'n', 'e', '"', ':', '1', '}'};
    CHECK(contains(read_replay(text, &r).message, "not a Tandem replay"));
  }
  SECTION("unknown version") {
    std::vector<uint8_t> bad = bytes;
    bad[8] = 3;
    Replay r;
    CHECK(read_replay(bad, &r).message == "offset 8: unknown replay format version 3 (this build reads versions 1…2)");
    bad[8] = 0;
    CHECK(read_replay(bad, &r).message == "offset 8: unknown replay format version 0 (this build reads versions 1…2)");
  }
  SECTION("data after END") {
    std::vector<uint8_t> bad = bytes;
    bad.push_back(0);
    Replay r;
    CHECK(read_replay(bad, &r).message == "offset " + std::to_string(bytes.size()) + ": 1 bytes after the END chunk");
  }
}

TEST_CASE("absurd lengths and counts are refused without allocating", "[replay][file]") {
  RecordSpec spec;
  spec.ticks = 4;
  spec.keyframe_interval = 0;
  const std::vector<uint8_t> base = without_end(record_scene(spec));
  Replay r;
  ReplayReadInfo info;

  SECTION("a 4 GB chunk length reads as a cut, never as an allocation") {
    std::vector<uint8_t> bytes = base;
    const std::vector<uint8_t> chunk = framed(k_chunk_tick, {}, 0xFFFFFFF0);
    bytes.insert(bytes.end(), chunk.begin(), chunk.begin() + 12);
    REQUIRE(read_replay(bytes, &r, &info).ok());
    CHECK(info.truncated);
    CHECK(info.truncated_at == base.size());
    CHECK(contains(info.warning, "after tick 4 (mid TICK chunk: it declares 4294967280 + 8 bytes, 0 left)"));
    CHECK(r.tick_count() == 4);
  }
  SECTION("a 4 G tick record count") {
    std::vector<uint8_t> payload;
    put32(&payload, 0xFFFFFFFF);
    std::vector<uint8_t> bytes = base;
    const std::vector<uint8_t> chunk = framed(k_chunk_tick, payload);
    bytes.insert(bytes.end(), chunk.begin(), chunk.end());
    const Status s = read_replay(bytes, &r);
    CHECK(s.message == "offset " + std::to_string(base.size() + 12) +
                           ": TICK chunk: expected tick record count of at most 0 (0 bytes left, at least 13 per "
                           "item), got 4294967295");
  }
  SECTION("a 4 GB user payload inside a tick, and one just past the bytes left") {
    for (uint32_t count : {0xFFFFFFFFu, 9u}) {
      std::vector<uint8_t> payload;
      put32(&payload, 1);
      put64(&payload, 5);    // tick
      payload.push_back(0);  // no hash
      put32(&payload, 1);    // one command
      payload.push_back(static_cast<uint8_t>(CommandType::user_input));
      put32(&payload, count);
      payload.resize(payload.size() + 8, 0);
      std::vector<uint8_t> bytes = base;
      const std::vector<uint8_t> chunk = framed(k_chunk_tick, payload);
      bytes.insert(bytes.end(), chunk.begin(), chunk.end());
      const Status s = read_replay(bytes, &r);
      const std::string at = "offset " + std::to_string(base.size() + 12 + 4 + 8 + 1 + 4 + 1) + ": TICK chunk: ";
      if (count == 9u)
        CHECK(starts_with(s.message, at + "expected tick 5 payload byte count of at most 8 (8 bytes left"));
      else
        CHECK(s.message == at + "expected tick 5 payload byte count at most 16777216, got 4294967295");
    }
  }
  SECTION("a keyframe image count of 4 G") {
    std::vector<uint8_t> payload;
    put64(&payload, 4);
    put64(&payload, 0);
    put32(&payload, 0xFFFFFFFF);
    std::vector<uint8_t> bytes = base;
    const std::vector<uint8_t> chunk = framed(k_chunk_keyframe, payload);
    bytes.insert(bytes.end(), chunk.begin(), chunk.end());
    const Status s = read_replay(bytes, &r);
    CHECK(starts_with(s.message, "offset " + std::to_string(base.size() + 12 + 16) +
                                     ": KEYF chunk: expected state image byte count of at most 0"));
  }
  SECTION("ticks out of order") {
    std::vector<uint8_t> payload;
    put32(&payload, 1);
    put64(&payload, 7);
    payload.push_back(0);
    put32(&payload, 0);
    std::vector<uint8_t> bytes = base;
    const std::vector<uint8_t> chunk = framed(k_chunk_tick, payload);
    bytes.insert(bytes.end(), chunk.begin(), chunk.end());
    CHECK(read_replay(bytes, &r).message ==
          "offset " + std::to_string(base.size() + 16) + ": TICK chunk: expected tick 5, got 7");
  }
  SECTION("an unknown chunk type") {
    std::vector<uint8_t> bytes = base;
    const std::vector<uint8_t> chunk = framed(chunk_code('Z', 'Z', 'Z', 'Z'), {1, 2, 3});
    bytes.insert(bytes.end(), chunk.begin(), chunk.end());
    CHECK(read_replay(bytes, &r).message ==
          "offset " + std::to_string(base.size()) + ": unknown chunk type \"ZZZZ\"");
  }
}

TEST_CASE("the recorder writes a file that survives a crash", "[replay][file]") {
  for (uint32_t flush_every : {1u, 4u}) {
    INFO("flush every " << flush_every);
    const std::string path = temp_path("crash.tnr");
    OwnedWorld world;
    ReplayRecorder rec;
    RecorderOptions options;
    options.keyframe_interval = 3;
    options.flush_every = flush_every;
    REQUIRE(rec.open_file(path, options).ok());
    const std::string scene = "scene text";
    REQUIRE(rec.begin(world.id, std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(scene.data()), scene.size()))
                .ok());
    for (int64_t t = 1; t <= 10; ++t) {
      for (const Command& c : scene_commands(t)) REQUIRE(rec.submit(c).ok());
      REQUIRE(rec.submit_payload({1, 2}).ok());
      REQUIRE(rec.step().ok());
      // What a crash now would leave on disk.
      Replay r;
      ReplayReadInfo info;
      const Status s = read_replay_file(path, &r, &info);
      INFO(s.message);
      REQUIRE(s.ok());
      // At most flush_every - 1 ticks are pending; keyframes flush too.
      CHECK(r.tick_count() + flush_every > t);
      if (t % 3 == 0) CHECK(r.tick_count() == t);
      CHECK(r.tick_count() <= t);
      if (flush_every == 1) CHECK(r.tick_count() == t);
      CHECK(info.truncated);
      CHECK(contains(info.warning, path + ": file cut at byte"));
      CHECK(contains(info.warning, "no END chunk"));
    }
    REQUIRE(rec.finish().ok());
    Replay r;
    ReplayReadInfo info;
    REQUIRE(read_replay_file(path, &r, &info).ok());
    CHECK(info.closed);
    CHECK_FALSE(info.truncated);
    CHECK(r.tick_count() == 10);
    CHECK(r.ticks.back().hash == rec.last_hash());
    CHECK(r.ticks.back().hash == world_state_hash(world.id));
    CHECK(r.keyframes.size() == 4);
    CHECK(r.header.scene_hash == XXH3_64bits(scene.data(), scene.size()));
    REQUIRE(r.ticks[0].commands.size() == scene_commands(1).size() + 1);
    CHECK(r.ticks[0].commands.back().payload == std::vector<uint8_t>{1, 2});
    std::remove(path.c_str());
  }
  Replay r;
  const Status missing = read_replay_file("/nonexistent/dir/x.tnr", &r);
  CHECK(starts_with(missing.message, "/nonexistent/dir/x.tnr: cannot open"));
}

// Session packets: round trips, and the decoder's refusals of truncated,
// garbled, oversized and inconsistent packets, each naming the byte offset
// and the field.
#include <catch2/catch.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "fixed/splitmix64.h"
#include "replay/session_packet.h"

using namespace tandem;

namespace {

SessionPacket sample_input() {
  SessionPacket p;
  p.type = SessionPacketType::input;
  p.session_id = 0x0102030405060708ull;
  p.sender = 1;
  p.sequence = 77;
  p.sender_tick = 1000;
  p.advantage = -3;
  p.input_ack = 998;
  p.hash_ack = 990;
  p.first_input_tick = 1001;
  p.input_count = 3;
  p.input_bytes = 4;
  for (uint32_t i = 0; i < 12; ++i) p.inputs[i] = static_cast<uint8_t>(i * 17);
  p.first_hash_tick = 991;
  p.hash_count = 2;
  p.hashes[0] = 0xAAAABBBBCCCCDDDDull;
  p.hashes[1] = 42;
  return p;
}

std::string refusal(const std::vector<uint8_t>& bytes, SessionPacketLimits limits = {}) {
  SessionPacket out;
  const Status s = decode_session_packet(bytes.data(), bytes.size(), limits, &out);
  return s.ok() ? std::string("ok") : s.message;
}

}  // namespace

TEST_CASE("session packets round-trip, little-endian at stated offsets", "[replay][session][packet]") {
  const SessionPacket p = sample_input();
  std::vector<uint8_t> bytes;
  REQUIRE(encode_session_packet(p, &bytes).ok());
  REQUIRE(bytes.size() == k_packet_header_bytes + 16 + 6 + 12 + 5 + 16);
  CHECK(bytes[0] == 'T');
  CHECK(bytes[1] == 'S');
  CHECK(bytes[2] == k_session_packet_version);
  CHECK(bytes[3] == 1);
  CHECK(bytes[4] == 0x08);  // session id, least significant byte first
  CHECK(bytes[11] == 0x01);
  CHECK(bytes[12] == 1);    // sender
  CHECK(bytes[13] == 77);   // sequence
  uint8_t fixed[k_packet_max_bytes];
  size_t written = 0;
  REQUIRE(encode_session_packet(p, fixed, sizeof fixed, &written).ok());
  REQUIRE(written == bytes.size());
  CHECK(std::vector<uint8_t>(fixed, fixed + bytes.size()) == bytes);
  const Status small = encode_session_packet(p, fixed, bytes.size() - 1, &written);
  CHECK(small.code == StatusCode::capacity_exceeded);
  CHECK(written == 0);
  CHECK(small.message.find(std::to_string(bytes.size())) != std::string::npos);

  SessionPacket q;
  REQUIRE(decode_session_packet(bytes.data(), bytes.size(), {2, 4}, &q).ok());
  CHECK(q.session_id == p.session_id);
  CHECK(q.sender == 1);
  CHECK(q.sequence == 77);
  CHECK(q.sender_tick == 1000);
  CHECK(q.advantage == -3);
  CHECK(q.input_ack == 998);
  CHECK(q.hash_ack == 990);
  CHECK(q.first_input_tick == 1001);
  CHECK(q.input_count == 3);
  CHECK(q.input(2)[3] == p.inputs[11]);
  CHECK(q.first_hash_tick == 991);
  CHECK(q.hash_count == 2);
  CHECK(q.hashes[0] == p.hashes[0]);

  SessionPacket d;
  d.type = SessionPacketType::desync;
  d.tick = 150;
  d.hash = 9;
  bytes.clear();
  REQUIRE(encode_session_packet(d, &bytes).ok());
  REQUIRE(decode_session_packet(bytes.data(), bytes.size(), {}, &q).ok());
  CHECK(q.type == SessionPacketType::desync);
  CHECK(q.tick == 150);
  CHECK(q.hash == 9);

  const uint8_t hb[16] = {1, 0, 0, 0, 0, 0, 0, 0, 2, 0, 0, 0, 0, 0, 0, 0x80};
  SessionPacket r;
  r.type = SessionPacketType::body_hash_reply;
  r.tick = 3;
  r.first_body = 5;
  r.body_count = 2;
  r.body_hash_bytes = hb;
  bytes.clear();
  REQUIRE(encode_session_packet(r, &bytes).ok());
  REQUIRE(decode_session_packet(bytes.data(), bytes.size(), {}, &q).ok());
  CHECK(q.body_count == 2);
  CHECK(q.first_body == 5);
  CHECK(q.body_hash(0) == 1);
  CHECK(q.body_hash(1) == 0x8000000000000002ull);
}

TEST_CASE("session packet decoder names the offset and field of every refusal", "[replay][session][packet]") {
  std::vector<uint8_t> good;
  REQUIRE(encode_session_packet(sample_input(), &good).ok());
  const SessionPacketLimits limits{2, 4};

  // Every truncation is refused and names where the missing field starts.
  for (size_t n = 0; n < good.size(); ++n) {
    const std::vector<uint8_t> cut(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(n));
    const std::string m = refusal(cut, limits);
    INFO("cut at " << n << ": " << m);
    REQUIRE(m.rfind("offset ", 0) == 0);
    REQUIRE(m.find("left") != std::string::npos);
  }
  CHECK(refusal({}, limits) == "offset 0: expected 1 byte of magic, 0 left");
  CHECK(refusal(std::vector<uint8_t>(good.begin(), good.begin() + 15), limits) ==
        "offset 13: expected 4 bytes of sequence, 2 left");

  auto edited = [&](size_t at, uint8_t v) {
    std::vector<uint8_t> b = good;
    b[at] = v;
    return refusal(b, limits);
  };
  CHECK(edited(0, 'X') == "offset 0: expected magic \"TS\", got bytes 88 83");
  CHECK(edited(2, 9) == "offset 2: expected version 1, got 9");
  CHECK(edited(3, 9) == "offset 3: expected type 1…4, got 9");
  CHECK(edited(12, 2) == "offset 12: expected sender endpoint 0…1, got 2");
  // input count (offset 37) above 32, input bytes (offset 38) other than the session's.
  CHECK(edited(37, 33) == "offset 37: expected input count at most 32, got 33");
  CHECK(edited(38, 5) == "offset 38: expected input bytes 4…4, got 5");
  CHECK(refusal(good, {2, 0}) == "ok");
  // An input count larger than the bytes present.
  CHECK(edited(37, 30).rfind("offset 39: expected 120 bytes of inputs", 0) == 0);
  // First input tick 0 with inputs.
  {
    std::vector<uint8_t> b = good;
    for (size_t i = 33; i < 37; ++i) b[i] = 0;
    CHECK(refusal(b, limits) == "offset 33: expected first input tick 1…4294967293, got 0");
  }
  // No inputs but a non-zero input size: a second encoding of the same packet (found by the fuzzer).
  {
    SessionPacket p = sample_input();
    p.input_count = 0;
    p.first_input_tick = 0;
    std::vector<uint8_t> b;
    REQUIRE(encode_session_packet(p, &b).ok());
    REQUIRE(refusal(b, limits) == "ok");
    b[38] = 2;
    CHECK(refusal(b, limits) == "offset 38: expected input bytes 0 with an input count of 0, got 2");
  }
  // Trailing bytes.
  {
    std::vector<uint8_t> b = good;
    b.push_back(0);
    CHECK(refusal(b, limits) == "offset " + std::to_string(good.size()) + ": expected the end of the packet, 1 bytes left over");
  }
  // Oversized body hash counts.
  {
    SessionPacket r;
    r.type = SessionPacketType::body_hash_request;
    r.body_count = 512;
    std::vector<uint8_t> b;
    REQUIRE(encode_session_packet(r, &b).ok());
    CHECK(refusal(b) == "ok");
    b[27] = 0x02;  // body count 512 + 2 · 65536
    CHECK(refusal(b) == "offset 25: expected body count at most 512, got 131584");
  }

  // Random garbling: every flipped byte is either accepted or refused with an
  // offset inside the packet; never a crash (ASan/UBSan builds run this too).
  uint64_t rng = 0x5EED;
  for (int i = 0; i < 20000; ++i) {
    std::vector<uint8_t> b = good;
    const int flips = 1 + static_cast<int>(splitmix64_next(&rng) % 4);
    for (int f = 0; f < flips; ++f) {
      const uint64_t r = splitmix64_next(&rng);
      b[r % b.size()] = static_cast<uint8_t>(r >> 32);
    }
    if (splitmix64_next(&rng) % 4 == 0) b.resize(splitmix64_next(&rng) % (b.size() + 8), 0xEE);
    SessionPacket out;
    const Status s = decode_session_packet(b.data(), b.size(), limits, &out);
    if (!s.ok()) {
      REQUIRE(s.message.rfind("offset ", 0) == 0);
      const size_t offset = std::stoul(s.message.substr(7));
      REQUIRE(offset <= b.size());
    } else {
      REQUIRE(out.input_count <= k_packet_max_inputs);
      REQUIRE(out.hash_count <= k_packet_max_hashes);
    }
  }
}

TEST_CASE("session packet ticks are int64_t, refused outside the u32 wire range by name", "[replay][session][packet]") {
  SessionPacket d;
  d.type = SessionPacketType::desync;
  d.tick = -1;
  std::vector<uint8_t> bytes;
  Status s = encode_session_packet(d, &bytes);
  CHECK(s.code == StatusCode::invalid_argument);
  CHECK(s.message == "session packet: tick -1 outside the encodable range 0…4294967295");
  CHECK(bytes.empty());  // nothing written on a refusal
  d.tick = int64_t{UINT32_MAX} + 1;
  uint8_t buffer[k_packet_max_bytes];
  size_t written = 7;
  s = encode_session_packet(d, buffer, sizeof buffer, &written);
  CHECK(s.message == "session packet: tick 4294967296 outside the encodable range 0…4294967295");
  CHECK(written == 0);
  // The largest encodable tick round-trips exactly.
  d.tick = int64_t{UINT32_MAX};
  REQUIRE(encode_session_packet(d, &bytes).ok());
  SessionPacket back;
  REQUIRE(decode_session_packet(bytes.data(), bytes.size(), {}, &back).ok());
  CHECK(back.tick == int64_t{UINT32_MAX});

  SessionPacket p = sample_input();
  p.sender_tick = -5;
  CHECK(check_session_packet(p).message == "session packet: sender tick -5 outside the encodable range 0…4294967295");
  p = sample_input();
  p.first_input_tick = int64_t{UINT32_MAX};  // + input_count − 1 passes the u32 range
  CHECK(check_session_packet(p).message.rfind("session packet: first input tick 4294967295 outside 1…", 0) == 0);
  p = sample_input();
  p.input_count = k_packet_max_inputs + 1;
  CHECK(check_session_packet(p).message == "session packet: input count 33, expected at most 32");
}

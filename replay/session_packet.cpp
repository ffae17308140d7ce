// session_packet.cpp — encoder and bounds-checked decoder of session packets
// (format in session_packet.h).
#include "replay/session_packet.h"

#include <cstring>

#include "replay/bytes.h"

namespace tandem {

namespace {

Status refuse(const std::string& message) { return Status{StatusCode::invalid_argument, message}; }

// Reads "first tick, u8 count" and checks the tick range; the u32 tick is
// widened to the API's int64_t.
bool read_tick_range(ByteReader& r, const char* tick_what, const char* count_what, uint32_t max_count,
                     int64_t* first_tick, uint8_t* count) {
  const size_t tick_at = r.offset();
  const uint32_t first = r.u32(tick_what);
  *first_tick = first;
  const size_t count_at = r.offset();
  *count = r.u8(count_what);
  if (!r.ok()) return false;
  if (*count > max_count) {
    r.fail_at(count_at, std::string("expected ") + count_what + " at most " + std::to_string(max_count) + ", got " +
                            std::to_string(*count));
    return false;
  }
  if (*count == 0 && first != 0) {
    r.fail_at(tick_at, std::string("expected ") + tick_what + " 0 with no entries, got " + std::to_string(first));
    return false;
  }
  if (*count != 0 && (first == 0 || first > UINT32_MAX - (*count - 1u))) {
    r.fail_at(tick_at, std::string("expected ") + tick_what + " 1…" + std::to_string(UINT32_MAX - (*count - 1u)) +
                           ", got " + std::to_string(first));
    return false;
  }
  return true;
}

}  // namespace

uint64_t SessionPacket::body_hash(uint32_t i) const {
  const uint8_t* p = body_hash_bytes.data() + size_t{i} * 8;
  uint64_t v = 0;
  for (int b = 7; b >= 0; --b) v = (v << 8) | p[b];
  return v;
}

Status decode_session_packet(const uint8_t* data, size_t size, const SessionPacketLimits& limits, SessionPacket* out) {
  if (data == nullptr && size != 0) return refuse("offset 0: null packet data");
  ByteReader r(data, size);
  const uint8_t m0 = r.u8("magic");
  const uint8_t m1 = r.u8("magic");
  if (!r.ok()) return refuse(r.error());
  if (m0 != 'T' || m1 != 'S') return refuse("offset 0: expected magic \"TS\", got bytes " + std::to_string(m0) + " " + std::to_string(m1));
  const uint8_t version = r.u8("version");
  if (r.ok() && version != k_session_packet_version) {
    return refuse("offset 2: expected version " + std::to_string(k_session_packet_version) + ", got " + std::to_string(version));
  }
  const uint8_t type = r.u8("type");
  if (r.ok() && (type < 1 || type > 4)) return refuse("offset 3: expected type 1…4, got " + std::to_string(type));
  out->type = static_cast<SessionPacketType>(type);
  out->session_id = r.u64("session id");
  const size_t sender_at = r.offset();
  out->sender = r.u8("sender endpoint");
  if (r.ok() && out->sender >= limits.endpoint_count) {
    return refuse("offset " + std::to_string(sender_at) + ": expected sender endpoint 0…" +
                  std::to_string(limits.endpoint_count - 1) + ", got " + std::to_string(out->sender));
  }
  out->sequence = r.u32("sequence");
  out->input_count = 0;
  out->hash_count = 0;
  out->body_count = 0;
  out->body_hash_bytes = {};
  switch (out->type) {
    case SessionPacketType::input: {
      out->sender_tick = r.u32("sender tick");
      out->advantage = r.i32("advantage");
      out->input_ack = r.u32("input ack");
      out->hash_ack = r.u32("hash ack");
      if (!read_tick_range(r, "first input tick", "input count", k_packet_max_inputs, &out->first_input_tick,
                           &out->input_count)) {
        break;
      }
      const size_t bytes_at = r.offset();
      out->input_bytes = r.u8("input bytes");
      if (!r.ok()) break;
      if (out->input_count == 0 && out->input_bytes != 0) {
        // One encoding per packet: without inputs the size byte is 0 (as written).
        r.fail_at(bytes_at, "expected input bytes 0 with an input count of 0, got " + std::to_string(out->input_bytes));
        break;
      }
      if (out->input_count != 0) {
        const bool size_ok = out->input_bytes >= 1 && out->input_bytes <= k_session_max_input_bytes &&
                             (limits.input_bytes == 0 || out->input_bytes == limits.input_bytes);
        if (!size_ok) {
          const uint32_t lo = limits.input_bytes != 0 ? limits.input_bytes : 1;
          const uint32_t hi = limits.input_bytes != 0 ? limits.input_bytes : k_session_max_input_bytes;
          r.fail_at(bytes_at, "expected input bytes " + std::to_string(lo) + "…" + std::to_string(hi) + ", got " +
                                  std::to_string(out->input_bytes));
          break;
        }
      }
      const size_t n = size_t{out->input_count} * out->input_bytes;
      std::span<const uint8_t> in = r.bytes(n, "inputs");
      if (!r.ok()) break;
      if (n != 0) std::memcpy(out->inputs.data(), in.data(), n);
      if (!read_tick_range(r, "first hash tick", "hash count", k_packet_max_hashes, &out->first_hash_tick,
                           &out->hash_count)) {
        break;
      }
      for (uint32_t i = 0; i < out->hash_count; ++i) out->hashes[i] = r.u64("hash");
      break;
    }
    case SessionPacketType::desync:
      out->tick = r.u32("tick");
      out->hash = r.u64("hash");
      break;
    case SessionPacketType::body_hash_request:
    case SessionPacketType::body_hash_reply: {
      out->tick = r.u32("tick");
      out->first_body = r.u32("first body");
      const size_t count_at = r.offset();
      out->body_count = r.u32("body count");
      if (!r.ok()) break;
      if (out->body_count > k_packet_max_body_hashes) {
        r.fail_at(count_at, "expected body count at most " + std::to_string(k_packet_max_body_hashes) + ", got " +
                                std::to_string(out->body_count));
        break;
      }
      if (out->first_body > UINT32_MAX - out->body_count) {
        r.fail_at(count_at, "expected first body + body count to fit in u32");
        break;
      }
      if (out->type == SessionPacketType::body_hash_reply) {
        out->body_hash_bytes = r.bytes(size_t{out->body_count} * 8, "body hashes");
      }
      break;
    }
  }
  if (!r.ok()) return refuse(r.error());
  if (!r.at_end()) {
    return refuse("offset " + std::to_string(r.offset()) + ": expected the end of the packet, " +
                  std::to_string(r.remaining()) + " bytes left over");
  }
  return {};
}

namespace {

// A tick field that check_session_packet accepted (0…UINT32_MAX).
uint32_t wire_tick(int64_t tick) { return static_cast<uint32_t>(tick); }

void write_packet(ByteWriter& w, const SessionPacket& p) {
  w.u8('T');
  w.u8('S');
  w.u8(k_session_packet_version);
  w.u8(static_cast<uint8_t>(p.type));
  w.u64(p.session_id);
  w.u8(p.sender);
  w.u32(p.sequence);
  switch (p.type) {
    case SessionPacketType::input:
      w.u32(wire_tick(p.sender_tick));
      w.i32(p.advantage);
      w.u32(wire_tick(p.input_ack));
      w.u32(wire_tick(p.hash_ack));
      w.u32(p.input_count != 0 ? wire_tick(p.first_input_tick) : 0);
      w.u8(p.input_count);
      w.u8(p.input_count != 0 ? p.input_bytes : 0);
      if (p.input_count != 0) w.bytes(p.inputs.data(), size_t{p.input_count} * p.input_bytes);
      w.u32(p.hash_count != 0 ? wire_tick(p.first_hash_tick) : 0);
      w.u8(p.hash_count);
      for (uint32_t i = 0; i < p.hash_count; ++i) w.u64(p.hashes[i]);
      break;
    case SessionPacketType::desync:
      w.u32(wire_tick(p.tick));
      w.u64(p.hash);
      break;
    case SessionPacketType::body_hash_request:
    case SessionPacketType::body_hash_reply:
      w.u32(wire_tick(p.tick));
      w.u32(p.first_body);
      w.u32(p.body_count);
      if (p.type == SessionPacketType::body_hash_reply) w.bytes(p.body_hash_bytes.data(), size_t{p.body_count} * 8);
      break;
  }
}

Status check_tick(const char* field, int64_t tick) {
  if (tick >= 0 && tick <= int64_t{UINT32_MAX}) return {};
  return refuse(std::string("session packet: ") + field + " " + std::to_string(tick) +
                " outside the encodable range 0…" + std::to_string(UINT32_MAX));
}

// A run of `count` consecutive ticks from `first` (ignored when count is 0).
Status check_tick_range(const char* field, int64_t first, uint32_t count) {
  if (count == 0) return {};
  const int64_t last = int64_t{UINT32_MAX} - (int64_t{count} - 1);
  if (first >= 1 && first <= last) return {};
  return refuse(std::string("session packet: ") + field + " " + std::to_string(first) + " outside 1…" +
                std::to_string(last) + " for " + std::to_string(count) + " entries");
}

Status count_error(const char* field, uint64_t got, uint64_t most) {
  return refuse(std::string("session packet: ") + field + " " + std::to_string(got) + ", expected at most " +
                std::to_string(most));
}

}  // namespace

Status check_session_packet(const SessionPacket& p) {
  if (p.input_count > k_packet_max_inputs) return count_error("input count", p.input_count, k_packet_max_inputs);
  if (p.hash_count > k_packet_max_hashes) return count_error("hash count", p.hash_count, k_packet_max_hashes);
  if (p.input_count != 0 && (p.input_bytes == 0 || p.input_bytes > k_session_max_input_bytes)) {
    return refuse("session packet: input bytes " + std::to_string(p.input_bytes) + ", expected 1…" +
                  std::to_string(k_session_max_input_bytes));
  }
  if (p.body_count > k_packet_max_body_hashes) return count_error("body count", p.body_count, k_packet_max_body_hashes);
  if (p.type == SessionPacketType::body_hash_reply && p.body_hash_bytes.size() != size_t{p.body_count} * 8) {
    return refuse("session packet: " + std::to_string(p.body_hash_bytes.size()) + " body hash bytes for body count " +
                  std::to_string(p.body_count) + ", expected 8 each");
  }
  Status s;
  if (p.type == SessionPacketType::input) {
    if (s = check_tick("sender tick", p.sender_tick); !s.ok()) return s;
    if (s = check_tick("input ack", p.input_ack); !s.ok()) return s;
    if (s = check_tick("hash ack", p.hash_ack); !s.ok()) return s;
    if (s = check_tick_range("first input tick", p.first_input_tick, p.input_count); !s.ok()) return s;
    if (s = check_tick_range("first hash tick", p.first_hash_tick, p.hash_count); !s.ok()) return s;
  } else {
    if (s = check_tick("tick", p.tick); !s.ok()) return s;
  }
  return {};
}

Status encode_session_packet(const SessionPacket& packet, uint8_t* buffer, size_t capacity, size_t* out_size) {
  *out_size = 0;
  Status s = check_session_packet(packet);
  if (!s.ok()) return s;
  ByteWriter w(buffer, capacity);
  write_packet(w, packet);
  if (w.overflowed()) {
    return Status{StatusCode::capacity_exceeded, "session packet: needs " + std::to_string(w.size()) +
                                                     " bytes, the buffer holds " + std::to_string(capacity)};
  }
  *out_size = w.size();
  return {};
}

Status encode_session_packet(const SessionPacket& packet, std::vector<uint8_t>* out) {
  Status s = check_session_packet(packet);
  if (!s.ok()) return s;
  ByteWriter w(out);
  write_packet(w, packet);
  return {};
}

}  // namespace tandem

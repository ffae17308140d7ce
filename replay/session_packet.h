// session_packet.h — the wire format of a lockstep / rollback session
// (replay/session.h): one packet type per message, encoded little-endian with
// replay/bytes.h and decoded with every length and count checked before use.
//
// FORMAT, version 1 (every integer little-endian; offsets from the packet start):
//   0   2  magic "TS"
//   2   1  u8 version (k_session_packet_version)
//   3   1  u8 type (SessionPacketType, 1…4)
//   4   8  u64 session id (both sides must agree; checked by the session)
//   12  1  u8 sender endpoint (players 0…P−1, spectators P…P+S−1)
//   13  4  u32 sequence number (per sender and receiver, from 1)
//   then by type:
//   input (1):      u32 sender tick (ticks the sender has simulated)
//                   i32 sender advantage (sender tick − the receiver's tick as
//                       the sender last heard it; time sync)
//                   u32 input ack (the sender holds the receiver's inputs of
//                       every tick ≤ this), u32 hash ack (same for hashes)
//                   u32 first input tick, u8 input count (≤ 32), u8 input
//                       bytes per tick (1…64), count × bytes of the sender's
//                       own inputs for consecutive ticks
//                   u32 first hash tick, u8 hash count (≤ 32), count × u64
//                       confirmed-tick hashes for consecutive ticks
//   desync (2):     u32 tick, u64 the sender's hash of that tick
//   body_hash_request (3): u32 tick, u32 first body index, u32 body count (≤ 512)
//   body_hash_reply (4):   u32 tick, u32 first body index, u32 count (≤ 512),
//                   count × u64 body_state_hash (0 for a dead slot)
//   Nothing may follow the last field.
// A count of 0 leaves out its first-tick field's meaning (the field is still
// present and must be 0; so must the input bytes field when the input count
// is 0), so every packet has exactly one encoding. Tick fields of inputs and hashes must be ≥ 1, and
// first + count − 1 must not overflow u32.
//
// DECODING never allocates: a SessionPacket holds fixed-size arrays for the
// largest legal packet, and body hash replies are a view into the input.
// Every refusal names the byte offset and the field ("offset 13: expected 4
// bytes of sequence, 2 left"; "offset 3: expected type 1…4, got 9").
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "physics/tandem.h"

namespace tandem {

/// The version written into and required from session packets.
inline constexpr uint8_t k_session_packet_version = 1;
/// Most inputs (ticks) in one input packet.
inline constexpr uint32_t k_packet_max_inputs = 32;
/// Most hashes in one input packet.
inline constexpr uint32_t k_packet_max_hashes = 32;
/// Most bytes of one player's input for one tick.
inline constexpr uint32_t k_session_max_input_bytes = 64;
/// Most body hashes in one request or reply.
inline constexpr uint32_t k_packet_max_body_hashes = 512;
/// Bytes before the type-specific part.
inline constexpr size_t k_packet_header_bytes = 17;
/// Largest legal packet (an input packet with every array full).
inline constexpr size_t k_packet_max_input_packet_bytes =
    k_packet_header_bytes + 16 + 6 + k_packet_max_inputs * k_session_max_input_bytes + 5 + k_packet_max_hashes * 8;
inline constexpr size_t k_packet_max_bytes = k_packet_max_input_packet_bytes > k_packet_header_bytes + 12 + k_packet_max_body_hashes * 8
                                                 ? k_packet_max_input_packet_bytes
                                                 : k_packet_header_bytes + 12 + k_packet_max_body_hashes * 8;

/// What a packet carries (the encoded type byte; never reorder).
enum class SessionPacketType : uint8_t {
  input = 1,              ///< inputs, acks, time sync and confirmed-tick hashes
  desync = 2,             ///< the sender found a hash mismatch at `tick` and stopped
  body_hash_request = 3,  ///< please send per-body hashes of `tick`
  body_hash_reply = 4,    ///< per-body hashes of `tick`
};

/// A decoded packet (fields of other types stay zero).
struct SessionPacket {
  SessionPacketType type = SessionPacketType::input;
  uint64_t session_id = 0;
  uint8_t sender = 0;
  uint32_t sequence = 0;
  // input. Ticks are int64_t as everywhere in the API; on the wire they are
  // u32, so the encoder refuses a tick outside 0…UINT32_MAX (naming it).
  int64_t sender_tick = 0;
  int32_t advantage = 0;
  int64_t input_ack = 0;
  int64_t hash_ack = 0;
  int64_t first_input_tick = 0;
  uint8_t input_count = 0;
  uint8_t input_bytes = 0;
  std::array<uint8_t, k_packet_max_inputs * k_session_max_input_bytes> inputs{};  ///< input_count × input_bytes used
  int64_t first_hash_tick = 0;
  uint8_t hash_count = 0;
  std::array<uint64_t, k_packet_max_hashes> hashes{};
  // desync, body hashes
  int64_t tick = 0;
  uint64_t hash = 0;            ///< desync: the sender's hash of `tick`
  uint32_t first_body = 0;      ///< body hash request / reply
  uint32_t body_count = 0;
  std::span<const uint8_t> body_hash_bytes;  ///< reply: body_count × 8 bytes (view into the decoded data)

  /// The input of tick first_input_tick + i (i < input_count).
  std::span<const uint8_t> input(uint32_t i) const { return {inputs.data() + size_t{i} * input_bytes, input_bytes}; }
  /// Body hash i of a reply (i < body_count).
  uint64_t body_hash(uint32_t i) const;
};

/// What a decoder accepts beyond the format itself.
struct SessionPacketLimits {
  uint32_t endpoint_count = 255;  ///< the sender must be < this
  uint32_t input_bytes = 0;       ///< when non-zero, input packets with inputs must use exactly this size
};

/// Decodes one packet (see the file comment) into *out without allocating.
/// On a refusal the status is invalid_argument and its message starts with
/// "offset N: " and names the field; *out is unspecified then.
Status decode_session_packet(const uint8_t* data, size_t size, const SessionPacketLimits& limits, SessionPacket* out);

/// Checks `packet` against the format: counts within their limits, input
/// bytes 1…64 when there are inputs, reply bytes = 8 × body count, and every
/// tick field within the u32 encoding (0…UINT32_MAX; first + count − 1 too,
/// and first ≥ 1 when count > 0). The message names the field and the value,
/// e.g. "session packet: tick -1 outside the encodable range 0…4294967295".
Status check_session_packet(const SessionPacket& packet);

/// Encodes `packet` into buffer[0, capacity) and writes the size to
/// *out_size (0 on a refusal; required). Refuses what check_session_packet
/// refuses, and a buffer too small (capacity_exceeded, naming both sizes;
/// nothing is written past the capacity). Only the fields of the packet's
/// type are written.
Status encode_session_packet(const SessionPacket& packet, uint8_t* buffer, size_t capacity, size_t* out_size);

/// Appends the encoding to *out (convenience for tests and tools); on a
/// refusal (as check_session_packet) *out is unchanged.
Status encode_session_packet(const SessionPacket& packet, std::vector<uint8_t>* out);

/// Deprecated (removed next release): returns the size written, 0 on any
/// refusal; use the Status form.
[[deprecated("use encode_session_packet(packet, buffer, capacity, &size), which returns a Status")]] inline size_t
encode_session_packet(const SessionPacket& packet, uint8_t* buffer, size_t capacity) {
  size_t size = 0;
  return encode_session_packet(packet, buffer, capacity, &size).ok() ? size : 0;
}

}  // namespace tandem

// session_net.cpp — the session's packet side (see session.h): building and
// sending input, desync and body-hash packets from the rings and resend
// history, and receiving them (validation, sequence numbers, storing remote
// inputs and hashes, spotting mispredictions for session.cpp's rollback).
// Split from session.cpp, which owns setup, the simulation and snapshot ring,
// frames and artifacts; both are members of the one Session class.
//
// Redundancy: each input packet repeats the sender's inputs from the oldest
// tick the receiver has not acknowledged (≤ 32 per packet), and the confirmed
// hashes likewise, so any loss pattern is repaired by the next packets that
// get through, oldest first. The sender's own inputs are kept for
// input_history_ticks (default 3600), beyond the ring, so an endpoint far
// behind (a spectator cut off for seconds) still gets every input; one
// further behind than that is dropped (a spectator) or stops the session (a
// player, which the bounds in session.cpp rule out).
#include <algorithm>
#include <cstring>
#include <string>

#include "replay/bytes.h"
#include "replay/session.h"
#include "replay/state.h"

namespace tandem {

namespace {

// Remote inputs further ahead of the confirmed tick than this are refused
// (see session.cpp's ring bounds).
constexpr uint64_t k_accept_ahead = 192;  // < k_session_ring_ticks − 32

Status bad(const std::string& message) { return Status{StatusCode::invalid_argument, message}; }

// A tick field of a decoded packet: read from a u32, so 0…UINT32_MAX.
uint64_t decoded(int64_t tick) { return static_cast<uint64_t>(tick); }

}  // namespace

// --- sending --------------------------------------------------------------------

void Session::send_packet(uint32_t endpoint) {
  size_t size = 0;
  const Status s = encode_session_packet(packet_out_, out_buffer_.data(), out_buffer_.size(), &size);
  if (!s.ok()) {
    // Only a tick past the u32 wire range (2^32 ticks: 2 years at 60 Hz) can
    // get here; stop instead of sending a truncated tick.
    stop(SessionState::error, "cannot send to endpoint " + std::to_string(endpoint) + ": " + s.message);
    return;
  }
  ++stats_.packets_sent;
  stats_.bytes_sent += size;
  callbacks_.send(endpoint, std::span<const uint8_t>(out_buffer_.data(), size));
}

void Session::send_packets() {
  SessionPacket& p = packet_out_;
  const bool notices = stop_.state == SessionState::desynced && desync_notices_left_ > 0;
  if (stop_.state != SessionState::running && !notices) return;
  for (uint32_t q = 0; q < endpoint_count(); ++q) {
    if (q == config_.local_endpoint || gone_[q] != 0) continue;
    p.session_id = config_.session_id;
    p.sender = static_cast<uint8_t>(config_.local_endpoint);
    p.sequence = ++sequence_out_[q];
    if (notices) {
      p.type = SessionPacketType::desync;
      p.tick = static_cast<int64_t>(desync_notice_tick_);
      p.hash = desync_notice_hash_;
      send_packet(q);
      continue;
    }
    p.type = SessionPacketType::input;
    p.sender_tick = static_cast<int64_t>(current_);
    p.advantage = static_cast<int32_t>(std::clamp<int64_t>(
        static_cast<int64_t>(current_) - static_cast<int64_t>(remote_tick_[q]), INT32_MIN, INT32_MAX));
    p.input_ack = q < config_.player_count ? static_cast<int64_t>(contiguous_[q]) : 0;
    p.hash_ack = static_cast<int64_t>(remote_hash_through_[q]);
    p.input_count = 0;
    p.input_bytes = static_cast<uint8_t>(config_.input_bytes);
    p.first_input_tick = 0;
    if (!is_spectator()) {
      // Oldest unacknowledged first, so a receiver behind by more than one
      // packet's worth still fills its gap, from the local input history:
      // players stay within the ring of each other (file comment), but a
      // spectator that heard nothing for seconds may be far behind.
      const uint64_t first = std::max<uint64_t>(input_ack_from_[q] + 1, config_.input_delay + 1);
      if (first <= last_local_tick_ && last_local_tick_ - first >= config_.input_history_ticks) {
        const std::string why = "endpoint " + std::to_string(q) + " needs our inputs from tick " +
                                std::to_string(first) + ", older than the " +
                                std::to_string(config_.input_history_ticks) + " ticks kept (input_history_ticks)";
        if (q < config_.player_count) {
          stop(SessionState::error, why);
          return;
        }
        gone_[q] = 1;  // a spectator: no longer sent to
        ++stats_.spectators_dropped;
        stats_.last_rejection = why;
        continue;
      }
      if (first <= last_local_tick_) {
        p.first_input_tick = static_cast<int64_t>(first);
        p.input_count = static_cast<uint8_t>(std::min<uint64_t>(last_local_tick_ - first + 1, k_packet_max_inputs));
        for (uint32_t i = 0; i < p.input_count; ++i) {
          const size_t slot = static_cast<size_t>((first + i) % config_.input_history_ticks);
          std::memcpy(p.inputs.data() + size_t{i} * config_.input_bytes,
                      local_history_.data() + slot * config_.input_bytes, config_.input_bytes);
        }
      }
    }
    p.hash_count = 0;
    p.first_hash_tick = 0;
    // Oldest unacknowledged first; hashes that left the ring are skipped (the
    // receiver sees the gap and skips those checks, counting them).
    uint64_t hfirst = hash_ack_from_[q] + 1;
    if (hfirst <= confirmed_ && confirmed_ - hfirst >= k_session_ring_ticks - 8) hfirst = confirmed_ - k_packet_max_hashes + 1;
    if (hfirst <= confirmed_) {
      p.first_hash_tick = static_cast<int64_t>(hfirst);
      p.hash_count = static_cast<uint8_t>(std::min<uint64_t>(confirmed_ - hfirst + 1, k_packet_max_hashes));
      for (uint32_t i = 0; i < p.hash_count; ++i) p.hashes[i] = hash_[ring(hfirst + i)];
    }
    send_packet(q);
  }
  if (notices) --desync_notices_left_;
}

// --- receiving ------------------------------------------------------------------

void Session::reject(const std::string& why) {
  ++stats_.packets_rejected;
  stats_.last_rejection = why;
}

void Session::receive(uint32_t from, std::span<const uint8_t> data) {
  if (stop_.state == SessionState::idle) return;
  ++stats_.packets_received;
  stats_.bytes_received += data.size();
  if (from >= endpoint_count() || from == config_.local_endpoint) {
    reject("packet from endpoint " + std::to_string(from) + ", expected another of 0…" +
           std::to_string(endpoint_count() - 1));
    return;
  }
  SessionPacketLimits limits;
  limits.endpoint_count = endpoint_count();
  limits.input_bytes = config_.input_bytes;
  SessionPacket& p = packet_in_;
  const Status s = decode_session_packet(data.data(), data.size(), limits, &p);
  if (!s.ok()) {
    reject("from endpoint " + std::to_string(from) + ": " + s.message);
    return;
  }
  if (p.session_id != config_.session_id) {
    reject("from endpoint " + std::to_string(from) + ": session id " + std::to_string(p.session_id) + ", expected " +
           std::to_string(config_.session_id));
    return;
  }
  if (p.sender != from) {
    reject("packet claims endpoint " + std::to_string(p.sender) + " but arrived from endpoint " + std::to_string(from));
    return;
  }
  last_heard_frame_[from] = stats_.frames;
  const bool fresh = p.sequence > last_sequence_in_[from];
  if (fresh) {
    last_sequence_in_[from] = p.sequence;
  } else {
    ++stats_.packets_stale;
  }
  switch (p.type) {
    case SessionPacketType::input:
      if (fresh) remote_advantage_[from] = p.advantage;
      handle_input(from, p);
      break;
    case SessionPacketType::desync:
      if (stop_.state == SessionState::running) {
        const uint64_t t = decoded(p.tick);
        const uint64_t mine = hash_tick_[ring(t)] == t ? hash_[ring(t)] : 0;
        desync(from, t, mine, p.hash, true);
      }
      break;
    case SessionPacketType::body_hash_request:
      handle_body_request(from, p);
      break;
    case SessionPacketType::body_hash_reply:
      remote_body_hashes_.endpoint = from;
      remote_body_hashes_.tick = p.tick;
      remote_body_hashes_.first_body = p.first_body;
      remote_body_hashes_.hashes.resize(p.body_count);
      for (uint32_t i = 0; i < p.body_count; ++i) remote_body_hashes_.hashes[i] = p.body_hash(i);
      break;
  }
}

void Session::handle_input(uint32_t from, const SessionPacket& p) {
  remote_tick_[from] = std::max<uint64_t>(remote_tick_[from], decoded(p.sender_tick));
  if (decoded(p.input_ack) <= last_local_tick_) input_ack_from_[from] = std::max<uint64_t>(input_ack_from_[from], decoded(p.input_ack));
  if (decoded(p.hash_ack) <= confirmed_) hash_ack_from_[from] = std::max<uint64_t>(hash_ack_from_[from], decoded(p.hash_ack));
  if (p.input_count != 0) {
    if (from >= config_.player_count) {
      reject("spectator endpoint " + std::to_string(from) + " sent inputs");
      return;
    }
    for (uint32_t i = 0; i < p.input_count; ++i) {
      const uint64_t t = decoded(p.first_input_tick) + i;
      const uint8_t* bytes = p.input(i).data();
      if (t > confirmed_ + k_accept_ahead) {
        // A sender starts at our oldest missing input, so only a first tick
        // past the window is wrong; later ones are kept for the next packets
        // (a spectator far behind gets 32 at a time but may hold fewer).
        if (i != 0) break;
        reject("player " + std::to_string(from) + " input for tick " + std::to_string(t) + ", more than " +
               std::to_string(k_accept_ahead) + " ahead of confirmed tick " + std::to_string(confirmed_));
        return;
      }
      if (t <= contiguous_[from] || input_known(from, t)) {
        if (input_known(from, t) && std::memcmp(input_at(from, t), bytes, config_.input_bytes) != 0) {
          reject("player " + std::to_string(from) + " sent a different input for tick " + std::to_string(t));
          return;
        }
        continue;
      }
      store_input(from, t, bytes);
      const size_t slot = size_t{from} * k_session_ring_ticks + ring(t);
      if (t <= current_ && used_tick_[slot] == t &&
          std::memcmp(used_.data() + slot * config_.input_bytes, bytes, config_.input_bytes) != 0) {
        if (pending_rollback_ == 0 || t < pending_rollback_) pending_rollback_ = t;
      }
    }
  }
  uint64_t& through = remote_hash_through_[from];
  if (p.hash_count != 0 && decoded(p.first_hash_tick) > through + 1) {
    // The sender acknowledged-through is never ahead of ours, so a gap means
    // it could not resend those hashes (they left its ring): skip them.
    stats_.hashes_skipped += decoded(p.first_hash_tick) - 1 - through;
    through = decoded(p.first_hash_tick) - 1;
    hash_checked_through_[from] = std::max(hash_checked_through_[from], through);
  }
  for (uint32_t i = 0; i < p.hash_count; ++i) {
    const uint64_t t = decoded(p.first_hash_tick) + i;
    if (t <= hash_checked_through_[from] || t >= hash_checked_through_[from] + k_session_ring_ticks) continue;
    const size_t r = size_t{from} * k_session_ring_ticks + ring(t);
    remote_hash_[r] = p.hashes[i];
    remote_hash_tick_[r] = t;
  }
  while (remote_hash_tick_[size_t{from} * k_session_ring_ticks + ring(through + 1)] == through + 1) ++through;
}

// --- per-body hashes ----------------------------------------------------------------

Status Session::local_body_hashes(int64_t tick, std::vector<uint64_t>* out) const {
  const Result<WorldId> w = ring_world(tick);
  if (!w.ok()) return w.status;
  const Status s = world_body_hashes(w.value, out);
  (void)destroy_world(w.value);
  return s;
}

Status Session::request_body_hashes(uint32_t endpoint, int64_t tick, uint32_t first_body, uint32_t count) {
  const char* fn = "Session::request_body_hashes";
  if (stop_.state == SessionState::idle) return bad(std::string(fn) + ": start() first");
  if (endpoint >= endpoint_count() || endpoint == config_.local_endpoint) {
    return bad(std::string(fn) + ": endpoint " + std::to_string(endpoint) + " is not a remote endpoint (0…" +
               std::to_string(endpoint_count() - 1) + ", not the local " + std::to_string(config_.local_endpoint) + ")");
  }
  if (tick < 0 || tick > int64_t{UINT32_MAX}) {
    return bad(std::string(fn) + ": tick " + std::to_string(tick) + " outside 0…" + std::to_string(UINT32_MAX));
  }
  SessionPacket& p = packet_out_;
  p.type = SessionPacketType::body_hash_request;
  p.session_id = config_.session_id;
  p.sender = static_cast<uint8_t>(config_.local_endpoint);
  p.sequence = ++sequence_out_[endpoint];
  p.tick = tick;
  p.first_body = first_body;
  p.body_count = std::min(count, k_packet_max_body_hashes);
  send_packet(endpoint);
  return Status{};
}

void Session::handle_body_request(uint32_t from, const SessionPacket& req) {
  std::vector<uint64_t>& all = body_hash_scratch_;
  uint32_t count = 0;
  if (local_body_hashes(req.tick, &all).ok() && req.first_body < all.size()) {
    count = static_cast<uint32_t>(std::min<size_t>(req.body_count, all.size() - req.first_body));
  }
  body_hash_bytes_.clear();
  ByteWriter w(&body_hash_bytes_);
  for (uint32_t i = 0; i < count; ++i) w.u64(all[req.first_body + i]);
  SessionPacket& p = packet_out_;
  p.type = SessionPacketType::body_hash_reply;
  p.session_id = config_.session_id;
  p.sender = static_cast<uint8_t>(config_.local_endpoint);
  p.sequence = ++sequence_out_[from];
  p.tick = req.tick;
  p.first_body = req.first_body;
  p.body_count = count;
  p.body_hash_bytes = std::span<const uint8_t>(body_hash_bytes_.data(), body_hash_bytes_.size());
  send_packet(from);
}

}  // namespace tandem

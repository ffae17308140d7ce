// session.cpp — the lockstep / rollback session (see session.h).
//
// Rings: inputs, the inputs used, local and remote hashes are indexed by
// tick % k_session_ring_ticks and tagged with the tick they hold, so a slot
// reused for a later tick is never read as an earlier one. Bounds that keep
// the live range inside the ring: the local state never runs more than
// prediction_window ticks past the last all-known tick, a player's inputs run
// at most input_delay + 1 ticks ahead of its state, so every tick anyone can
// legitimately send lies within 2 · (30 + 30) + 2 ticks of the confirmed tick;
// remote inputs further ahead than k_accept_ahead are refused.
//
// Packets (sending, receiving, resend history, body-hash requests) are in
// session_net.cpp; this file owns setup, the input rings, simulation with the
// snapshot ring and rollbacks, frames, stopping and artifacts.
#include "replay/session.h"

#include <algorithm>
#include <cstdio>
#include <cstring>

#define XXH_INLINE_ALL
#include <xxhash.h>

#include "replay/rollback.h"
#include "replay/state.h"

namespace tandem {

namespace {

constexpr uint32_t k_sync_samples = 16;
constexpr int64_t k_sync_min_frames = 2;
constexpr uint32_t k_spectator_catch_up = 4;  // most ticks a spectator steps in one frame

Status bad(const std::string& message) { return Status{StatusCode::invalid_argument, message}; }

std::string range_text(const char* field, uint64_t lo, uint64_t hi, uint64_t got) {
  return std::string("session config ") + field + ": expected " + std::to_string(lo) + "…" + std::to_string(hi) +
         ", got " + std::to_string(got);
}

Status snapshot_into(WorldId world, std::vector<uint8_t>* out) {
  if (out->size() < out->capacity()) out->resize(out->capacity());
  size_t written = 0;
  Status s = world_snapshot(world, out->data(), out->size(), &written);
  if (s.code == StatusCode::capacity_exceeded) {
    out->resize(written);
    s = world_snapshot(world, out->data(), out->size(), &written);
  }
  if (!s.ok()) return s;
  out->resize(written);
  return {};
}

Status write_file(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) return bad(path + ": cannot create the file");
  const size_t n = bytes.empty() ? 0 : std::fwrite(bytes.data(), 1, bytes.size(), f);
  const bool closed = std::fclose(f) == 0;
  if (n != bytes.size() || !closed) return bad(path + ": write failed");
  return {};
}

}  // namespace

const char* session_state_name(SessionState state) {
  switch (state) {
    case SessionState::idle: return "idle";
    case SessionState::running: return "running";
    case SessionState::desynced: return "desynced";
    case SessionState::peer_left: return "peer left";
    case SessionState::error: return "error";
  }
  return "unknown";
}

uint64_t session_state_hash(WorldId world, std::span<const uint8_t> game_state) {
  const uint64_t wh = world_state_hash(world);
  if (game_state.empty()) return wh;
  return wh ^ (XXH3_64bits(game_state.data(), game_state.size()) * 0x9E3779B97F4A7C15ull);
}

// --- setup --------------------------------------------------------------------

Status Session::start(WorldId world, const SessionConfig& c, SessionCallbacks callbacks) {
  if (stop_.state != SessionState::idle) return bad("session already started");
  if (c.player_count < 2 || c.player_count > k_session_max_players) {
    return bad(range_text("player_count", 2, k_session_max_players, c.player_count));
  }
  if (c.spectator_count > k_session_max_spectators) {
    return bad(range_text("spectator_count", 0, k_session_max_spectators, c.spectator_count));
  }
  if (c.local_endpoint >= c.player_count + c.spectator_count) {
    return bad(range_text("local_endpoint", 0, c.player_count + c.spectator_count - 1, c.local_endpoint));
  }
  if (c.input_bytes < 1 || c.input_bytes > k_session_max_input_bytes) {
    return bad(range_text("input_bytes", 1, k_session_max_input_bytes, c.input_bytes));
  }
  if (c.input_delay > k_session_max_input_delay) {
    return bad(range_text("input_delay", 0, k_session_max_input_delay, c.input_delay));
  }
  if (c.prediction_window < 1 || c.prediction_window > k_session_max_prediction) {
    return bad(range_text("prediction_window", 1, k_session_max_prediction, c.prediction_window));
  }
  if (c.history_ticks < c.prediction_window + 2 || c.history_ticks > k_session_ring_ticks) {
    return bad(range_text("history_ticks", c.prediction_window + 2, k_session_ring_ticks, c.history_ticks));
  }
  if (c.input_history_ticks < k_session_ring_ticks || c.input_history_ticks > (1u << 20)) {
    return bad(range_text("input_history_ticks", k_session_ring_ticks, 1u << 20, c.input_history_ticks));
  }
  if (c.time_step.raw <= 0) return bad("session config time_step: expected > 0, got raw " + std::to_string(c.time_step.raw));
  if (!callbacks.send) return bad("session callbacks: send is required");
  if (!callbacks.make_commands) return bad("session callbacks: make_commands is required");
  if (static_cast<bool>(callbacks.save_game) != static_cast<bool>(callbacks.load_game)) {
    return bad("session callbacks: save_game and load_game go together");
  }
  if (!world_is_valid(world)) return bad("session: invalid world " + describe(world));

  world_ = world;
  config_ = c;
  callbacks_ = std::move(callbacks);
  const size_t players = c.player_count, endpoints = c.player_count + c.spectator_count, R = k_session_ring_ticks;
  inputs_.assign(players * R * c.input_bytes, 0);
  input_tick_.assign(players * R, UINT64_MAX);
  used_.assign(players * R * c.input_bytes, 0);
  used_tick_.assign(players * R, UINT64_MAX);
  contiguous_.assign(players, c.input_delay);
  local_history_.assign(c.local_endpoint < c.player_count ? size_t{c.input_history_ticks} * c.input_bytes : 0, 0);
  hash_.assign(R, 0);
  world_hash_.assign(R, 0);
  hash_tick_.assign(R, UINT64_MAX);
  remote_hash_.assign(endpoints * R, 0);
  remote_hash_tick_.assign(endpoints * R, UINT64_MAX);
  remote_hash_through_.assign(endpoints, 0);
  hash_checked_through_.assign(endpoints, 0);
  input_ack_from_.assign(endpoints, c.input_delay);
  hash_ack_from_.assign(endpoints, 0);
  remote_tick_.assign(endpoints, 0);
  remote_advantage_.assign(endpoints, 0);
  last_sequence_in_.assign(endpoints, 0);
  sequence_out_.assign(endpoints, 0);
  last_heard_frame_.assign(endpoints, 0);
  gone_.assign(endpoints, 0);
  snap_world_.assign(c.history_ticks, {});
  snap_keyframe_.assign(c.history_ticks, {});
  snap_game_.assign(c.history_ticks, {});
  snap_tick_.assign(c.history_ticks, UINT64_MAX);
  snap_commands_.assign(c.history_ticks, {});
  sync_samples_.assign(k_sync_samples, 0);
  tick_inputs_.assign(players * c.input_bytes, 0);
  out_buffer_.assign(k_packet_max_bytes, 0);
  body_hash_bytes_.reserve(k_packet_max_body_hashes * 8);
  stats_ = {};
  current_ = confirmed_ = 0;
  pending_rollback_ = 0;
  last_local_tick_ = c.input_delay;

  // Ticks 1…K: all-zero inputs, known to everyone.
  const std::vector<uint8_t> zeros(c.input_bytes, 0);
  for (uint32_t p = 0; p < c.player_count; ++p) {
    for (uint64_t t = 1; t <= c.input_delay; ++t) store_input(p, t, zeros.data());
  }
  // Tick 0: the start state.
  Status s = rollback_save(world, &snap_world_[0]);
  if (!s.ok()) return s;
  if (c.record_replay) {
    s = snapshot_into(world, &snap_keyframe_[0]);  // the replay's start state
    if (!s.ok()) return s;
  }
  if (callbacks_.save_game) callbacks_.save_game(&snap_game_[0]);
  snap_tick_[0] = 0;
  start_hash_ = world_state_hash(world);
  hash_tick_[0] = 0;
  hash_[0] = start_hash_;
  world_hash_[0] = start_hash_;

  recording_ = c.record_replay;
  if (recording_) {
    writer_.open_memory();
    ReplayHeader header;
    header.time_step = c.time_step;
    header.keyframe_interval = c.keyframe_interval;
    header.tick_hashes = true;
    if (!c.replay_scene.empty()) {
      header.has_scene_bytes = true;
      header.scene_bytes = c.replay_scene;
      header.has_scene_hash = true;
      header.scene_hash = XXH3_64bits(c.replay_scene.data(), c.replay_scene.size());
    }
    s = writer_.write_header(header, snap_keyframe_[0], snap_game_[0]);
    if (!s.ok()) return s;
  }
  stop_ = {};
  stop_.state = SessionState::running;
  return {};
}

// --- input rings --------------------------------------------------------------

uint8_t* Session::input_at(uint32_t player, uint64_t tick) {
  return inputs_.data() + ((size_t{player} * k_session_ring_ticks) + ring(tick)) * config_.input_bytes;
}
const uint8_t* Session::input_at(uint32_t player, uint64_t tick) const {
  return inputs_.data() + ((size_t{player} * k_session_ring_ticks) + ring(tick)) * config_.input_bytes;
}
bool Session::input_known(uint32_t player, uint64_t tick) const {
  return input_tick_[size_t{player} * k_session_ring_ticks + ring(tick)] == tick;
}
void Session::store_input(uint32_t player, uint64_t tick, const uint8_t* bytes) {
  std::memcpy(input_at(player, tick), bytes, config_.input_bytes);
  if (player == config_.local_endpoint) {
    std::memcpy(local_history_.data() + static_cast<size_t>(tick % config_.input_history_ticks) * config_.input_bytes,
                bytes, config_.input_bytes);
  }
  input_tick_[size_t{player} * k_session_ring_ticks + ring(tick)] = tick;
  uint64_t& c = contiguous_[player];
  while (input_known(player, c + 1)) ++c;
}
uint64_t Session::all_known_through() const {
  uint64_t m = UINT64_MAX;
  for (uint32_t p = 0; p < config_.player_count; ++p) m = std::min(m, contiguous_[p]);
  return m;
}

// --- simulation -----------------------------------------------------------------

bool Session::simulate(uint64_t tick) {
  const uint32_t n = config_.input_bytes;
  for (uint32_t p = 0; p < config_.player_count; ++p) {
    const uint8_t* src = input_known(p, tick) ? input_at(p, tick) : input_at(p, contiguous_[p]);
    uint8_t* dst = tick_inputs_.data() + size_t{p} * n;
    std::memcpy(dst, src, n);
    const size_t slot = size_t{p} * k_session_ring_ticks + ring(tick);
    std::memcpy(used_.data() + slot * n, src, n);
    used_tick_[slot] = tick;
  }
  SessionTickInputs in{config_.player_count, n, tick_inputs_.data()};
  commands_.clear();
  Status s = callbacks_.make_commands(static_cast<int64_t>(tick), in, world_, &commands_);
  if (!s.ok()) {
    stop(SessionState::error, "tick " + std::to_string(tick) + ": make_commands failed: " + s.message);
    return false;
  }
  for (const Command& c : commands_) {
    if (!apply_command(world_, c).ok()) ++stats_.commands_refused;
  }
  const StepResult step = world_step(world_, config_.time_step);
  if (!step.status.ok()) {
    stop(SessionState::error, "tick " + std::to_string(tick) + ": step refused: " + step.status.message);
    return false;
  }
  if (callbacks_.after_step) callbacks_.after_step(static_cast<int64_t>(tick), world_);
  const size_t h = static_cast<size_t>(tick % config_.history_ticks);
  s = rollback_save(world_, &snap_world_[h]);
  if (s.ok() && recording_ && config_.keyframe_interval != 0 && tick % config_.keyframe_interval == 0) {
    s = snapshot_into(world_, &snap_keyframe_[h]);  // a replay keyframe: the portable image, taken after the step
  }
  if (!s.ok()) {
    stop(SessionState::error, "tick " + std::to_string(tick) + ": snapshot failed: " + s.message);
    return false;
  }
  uint64_t game_hash = 0;
  if (callbacks_.save_game) {
    callbacks_.save_game(&snap_game_[h]);
    if (!snap_game_[h].empty()) game_hash = XXH3_64bits(snap_game_[h].data(), snap_game_[h].size()) * 0x9E3779B97F4A7C15ull;
  }
  snap_tick_[h] = tick;
  if (recording_) snap_commands_[h] = commands_;
  const uint64_t wh = world_state_hash(world_);
  hash_[ring(tick)] = wh ^ game_hash;
  world_hash_[ring(tick)] = wh;
  hash_tick_[ring(tick)] = tick;
  ++stats_.ticks_simulated;
  return true;
}

void Session::rollback() {
  if (pending_rollback_ == 0) return;
  const uint64_t from = pending_rollback_;
  pending_rollback_ = 0;
  if (from > current_) return;  // not simulated yet: nothing to undo
  const uint64_t base = from - 1;
  const size_t h = static_cast<size_t>(base % config_.history_ticks);
  if (snap_tick_[h] != base) {
    stop(SessionState::error, "rollback to tick " + std::to_string(base) + ": snapshot no longer kept");
    return;
  }
  const Status s = rollback_restore(world_, snap_world_[h]);
  if (!s.ok()) {
    stop(SessionState::error, "rollback to tick " + std::to_string(base) + ": restore failed: " + s.message);
    return;
  }
  if (callbacks_.load_game) callbacks_.load_game(snap_game_[h]);
  const uint64_t depth = current_ - base;
  ++stats_.rollbacks;
  stats_.resimulated_ticks += depth;
  stats_.max_rollback_depth = std::max(stats_.max_rollback_depth, depth);
  for (uint64_t t = from; t <= current_; ++t) {
    if (!simulate(t)) return;
  }
}

void Session::confirm() {
  if (pending_rollback_ != 0 || stop_.state != SessionState::running) return;
  const uint64_t target = std::min(current_, all_known_through());
  while (confirmed_ < target) {
    const uint64_t t = confirmed_ + 1;
    if (recording_) {
      const size_t h = static_cast<size_t>(t % config_.history_ticks);
      TickRecord rec;
      rec.tick = static_cast<int64_t>(t);
      std::vector<uint8_t> all(size_t{config_.player_count} * config_.input_bytes);
      for (uint32_t p = 0; p < config_.player_count; ++p) {
        std::memcpy(all.data() + size_t{p} * config_.input_bytes, input_at(p, t), config_.input_bytes);
      }
      rec.commands.reserve(snap_commands_[h].size() + 1);
      rec.commands.push_back(make_user_input(std::move(all)));
      for (const Command& c : snap_commands_[h]) rec.commands.push_back(c);
      rec.has_hash = true;
      rec.hash = world_hash_[ring(t)];
      if (callbacks_.save_game) {
        rec.has_game_state = true;
        rec.game_state = snap_game_[h];
      }
      Status s = writer_.append_tick(std::move(rec));
      if (s.ok() && config_.keyframe_interval != 0 && t % config_.keyframe_interval == 0) {
        s = writer_.append_keyframe(static_cast<int64_t>(t), snap_keyframe_[h], snap_game_[h]);
      }
      if (!s.ok()) {
        stop(SessionState::error, "recording tick " + std::to_string(t) + ": " + s.message);
        return;
      }
    }
    confirmed_ = t;
  }
}

void Session::check_hashes() {
  for (uint32_t q = 0; q < endpoint_count(); ++q) {
    if (q == config_.local_endpoint || stop_.state != SessionState::running) continue;
    const uint64_t limit = std::min(confirmed_, remote_hash_through_[q]);
    while (hash_checked_through_[q] < limit) {
      const uint64_t t = hash_checked_through_[q] + 1;
      const size_t r = size_t{q} * k_session_ring_ticks + ring(t);
      if (hash_tick_[ring(t)] == t && remote_hash_tick_[r] == t) {
        ++stats_.hashes_compared;
        if (hash_[ring(t)] != remote_hash_[r]) {
          desync(q, t, hash_[ring(t)], remote_hash_[r], false);
          return;
        }
      }
      hash_checked_through_[q] = t;
    }
  }
}

// --- frames ---------------------------------------------------------------------

bool Session::begin_frame() {
  if (stop_.state != SessionState::running) {
    send_packets();  // desync notices, while any are left
    return false;
  }
  ++stats_.frames;
  if (config_.disconnect_timeout_frames != 0) {
    for (uint32_t q = 0; q < config_.player_count; ++q) {
      if (q == config_.local_endpoint) continue;
      if (stats_.frames - last_heard_frame_[q] > config_.disconnect_timeout_frames) {
        stop_.endpoint = q;
        stop_.last_heard_tick = static_cast<int64_t>(remote_tick_[q]);
        stop(SessionState::peer_left, "player " + std::to_string(q) + " silent for " +
                                          std::to_string(config_.disconnect_timeout_frames) + " frames (last tick heard " +
                                          std::to_string(remote_tick_[q]) + ", local tick " + std::to_string(current_) + ")");
        return false;
      }
    }
  }
  return true;
}

void Session::end_frame() {
  if (!is_spectator()) {
    int64_t sample = INT64_MIN;
    for (uint32_t q = 0; q < config_.player_count; ++q) {
      if (q == config_.local_endpoint) continue;
      const int64_t local_adv = static_cast<int64_t>(current_) - static_cast<int64_t>(remote_tick_[q]);
      sample = std::max(sample, local_adv - remote_advantage_[q]);
    }
    sync_samples_[sync_count_ % k_sync_samples] = sample;
    ++sync_count_;
  }
  send_packets();
}

AdvanceResult Session::idle_frame() {
  if (!begin_frame()) return AdvanceResult::stopped;
  rollback();
  confirm();
  check_hashes();
  end_frame();
  return stop_.state == SessionState::running ? AdvanceResult::stalled : AdvanceResult::stopped;
}

AdvanceResult Session::advance_frame(std::span<const uint8_t> local_input) {
  if (!begin_frame()) return AdvanceResult::stopped;
  if (!is_spectator()) {
    const uint64_t target = current_ + 1 + config_.input_delay;
    if (last_local_tick_ < target) {
      if (local_input.size() != config_.input_bytes) {
        stop(SessionState::error, "local input has " + std::to_string(local_input.size()) + " bytes, expected " +
                                      std::to_string(config_.input_bytes));
        return AdvanceResult::stopped;
      }
      store_input(config_.local_endpoint, target, local_input.data());
      last_local_tick_ = target;
    }
  }
  rollback();
  confirm();
  check_hashes();
  if (stop_.state != SessionState::running) return AdvanceResult::stopped;

  const uint64_t next = current_ + 1;
  const uint64_t known = all_known_through();
  const bool predict = config_.mode == SessionMode::rollback && !is_spectator();
  const bool can_step = predict ? next <= known + config_.prediction_window : next <= known;
  if (can_step) {
    if (!simulate(next)) return AdvanceResult::stopped;
    current_ = next;
    confirm();
    check_hashes();
    // A spectator behind (inputs known beyond the next tick) catches up:
    // up to k_spectator_catch_up ticks per frame.
    for (uint32_t extra = 1; is_spectator() && extra < k_spectator_catch_up && stop_.state == SessionState::running &&
                             current_ + 1 <= all_known_through();
         ++extra) {
      if (!simulate(current_ + 1)) return AdvanceResult::stopped;
      ++current_;
      confirm();
      check_hashes();
    }
  } else {
    ++stats_.stalls;
  }
  end_frame();
  if (stop_.state != SessionState::running) return AdvanceResult::stopped;
  return can_step ? AdvanceResult::stepped : AdvanceResult::stalled;
}

int32_t Session::frames_ahead() const {
  if (is_spectator() || sync_count_ == 0) return 0;
  const uint64_t n = std::min<uint64_t>(sync_count_, k_sync_samples);
  int64_t sum = 0;
  for (uint64_t i = 0; i < n; ++i) sum += sync_samples_[static_cast<size_t>(i)];
  const int64_t ahead = sum / static_cast<int64_t>(n) / 2;
  // Below k_sync_min_frames the difference is jitter (as GGPO's minimum frame advantage).
  if (ahead < k_sync_min_frames) return 0;
  return static_cast<int32_t>(std::min<int64_t>(ahead, 1000));
}

int64_t Session::remote_confirmed_through() const {
  uint64_t m = UINT64_MAX;
  for (uint32_t q = 0; q < endpoint_count(); ++q) {
    if (q != config_.local_endpoint && gone_[q] == 0) m = std::min(m, remote_hash_through_[q]);
  }
  return m == UINT64_MAX ? 0 : static_cast<int64_t>(m);
}

uint64_t Session::confirmed_hash(int64_t signed_tick) const {
  if (signed_tick < 0) return 0;
  const uint64_t tick = static_cast<uint64_t>(signed_tick);
  if (tick > confirmed_ || hash_tick_.empty() || hash_tick_[ring(tick)] != tick) return 0;
  return hash_[ring(tick)];
}

// --- stopping and artifacts ---------------------------------------------------------

void Session::stop(SessionState state, const std::string& message) {
  if (stop_.state != SessionState::running) return;
  stop_.state = state;
  stop_.tick = state == SessionState::desynced ? stop_.tick : static_cast<int64_t>(current_);
  stop_.message = message;
}

void Session::desync(uint32_t endpoint, uint64_t tick, uint64_t local_hash, uint64_t remote_hash, bool reported) {
  if (stop_.state != SessionState::running) return;
  stop_.tick = static_cast<int64_t>(tick);
  stop_.endpoint = endpoint;
  stop_.local_hash = local_hash;
  stop_.remote_hash = remote_hash;
  std::string message = reported ? "endpoint " + std::to_string(endpoint) + " reported a desync at tick " + std::to_string(tick)
                                 : "desync at tick " + std::to_string(tick) + " with endpoint " + std::to_string(endpoint);
  message += ": local hash " + std::to_string(local_hash) + ", remote " + std::to_string(remote_hash);
  const Status s = state_image(static_cast<int64_t>(tick), &desync_image_);
  desync_image_tick_ = s.ok() ? tick : 0;
  if (!s.ok()) message += " (state image of that tick no longer kept: " + s.message + ")";
  stop(SessionState::desynced, message);
  desync_notice_tick_ = tick;
  desync_notice_hash_ = local_hash;
  desync_notices_left_ = 8;
  send_packets();
}

Status Session::ring_slot(int64_t signed_tick, size_t* slot) const {
  if (snap_tick_.empty()) return bad("session not started");
  if (signed_tick < 0) return bad("tick " + std::to_string(signed_tick) + " is negative");
  const uint64_t tick = static_cast<uint64_t>(signed_tick);
  const size_t h = static_cast<size_t>(tick % config_.history_ticks);
  if (tick > current_ || snap_tick_[h] != tick) {
    return bad("tick " + std::to_string(tick) + " is not in the snapshot ring (ticks " +
               std::to_string(current_ >= config_.history_ticks ? current_ - config_.history_ticks + 1 : 0) + "…" +
               std::to_string(current_) + ")");
  }
  *slot = h;
  return {};
}

Result<WorldId> Session::ring_world(int64_t tick) const {
  size_t h = 0;
  const Status kept = ring_slot(tick, &h);
  if (!kept.ok()) return {kept, {}};
  Result<WorldId> w = create_world(default_world_def());
  if (!w.ok()) return w;
  const Status s = rollback_restore(w.value, snap_world_[h]);
  if (s.ok()) return w;
  (void)destroy_world(w.value);
  return {s, {}};
}

Status Session::state_image(int64_t tick, std::vector<uint8_t>* out) const {
  // The compact image restored into a scratch world, then encoded portably.
  // Contacts between simulated bodies carry no manifold geometry in the
  // compact image (the next step recomputes it), so those fields read as zero
  // here on every peer alike; bodies, joints and impulses are exact.
  const Result<WorldId> w = ring_world(tick);
  if (!w.ok()) return w.status;
  const Status s = snapshot_into(w.value, out);
  (void)destroy_world(w.value);
  return s;
}

std::vector<uint8_t> Session::replay_bytes() {
  if (!recording_) return {};
  if (stop_.state == SessionState::running) {
    (void)writer_.flush();
    return writer_.memory();
  }
  (void)writer_.finish();
  return writer_.memory();
}

Status Session::write_artifacts(const std::string& prefix) {
  if (recording_) {
    const Status s = write_file(prefix + ".replay", replay_bytes());
    if (!s.ok()) return s;
  }
  if (stop_.state == SessionState::desynced && desync_image_tick_ != 0) return write_file(prefix + ".state", desync_image_);
  std::vector<uint8_t> image;
  const Status s = state_image(static_cast<int64_t>(confirmed_), &image);
  if (!s.ok()) return s;
  return write_file(prefix + ".state", image);
}

void Session::peer_disconnected(uint32_t endpoint) {
  if (endpoint >= endpoint_count() || endpoint == config_.local_endpoint || stop_.state != SessionState::running) return;
  if (endpoint >= config_.player_count) {
    gone_[endpoint] = 1;
    return;
  }
  stop_.endpoint = endpoint;
  stop_.last_heard_tick = static_cast<int64_t>(remote_tick_[endpoint]);
  stop(SessionState::peer_left, "player " + std::to_string(endpoint) + " disconnected (last tick heard " +
                                    std::to_string(remote_tick_[endpoint]) + ", local tick " + std::to_string(current_) + ")");
}

}  // namespace tandem

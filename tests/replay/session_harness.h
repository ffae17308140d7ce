// session_harness.h — in-process session tests: a simulated network (seeded
// loss, latency, jitter, duplication, hence reordering) between N peers, each
// with its own world running the arena game (tools/net/arena_game.h), driven
// one frame at a time; and a single-machine reference run of the same inputs.
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "fixed/splitmix64.h"
#include "physics/tandem.h"
#include "replay/session.h"
#include "replay/state.h"
#include "tools/net/arena_game.h"

namespace tandem::session_test {

/// Network conditions, in frames and per-mille.
struct NetConditions {
  uint64_t seed = 1;
  uint32_t loss_per_mille = 0;
  uint32_t duplicate_per_mille = 0;
  uint32_t latency_frames = 0;
  uint32_t jitter_frames = 0;  ///< each packet waits latency + uniform 0…jitter (so packets reorder)
};

/// A simulated network: packets are queued with a delivery frame.
class SimNet {
 public:
  explicit SimNet(const NetConditions& c) : c_(c), rng_(c.seed) {}
  /// Sends a packet at frame `now`.
  void send(uint32_t from, uint32_t to, std::span<const uint8_t> bytes, uint64_t now) {
    if (blocked_from_ != UINT32_MAX && from == blocked_from_) return;
    if (blocked_to_ != UINT32_MAX && to == blocked_to_) return;
    if (draw(1000) < c_.loss_per_mille) return;
    const int copies = draw(1000) < c_.duplicate_per_mille ? 2 : 1;
    for (int i = 0; i < copies; ++i) {
      const uint64_t delay = c_.latency_frames + draw(c_.jitter_frames + 1);
      queue_.push_back(Msg{now + delay, order_++, from, to, std::vector<uint8_t>(bytes.begin(), bytes.end())});
    }
  }
  /// Delivers every packet for `to` due at or before `now`, in (due, send order).
  void deliver(uint32_t to, uint64_t now, const std::function<void(uint32_t from, std::span<const uint8_t>)>& fn) {
    std::vector<Msg> due;
    auto it = std::stable_partition(queue_.begin(), queue_.end(), [&](const Msg& m) { return !(m.to == to && m.at <= now); });
    due.assign(std::make_move_iterator(it), std::make_move_iterator(queue_.end()));
    queue_.erase(it, queue_.end());
    std::sort(due.begin(), due.end(), [](const Msg& a, const Msg& b) { return a.at != b.at ? a.at < b.at : a.order < b.order; });
    for (const Msg& m : due) fn(m.from, m.bytes);
  }
  /// Drops everything `from` sends from now on (UINT32_MAX: none).
  void block_from(uint32_t from) { blocked_from_ = from; }
  /// Drops everything sent to `to` from now on (UINT32_MAX: none).
  void block_to(uint32_t to) { blocked_to_ = to; }

 private:
  struct Msg {
    uint64_t at, order;
    uint32_t from, to;
    std::vector<uint8_t> bytes;
  };
  uint32_t draw(uint32_t n) { return n == 0 ? 0 : static_cast<uint32_t>(splitmix64_next(&rng_) % n); }
  NetConditions c_;
  uint64_t rng_;
  uint64_t order_ = 0;
  uint32_t blocked_from_ = UINT32_MAX;
  uint32_t blocked_to_ = UINT32_MAX;
  std::vector<Msg> queue_;
};

/// What a rig runs.
struct RigOptions {
  SessionConfig config;           ///< local_endpoint is set per peer
  NetConditions net;
  int64_t ticks = 300;            ///< run until every peer confirmed this many
  uint64_t frame_limit = 5000;
  uint64_t bot_seed = 7;
  uint32_t change_every = 4;      ///< bots change input every this many ticks (1: every tick)
  uint32_t crates = 12;
  bool time_sync = true;          ///< skip a frame while frames_ahead() > 0
  uint32_t fast_peer_every = 0;   ///< peer 0 runs an extra frame every this many frames (0: never)
  int64_t perturb_tick = 0;       ///< nudge player 0's disc by one raw unit on peer perturb_peer after this tick
  uint32_t perturb_peer = 1;
  uint64_t silence_peer_at = 0;   ///< from this frame on, peer perturb_peer stops (no frames, no packets)
  uint32_t cut_off_peer = UINT32_MAX;  ///< every packet to this peer is lost in frames [cut_off_from, cut_off_until)
  uint64_t cut_off_from = 0, cut_off_until = 0;
};

/// One peer.
struct Peer {
  WorldId world;
  arena::Game game;
  Session session;
  std::vector<uint64_t> hashes;  ///< confirmed_hash(t) at index t − 1
  bool silent = false;
  uint64_t last_idle = 0;
  ~Peer() {
    if (world_is_valid(world)) (void)destroy_world(world);
  }
};

/// Builds the peers and runs them (see RigOptions).
struct Rig {
  RigOptions options;
  SimNet net;
  std::vector<std::unique_ptr<Peer>> peers;
  uint64_t frame = 0;
  uint64_t max_tick_gap = 0;
  uint64_t idle_frames = 0;   ///< frames a peer waited for time sync  ///< most |current tick difference| between peers 0 and 1 seen

  explicit Rig(const RigOptions& o) : options(o), net(o.net) {
    const uint32_t n = o.config.player_count + o.config.spectator_count;
    for (uint32_t e = 0; e < n; ++e) {
      auto peer = std::make_unique<Peer>();
      Result<WorldId> w = create_world(default_world_def());
      REQUIRE(w.ok());
      peer->world = w.value;
      REQUIRE(peer->game.build(w.value, o.config.player_count, o.crates).ok());
      SessionConfig c = o.config;
      c.local_endpoint = e;
      Peer* self = peer.get();
      SessionCallbacks cb = peer->game.callbacks([this, e](uint32_t to, std::span<const uint8_t> bytes) { net.send(e, to, bytes, frame); });
      if (o.perturb_tick != 0 && e == o.perturb_peer) {
        cb.after_step = [self, t0 = o.perturb_tick](int64_t tick, WorldId world) {
          self->game.after_step(tick, world);
          if (tick == t0) {
            const BodyId b = body_id(world, self->game.players[0]);
            Vec2 p = body_position(b);
            p.x.raw += 1;
            REQUIRE(body_set_transform(b, p, body_rotation(b)).ok());
          }
        };
      }
      const Status s = peer->session.start(w.value, c, std::move(cb));
      INFO(s.message);
      REQUIRE(s.ok());
      peers.push_back(std::move(peer));
    }
  }

  void frame_of(uint32_t e) {
    Peer& p = *peers[e];
    if (p.silent) return;
    net.deliver(e, frame, [&](uint32_t from, std::span<const uint8_t> bytes) { p.session.receive(from, bytes); });
    if (options.time_sync && p.session.frames_ahead() > 0 && p.session.state() == SessionState::running &&
        frame > p.last_idle + 1) {  // at most every other frame, as a game sleeps a little at a time
      p.last_idle = frame;
      (void)p.session.idle_frame();
      ++idle_frames;
    } else {
      uint8_t in[arena::k_input_bytes];
      arena::bot_input(options.bot_seed, e, p.session.current_tick() + 1 + int64_t{options.config.input_delay}, options.change_every, in);
      (void)p.session.advance_frame(in);
    }
    for (int64_t t = static_cast<int64_t>(p.hashes.size()) + 1; t <= p.session.confirmed_tick(); ++t) p.hashes.push_back(p.session.confirmed_hash(t));
  }

  /// Runs until every running peer confirmed options.ticks, one stops, or the frame limit.
  void run() {
    while (frame < options.frame_limit) {
      ++frame;
      if (options.silence_peer_at != 0 && frame == options.silence_peer_at) peers[options.perturb_peer]->silent = true;
      if (options.cut_off_peer != UINT32_MAX && frame == options.cut_off_from) net.block_to(options.cut_off_peer);
      if (options.cut_off_peer != UINT32_MAX && frame == options.cut_off_until) net.block_to(UINT32_MAX);
      for (uint32_t e = 0; e < peers.size(); ++e) {
        frame_of(e);
        if (e == 0 && options.fast_peer_every != 0 && frame % options.fast_peer_every == 0) frame_of(0);
      }
      if (peers.size() >= 2) {
        const int64_t a = peers[0]->session.current_tick(), b = peers[1]->session.current_tick();
        max_tick_gap = std::max(max_tick_gap, static_cast<uint64_t>(a > b ? a - b : b - a));
      }
      bool done = true, stopped = false;
      for (const auto& p : peers) {
        if (p->silent) continue;
        if (p->session.state() != SessionState::running) stopped = true;
        if (p->session.confirmed_tick() < options.ticks) done = false;
      }
      if (done || stopped) break;
    }
    // Let desync notices and last packets arrive.
    for (int extra = 0; extra < 40; ++extra) {
      ++frame;
      bool any_running = false;
      for (const auto& p : peers) any_running = any_running || (!p->silent && p->session.state() == SessionState::running);
      if (!any_running) break;
      bool any_stopped = false;
      for (const auto& p : peers) any_stopped = any_stopped || p->session.state() != SessionState::running;
      if (!any_stopped) break;
      for (uint32_t e = 0; e < peers.size(); ++e) frame_of(e);
    }
  }
};

/// The single-machine reference: hash (session_state_hash) after each tick
/// 1…ticks of the same bots' inputs.
inline std::vector<uint64_t> reference_hashes(const RigOptions& o) {
  Result<WorldId> w = create_world(default_world_def());
  REQUIRE(w.ok());
  arena::Game game;
  REQUIRE(game.build(w.value, o.config.player_count, o.crates).ok());
  const uint32_t n = arena::k_input_bytes;
  std::vector<uint8_t> all(size_t{o.config.player_count} * n);
  std::vector<Command> commands;
  std::vector<uint8_t> game_state;
  std::vector<uint64_t> out;
  for (int64_t t = 1; t <= o.ticks; ++t) {
    for (uint32_t p = 0; p < o.config.player_count; ++p) {
      if (t <= o.config.input_delay) {
        std::fill_n(all.data() + size_t{p} * n, n, uint8_t{0});
      } else {
        arena::bot_input(o.bot_seed, p, t, o.change_every, all.data() + size_t{p} * n);
      }
    }
    commands.clear();
    REQUIRE(game.make_commands(t, SessionTickInputs{o.config.player_count, n, all.data()}, w.value, &commands).ok());
    for (const Command& c : commands) (void)apply_command(w.value, c);
    REQUIRE(world_step(w.value, o.config.time_step).status.ok());
    game.after_step(t, w.value);
    game.save(&game_state);
    out.push_back(session_state_hash(w.value, game_state));
  }
  (void)destroy_world(w.value);
  return out;
}

}  // namespace tandem::session_test

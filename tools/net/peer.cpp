// peer.cpp — one session peer over UDP (see peer.h).
#include "tools/net/peer.h"

#include <chrono>
#include <thread>

#include "tools/net/arena_game.h"

namespace tandem::net {

void run_peer(EnetTransport& transport, const PeerOptions& o, PeerResult* out) {
  using Clock = std::chrono::steady_clock;
  *out = {};
  const auto started = Clock::now();
  Result<WorldId> w = o.make_world ? o.make_world() : create_world(default_world_def());
  if (!w.ok()) {
    out->status = w.status;
    return;
  }
  const UniqueWorld guard{w.value};
  arena::Game game;
  out->status = o.make_world ? game.add_players(w.value, o.config.player_count)
                             : game.build(w.value, o.config.player_count, o.crates);
  if (!out->status.ok()) return;
  SessionCallbacks cb = game.callbacks([&](uint32_t to, std::span<const uint8_t> bytes) { transport.send(to, bytes); });
  if (o.inject_desync_tick != 0) {
    cb.after_step = [&game, t0 = o.inject_desync_tick](int64_t tick, WorldId world) {
      game.after_step(tick, world);
      if (tick == t0) {
        const BodyId b = body_id(world, game.players[0]);
        Vec2 p = body_position(b);
        p.x.raw += 1;
        (void)body_set_transform(b, p, body_rotation(b));
      }
    };
  }
  Session session;
  SessionConfig config = o.config;
  if (config.replay_scene.empty() && !game.players.empty())
    config.replay_scene = arena::replay_scene(config.player_count, game.players[0].index);
  out->status = session.start(w.value, config, std::move(cb));
  if (!out->status.ok()) return;

  const auto frame = std::chrono::microseconds(o.frame_us);
  auto next = Clock::now();
  const auto deadline = started + std::chrono::milliseconds(o.run_timeout_ms);
  uint32_t linger = 0;
  bool ending = false, idled = false;
  uint8_t input[arena::k_input_bytes];
  auto on_packet = [&](uint32_t from, std::span<const uint8_t> bytes) { session.receive(from, bytes); };
  auto on_disconnect = [&](uint32_t e) {
    if (!ending && session.confirmed_tick() < o.ticks) session.peer_disconnected(e);  // else the game is over
  };
  for (;;) {
    const auto now = Clock::now();
    const uint32_t wait_ms =
        next > now ? static_cast<uint32_t>(std::chrono::duration_cast<std::chrono::milliseconds>(next - now).count()) : 0;
    transport.poll(wait_ms, on_packet, on_disconnect);
    next += frame;
    if (session.state() == SessionState::running) {
      if (session.frames_ahead() > 0 && !idled) {
        (void)session.idle_frame();
        idled = true;
      } else {
        arena::bot_input(o.bot_seed, o.config.local_endpoint, session.current_tick() + 1 + int64_t{o.config.input_delay},
                         o.change_every, input);
        (void)session.advance_frame(input);
        idled = false;
      }
    } else {
      (void)session.advance_frame({});  // sends the remaining desync notices
    }
    if (o.crash_at_tick != 0 && session.current_tick() >= o.crash_at_tick) {
      transport.close(0);  // no disconnect message: the others must notice the silence
      break;
    }
    for (int64_t t = static_cast<int64_t>(out->hashes.size()) + 1; t <= session.confirmed_tick(); ++t) out->hashes.push_back(session.confirmed_hash(t));
    if (o.progress) o.progress(session.confirmed_tick(), o.ticks);
    if (!ending && session.state() != SessionState::running) ending = true;
    if (!ending && session.confirmed_tick() >= o.ticks && session.remote_confirmed_through() >= o.ticks) ending = true;
    if (ending && ++linger > o.linger_frames) break;
    if (Clock::now() > deadline) {
      out->status = Status{StatusCode::invalid_argument,
                           "endpoint " + std::to_string(o.config.local_endpoint) + ": timed out after " +
                               std::to_string(o.run_timeout_ms) + " ms at confirmed tick " +
                               std::to_string(session.confirmed_tick()) + " of " + std::to_string(o.ticks)};
      break;
    }
  }
  if (session.state() == SessionState::desynced && !o.artifacts_prefix.empty()) {
    const Status s = session.write_artifacts(o.artifacts_prefix);
    if (s.ok()) {
      if (o.config.record_replay) out->artifacts.push_back(o.artifacts_prefix + ".replay");
      out->artifacts.push_back(o.artifacts_prefix + ".state");
    } else if (out->status.ok()) {
      out->status = s;
    }
  }
  if (o.config.record_replay) out->replay = session.replay_bytes();
  transport.close(200);
  out->stop = session.stop_info();
  out->stats = session.stats();
  out->transport = transport.stats();
  out->confirmed_tick = session.confirmed_tick();
  out->final_hash = o.ticks > 0 && static_cast<int64_t>(out->hashes.size()) >= o.ticks ? out->hashes[static_cast<size_t>(o.ticks - 1)] : 0;
  out->seconds = std::chrono::duration<double>(Clock::now() - started).count();
}

}  // namespace tandem::net

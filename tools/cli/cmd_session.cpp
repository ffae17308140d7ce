// cmd_session.cpp — `tandem session` (one peer of a networked game, one
// process per player) and `tandem netplay` (N peers on loopback in one
// process): the bundled arena game (tools/net/arena_game.h) with a seeded bot
// on every player's disc, played over UDP (ENet, tools/net) in lockstep or
// rollback mode (replay/session.h).
//
// Both print one summary: ticks, rollbacks and their deepest, stalls, bytes
// per tick per player, the final confirmed hash of each peer (equal when the
// game stayed in sync) and, after a desync, its tick plus the body and field
// where the peers' state images differ. Exit codes: 0 played to the end in
// sync, 1 desync or a peer left, 2 bad usage or could not run.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <ctime>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "cli.h"
#include "cli_util.h"
#include "replay/replay_file.h"
#include "replay/session.h"
#include "replay/verify.h"
#include "scene/scene.h"
#include "tools/net/arena_game.h"
#include "tools/net/enet_transport.h"
#include "tools/net/peer.h"

namespace tandem::cli {
namespace {

using Json = nlohmann::ordered_json;

struct PlayArgs {
  // session
  uint32_t endpoint = 0;
  std::vector<std::string> peers;
  // netplay
  uint32_t players = 2;
  std::string artifacts_dir = ".";
  // both
  std::string mode = "rollback";
  int64_t ticks = 600;
  uint32_t delay = 2, window = 8;
  double loss = 0;  // percent (tools only: turned into per-mille)
  uint32_t latency = 0, jitter = 0;
  uint64_t seed = 1;
  int64_t inject_desync = 0;
  uint32_t frame_us = 16667;
  uint32_t crates = 40;
  std::string scene;  // --scene: the arena's walls and crates from a scene file
  std::shared_ptr<const scene::Scene> loaded_scene;
  uint32_t connect_timeout_ms = 10000;
  uint32_t timeout_s = 120;
  bool json = false, quiet = false;
};

net::PeerOptions peer_options(const PlayArgs& a, uint32_t players, uint32_t endpoint, const std::string& prefix) {
  net::PeerOptions o;
  o.config.mode = a.mode == "lockstep" ? SessionMode::lockstep : SessionMode::rollback;
  o.config.player_count = players;
  o.config.local_endpoint = endpoint;
  o.config.input_bytes = arena::k_input_bytes;
  o.config.input_delay = a.delay;
  o.config.prediction_window = a.window;
  o.config.session_id = a.seed;
  o.config.disconnect_timeout_frames = 180;
  o.config.record_replay = true;
  o.config.keyframe_interval = 60;
  o.ticks = a.ticks;
  o.frame_us = a.frame_us;
  o.bot_seed = a.seed;
  o.crates = a.crates;
  if (a.loaded_scene) {
    o.make_world = [scene = a.loaded_scene]() -> Result<WorldId> {
      Result<scene::BuiltScene> built = scene::build_world(*scene);
      Result<WorldId> w;
      w.status = built.status;
      if (built.ok()) w.value = built.value.world;
      return w;
    };
  }
  o.inject_desync_tick = endpoint == 1 ? a.inject_desync : 0;
  o.run_timeout_ms = a.timeout_s * 1000;
  o.artifacts_prefix = prefix;
  return o;
}

net::Conditions conditions(const PlayArgs& a, uint32_t endpoint) {
  net::Conditions c;
  c.seed = a.seed * 1000 + endpoint;
  c.loss_per_mille = static_cast<uint32_t>(a.loss * 10.0 + 0.5);
  c.latency_ms = a.latency;
  c.jitter_ms = a.jitter;
  return c;
}

std::string hex(uint64_t v) {
  char b[24];
  std::snprintf(b, sizeof b, "0x%016" PRIx64, v);
  return b;
}

// Prints the summary of `results` (endpoint order) and returns the exit code.
int report(const char* command, const PlayArgs& a, const std::vector<net::PeerResult>& results, bool json) {
  for (const net::PeerResult& r : results) {
    if (!r.status.ok()) return fail(command, r.status.message);
  }
  bool in_sync = true, desync = false;
  for (const net::PeerResult& r : results) {
    in_sync = in_sync && r.stop.state == SessionState::running && r.final_hash == results[0].final_hash;
    desync = desync || r.stop.state == SessionState::desynced;
  }
  // After a desync, diff the state images the peers wrote (two or more in this process).
  DiffReport diff;
  bool diffed = false;
  if (desync && results.size() >= 2 && results[0].artifacts.size() == 2 && results[1].artifacts.size() == 2) {
    std::vector<uint8_t> sa, sb;
    if (read_file_bytes(results[0].artifacts[1], &sa).ok() && read_file_bytes(results[1].artifacts[1], &sb).ok()) {
      diff = diff_snapshots(sa, sb);
      diffed = true;
    }
  }
  if (json) {
    Json j;
    j["mode"] = a.mode;
    j["ticks"] = a.ticks;
    j["in_sync"] = in_sync;
    Json peers = Json::array();
    for (size_t e = 0; e < results.size(); ++e) {
      const net::PeerResult& r = results[e];
      const uint64_t ticks = r.confirmed_tick <= 0 ? 1 : static_cast<uint64_t>(r.confirmed_tick);
      Json p;
      p["endpoint"] = a.peers.empty() ? e : a.endpoint;
      p["state"] = session_state_name(r.stop.state);
      if (r.stop.state != SessionState::running) p["message"] = r.stop.message;
      p["confirmed_tick"] = r.confirmed_tick;
      p["rollbacks"] = r.stats.rollbacks;
      p["max_rollback_depth"] = r.stats.max_rollback_depth;
      p["resimulated_ticks"] = r.stats.resimulated_ticks;
      p["stalls"] = r.stats.stalls;
      p["bytes_sent_per_tick"] = r.transport.bytes_sent / ticks;
      p["packets_rejected"] = r.stats.packets_rejected;
      p["final_hash"] = hex(r.final_hash);
      if (!r.artifacts.empty()) p["artifacts"] = r.artifacts;
      peers.push_back(p);
    }
    j["peers"] = peers;
    if (diffed && diff.located) {
      j["desync"] = Json{{"tick", results[0].stop.tick}, {"difference", diff.difference.describe()}};
    }
    std::printf("%s\n", j.dump(2).c_str());
  } else {
    std::printf("%-8s %-9s %7s %9s %6s %7s %7s %11s  %s\n", "endpoint", "state", "ticks", "rollbacks", "depth", "stalls",
                "B/tick", "rejected", "final hash");
    for (size_t e = 0; e < results.size(); ++e) {
      const net::PeerResult& r = results[e];
      const uint64_t ticks = r.confirmed_tick <= 0 ? 1 : static_cast<uint64_t>(r.confirmed_tick);
      std::printf("%-8zu %-9s %7" PRId64 " %9" PRIu64 " %6" PRIu64 " %7" PRIu64 " %7" PRIu64 " %11" PRIu64 "  %s\n",
                  a.peers.empty() ? e : size_t{a.endpoint}, session_state_name(r.stop.state), r.confirmed_tick,
                  r.stats.rollbacks, r.stats.max_rollback_depth, r.stats.stalls, r.transport.bytes_sent / ticks,
                  r.stats.packets_rejected, hex(r.final_hash).c_str());
    }
    for (size_t e = 0; e < results.size(); ++e) {
      const net::PeerResult& r = results[e];
      if (r.stop.state != SessionState::running) std::printf("endpoint %zu: %s\n", a.peers.empty() ? e : size_t{a.endpoint}, r.stop.message.c_str());
      for (const std::string& f : r.artifacts) std::printf("wrote %s\n", f.c_str());
    }
    if (diffed) std::printf("first difference at tick %" PRId64 ": %s\n", results[0].stop.tick, diff.located ? diff.difference.describe().c_str() : "not located");
    if (results.size() > 1) std::printf("%s\n", in_sync ? "in sync: every peer ended with the same hash" : "NOT in sync");
  }
  return in_sync ? 0 : 1;
}

int check_common(const char* command, const PlayArgs& a) {
  if (a.mode != "rollback" && a.mode != "lockstep") return fail(command, "--mode must be rollback or lockstep, got " + a.mode);
  if (a.loss < 0 || a.loss > 100) return fail(command, "--loss must be 0…100 (percent)");
  return -1;
}

// Loads --scene (when given) into a.loaded_scene; prints the error (exit 2).
int load_arena_scene(const char* command, PlayArgs* a, const GlobalOptions& g) {
  if (a->scene.empty()) return 0;
  std::vector<uint8_t> text;
  Status s = read_file_bytes(a->scene, &text);
  if (!s.ok()) return fail(command, s.message);
  Result<scene::Scene> loaded =
      scene::load_scene_text(std::string_view(reinterpret_cast<const char*>(text.data()), text.size()), a->scene, g.scene_limits);
  if (!loaded.ok()) return fail(command, loaded.status.message);
  a->loaded_scene = std::make_shared<const scene::Scene>(std::move(loaded.value));
  return 0;
}

int run_session(PlayArgs& a, const GlobalOptions& g) {
  if (int rc = load_arena_scene("session", &a, g)) return rc;
  const int bad = check_common("session", a);
  if (bad >= 0) return bad;
  if (a.peers.size() < 2 || a.peers.size() > 8) return fail("session", "--peers needs 2…8 addresses, got " + std::to_string(a.peers.size()));
  if (a.endpoint >= a.peers.size()) return fail("session", "--endpoint must be 0…" + std::to_string(a.peers.size() - 1));
  std::vector<net::Address> addresses(a.peers.size());
  for (size_t i = 0; i < a.peers.size(); ++i) {
    const Status s = net::parse_address(a.peers[i], &addresses[i]);
    if (!s.ok()) return fail("session", s.message);
  }
  const uint32_t n = static_cast<uint32_t>(a.peers.size());
  net::EnetTransport transport;
  Status s = transport.open(addresses[a.endpoint], a.endpoint, n, conditions(a, a.endpoint));
  if (!s.ok()) return fail("session", s.message);
  const bool quiet = a.quiet || g.quiet, json = a.json || g.json;
  if (!quiet) std::fprintf(stderr, "tandem session: endpoint %u on port %u, waiting for %u peers...\n", a.endpoint, transport.local_port(), n - 1);
  s = transport.connect_all(addresses, a.connect_timeout_ms);
  if (!s.ok()) return fail("session", s.message);
  std::vector<net::PeerResult> results(1);
  net::PeerOptions o = peer_options(a, n, a.endpoint, a.artifacts_dir + "/peer" + std::to_string(a.endpoint));
  ProgressBar bar("session", quiet || json);
  o.progress = [&bar](int64_t done, int64_t total) { bar.update(static_cast<uint64_t>(done), static_cast<uint64_t>(total)); };
  net::run_peer(transport, o, &results[0]);
  bar.finish();
  return report("session", a, results, json);
}

int run_netplay(PlayArgs& a, const GlobalOptions& g) {
  if (int rc = load_arena_scene("netplay", &a, g)) return rc;
  const int bad = check_common("netplay", a);
  if (bad >= 0) return bad;
  if (a.players < 2 || a.players > 8) return fail("netplay", "--players must be 2…8");
  const uint32_t n = a.players;
  std::vector<net::EnetTransport> transports(n);
  std::vector<net::Address> addresses(n);
  for (uint32_t e = 0; e < n; ++e) {
    const Status s = transports[e].open(net::Address{"127.0.0.1", 0}, e, n, conditions(a, e));
    if (!s.ok()) return fail("netplay", s.message);
    addresses[e] = net::Address{"127.0.0.1", transports[e].local_port()};
  }
  const bool quiet = a.quiet || g.quiet, json = a.json || g.json;
  std::vector<net::PeerResult> results(n);
  std::vector<Status> connects(n);
  ProgressBar bar("netplay", quiet || json);
  std::vector<std::thread> threads;
  for (uint32_t e = 0; e < n; ++e) {
    threads.emplace_back([&, e] {
      connects[e] = transports[e].connect_all(addresses, a.connect_timeout_ms);
      if (!connects[e].ok()) return;
      net::PeerOptions o = peer_options(a, n, e, a.artifacts_dir + "/netplay_peer" + std::to_string(e));
      net::run_peer(transports[e], o, &results[e]);
    });
  }
  for (std::thread& t : threads) t.join();
  bar.finish();
  for (const Status& s : connects) {
    if (!s.ok()) return fail("netplay", s.message);
  }
  return report("netplay", a, results, json);
}

void add_common(CLI::App* c, PlayArgs* a) {
  c->add_option("--mode", a->mode, "rollback (default) or lockstep");
  c->add_option("--ticks", a->ticks, "ticks to play (default 600 = 10 s at 60 Hz)")->check(CLI::Range(int64_t{1}, int64_t{1} << 31));
  c->add_option("--delay", a->delay, "input delay K in ticks (default 2)")->check(CLI::Range(0, 30));
  c->add_option("--window", a->window, "rollback: prediction window in ticks (default 8)")->check(CLI::Range(1, 30));
  c->add_option("--loss", a->loss, "simulated loss of input packets, percent (default 0)");
  c->add_option("--latency", a->latency, "simulated one-way latency, ms (default 0)")->check(CLI::Range(0, 2000));
  c->add_option("--jitter", a->jitter, "plus uniform 0…MS of jitter (default 0; reorders packets)")->check(CLI::Range(0, 2000));
  c->add_option("--seed", a->seed, "bots, network simulator and session id (default 1; every peer must agree)");
  c->add_option("--inject-desync", a->inject_desync, "nudge player 0's disc by one raw unit on endpoint 1 after this tick")
      ->check(CLI::Range(int64_t{0}, INT64_MAX));
  c->add_option("--frame-us", a->frame_us, "frame length in microseconds (default 16667: 60 Hz)")->check(CLI::Range(1000, 1000000));
  auto* crates = c->add_option("--crates", a->crates, "crates in the arena built in code (default 40)")->check(CLI::Range(0, 1000));
  c->add_option("--scene", a->scene,
                "the arena from a scene file instead (scenes/arena.json: walls and crates; the players' discs are added "
                "after its bodies)")
      ->excludes(crates);
  c->add_option("--artifacts", a->artifacts_dir, "where a desync writes peerN.replay and peerN.state (default .)");
  c->add_option("--connect-timeout", a->connect_timeout_ms, "ms to wait for every peer (default 10000)");
  c->add_option("--timeout", a->timeout_s, "give up after this many seconds (default 120)");
  add_output_flags(c, &a->json, &a->quiet, "no progress bar");
}


// --- session-bench -------------------------------------------------------------
// Rollback cost per frame (CPU time of the thread): two in-process sessions (input delay 0, bots that
// change input every tick, so every late input is a misprediction); peer 1's
// packets reach peer 0 `depth` frames late, so each of peer 0's frames
// restores and re-simulates `depth` ticks, then steps one new tick (each tick
// with its snapshot and hash, as in a game). Timed: peer 0's advance_frame.
struct BenchArgs {
  std::vector<uint32_t> bodies{100, 1000};
  std::vector<uint32_t> depths{2, 4, 8};
  uint32_t frames = 120;
  uint32_t repeats = 3;
  bool json = false, quiet = false;
};

// CPU time of this thread, ms (the VM is shared: wall time measures the neighbours).
double thread_cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) * 1e-6;
}

int run_session_bench(const BenchArgs& a, const GlobalOptions& g) {
  const bool json = a.json || g.json;
  Json rows = Json::array();
  if (!json) std::printf("%7s %6s %12s %12s %10s %12s\n", "bodies", "depth", "ms/frame", "ms/frame max", "rollbacks", "resim/frame");
  for (uint32_t bodies : a.bodies) {
    for (uint32_t depth : a.depths) {
      if (depth < 1 || depth > 30) return fail("session-bench", "--depths must be 1…30");
      const uint32_t crates = bodies > 6 ? bodies - 6 : 0;  // 4 walls + 2 discs
      if (crates > arena::k_max_crates) return fail("session-bench", "--bodies at most " + std::to_string(arena::k_max_crates + 6));
      std::vector<double> medians;
      uint64_t rollbacks = 0, resim = 0, measured = 0;
      double worst = 0;
      for (uint32_t rep = 0; rep < a.repeats; ++rep) {
        struct BenchPeer {
          OwnedWorld world;
          arena::Game game;
          Session session;
          std::vector<std::pair<uint64_t, std::vector<uint8_t>>> inbox;  // (due frame, bytes)
        };
        BenchPeer peers[2];
        uint64_t frame = 0;
        for (uint32_t e = 0; e < 2; ++e) {
          peers[e].world.id = create_world(default_world_def()).value;
          const Status s = peers[e].game.build(peers[e].world.id, 2, crates);
          if (!s.ok()) return fail("session-bench", s.message);
          SessionConfig c;
          c.mode = SessionMode::rollback;
          c.player_count = 2;
          c.local_endpoint = e;
          c.input_bytes = arena::k_input_bytes;
          c.input_delay = 0;
          c.prediction_window = std::max<uint32_t>(8, depth + 1);
          c.history_ticks = c.prediction_window + 2;
          c.disconnect_timeout_frames = 0;
          BenchPeer* other = &peers[1 - e];
          const uint64_t delay = e == 1 ? depth : 0;
          const Status st = peers[e].session.start(peers[e].world.id, c, peers[e].game.callbacks([other, delay, &frame](uint32_t, std::span<const uint8_t> b) {
            other->inbox.emplace_back(frame + delay, std::vector<uint8_t>(b.begin(), b.end()));
          }));
          if (!st.ok()) return fail("session-bench", st.message);
        }
        std::vector<double> times;
        uint8_t in[arena::k_input_bytes];
        for (uint32_t f = 0; f < a.frames + 60; ++f) {
          ++frame;
          for (uint32_t e = 0; e < 2; ++e) {
            BenchPeer& p = peers[e];
            std::vector<std::pair<uint64_t, std::vector<uint8_t>>> keep;
            for (auto& [due, bytes] : p.inbox) {
              if (due <= frame) {
                p.session.receive(1 - e, bytes);
              } else {
                keep.emplace_back(due, std::move(bytes));
              }
            }
            p.inbox.swap(keep);
            arena::bot_input(1, e, p.session.current_tick() + 1, 1, in);
            const SessionStats before = p.session.stats();
            const double t0 = thread_cpu_ms();
            (void)p.session.advance_frame(in);
            const double ms = thread_cpu_ms() - t0;
            if (e == 0 && f >= 60) {
              times.push_back(ms);
              rollbacks += p.session.stats().rollbacks - before.rollbacks;
              resim += p.session.stats().resimulated_ticks - before.resimulated_ticks;
              ++measured;
            }
          }
        }
        if (peers[0].session.state() != SessionState::running) return fail("session-bench", peers[0].session.stop_info().message);
        std::sort(times.begin(), times.end());
        medians.push_back(times[times.size() / 2]);
        worst = std::max(worst, times.back());
      }
      std::sort(medians.begin(), medians.end());
      const double median = medians[medians.size() / 2];
      const double resim_per_frame = measured == 0 ? 0 : static_cast<double>(resim) / static_cast<double>(measured);
      if (json) {
        rows.push_back(Json{{"bodies", bodies}, {"depth", depth}, {"ms_per_frame_median", median}, {"ms_per_frame_max", worst},
                            {"rollbacks", rollbacks}, {"resimulated_per_frame", resim_per_frame}});
      } else {
        std::printf("%7u %6u %12.3f %12.3f %10" PRIu64 " %12.2f\n", bodies, depth, median, worst, rollbacks, resim_per_frame);
      }
    }
  }
  if (json) std::printf("%s\n", rows.dump(2).c_str());
  return 0;
}

}  // namespace

void register_session_commands(CLI::App& app, const GlobalOptions& options, std::vector<Command>* commands) {
  auto* session = app.add_subcommand("session", "Play one peer of a networked arena game over UDP (one process per player)");
  session->alias("peer");  // `tandem peer`: the same command under the name the netplay docs use
  auto sa = std::make_shared<PlayArgs>();
  session->add_option("--endpoint", sa->endpoint, "this peer's index in --peers (0…)")->required();
  session->add_option("--peers", sa->peers, "every peer's HOST:PORT, in endpoint order (2…8)")->required()->delimiter(',');
  add_common(session, sa.get());
  session->footer(
      "Every peer gets the same --peers list and options; endpoint i binds the i-th address.\n"
      "`tandem peer` is the same command.\n"
      "Example (two terminals):\n"
      "  tandem session --endpoint 0 --peers 127.0.0.1:7000,127.0.0.1:7001 --latency 40 --jitter 10\n"
      "  tandem session --endpoint 1 --peers 127.0.0.1:7000,127.0.0.1:7001 --latency 40 --jitter 10");
  commands->push_back({session, [sa, &options] { return run_session(*sa, options); }});

  auto* netplay = app.add_subcommand("netplay", "Play N local peers of the arena game over loopback UDP and compare them");
  auto na = std::make_shared<PlayArgs>();
  netplay->add_option("--players", na->players, "peers, one thread each (2…8, default 2)")->check(CLI::Range(2, 8));
  add_common(netplay, na.get());
  netplay->footer(
      "Example:\n"
      "  tandem netplay --players 4 --mode rollback --loss 10 --latency 60 --jitter 20\n"
      "  tandem netplay --players 2 --inject-desync 300 --artifacts /tmp\n"
      "  tandem netplay --players 3 --scene scenes/arena.json");
  commands->push_back({netplay, [na, &options] { return run_netplay(*na, options); }});

  auto* bench = app.add_subcommand("session-bench", "Rollback cost per frame of a 2-player session (in process, no sockets)");
  auto ba = std::make_shared<BenchArgs>();
  bench->add_option("--bodies", ba->bodies, "body counts (default 100,1000)")->delimiter(',');
  bench->add_option("--depths", ba->depths, "rollback depths in ticks (default 2,4,8)")->delimiter(',');
  bench->add_option("--frames", ba->frames, "timed frames per run (default 120)")->check(CLI::Range(10, 100000));
  bench->add_option("--repeats", ba->repeats, "runs per row; the median of the runs' medians is shown (default 3)")
      ->check(CLI::Range(1, 100));
  add_output_flags(bench, &ba->json, &ba->quiet, "(no effect)");
  commands->push_back({bench, [ba, &options] { return run_session_bench(*ba, options); }});
}

}  // namespace tandem::cli

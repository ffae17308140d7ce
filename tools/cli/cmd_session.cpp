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

#include <cinttypes>
#include <cstdio>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "cli.h"
#include "cli_util.h"
#include "replay/replay_file.h"
#include "replay/session.h"
#include "replay/verify.h"
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
  uint64_t ticks = 600;
  uint32_t delay = 2, window = 8;
  double loss = 0;  // percent (tools only: turned into per-mille)
  uint32_t latency = 0, jitter = 0;
  uint64_t seed = 1;
  uint64_t inject_desync = 0;
  uint32_t frame_us = 16667;
  uint32_t crates = 40;
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
      const uint64_t ticks = r.confirmed_tick == 0 ? 1 : r.confirmed_tick;
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
      const uint64_t ticks = r.confirmed_tick == 0 ? 1 : r.confirmed_tick;
      std::printf("%-8zu %-9s %7" PRIu64 " %9" PRIu64 " %6" PRIu64 " %7" PRIu64 " %7" PRIu64 " %11" PRIu64 "  %s\n",
                  a.peers.empty() ? e : size_t{a.endpoint}, session_state_name(r.stop.state), r.confirmed_tick,
                  r.stats.rollbacks, r.stats.max_rollback_depth, r.stats.stalls, r.transport.bytes_sent / ticks,
                  r.stats.packets_rejected, hex(r.final_hash).c_str());
    }
    for (size_t e = 0; e < results.size(); ++e) {
      const net::PeerResult& r = results[e];
      if (r.stop.state != SessionState::running) std::printf("endpoint %zu: %s\n", a.peers.empty() ? e : size_t{a.endpoint}, r.stop.message.c_str());
      for (const std::string& f : r.artifacts) std::printf("wrote %s\n", f.c_str());
    }
    if (diffed) std::printf("first difference at tick %" PRIu64 ": %s\n", results[0].stop.tick, diff.located ? diff.difference.describe().c_str() : "not located");
    if (results.size() > 1) std::printf("%s\n", in_sync ? "in sync: every peer ended with the same hash" : "NOT in sync");
  }
  return in_sync ? 0 : 1;
}

int check_common(const char* command, const PlayArgs& a) {
  if (a.mode != "rollback" && a.mode != "lockstep") return fail(command, "--mode must be rollback or lockstep, got " + a.mode);
  if (a.loss < 0 || a.loss > 100) return fail(command, "--loss must be 0…100 (percent)");
  return -1;
}

int run_session(const PlayArgs& a, const GlobalOptions& g) {
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
  o.progress = [&bar](uint64_t done, uint64_t total) { bar.update(done, total); };
  net::run_peer(transport, o, &results[0]);
  bar.finish();
  return report("session", a, results, json);
}

int run_netplay(const PlayArgs& a, const GlobalOptions& g) {
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
  c->add_option("--ticks", a->ticks, "ticks to play (default 600 = 10 s at 60 Hz)")->check(CLI::Range(uint64_t{1}, uint64_t{1} << 31));
  c->add_option("--delay", a->delay, "input delay K in ticks (default 2)")->check(CLI::Range(0, 30));
  c->add_option("--window", a->window, "rollback: prediction window in ticks (default 8)")->check(CLI::Range(1, 30));
  c->add_option("--loss", a->loss, "simulated loss of input packets, percent (default 0)");
  c->add_option("--latency", a->latency, "simulated one-way latency, ms (default 0)")->check(CLI::Range(0, 2000));
  c->add_option("--jitter", a->jitter, "plus uniform 0…MS of jitter (default 0; reorders packets)")->check(CLI::Range(0, 2000));
  c->add_option("--seed", a->seed, "bots, network simulator and session id (default 1; every peer must agree)");
  c->add_option("--inject-desync", a->inject_desync, "nudge player 0's disc by one raw unit on endpoint 1 after this tick")
      ->check(CLI::NonNegativeNumber);
  c->add_option("--frame-us", a->frame_us, "frame length in microseconds (default 16667: 60 Hz)")->check(CLI::Range(1000, 1000000));
  c->add_option("--crates", a->crates, "crates in the arena (default 40)")->check(CLI::Range(0, 400));
  c->add_option("--artifacts", a->artifacts_dir, "where a desync writes peerN.replay and peerN.state (default .)");
  c->add_option("--connect-timeout", a->connect_timeout_ms, "ms to wait for every peer (default 10000)");
  c->add_option("--timeout", a->timeout_s, "give up after this many seconds (default 120)");
  add_output_flags(c, &a->json, &a->quiet, "no progress bar");
}

}  // namespace

void register_session_commands(CLI::App& app, const GlobalOptions& options, std::vector<Command>* commands) {
  auto* session = app.add_subcommand("session", "Play one peer of a networked arena game over UDP (one process per player)");
  auto sa = std::make_shared<PlayArgs>();
  session->add_option("--endpoint", sa->endpoint, "this peer's index in --peers (0…)")->required();
  session->add_option("--peers", sa->peers, "every peer's HOST:PORT, in endpoint order (2…8)")->required()->delimiter(',');
  add_common(session, sa.get());
  session->footer(
      "Every peer gets the same --peers list and options; endpoint i binds the i-th address.\n"
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
      "  tandem netplay --players 2 --inject-desync 300 --artifacts /tmp");
  commands->push_back({netplay, [na, &options] { return run_netplay(*na, options); }});
}

}  // namespace tandem::cli

// Lockstep and rollback sessions over a simulated lossy network
// (session_harness.h): every confirmed tick's hash equals the single-machine
// run of the same inputs on every peer; rollbacks are bounded; the session
// stalls at the prediction window; time sync slows the peer that runs ahead;
// a one-raw-unit desync is caught at its tick and located; peers that leave
// are reported; recorded replays verify.
#include <catch2/catch.hpp>

#include <string>

#include "replay/replay_file.h"
#include "replay/session.h"
#include "replay/verify.h"
#include "session_harness.h"

using namespace tandem;
using namespace tandem::session_test;

namespace {

RigOptions lossy(uint32_t players, SessionMode mode, uint64_t seed) {
  RigOptions o;
  o.config.mode = mode;
  o.config.player_count = players;
  o.config.input_bytes = arena::k_input_bytes;
  o.config.input_delay = 2;
  o.config.prediction_window = 8;
  o.config.session_id = 0x5E55;
  o.config.record_replay = true;
  o.config.keyframe_interval = 100;
  o.net.seed = seed;
  o.net.loss_per_mille = 100;
  o.net.duplicate_per_mille = 20;
  o.net.latency_frames = 3;
  o.net.jitter_frames = 2;
  return o;
}

void check_against_reference(Rig& rig, const std::vector<uint64_t>& ref) {
  for (size_t e = 0; e < rig.peers.size(); ++e) {
    const Peer& p = *rig.peers[e];
    INFO("peer " << e << ": " << p.session.stop_info().message << " last rejection: " << p.session.stats().last_rejection);
    REQUIRE(p.session.state() == SessionState::running);
    REQUIRE(static_cast<int64_t>(p.hashes.size()) >= rig.options.ticks);
    for (size_t t = 1; t <= static_cast<size_t>(rig.options.ticks); ++t) {
      INFO("tick " << t);
      REQUIRE(p.hashes[t - 1] == ref[t - 1]);
    }
  }
}

void check_replay_verifies(Session& s, int64_t min_ticks) {
  const std::vector<uint8_t> bytes = s.replay_bytes();
  Replay replay;
  ReplayReadInfo info;
  const Status st = read_replay(bytes, &replay, &info);
  INFO(st.message);
  REQUIRE(st.ok());
  REQUIRE(replay.tick_count() >= min_ticks);
  const VerifyReport rep = verify_replay(replay);
  INFO(format_verify_report(rep));
  REQUIRE(rep.ok());
  REQUIRE(static_cast<int64_t>(rep.hashes_checked) == replay.tick_count());
}

}  // namespace

TEST_CASE("session: 2, 4 and 8 players in both modes match the single-machine run every tick", "[replay][session]") {
  for (uint32_t players : {2u, 4u, 8u}) {
    for (SessionMode mode : {SessionMode::lockstep, SessionMode::rollback}) {
      INFO(players << " players, " << (mode == SessionMode::rollback ? "rollback" : "lockstep"));
      RigOptions o = lossy(players, mode, 11 + players);
      o.ticks = players == 8 ? 150 : 240;
      o.crates = players == 8 ? 4 : 12;
      Rig rig(o);
      rig.run();
      check_against_reference(rig, reference_hashes(o));
      const SessionStats& st = rig.peers[0]->session.stats();
      if (mode == SessionMode::rollback) {
        CHECK(st.rollbacks > 0);
        CHECK(st.max_rollback_depth <= o.config.prediction_window);
        CHECK(st.resimulated_ticks <= st.rollbacks * o.config.prediction_window);
      } else {
        CHECK(st.rollbacks == 0);
        CHECK(st.resimulated_ticks == 0);
      }
      CHECK(st.packets_rejected == 0);
      check_replay_verifies(rig.peers[0]->session, o.ticks);
    }
  }
}

TEST_CASE("session: rollback with every prediction wrong equals lockstep", "[replay][session]") {
  RigOptions o = lossy(2, SessionMode::rollback, 5);
  o.change_every = 1;  // every tick a new input: every prediction of a late input is wrong
  o.ticks = 300;
  Rig rollback(o);
  rollback.run();
  RigOptions l = o;
  l.config.mode = SessionMode::lockstep;
  Rig lockstep(l);
  lockstep.run();
  const std::vector<uint64_t> ref = reference_hashes(o);
  check_against_reference(rollback, ref);
  check_against_reference(lockstep, ref);
  const SessionStats& st = rollback.peers[0]->session.stats();
  CHECK(st.rollbacks > 20);
  CHECK(st.max_rollback_depth >= 3);  // latency 3…5 frames
  CHECK(st.max_rollback_depth <= o.config.prediction_window);
  CHECK(st.ticks_simulated == static_cast<uint64_t>(rollback.peers[0]->session.current_tick()) + st.resimulated_ticks);
}

TEST_CASE("session: spectators follow the confirmed inputs", "[replay][session]") {
  RigOptions o = lossy(2, SessionMode::rollback, 9);
  o.config.spectator_count = 2;
  o.ticks = 200;
  Rig rig(o);
  rig.run();
  check_against_reference(rig, reference_hashes(o));
  for (size_t e = 2; e < 4; ++e) {
    CHECK(rig.peers[e]->session.is_spectator());
    CHECK(rig.peers[e]->session.stats().rollbacks == 0);
    CHECK(rig.peers[e]->session.stats().hashes_compared > 0);
  }
}

TEST_CASE("session: a spectator cut off for 8 s (480 ticks, past the 256-tick ring) is resent every input and catches up",
          "[replay][session]") {
  RigOptions o = lossy(2, SessionMode::rollback, 21);
  o.config.spectator_count = 1;
  o.config.disconnect_timeout_frames = 0;  // the spectator hears nothing while cut off
  o.ticks = 900;
  o.frame_limit = 4000;
  o.cut_off_peer = 2;
  o.cut_off_from = 100;
  o.cut_off_until = 580;
  Rig rig(o);
  rig.run();
  check_against_reference(rig, reference_hashes(o));
  const Session& spectator = rig.peers[2]->session;
  INFO(spectator.stats().last_rejection);
  CHECK(spectator.stats().packets_rejected == 0);
  for (size_t e = 0; e < 2; ++e) {
    const Session& player = rig.peers[e]->session;
    CHECK(player.stats().spectators_dropped == 0);
    // It caught up (4 ticks a frame while behind): within the latency of the players.
    CHECK(player.current_tick() < spectator.current_tick() + 30);
  }
  // With an input history smaller than the gap the spectator is dropped, not fed
  // stale inputs: the players go on, the spectator stays behind.
  RigOptions small = o;
  small.config.input_history_ticks = 256;
  small.ticks = 700;
  Rig cut(small);
  cut.run();
  for (size_t e = 0; e < 2; ++e) {
    const Session& player = cut.peers[e]->session;
    INFO("player " << e << ": " << player.stats().last_rejection);
    CHECK(player.state() == SessionState::running);
    CHECK(player.stats().spectators_dropped == 1);
    CHECK(player.stats().last_rejection.find("older than the 256 ticks kept (input_history_ticks)") != std::string::npos);
  }
  CHECK(cut.peers[2]->session.stats().packets_rejected == 0);
  CHECK(cut.peers[2]->session.confirmed_tick() < 200);
}

TEST_CASE("session: rollback stalls at the prediction window instead of running on", "[replay][session]") {
  RigOptions o = lossy(2, SessionMode::rollback, 3);
  o.net.loss_per_mille = 0;
  o.net.duplicate_per_mille = 0;
  o.net.jitter_frames = 0;
  o.config.disconnect_timeout_frames = 0;
  o.time_sync = false;
  o.ticks = 60;
  Rig rig(o);
  rig.run();
  REQUIRE(rig.peers[0]->session.confirmed_tick() >= 60);
  // Player 1 goes quiet: player 0 predicts exactly prediction_window ticks past
  // the last tick whose inputs it has, then stalls.
  rig.peers[1]->silent = true;
  const uint64_t stalls_before = rig.peers[0]->session.stats().stalls;
  for (int i = 0; i < 40; ++i) {
    ++rig.frame;
    rig.frame_of(0);
  }
  Session& s = rig.peers[0]->session;
  int64_t known = s.confirmed_tick();
  CHECK(s.current_tick() == known + o.config.prediction_window);
  CHECK(s.stats().stalls > stalls_before + 20);
  // Player 1 comes back: both continue and still match the reference.
  rig.peers[1]->silent = false;
  rig.options.ticks = 200;
  rig.run();
  check_against_reference(rig, reference_hashes(rig.options));
}

TEST_CASE("session: lockstep never runs ahead of the inputs", "[replay][session]") {
  RigOptions o = lossy(2, SessionMode::lockstep, 4);
  o.ticks = 30;
  o.config.disconnect_timeout_frames = 0;
  Rig rig(o);
  rig.run();
  rig.peers[1]->silent = true;
  for (int i = 0; i < 30; ++i) {
    ++rig.frame;
    rig.frame_of(0);
  }
  Session& s = rig.peers[0]->session;
  CHECK(s.current_tick() == s.confirmed_tick());
  CHECK(s.current_tick() <= 30 + o.config.input_delay + 1 + o.net.latency_frames + o.net.jitter_frames + 2);
}

TEST_CASE("session: time sync slows the peer that runs ahead", "[replay][session]") {
  auto run = [](bool sync) {
    RigOptions o = lossy(2, SessionMode::rollback, 21);
    o.net.loss_per_mille = 0;
    o.fast_peer_every = 5;  // peer 0's clock runs 20 % fast
    o.time_sync = sync;
    o.ticks = 600;
    Rig rig(o);
    rig.run();
    check_against_reference(rig, reference_hashes(o));
    return std::tuple<uint64_t, uint64_t, uint64_t, uint64_t>{rig.peers[0]->session.stats().stalls,
                                                              rig.peers[0]->session.stats().rollbacks, rig.max_tick_gap, rig.idle_frames};
  };
  const auto [stalls_off, rollbacks_off, gap_off, idle_off] = run(false);
  const auto [stalls_on, rollbacks_on, gap_on, idle_on] = run(true);
  INFO("gap/idle " << gap_off << "/" << idle_off << " vs " << gap_on << "/" << idle_on);
  INFO("stalls without sync " << stalls_off << ", with " << stalls_on << "; rollbacks " << rollbacks_off << " / " << rollbacks_on);
  // Without sync the fast peer keeps hitting the prediction window; with it
  // the peer waits early instead, so it stalls far less.
  CHECK(stalls_off > 50);
  CHECK(stalls_on * 4 < stalls_off);
  CHECK(gap_on < gap_off);
  CHECK(idle_on > 60);  // about one frame in five waited
}

TEST_CASE("session: a one-raw-unit desync stops every peer at its tick and is located", "[replay][session]") {
  for (SessionMode mode : {SessionMode::lockstep, SessionMode::rollback}) {
    RigOptions o = lossy(3, mode, 31);
    o.ticks = 400;
    o.perturb_tick = 150;
    o.perturb_peer = 1;
    Rig rig(o);
    rig.run();
    for (size_t e = 0; e < rig.peers.size(); ++e) {
      const Session& s = rig.peers[e]->session;
      INFO("peer " << e << ": " << s.stop_info().message);
      REQUIRE(s.state() == SessionState::desynced);
      CHECK(s.stop_info().tick == 150);
    }
    std::vector<uint8_t> img0, img1;
    REQUIRE(rig.peers[0]->session.state_image(150, &img0).ok());
    REQUIRE(rig.peers[1]->session.state_image(150, &img1).ok());
    const DiffReport d = diff_snapshots(img0, img1);
    INFO(format_diff_report(d));
    REQUIRE(d.differs);
    REQUIRE(d.located);
    CHECK(d.difference.kind == "body");
    CHECK(d.difference.index == static_cast<int64_t>(rig.peers[0]->game.players[0].index));
    CHECK(d.difference.field == "position.x");
    CHECK(d.difference.value_b - d.difference.value_a == 1);

    // The replays: each verifies its own recorded run up to the desync (the
    // perturbed one fails at tick 150: the nudge is not an input); their
    // hash chains part at tick 150.
    Replay r0, r1;
    REQUIRE(read_replay(rig.peers[0]->session.replay_bytes(), &r0).ok());
    REQUIRE(read_replay(rig.peers[1]->session.replay_bytes(), &r1).ok());
    CHECK(verify_replay(r0).ok());
    const VerifyReport v1 = verify_replay(r1);
    CHECK(v1.mismatch);
    CHECK(v1.mismatch_tick == 150);
    const DiffReport dr = diff_replays(r0, r1);
    CHECK(dr.differs);
    CHECK(dr.tick == 150);
    CHECK_FALSE(dr.inputs_differ);

    // Per-body hashes on request name the same body.
    Session& s0 = rig.peers[0]->session;
    REQUIRE(s0.request_body_hashes(1, 150, 0, 512).ok());
    for (int i = 0; i < 20 && rig.peers[0]->session.remote_body_hashes().hashes.empty(); ++i) {
      ++rig.frame;
      rig.net.deliver(1, rig.frame, [&](uint32_t from, std::span<const uint8_t> b) { rig.peers[1]->session.receive(from, b); });
      rig.net.deliver(0, rig.frame, [&](uint32_t from, std::span<const uint8_t> b) { rig.peers[0]->session.receive(from, b); });
      if (rig.peers[0]->session.remote_body_hashes().hashes.empty() && i % 5 == 4) REQUIRE(s0.request_body_hashes(1, 150, 0, 512).ok());
    }
    const Session::BodyHashes& remote = s0.remote_body_hashes();
    REQUIRE_FALSE(remote.hashes.empty());
    CHECK(remote.tick == 150);
    // Ticks are int64_t: negative or past the packet's u32 field is refused by name.
    CHECK(s0.request_body_hashes(1, -1, 0, 1).message ==
          "Session::request_body_hashes: tick -1 outside 0…4294967295");
    CHECK(s0.request_body_hashes(1, int64_t{1} << 32, 0, 1).message.find("tick 4294967296 outside") != std::string::npos);
    CHECK(s0.request_body_hashes(0, 150, 0, 1).message.find("endpoint 0 is not a remote endpoint") != std::string::npos);
    std::vector<uint8_t> image;
    CHECK(s0.state_image(-3, &image).message == "tick -3 is negative");
    CHECK(s0.confirmed_hash(-1) == 0);
    std::vector<uint64_t> local;
    REQUIRE(s0.local_body_hashes(150, &local).ok());
    REQUIRE(local.size() == remote.hashes.size());
    size_t first = local.size();
    for (size_t i = 0; i < local.size(); ++i) {
      if (local[i] != remote.hashes[i]) {
        first = i;
        break;
      }
    }
    CHECK(first == rig.peers[0]->game.players[0].index);
  }
}

TEST_CASE("session: a player that goes silent is reported as left within the timeout", "[replay][session]") {
  RigOptions o = lossy(3, SessionMode::rollback, 41);
  o.config.disconnect_timeout_frames = 60;
  o.ticks = 1000;
  o.silence_peer_at = 200;
  o.perturb_peer = 2;
  Rig rig(o);
  rig.run();
  for (size_t e = 0; e < 2; ++e) {
    const Session& s = rig.peers[e]->session;
    INFO(s.stop_info().message);
    REQUIRE(s.state() == SessionState::peer_left);
    CHECK(s.stop_info().endpoint == 2);
    CHECK(s.stop_info().message.find("player 2") != std::string::npos);
    CHECK(s.stats().frames <= 200 + 60 + o.net.latency_frames + o.net.jitter_frames + 1);
    CHECK(s.stats().frames >= 200 + 60 - o.net.latency_frames - o.net.jitter_frames - 40);
  }
  rig.peers[0]->session.peer_disconnected(1);  // after the stop: no change
  CHECK(rig.peers[0]->session.stop_info().endpoint == 2);
}

TEST_CASE("session: refused packets are counted, never applied", "[replay][session]") {
  RigOptions o = lossy(2, SessionMode::rollback, 51);
  o.net.loss_per_mille = 0;
  o.ticks = 20;
  Rig rig(o);
  rig.run();
  Session& s = rig.peers[0]->session;
  const uint64_t before = s.stats().packets_rejected;
  // A packet from player 1 claiming to be player 0's... and one for another session.
  SessionPacket p;
  p.type = SessionPacketType::input;
  p.session_id = o.config.session_id;
  p.sender = 0;
  p.sequence = 1000;
  std::vector<uint8_t> bytes;
  REQUIRE(encode_session_packet(p, &bytes).ok());
  s.receive(1, bytes);
  CHECK(s.stats().last_rejection.find("claims endpoint 0") != std::string::npos);
  p.sender = 1;
  p.session_id = 99;
  bytes.clear();
  REQUIRE(encode_session_packet(p, &bytes).ok());
  s.receive(1, bytes);
  CHECK(s.stats().last_rejection.find("session id 99") != std::string::npos);
  // An input contradicting one already received for the same tick.
  p.session_id = o.config.session_id;
  p.first_input_tick = 5;
  p.input_count = 1;
  p.input_bytes = arena::k_input_bytes;
  uint8_t real[arena::k_input_bytes];
  arena::bot_input(o.bot_seed, 1, 5, o.change_every, real);
  for (uint32_t i = 0; i < arena::k_input_bytes; ++i) p.inputs[i] = static_cast<uint8_t>(real[i] ^ 0x55);
  bytes.clear();
  REQUIRE(encode_session_packet(p, &bytes).ok());
  s.receive(1, bytes);
  CHECK(s.stats().last_rejection.find("different input for tick 5") != std::string::npos);
  // Truncated garbage.
  bytes.resize(7);
  s.receive(1, bytes);
  CHECK(s.stats().last_rejection.find("offset") != std::string::npos);
  s.receive(7, bytes);
  CHECK(s.stats().packets_rejected == before + 5);
  // The session goes on unharmed.
  rig.options.ticks = 120;
  rig.run();
  check_against_reference(rig, reference_hashes(rig.options));
}

TEST_CASE("session: config errors name the field and range", "[replay][session]") {
  Result<WorldId> w = create_world(default_world_def());
  REQUIRE(w.ok());
  SessionCallbacks cb;
  cb.send = [](uint32_t, std::span<const uint8_t>) {};
  cb.make_commands = [](int64_t, const SessionTickInputs&, WorldId, std::vector<Command>*) { return Status{}; };
  auto message = [&](auto edit) {
    SessionConfig c;
    edit(c);
    Session s;
    return s.start(w.value, c, cb).message;
  };
  CHECK(message([](SessionConfig& c) { c.player_count = 9; }) == "session config player_count: expected 2…8, got 9");
  CHECK(message([](SessionConfig& c) { c.input_bytes = 65; }) == "session config input_bytes: expected 1…64, got 65");
  CHECK(message([](SessionConfig& c) { c.local_endpoint = 2; }) == "session config local_endpoint: expected 0…1, got 2");
  CHECK(message([](SessionConfig& c) { c.prediction_window = 31; }) ==
        "session config prediction_window: expected 1…30, got 31");
  CHECK(message([](SessionConfig& c) { c.history_ticks = 9; }) == "session config history_ticks: expected 10…256, got 9");
  SessionConfig ok;
  Session s;
  REQUIRE(s.start(w.value, ok, cb).ok());
  // A local input of the wrong size stops the session with a message.
  const uint8_t three[3] = {1, 2, 3};
  CHECK(s.advance_frame(three) == AdvanceResult::stopped);
  CHECK(s.stop_info().message == "local input has 3 bytes, expected 4");
  (void)destroy_world(w.value);
}

TEST_CASE("session: a backlog longer than one packet is resent oldest first", "[replay][session]") {
  // Lockstep with a long input delay: while player 1's packets are lost,
  // player 1 runs up to 2K + 2 ticks of inputs ahead of what player 0 holds,
  // more than one packet carries (32); player 0 must still catch up.
  RigOptions o = lossy(2, SessionMode::lockstep, 61);
  o.net.loss_per_mille = 0;
  o.net.duplicate_per_mille = 0;
  o.config.input_delay = 20;
  o.config.disconnect_timeout_frames = 0;
  o.time_sync = false;
  o.ticks = 40;
  Rig rig(o);
  rig.run();
  rig.net.block_from(1);
  for (int i = 0; i < 80; ++i) {
    ++rig.frame;
    rig.frame_of(0);
    rig.frame_of(1);
  }
  // Player 1's inputs reach tick current + K + 1; player 0 holds them only through its own tick.
  CHECK(rig.peers[1]->session.current_tick() + o.config.input_delay + 1 > rig.peers[0]->session.current_tick() + 32);
  rig.net.block_from(UINT32_MAX);
  rig.options.ticks = 250;
  rig.run();
  check_against_reference(rig, reference_hashes(rig.options));
}

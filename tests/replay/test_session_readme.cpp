// The README's session example ("Lockstep and rollback sessions"): two peers
// wired through in-memory inboxes, compiled and run so the README cannot
// drift from the API. Keep the block between the markers identical to the
// README's example (this test checks it).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <functional>
#include <span>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "physics/tandem.h"
#include "replay/replay_file.h"
#include "replay/session.h"
#include "replay/verify.h"

using namespace tandem;
using namespace tandem::literals;

namespace readme {
// --- README session example begins ---
struct Peer {
  WorldId world;                 // built the same way on every machine
  std::vector<BodyRef> discs;    // so these refs are the same everywhere
  Session session;
  std::vector<std::pair<uint32_t, std::vector<uint8_t>>> inbox;  // filled by your transport
};

Status start_peer(Peer& peer, uint32_t my_endpoint, std::function<void(uint32_t, std::span<const uint8_t>)> send) {
  SessionConfig config;
  config.mode = SessionMode::rollback;   // or SessionMode::lockstep
  config.player_count = 2;               // 2…8, plus up to 8 spectators
  config.local_endpoint = my_endpoint;
  config.input_bytes = 1;                // one opaque byte per player per tick
  config.input_delay = 2;                // ticks
  config.prediction_window = 8;          // rollback: stall rather than predict further
  config.record_replay = true;           // `tandem verify` accepts session.replay_bytes()
  SessionCallbacks callbacks;
  callbacks.send = std::move(send);      // unreliable datagrams are enough
  callbacks.make_commands = [&peer](int64_t, const SessionTickInputs& in, WorldId, std::vector<Command>* out) {
    for (uint32_t p = 0; p < in.player_count; ++p) {  // deterministic: runs again after a rollback
      const Q32 push = Q32::from_int(static_cast<int8_t>(in.input(p)[0]));
      out->push_back(make_apply_force_to_center(peer.discs[p], Vec2{push, 0_q32}));
    }
    return Status{};
  };
  return peer.session.start(peer.world, config, std::move(callbacks));
}

void frame(Peer& peer, uint8_t my_input) {  // once per frame, 60 Hz
  for (auto& [from, bytes] : peer.inbox) peer.session.receive(from, bytes);
  peer.inbox.clear();
  if (peer.session.frames_ahead() > 0) {
    peer.session.idle_frame();                   // time sync: let the others catch up
  } else {
    peer.session.advance_frame({&my_input, 1});  // steps, or stalls while inputs are missing
  }
  if (peer.session.state() == SessionState::desynced) {
    Status s = peer.session.write_artifacts("desync");  // desync.replay + desync.state for `tandem diff`
    if (!s.ok()) std::fprintf(stderr, "%s\n", s.message.c_str());
  }
}
// --- README session example ends ---
}  // namespace readme

TEST_CASE("the README session example runs as written", "[replay][session][readme]") {
  readme::Peer peers[2];
  for (readme::Peer& peer : peers) {
    peer.world = create_world(default_world_def()).value;
    for (int i = 0; i < 2; ++i) {
      BodyDef def = default_body_def();
      def.type = BodyType::dynamic_body;
      def.gravity_scale = 0_q32;
      def.position = Vec2{Q32::from_int(3 * i), 0_q32};
      const BodyId b = create_body(peer.world, def).value;
      REQUIRE(create_circle_shape(b, default_shape_def(), Circle{Vec2{}, 0.5_q32}).ok());
      peer.discs.push_back(body_ref(b));
    }
  }
  for (uint32_t e = 0; e < 2; ++e) {
    readme::Peer& other = peers[1 - e];
    REQUIRE(readme::start_peer(peers[e], e, [&other, e](uint32_t, std::span<const uint8_t> packet) {
              other.inbox.emplace_back(e, std::vector<uint8_t>(packet.begin(), packet.end()));
            }).ok());
  }
  for (int f = 0; f < 200; ++f) {
    for (uint32_t e = 0; e < 2; ++e) {
      readme::frame(peers[e], static_cast<uint8_t>((f / 7 + static_cast<int>(e)) % 5 - 2));
    }
  }
  REQUIRE(peers[0].session.state() == SessionState::running);
  REQUIRE(peers[1].session.state() == SessionState::running);
  const int64_t t = std::min(peers[0].session.confirmed_tick(), peers[1].session.confirmed_tick());
  REQUIRE(t >= 150);
  CHECK(peers[0].session.confirmed_hash(t) == peers[1].session.confirmed_hash(t));
  Replay replay;
  REQUIRE(read_replay(peers[0].session.replay_bytes(), &replay).ok());
  CHECK(verify_replay(replay).ok());
  for (readme::Peer& peer : peers) (void)destroy_world(peer.world);

  // The README holds the same block.
  std::ifstream readme_file(TANDEM_SESSION_SOURCE_DIR "/README.md");
  REQUIRE(readme_file.good());
  std::stringstream text;
  text << readme_file.rdbuf();
  std::ifstream self(TANDEM_SESSION_SOURCE_DIR "/tests/replay/test_session_readme.cpp");
  std::stringstream me;
  me << self.rdbuf();
  const std::string src = me.str();
  const std::string begin = "// --- README session example begins ---\n", end = "// --- README session example ends ---";
  const size_t b = src.find(begin), e = src.find(end);
  REQUIRE(b != std::string::npos);
  REQUIRE(e != std::string::npos);
  const std::string block_text = src.substr(b + begin.size(), e - b - begin.size());
  CHECK(text.str().find(block_text) != std::string::npos);
}

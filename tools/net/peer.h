// peer.h — one session peer over UDP: the arena game (arena_game.h) in its
// own world, a bot on the local player's input, a Session (replay/session.h)
// and an EnetTransport, paced at a fixed frame length with time sync. Used
// by `tandem session`, `tandem netplay` and the loopback tests.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "replay/session.h"
#include "tools/net/enet_transport.h"

namespace tandem::net {

/// What a peer plays.
struct PeerOptions {
  SessionConfig config;            ///< local_endpoint names this peer
  int64_t ticks = 600;             ///< play until every peer confirmed this many ticks
  uint32_t frame_us = 16667;       ///< frame length (60 Hz)
  uint64_t bot_seed = 7;
  uint32_t change_every = 6;       ///< bots change input every this many ticks
  uint32_t crates = 40;            ///< arena crates (0…1000), when the arena is built in code
  /// Builds the arena from elsewhere (a scene file: walls, crates) into a new
  /// world; the players' discs are added after its bodies. Unset: built in code.
  std::function<Result<WorldId>()> make_world;
  int64_t inject_desync_tick = 0;  ///< nudge player 0's disc by one raw unit after this tick (0: never)
  uint32_t run_timeout_ms = 60000; ///< give up (status error) after this long
  uint32_t linger_frames = 30;     ///< frames played after the end so the others finish too
  int64_t crash_at_tick = 0;       ///< tests: vanish without a goodbye at this tick (0: never)
  std::string artifacts_prefix;    ///< on a desync: write PREFIX.replay and PREFIX.state (empty: don't)
  std::function<void(int64_t confirmed, int64_t ticks)> progress;  ///< every frame (optional)
};

/// What a peer did.
struct PeerResult {
  Status status;                   ///< not ok: could not run (bad options, timeout)
  SessionStop stop;                ///< state running at the end of a clean game
  SessionStats stats;
  TransportStats transport;
  int64_t confirmed_tick = 0;
  uint64_t final_hash = 0;         ///< confirmed hash of tick `ticks` (0 if not reached)
  std::vector<uint64_t> hashes;    ///< confirmed hash of every tick 1…, in order
  std::vector<std::string> artifacts;  ///< files written
  std::vector<uint8_t> replay;     ///< with config.record_replay: the recorded replay (Session::replay_bytes)
  double seconds = 0;
};

/// Plays one peer on an opened and connected transport (see PeerOptions).
void run_peer(EnetTransport& transport, const PeerOptions& options, PeerResult* result);

}  // namespace tandem::net

// session.h — a lockstep or rollback session between 2…8 players (and up to
// 8 spectators), independent of any transport: the game hands packets to
// receive() and gets outgoing packets through a send callback (format:
// replay/session_packet.h). Nothing here opens a socket or reads a clock;
// time is the number of advance_frame() calls.
//
// TICKS are numbered as in a replay (replay_file.h): tick t applies the
// commands made from tick t's inputs to the state after tick t − 1, then
// steps. Ticks 1…K (K = input delay) use all-zero inputs for every player.
// Tick numbers are int64_t in this API (as everywhere in Tandem); packets
// carry them as u32 (session_packet.h), and a tick outside that range is
// refused by name, never truncated.
//
// INPUTS. Each player supplies `input_bytes` opaque bytes per frame; the
// input given to the advance_frame() that simulates tick t is scheduled for
// tick t + K. A game callback (make_commands) turns one tick's inputs of all
// players (player order) into engine commands (replay/commands.h); it must be
// a deterministic function of the tick, the inputs, the world and the game
// state, because it runs again for the same tick after a rollback.
//
// MODES.
//   lockstep: a tick is simulated only when every player's input for it is in.
//   rollback: a missing remote input is predicted as that player's last known
//     input; when the real one arrives and differs from what was used, the
//     session restores the snapshot before that tick and re-simulates to the
//     present. Prediction is bounded: the session stalls (does not step)
//     rather than run more than prediction_window ticks past the last tick
//     whose inputs are all known.
//   Spectators (local_endpoint ≥ player_count) never predict: they step when
//   all players' inputs for a tick are in (players send them their inputs),
//   up to 4 ticks in one frame while they are behind, so one that was cut off
//   for a while catches up (players keep input_history_ticks of their inputs
//   to resend it).
//
// TIME SYNC (as GGPO's frame advantage): every input packet carries the
// sender's tick and its advantage over the receiver (its tick minus the
// receiver's tick as last heard). frames_ahead() averages, over the last 32
// frames, half the difference between the local advantage and the remote
// one (the latency terms cancel); a positive value says this peer runs ahead
// and should skip that many frames (call advance_frame less often).
//
// DESYNC DETECTION. After every confirmed tick (all inputs real, simulated
// with them) the session hashes the world (world_state_hash, XOR-mixed with
// XXH3 of the game state when save_game is set) and sends the hashes of the
// ticks the receiver has not acknowledged (≤ 32 per packet). When a remote
// hash of a tick differs from the local one the session stops (state
// desynced), sends a desync packet to every endpoint so they stop too, and
// keeps the state image of that tick; write_artifacts() then writes the
// replay and the state image, and `tandem diff` of two peers' state images
// names the body and the field (the replays' hash chains name the tick).
//
// RECORDING. With record_replay set the session records every confirmed
// tick: a user_input command holding all players' inputs (player order,
// input_bytes each), then the engine commands the callback made, and the
// world hash, and the game state after the tick (save_game's bytes, replay
// format 2), also at every keyframe. `tandem verify` re-runs it without the
// game (user_input commands are ignored by apply_command) and checks the game
// states when it knows the game (VerifyOptions::game; the CLI knows the
// bundled arena by the replay's scene bytes, SessionConfig::replay_scene).
// Keyframes every keyframe_interval confirmed ticks.
//
// ALLOCATION. Rings (inputs, hashes, snapshots) are sized at start(); after
// the snapshot buffers have grown to the world's size and the command vector
// to the game's largest tick, the session's own code allocates nothing per
// tick without recording (with recording, each confirmed tick is appended to
// the in-memory replay). Measured with a counting operator new (2 peers,
// arena, 300 frames): applying the engine commands allocated in proportion to
// the ticks simulated, because the body functions built their error text even
// on success; since 2026-11-25 they build it only on a refusal, and
// apply_command of apply_force, apply_linear_impulse and set_linear_velocity
// on a live body allocates nothing (tests/replay/test_command_allocations.cpp).
// Per-tick snapshots are compact rollback images (replay/rollback.h): a
// save into a slot that held the same scene does not allocate either.
//
// ORDER. Everything the simulation sees is ordered by data: inputs by
// (tick, player), commands in the order the callback produced them. Packet
// arrival order only changes when a rollback happens, never its result.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "physics/tandem.h"
#include "replay/commands.h"
#include "replay/replay_file.h"
#include "replay/rollback.h"
#include "replay/session_packet.h"

namespace tandem {

/// How the session advances.
enum class SessionMode : uint8_t { lockstep = 0, rollback = 1 };

/// Most players; most spectators.
inline constexpr uint32_t k_session_max_players = 8;
inline constexpr uint32_t k_session_max_spectators = 8;
/// Largest input delay and prediction window (ticks).
inline constexpr uint32_t k_session_max_input_delay = 30;
inline constexpr uint32_t k_session_max_prediction = 30;
/// Ticks of inputs and hashes kept in the rings.
inline constexpr uint32_t k_session_ring_ticks = 256;

/// Settings of a session; every peer must use the same values except
/// local_endpoint.
struct SessionConfig {
  SessionMode mode = SessionMode::rollback;
  uint32_t player_count = 2;        ///< 2…8
  uint32_t spectator_count = 0;     ///< 0…8; spectator endpoints follow the players
  uint32_t local_endpoint = 0;      ///< this peer: a player 0…P−1 or a spectator P…P+S−1
  uint32_t input_bytes = 4;         ///< bytes of one player's input per tick, 1…64
  uint32_t input_delay = 2;         ///< K, ticks, 0…30
  uint32_t prediction_window = 8;   ///< rollback: most ticks simulated past the last all-known tick, 1…30
  uint64_t session_id = 0;          ///< packets with another id are refused
  Q32 time_step = Q32::from_ratio(1, 60);  ///< seconds per tick (> 0)
  uint32_t history_ticks = 64;      ///< snapshots kept (for rollbacks and desync images), ≥ prediction_window + 2, ≤ 256
  uint32_t disconnect_timeout_frames = 300;  ///< a player silent this many frames has left (0: never)
  uint32_t input_history_ticks = 3600; ///< local inputs kept for resending to an endpoint that fell behind (a
                                       ///< spectator that lost every packet for a while), 256…1 << 20 (60 s at 60 Hz)
  bool record_replay = false;       ///< record confirmed ticks into an in-memory replay
  uint32_t keyframe_interval = 600; ///< replay keyframes every this many ticks (0: only tick 0)
  std::vector<uint8_t> replay_scene; ///< embedded in the replay header as its scene bytes (empty: none), e.g. what game and settings
};

/// One tick's inputs of every player, player order (a view; valid during the call).
struct SessionTickInputs {
  uint32_t player_count = 0;
  uint32_t input_bytes = 0;
  const uint8_t* data = nullptr;  ///< player_count × input_bytes
  /// Player p's input (p < player_count).
  std::span<const uint8_t> input(uint32_t p) const { return {data + size_t{p} * input_bytes, input_bytes}; }
};

/// What the game supplies. send is required; make_commands is required;
/// the others are optional.
struct SessionCallbacks {
  /// Delivers a packet to an endpoint (unreliable is fine; the bytes are only
  /// valid during the call).
  std::function<void(uint32_t endpoint, std::span<const uint8_t> packet)> send;
  /// Appends the engine commands of `tick` made from `inputs` (the vector is
  /// cleared before the call). Must be deterministic. A non-ok status stops
  /// the session (state error).
  std::function<Status(int64_t tick, const SessionTickInputs& inputs, WorldId world, std::vector<Command>* out)>
      make_commands;
  /// Game logic after the step of `tick` (scores, timers). Deterministic.
  std::function<void(int64_t tick, WorldId world)> after_step;
  /// Serialises the game state beyond the world (replace *out).
  std::function<void(std::vector<uint8_t>* out)> save_game;
  /// Restores what save_game wrote.
  std::function<void(std::span<const uint8_t> state)> load_game;
};

/// Why a session is not running.
enum class SessionState : uint8_t { idle = 0, running, desynced, peer_left, error };

/// "idle", "running", "desynced", "peer left", "error".
const char* session_state_name(SessionState state);

/// Why a session stopped (state != running).
struct SessionStop {
  SessionState state = SessionState::idle;
  int64_t tick = 0;           ///< desynced: the first mismatching tick; peer_left: the local tick then
  uint32_t endpoint = 0;      ///< the endpoint whose hash differed / that left / that reported the desync
  uint64_t local_hash = 0;    ///< desynced: this peer's hash of `tick`
  uint64_t remote_hash = 0;   ///< desynced: the remote hash of `tick`
  int64_t last_heard_tick = 0;   ///< peer_left: the endpoint's last reported tick
  std::string message;        ///< one line
};

/// Counters.
struct SessionStats {
  uint64_t frames = 0;              ///< advance_frame calls
  uint64_t stalls = 0;              ///< frames that could not step
  uint64_t rollbacks = 0;           ///< restores
  uint64_t max_rollback_depth = 0;  ///< most ticks re-simulated by one rollback
  uint64_t resimulated_ticks = 0;   ///< ticks stepped again
  uint64_t ticks_simulated = 0;     ///< every step, first and again
  uint64_t packets_sent = 0, bytes_sent = 0;
  uint64_t packets_received = 0, bytes_received = 0;
  uint64_t packets_rejected = 0;    ///< malformed, wrong session, wrong sender, inconsistent
  uint64_t packets_stale = 0;       ///< sequence not newer (duplicates, reordering): inputs still used
  uint64_t commands_refused = 0;    ///< engine commands the world refused (replayed identically)
  uint64_t hashes_compared = 0;     ///< remote confirmed hashes checked
  uint64_t hashes_skipped = 0;      ///< remote hashes never received (the sender's ring had moved on)
  uint64_t spectators_dropped = 0;  ///< spectators no longer sent to: behind by more than input_history_ticks
  std::string last_rejection;       ///< why the last packet was refused
};

/// What one advance_frame() did.
enum class AdvanceResult : uint8_t { stepped = 0, stalled, stopped };

/// The hash a session exchanges for a tick: world_state_hash(world), XOR
/// XXH3-64 of the game state times an odd constant when game_state is not
/// empty (for single-machine reference runs).
uint64_t session_state_hash(WorldId world, std::span<const uint8_t> game_state);

/// A session (see the file comment). Not copyable; one per peer.
class Session {
 public:
  Session() = default;
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  /// Validates the config (the message names the field and its range) and
  /// starts at tick 0 from the world's current state, which must be the same
  /// on every peer (compare start_hash()). The world stays owned by the
  /// caller and must not be changed outside the session afterwards.
  Status start(WorldId world, const SessionConfig& config, SessionCallbacks callbacks);

  /// One frame: schedules `local_input` (input_bytes bytes; ignored for a
  /// spectator or when this tick's input was already given during a stall)
  /// for tick current_tick() + 1 + K, handles rollbacks from inputs received
  /// since the last frame, steps one tick if allowed, confirms ticks, checks
  /// hashes and sends packets. Returns stopped once state() != running.
  AdvanceResult advance_frame(std::span<const uint8_t> local_input);

  /// A frame in which the game waits (time sync) instead of advancing:
  /// handles received inputs (rollbacks, confirmations, hash checks), counts
  /// the frame for disconnect timeouts and sends packets, but schedules no
  /// input and steps no new tick. Returns stalled, or stopped.
  AdvanceResult idle_frame();

  /// Hands a packet received from `from_endpoint` to the session. Refused
  /// packets (malformed, wrong session id, sender other than from_endpoint,
  /// inputs contradicting known ones) are counted and otherwise ignored.
  void receive(uint32_t from_endpoint, std::span<const uint8_t> packet);

  /// The transport lost `endpoint` (a player: the session stops, peer_left;
  /// a spectator: it is no longer sent to).
  void peer_disconnected(uint32_t endpoint);

  /// Time sync: frames this peer should wait to let the others catch up (≤ 0: none).
  int32_t frames_ahead() const;

  /// Ticks simulated (the world is in the state after this tick).
  int64_t current_tick() const { return static_cast<int64_t>(current_); }
  /// Last tick simulated with every player's real input.
  int64_t confirmed_tick() const { return static_cast<int64_t>(confirmed_); }
  /// The hash (world, mixed with the game state) of a confirmed tick still in
  /// the ring; 0 otherwise (a negative tick included).
  uint64_t confirmed_hash(int64_t tick) const;
  /// The lowest tick through which every other endpoint still connected has
  /// sent its confirmed hashes (so they have confirmed at least this far).
  int64_t remote_confirmed_through() const;
  /// world_state_hash of the start state.
  uint64_t start_hash() const { return start_hash_; }
  SessionState state() const { return stop_.state; }
  const SessionStop& stop_info() const { return stop_; }
  const SessionStats& stats() const { return stats_; }
  const SessionConfig& config() const { return config_; }
  bool is_spectator() const { return config_.local_endpoint >= config_.player_count; }

  /// The in-memory replay so far (finished: with an END chunk) — empty
  /// without record_replay.
  std::vector<uint8_t> replay_bytes();
  /// The state image (replay/state.h) of a tick still in the snapshot ring
  /// (within history_ticks of current_tick(), ≤ current_tick()). Made by
  /// restoring the ring's compact image (replay/rollback.h) into a scratch
  /// world: bodies, joints, contact impulses and feature ids are exact; the
  /// manifold geometry of contacts between simulated bodies reads as zero
  /// (the compact image omits it), alike on every peer, so `tandem diff` of
  /// two peers' images names the first state that really differs. Its
  /// world_state_hash is therefore not the tick's exchanged hash. A tick
  /// outside the ring (negative included) is refused, naming it.
  Status state_image(int64_t tick, std::vector<uint8_t>* out) const;
  /// Writes `prefix`.replay (when recording) and `prefix`.state: the image
  /// of the desync tick when desynced, else of the confirmed tick.
  Status write_artifacts(const std::string& prefix);

  /// Asks endpoint `endpoint` for per-body hashes of `tick` (bodies
  /// [first_body, first_body + count), count ≤ 512); the answer appears in
  /// remote_body_hashes(). Refused (nothing sent) before start(), for the
  /// local or an unknown endpoint, and for a tick outside 0…UINT32_MAX (the
  /// packet's encoding); a count above 512 is clamped to 512.
  Status request_body_hashes(uint32_t endpoint, int64_t tick, uint32_t first_body, uint32_t count);
  /// Per-body hashes last received: tick, first body and the hashes.
  struct BodyHashes {
    uint32_t endpoint = 0;
    int64_t tick = 0;
    uint32_t first_body = 0;
    std::vector<uint64_t> hashes;
  };
  const BodyHashes& remote_body_hashes() const { return remote_body_hashes_; }
  /// Per-body hashes of a tick in the snapshot ring (index order; 0 for dead slots).
  Status local_body_hashes(int64_t tick, std::vector<uint64_t>* out) const;

 private:
  struct Slot;
  uint32_t endpoint_count() const { return config_.player_count + config_.spectator_count; }
  size_t ring(uint64_t tick) const { return static_cast<size_t>(tick % k_session_ring_ticks); }
  uint8_t* input_at(uint32_t player, uint64_t tick);
  const uint8_t* input_at(uint32_t player, uint64_t tick) const;
  bool input_known(uint32_t player, uint64_t tick) const;
  void store_input(uint32_t player, uint64_t tick, const uint8_t* bytes);
  uint64_t all_known_through() const;
  Status ring_slot(int64_t tick, size_t* slot) const;  // the snapshot slot holding `tick`, or why none does
  Result<WorldId> ring_world(int64_t tick) const;      // a scratch world restored from that slot (caller destroys it)
  bool simulate(uint64_t tick);
  void rollback();
  void confirm();
  void check_hashes();
  void send_packets();
  bool begin_frame();
  void end_frame();
  void stop(SessionState state, const std::string& message);
  void desync(uint32_t endpoint, uint64_t tick, uint64_t local_hash, uint64_t remote_hash, bool reported);
  void reject(const std::string& why);
  void send_packet(uint32_t endpoint);  // encodes packet_out_ into out_buffer_ and sends it
  void handle_input(uint32_t from, const SessionPacket& p);
  void handle_body_request(uint32_t from, const SessionPacket& p);

  WorldId world_;
  SessionConfig config_;
  SessionCallbacks callbacks_;
  SessionStop stop_;
  SessionStats stats_;
  uint64_t start_hash_ = 0;
  uint64_t current_ = 0;
  uint64_t confirmed_ = 0;
  uint64_t last_local_tick_ = 0;      // last tick with the local input scheduled
  uint64_t pending_rollback_ = 0;     // earliest mispredicted tick (0: none)
  uint64_t desync_image_tick_ = 0;
  std::vector<uint8_t> desync_image_;

  // Per player × ring: inputs (known real ones), the tick each slot holds, and the input used.
  std::vector<uint8_t> inputs_;
  std::vector<uint64_t> input_tick_;
  std::vector<uint8_t> used_;
  std::vector<uint64_t> used_tick_;
  std::vector<uint64_t> contiguous_;  // per player: every input ≤ this is known
  std::vector<uint8_t> local_history_;  // the local player's inputs, input_history_ticks slots (tick % slots)

  // Per ring: local confirmed hash (+ world-only hash for the replay).
  std::vector<uint64_t> hash_;
  std::vector<uint64_t> world_hash_;
  std::vector<uint64_t> hash_tick_;

  // Per endpoint.
  std::vector<uint64_t> remote_hash_;       // endpoint × ring
  std::vector<uint64_t> remote_hash_tick_;  // endpoint × ring
  std::vector<uint64_t> remote_hash_through_;
  std::vector<uint64_t> hash_checked_through_;
  std::vector<uint64_t> input_ack_from_;    // the endpoint holds our inputs ≤ this
  std::vector<uint64_t> hash_ack_from_;
  std::vector<uint64_t> remote_tick_;
  std::vector<int64_t> remote_advantage_;
  std::vector<uint32_t> last_sequence_in_;
  std::vector<uint32_t> sequence_out_;
  std::vector<uint64_t> last_heard_frame_;
  std::vector<uint8_t> gone_;

  // Snapshot ring (history_ticks slots, tick % history_ticks): compact
  // rollback images (replay/rollback.h); the portable image of a slot only
  // for keyframe ticks while recording (the replay's keyframes).
  std::vector<RollbackBuffer> snap_world_;
  std::vector<std::vector<uint8_t>> snap_keyframe_;
  std::vector<std::vector<uint8_t>> snap_game_;
  std::vector<uint64_t> snap_tick_;
  std::vector<std::vector<Command>> snap_commands_;  // recording only

  // Time sync samples.
  std::vector<int64_t> sync_samples_;
  uint64_t sync_count_ = 0;

  std::vector<uint8_t> tick_inputs_;  // scratch: one tick of all players
  std::vector<Command> commands_;     // scratch
  std::vector<uint8_t> out_buffer_;   // scratch: one packet
  SessionPacket packet_in_;
  SessionPacket packet_out_;
  std::vector<uint8_t> game_scratch_;
  BodyHashes remote_body_hashes_;
  std::vector<uint64_t> body_hash_scratch_;
  std::vector<uint8_t> body_hash_bytes_;

  bool recording_ = false;
  ReplayWriter writer_;
  std::vector<uint8_t> start_image_;
  uint32_t desync_notices_left_ = 0;
  uint64_t desync_notice_tick_ = 0;
  uint64_t desync_notice_hash_ = 0;
};

}  // namespace tandem

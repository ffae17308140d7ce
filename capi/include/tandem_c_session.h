/* tandem_c_session.h — a lockstep or rollback session between 2…8 players
 * (replay/session.h), independent of any transport. Part of the C API;
 * include tandem_c.h (the umbrella) or this file alone. The conventions
 * (numbers, handles, errors, buffers) are in tandem_c.h.
 *
 * The game supplies C callbacks with one user context pointer: send (the
 * transport: deliver the packet bytes to an endpoint, unreliable is fine),
 * make_commands (one tick's inputs of every player → engine commands,
 * deterministic), and optionally after_step, save_game and load_game. Packets
 * received from the transport go to tandem_session_receive(). Time is the
 * number of tandem_session_advance_frame() calls; nothing here opens a socket
 * or reads a clock. Callbacks run inside the session's calls on the calling
 * thread; they must not destroy the session. A session is named by a
 * tandem_session_id owned by this library until tandem_session_destroy(); the
 * world stays the caller's and must not be changed outside the session. */
#ifndef TANDEM_C_SESSION_H
#define TANDEM_C_SESSION_H

#include "tandem_c_base.h"
#include "tandem_c_replay.h"

#ifdef __cplusplus
extern "C" {
#endif

/** A session handle (index + 1, generation); all-zero is null. */
typedef struct tandem_session_id { uint32_t index1, generation; } tandem_session_id;

/** Modes (SessionMode). */
#define TANDEM_SESSION_LOCKSTEP 0
#define TANDEM_SESSION_ROLLBACK 1

/** States (SessionState). */
#define TANDEM_SESSION_IDLE 0
#define TANDEM_SESSION_RUNNING 1
#define TANDEM_SESSION_DESYNCED 2
#define TANDEM_SESSION_PEER_LEFT 3
#define TANDEM_SESSION_ERROR 4

/** What one frame did (AdvanceResult). */
#define TANDEM_ADVANCE_STEPPED 0
#define TANDEM_ADVANCE_STALLED 1
#define TANDEM_ADVANCE_STOPPED 2

/** Settings (SessionConfig); every peer uses the same values except
 * local_endpoint. Ranges are checked by tandem_session_create. */
typedef struct tandem_session_config {
  int32_t mode;                       /**< TANDEM_SESSION_LOCKSTEP or _ROLLBACK */
  uint32_t player_count;              /**< 2…8 */
  uint32_t spectator_count;           /**< 0…8 */
  uint32_t local_endpoint;            /**< a player 0…P−1 or a spectator P…P+S−1 */
  uint32_t input_bytes;               /**< bytes of one player's input per tick, 1…64 */
  uint32_t input_delay;               /**< ticks, 0…30 */
  uint32_t prediction_window;         /**< rollback: 1…30 */
  uint64_t session_id;                /**< packets with another id are refused */
  tandem_q32 time_step;               /**< seconds per tick (> 0) */
  uint32_t history_ticks;             /**< snapshots kept, ≥ prediction_window + 2, ≤ 256 */
  uint32_t disconnect_timeout_frames; /**< 0: never */
  bool record_replay;                 /**< keep an in-memory replay of confirmed ticks */
  uint32_t keyframe_interval;         /**< replay keyframes every this many ticks */
} tandem_session_config;

/** Where save_game writes the game state; valid during that callback. */
typedef struct tandem_bytes tandem_bytes;
/** Replaces the bytes of *out with data[0, size). */
TANDEM_C_API tandem_status tandem_bytes_assign(tandem_bytes* out, const uint8_t* data, size_t size);

/** The game's callbacks (SessionCallbacks); send and make_commands are
 * required. `inputs` holds player_count × input_bytes bytes (player order). A
 * make_commands status other than TANDEM_OK stops the session (state error). */
typedef struct tandem_session_callbacks {
  void* context;  /**< passed to every callback */
  void (*send)(void* context, uint32_t endpoint, const uint8_t* packet, size_t size);
  tandem_status (*make_commands)(void* context, int64_t tick, const uint8_t* inputs, uint32_t player_count,
                                 uint32_t input_bytes, tandem_world_id world, tandem_command_list* out);
  void (*after_step)(void* context, int64_t tick, tandem_world_id world);       /**< optional */
  void (*save_game)(void* context, tandem_bytes* out);                            /**< optional */
  void (*load_game)(void* context, const uint8_t* state, size_t size);            /**< optional */
} tandem_session_callbacks;

/** Why a session stopped (SessionStop); the message: tandem_session_stop_message. */
typedef struct tandem_session_stop {
  int32_t state;              /**< TANDEM_SESSION_* */
  int64_t tick;               /**< desynced: first mismatching tick; peer_left: the local tick then */
  uint32_t endpoint;
  uint64_t local_hash, remote_hash;
  int64_t last_heard_tick;
} tandem_session_stop;

/** Counters (SessionStats); the last rejection: tandem_session_last_rejection. */
typedef struct tandem_session_stats {
  uint64_t frames, stalls, rollbacks, max_rollback_depth, resimulated_ticks, ticks_simulated;
  uint64_t packets_sent, bytes_sent, packets_received, bytes_received;
  uint64_t packets_rejected, packets_stale, commands_refused, hashes_compared, hashes_skipped;
} tandem_session_stats;

/** The C++ defaults (rollback, 2 players, 4 input bytes, delay 2, ...). */
TANDEM_C_API tandem_session_config tandem_default_session_config(void);
/** "idle", "running", "desynced", "peer left", "error" ("unknown" otherwise). */
TANDEM_C_API const char* tandem_session_state_name(int32_t state);
/** The hash a session exchanges: world_state_hash mixed with XXH3 of the
 * game state when size > 0 (for single-machine reference runs). */
TANDEM_C_API uint64_t tandem_session_state_hash(tandem_world_id world, const uint8_t* game_state, size_t size);

/** Validates the config (the message names the field and its range) and
 * starts a session at tick 0 from the world's current state. */
TANDEM_C_API tandem_status tandem_session_create(tandem_world_id world, const tandem_session_config* config,
                                                 const tandem_session_callbacks* callbacks,
                                                 tandem_session_id* out_session);
/** Destroys a session (the world is left as it is). */
TANDEM_C_API tandem_status tandem_session_destroy(tandem_session_id session);

/** One frame: schedules local_input (input_bytes bytes; ignored for a
 * spectator), handles rollbacks, steps if allowed, confirms, checks hashes,
 * sends. *out_result: TANDEM_ADVANCE_*. */
TANDEM_C_API tandem_status tandem_session_advance_frame(tandem_session_id session, const uint8_t* local_input,
                                                        size_t size, int32_t* out_result);
/** A frame spent waiting (time sync): no input, no new tick. */
TANDEM_C_API tandem_status tandem_session_idle_frame(tandem_session_id session, int32_t* out_result);
/** Hands a packet received from from_endpoint to the session (refused
 * packets are counted in the stats, not an error here). */
TANDEM_C_API tandem_status tandem_session_receive(tandem_session_id session, uint32_t from_endpoint,
                                                  const uint8_t* packet, size_t size);
/** The transport lost an endpoint (a player: the session stops, peer left). */
TANDEM_C_API tandem_status tandem_session_peer_disconnected(tandem_session_id session, uint32_t endpoint);

/** Frames this peer should wait to let the others catch up (≤ 0: none; 0
 * for an invalid handle). */
TANDEM_C_API int32_t tandem_session_frames_ahead(tandem_session_id session);
/** Ticks simulated; last tick simulated with every real input; the lowest
 * tick every connected endpoint has confirmed; the start state's hash (0
 * for an invalid handle). */
TANDEM_C_API int64_t tandem_session_current_tick(tandem_session_id session);
TANDEM_C_API int64_t tandem_session_confirmed_tick(tandem_session_id session);
TANDEM_C_API int64_t tandem_session_remote_confirmed_through(tandem_session_id session);
TANDEM_C_API uint64_t tandem_session_start_hash(tandem_session_id session);
/** The hash of a confirmed tick still in the ring; 0 otherwise. */
TANDEM_C_API uint64_t tandem_session_confirmed_hash(tandem_session_id session, int64_t tick);
/** TANDEM_SESSION_* (TANDEM_SESSION_IDLE for an invalid handle). */
TANDEM_C_API int32_t tandem_session_state(tandem_session_id session);
/** True when the local endpoint is a spectator. */
TANDEM_C_API bool tandem_session_is_spectator(tandem_session_id session);
/** The session's config. */
TANDEM_C_API tandem_status tandem_session_get_config(tandem_session_id session, tandem_session_config* out_config);
/** Why it stopped (state TANDEM_SESSION_RUNNING while running). */
TANDEM_C_API tandem_status tandem_session_get_stop(tandem_session_id session, tandem_session_stop* out_stop);
/** The stop message, one line (text rule of tandem_q32_to_text). */
TANDEM_C_API tandem_status tandem_session_stop_message(tandem_session_id session, char* out_text, size_t capacity,
                                                       size_t* out_length);
/** Counters. */
TANDEM_C_API tandem_status tandem_session_get_stats(tandem_session_id session, tandem_session_stats* out_stats);
/** Why the last packet was refused (text rule). */
TANDEM_C_API tandem_status tandem_session_last_rejection(tandem_session_id session, char* out_text,
                                                         size_t capacity, size_t* out_length);

/** The in-memory replay so far, finished (buffer rule over bytes; empty
 * without record_replay). Load it with tandem_replay_load_memory. */
TANDEM_C_API tandem_status tandem_session_replay_bytes(tandem_session_id session, uint8_t* out_bytes,
                                                       size_t capacity, size_t* out_size);
/** The state image of a tick still in the snapshot ring (buffer rule). */
TANDEM_C_API tandem_status tandem_session_state_image(tandem_session_id session, int64_t tick, uint8_t* out_bytes,
                                                      size_t capacity, size_t* out_size);
/** Writes prefix.replay (when recording) and prefix.state. */
TANDEM_C_API tandem_status tandem_session_write_artifacts(tandem_session_id session, const char* prefix);
/** Asks an endpoint for per-body hashes of a tick (count ≤ 512). */
TANDEM_C_API tandem_status tandem_session_request_body_hashes(tandem_session_id session, uint32_t endpoint,
                                                              int64_t tick, uint32_t first_body, uint32_t count);
/** The per-body hashes last received (buffer rule over the hashes; endpoint,
 * tick and first body into the optional out pointers). */
TANDEM_C_API tandem_status tandem_session_remote_body_hashes(tandem_session_id session, uint32_t* out_endpoint,
                                                             int64_t* out_tick, uint32_t* out_first_body,
                                                             uint64_t* out_hashes, int32_t capacity,
                                                             int32_t* out_count);
/** Per-body hashes of a tick in the snapshot ring, body index order (buffer rule). */
TANDEM_C_API tandem_status tandem_session_local_body_hashes(tandem_session_id session, int64_t tick,
                                                            uint64_t* out_hashes, int32_t capacity,
                                                            int32_t* out_count);

#ifdef __cplusplus
}  /* extern "C" */
#endif

#endif /* TANDEM_C_SESSION_H */

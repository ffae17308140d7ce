/* tandem_c_replay.h — snapshots, hashes, commands, recorders, replays, verify,
 * diff, the sync test and scenes (replay/, scene/).
 * Part of the C API; include tandem_c.h (the umbrella) or this file alone.
 * The conventions (numbers, handles, errors, buffers) are in tandem_c.h. */
#ifndef TANDEM_C_REPLAY_H
#define TANDEM_C_REPLAY_H

#include "tandem_c_base.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------------ */
/* Snapshots and hashes (replay/state.h)                                     */
/* ------------------------------------------------------------------------ */

/** The exact size in bytes of the world's state image (0 for an invalid
 * world). */
TANDEM_C_API size_t tandem_world_snapshot_size(tandem_world_id world);
/** Writes the world's canonical state image (buffer rule over bytes;
 * *out_size receives its size). */
TANDEM_C_API tandem_status tandem_world_snapshot(tandem_world_id world, uint8_t* out_bytes, size_t capacity, size_t* out_size);
/** Replaces the world's state with an image; the whole image is validated
 * first, a refused image leaves the world unchanged (the message names the
 * byte offset). */
TANDEM_C_API tandem_status tandem_world_restore(tandem_world_id world, const uint8_t* bytes, size_t size);
/** Creates a new world from a state image. */
TANDEM_C_API tandem_status tandem_create_world_from_snapshot(const uint8_t* bytes, size_t size, tandem_world_id* out_world);
/** XXH3-64 of the world's canonical state (0 for an invalid or locked world). */
TANDEM_C_API uint64_t tandem_world_state_hash(tandem_world_id world);
/** XXH3-64 of one body's record and its shapes (0 for an invalid body). */
TANDEM_C_API uint64_t tandem_body_state_hash(tandem_body_id body);
/** body_state_hash of every body slot in index order, 0 for dead slots
 * (buffer rule). */
TANDEM_C_API tandem_status tandem_world_body_hashes(tandem_world_id world, uint64_t* out_hashes, int32_t capacity,
                                                    int32_t* out_count);

/** Encodes state image `image` as a delta against state image `base`
 * (replay/state.h: XOR with the base, run-length coded; small for the ticks
 * of a rollback window). Buffer rule over bytes (*out_size: the delta's
 * size; a size query encodes once to measure). */
TANDEM_C_API tandem_status tandem_encode_state_delta(const uint8_t* base, size_t base_size, const uint8_t* image,
                                                     size_t image_size, uint8_t* out_delta, size_t capacity, size_t* out_size);
/** Rebuilds the image from `base` and a delta made against it (buffer rule
 * over bytes). Refuses a delta made against another base and corrupt data,
 * naming the byte offset. */
TANDEM_C_API tandem_status tandem_apply_state_delta(const uint8_t* base, size_t base_size, const uint8_t* delta,
                                                    size_t delta_size, uint8_t* out_image, size_t capacity, size_t* out_size);

/** Where two states or runs part (replay/verify.h DiffReport). Free with
 * tandem_free_diff_report. */
typedef struct tandem_diff_report {
  tandem_status error;      /**< not TANDEM_OK: the comparison could not run (see text) */
  bool differs;
  int64_t tick;             /**< first tick whose states differ */
  uint64_t hash_a, hash_b;
  bool located;             /**< difference_text names the record and field */
  int64_t located_tick;
  char* difference_text;    /**< "body 3 linear_velocity.x: a = ..., b = ..."; owned */
  char* text;               /**< the full human-readable report; owned */
  int64_t ticks_compared;   /**< ticks whose states were compared */
  bool inputs_differ;       /**< replays: the recorded inputs differ ... */
  int64_t inputs_differ_tick;   /**< ... first at this tick */
  bool length_differs;      /**< replays: different tick counts */
  int64_t ticks_a, ticks_b;
} tandem_diff_report;

/** Compares two state images: the first differing record and field. */
TANDEM_C_API tandem_status tandem_diff_snapshots(const uint8_t* a, size_t a_size, const uint8_t* b, size_t b_size,
                                                 tandem_diff_report* out_report);
/** Frees the texts of a report filled by a tandem_diff_* function and
 * zeroes it (NULL or an already freed report: nothing happens). */
TANDEM_C_API void tandem_free_diff_report(tandem_diff_report* report);

/* Decoded states (replay/state.h): a state image as named records and
 * fields, for tools and diffs. A decoded state is library-owned, named by a
 * tandem_decoded_state_id until tandem_decoded_state_destroy(); the strings
 * its getters return live as long as it does. */
typedef struct tandem_decoded_state_id { uint32_t index1, generation; } tandem_decoded_state_id;

/** One record (DecodedRecord). */
typedef struct tandem_decoded_record {
  const char* kind;      /**< "header", "world", "body_slot", "body", "shape", "contact", "joint", ... */
  int64_t index;         /**< slot / body / shape index; contacts and pairs: the lower shape index */
  int64_t index2;        /**< contacts and pairs: the higher shape index; −1 otherwise */
  uint32_t generation;   /**< bodies and shapes: the slot's generation */
  int32_t field_count;
} tandem_decoded_record;

/** One named value (DecodedField). */
typedef struct tandem_decoded_field {
  const char* name;      /**< "position.x", "points[1].normal_impulse" */
  int64_t value;         /**< the raw integer (Q32 raw when is_q32; bools 0/1; enums their number) */
  bool is_q32;
} tandem_decoded_field;

/** The first difference between two decoded states (StateDifference);
 * strings owned, freed by tandem_free_state_difference. */
typedef struct tandem_state_difference {
  bool differs;
  char* kind;            /**< record kind ("" when identical) */
  int64_t index, index2;
  uint32_t generation;
  char* field;           /**< "" when a record is missing on one side */
  int64_t value_a, value_b;
  bool is_q32, missing_in_a, missing_in_b;
  char* text;            /**< StateDifference::describe(): "body 3 linear_velocity.x: ..." (the generation only when the sides differ) or "identical" */
} tandem_state_difference;

/** Decodes and validates a state image (the checks of tandem_world_restore;
 * errors name the byte offset). */
TANDEM_C_API tandem_status tandem_decode_world_state(const uint8_t* bytes, size_t size,
                                                     tandem_decoded_state_id* out_state);
/** Frees a decoded state. */
TANDEM_C_API tandem_status tandem_decoded_state_destroy(tandem_decoded_state_id state);
/** The image's format version and its number of records. */
TANDEM_C_API tandem_status tandem_decoded_state_info(tandem_decoded_state_id state, uint32_t* out_version,
                                                     int32_t* out_record_count);
/** Record `record` (0-based, canonical order). */
TANDEM_C_API tandem_status tandem_decoded_state_record(tandem_decoded_state_id state, int32_t record,
                                                       tandem_decoded_record* out_record);
/** Field `field` of record `record`. */
TANDEM_C_API tandem_status tandem_decoded_state_field(tandem_decoded_state_id state, int32_t record, int32_t field,
                                                      tandem_decoded_field* out_field);
/** The first difference between two decoded states, in canonical order. */
TANDEM_C_API tandem_status tandem_diff_decoded_states(tandem_decoded_state_id a, tandem_decoded_state_id b,
                                                      tandem_state_difference* out_difference);
/** Frees a difference's strings and zeroes it (NULL: nothing happens). */
TANDEM_C_API void tandem_free_state_difference(tandem_state_difference* difference);
/** The byte offset of one field in a valid image (locate_state_field): kind
 * "world", "body", "shape" or "contact"; index the body / shape index or the
 * contact's position; field as decoded ("linear_velocity.x"). */
TANDEM_C_API tandem_status tandem_locate_state_field(const uint8_t* bytes, size_t size, const char* kind,
                                                     int64_t index, const char* field, size_t* out_offset);

/* ------------------------------------------------------------------------ */
/* Commands (replay/commands.h): inputs that can be recorded and replayed    */
/* ------------------------------------------------------------------------ */

#define TANDEM_COMMAND_CREATE_BODY 1
#define TANDEM_COMMAND_DESTROY_BODY 2
#define TANDEM_COMMAND_APPLY_FORCE 3
#define TANDEM_COMMAND_APPLY_TORQUE 4
#define TANDEM_COMMAND_APPLY_LINEAR_IMPULSE 5
#define TANDEM_COMMAND_APPLY_ANGULAR_IMPULSE 6
#define TANDEM_COMMAND_SET_LINEAR_VELOCITY 7
#define TANDEM_COMMAND_SET_ANGULAR_VELOCITY 8
#define TANDEM_COMMAND_SET_TRANSFORM 9
#define TANDEM_COMMAND_SET_AWAKE 10
#define TANDEM_COMMAND_SET_ENABLED 11
#define TANDEM_COMMAND_SET_GRAVITY 12
/* 13 is the C++ user_input command: use tandem_recorder_submit_payload. */
#define TANDEM_COMMAND_CREATE_JOINT 14          /**< joint_spec */
#define TANDEM_COMMAND_DESTROY_JOINT 15         /**< joint_index, joint_generation */
#define TANDEM_COMMAND_SET_JOINT_MOTOR_SPEED 16 /**< joint; scalar = speed */
#define TANDEM_COMMAND_SET_JOINT_TARGET 17      /**< joint; vector = target */
#define TANDEM_COMMAND_SET_JOINT_LENGTH 18      /**< joint; scalar = length */
#define TANDEM_COMMAND_SET_JOINT_LIMITS 19      /**< joint; scalar = lower, scalar2 = upper */

/** Shape kinds of a create_body command. */
#define TANDEM_SHAPE_KIND_CIRCLE 0
#define TANDEM_SHAPE_KIND_CAPSULE 1
#define TANDEM_SHAPE_KIND_SEGMENT 2
#define TANDEM_SHAPE_KIND_POLYGON 3
#define TANDEM_SHAPE_KIND_CHAIN 4

/** One shape of a create_body command (the member matching `kind`). */
typedef struct tandem_shape_spec {
  int32_t kind;                     /**< TANDEM_SHAPE_KIND_* */
  tandem_shape_def def;
  tandem_circle circle;
  tandem_capsule capsule;
  tandem_segment segment;
  tandem_polygon polygon;
  const tandem_vec2* chain_points;  /**< chain: borrowed for the call */
  int32_t chain_point_count;
  bool chain_loop;
} tandem_shape_spec;

/** A joint of any kind for a create_joint command (JointSpec,
 * replay/commands.h: the kind's create function reads the fields its
 * definition has; lower/upper are the angle, translation or length limits,
 * motor_force the max motor force or torque, target the mouse target or the
 * motor joint's linear offset, hertz/damping_ratio the spring or the weld's
 * linear stiffness). Bodies by index (index1 − 1) and generation. */
typedef struct tandem_joint_spec {
  int32_t type;  /**< TANDEM_JOINT_* */
  uint32_t body_a_index, body_a_generation, body_b_index, body_b_generation;
  tandem_vec2 local_anchor_a, local_anchor_b;
  bool collide_connected;
  tandem_q32 break_force, break_torque;
  uint64_t user_data;
  tandem_vec2 local_axis;
  tandem_q32 reference_angle;
  bool enable_spring, enable_limit, enable_motor;
  tandem_q32 hertz, damping_ratio, angular_hertz, angular_damping_ratio;
  tandem_q32 length, lower, upper, motor_speed, motor_force;
  tandem_vec2 target;
  tandem_q32 angular_offset, max_force, max_torque, correction_factor;
} tandem_joint_spec;

/** An engine command as plain data (see replay/commands.h for the fields
 * each type uses). Bodies are named by index (index1 − 1) and generation. */
typedef struct tandem_command {
  int32_t type;                     /**< TANDEM_COMMAND_* */
  uint32_t body_index, body_generation;
  tandem_body_def body_def;         /**< create_body */
  const tandem_shape_spec* shapes;  /**< create_body: borrowed for the call */
  int32_t shape_count;
  tandem_vec2 vector;               /**< force, impulse, velocity, position or gravity */
  tandem_vec2 point;                /**< world point unless at_center */
  bool at_center;
  tandem_q32 scalar;                /**< torque, angular impulse or angular velocity */
  tandem_rot rotation;              /**< set_transform */
  bool flag;                        /**< wake / awake / enabled */
  uint32_t joint_index, joint_generation;  /**< joint commands but create_joint */
  tandem_joint_spec joint_spec;     /**< create_joint */
  tandem_q32 scalar2;               /**< set_joint_limits: upper */
} tandem_command;

/** Where a callback (a replay payload handler, a session's make_commands)
 * appends engine commands; valid only during that callback. */
typedef struct tandem_command_list tandem_command_list;
/** Appends a converted copy of *command (its borrowed arrays are copied). */
TANDEM_C_API tandem_status tandem_command_list_push(tandem_command_list* list, const tandem_command* command);

/** "apply_force", "create_joint", ... (command_type_name); "unknown" outside 1…19. */
TANDEM_C_API const char* tandem_command_type_name(int32_t type);

/** A command of `type` with defaults (at_center and flag true, identity
 * rotation, default body def, the JointSpec defaults in joint_spec). */
TANDEM_C_API tandem_command tandem_default_command(int32_t type);
/** A shape spec of `kind` with a default shape def. */
TANDEM_C_API tandem_shape_spec tandem_default_shape_spec(int32_t kind);
/** Applies a command to a world (create_body: *out_created, may be NULL,
 * receives the body). */
TANDEM_C_API tandem_status tandem_apply_command(tandem_world_id world, const tandem_command* command,
                                                tandem_body_id* out_created);

/* ------------------------------------------------------------------------ */
/* Replays: record, load, verify, diff (replay/replay_file.h, verify.h)      */
/* ------------------------------------------------------------------------ */

/** Recorder settings. */
typedef struct tandem_recorder_options {
  uint32_t keyframe_interval;  /**< ticks between keyframes; default 600; 0: initial only */
  bool record_hashes;          /**< default true */
  uint32_t flush_every;        /**< ticks per flush; default 1 */
  tandem_q32 time_step;        /**< s per tick; default 1/60 */
} tandem_recorder_options;

/** Default recorder options. */
TANDEM_C_API tandem_recorder_options tandem_default_recorder_options(void);
/** A recorder that writes into memory (tandem_recorder_memory). */
TANDEM_C_API tandem_status tandem_recorder_create_memory(const tandem_recorder_options* options, tandem_recorder_id* out_recorder);
/** A recorder that writes the file at `path` (UTF-8), created at begin. */
TANDEM_C_API tandem_status tandem_recorder_create_file(const char* path, const tandem_recorder_options* options,
                                                       tandem_recorder_id* out_recorder);
/** Destroys a recorder (an unfinished file is left as written so far). */
TANDEM_C_API tandem_status tandem_recorder_destroy(tandem_recorder_id recorder);
/** Starts recording `world` in its current state; `scene` bytes (may be
 * NULL with size 0) are embedded. */
TANDEM_C_API tandem_status tandem_recorder_begin(tandem_recorder_id recorder, tandem_world_id world, const uint8_t* scene,
                                                 size_t scene_size);
/** Applies a command to the recorded world and records it. */
TANDEM_C_API tandem_status tandem_recorder_submit(tandem_recorder_id recorder, const tandem_command* command);
/** Records an opaque game payload for the current tick (not applied). */
TANDEM_C_API tandem_status tandem_recorder_submit_payload(tandem_recorder_id recorder, const uint8_t* payload, size_t size);
/** Steps the recorded world, records the tick and its hash. */
TANDEM_C_API tandem_status tandem_recorder_step(tandem_recorder_id recorder, uint32_t* out_flags);
/** Finishes the replay (END chunk; closes a file). */
TANDEM_C_API tandem_status tandem_recorder_finish(tandem_recorder_id recorder);
/** Ticks recorded (0 for an invalid handle). */
TANDEM_C_API int64_t tandem_recorder_tick_count(tandem_recorder_id recorder);
/** The hash recorded after the last step (0 for an invalid handle). */
TANDEM_C_API uint64_t tandem_recorder_last_hash(tandem_recorder_id recorder);
/** The bytes of a memory recorder so far (buffer rule over bytes). */
TANDEM_C_API tandem_status tandem_recorder_memory(tandem_recorder_id recorder, uint8_t* out_bytes, size_t capacity,
                                                  size_t* out_size);

/** True when the bytes start with the replay magic (is_replay_image). */
TANDEM_C_API bool tandem_is_replay_image(const uint8_t* bytes, size_t size);
/** Loads a replay image from memory (copied). */
TANDEM_C_API tandem_status tandem_replay_load_memory(const uint8_t* bytes, size_t size, tandem_replay_id* out_replay);
/** Loads a replay file (path UTF-8). */
TANDEM_C_API tandem_status tandem_replay_load_file(const char* path, tandem_replay_id* out_replay);
/** Frees a loaded replay. */
TANDEM_C_API tandem_status tandem_replay_destroy(tandem_replay_id replay);
/** Ticks in the replay (0 for an invalid handle). */
TANDEM_C_API int64_t tandem_replay_tick_count(tandem_replay_id replay);
/** The recorded hash after `tick` (1-based); TANDEM_ERROR_INVALID_ARGUMENT
 * if the tick is out of range or has no hash. */
TANDEM_C_API tandem_status tandem_replay_tick_hash(tandem_replay_id replay, int64_t tick, uint64_t* out_hash);
/** A new world in the state after `tick` ticks. */
TANDEM_C_API tandem_status tandem_replay_create_world_at(tandem_replay_id replay, int64_t tick, tandem_world_id* out_world);

/** Puts an existing world into the replay's state after `tick` ticks
 * (restores the nearest keyframe, then re-runs the recorded ticks). */
TANDEM_C_API tandem_status tandem_replay_seek(tandem_replay_id replay, tandem_world_id world, int64_t tick);

/** The outcome of tandem_verify_replay. Free with tandem_free_verify_report. */
typedef struct tandem_verify_report {
  tandem_status error;       /**< not TANDEM_OK: the check could not run */
  bool ok;                   /**< every check passed */
  int64_t ticks_run;
  uint64_t hashes_checked, keyframes_checked;
  bool mismatch;
  int64_t mismatch_tick;
  uint64_t expected_hash, actual_hash;
  bool located;
  int64_t located_tick;
  bool self_consistent;
  char* difference_text;     /**< owned; "" when not located */
  char* text;                /**< the full human-readable report; owned */
  uint32_t refused_commands; /**< commands refused while re-running (also refused when recorded) */
  uint32_t skipped_payloads; /**< user payloads skipped (no payload handler) */
} tandem_verify_report;

/** Re-simulates a replay and compares every recorded hash and keyframe
 * (max_ticks: INT64_MAX for all; negative is refused). The returned status is TANDEM_OK when
 * the check ran (a mismatch is reported in the report, not as an error). */
TANDEM_C_API tandem_status tandem_verify_replay(tandem_replay_id replay, int64_t max_ticks, bool locate,
                                                tandem_verify_report* out_report);
/** Turns a game's opaque payload recorded at `tick` into engine commands
 * (PayloadHandler): push them to *out. A status other than TANDEM_OK stops
 * the run. Must be deterministic. */
typedef tandem_status (*tandem_payload_fn)(void* context, int64_t tick, const uint8_t* payload, size_t size,
                                           tandem_command_list* out);
/** Progress of a long check: ticks done of total. */
typedef void (*tandem_progress_fn)(void* context, int64_t done, int64_t total);
/** Advances a live world by one tick (tick is 1-based); TANDEM_OK to go on. */
typedef tandem_status (*tandem_live_tick_fn)(void* context, int64_t tick);

/** Options of tandem_verify_replay_with (VerifyOptions); NULL functions
 * are unset (payloads skipped, no progress). */
typedef struct tandem_verify_options {
  int64_t max_ticks;           /**< INT64_MAX: all (≥ 0) */
  bool locate;                 /**< on a mismatch, find the body and field */
  tandem_payload_fn payloads;
  void* payload_context;
  tandem_progress_fn progress;
  void* progress_context;
} tandem_verify_options;
/** The C++ defaults: every tick, locate, no handlers. */
TANDEM_C_API tandem_verify_options tandem_default_verify_options(void);
/** tandem_verify_replay with payload handler and progress callback. */
TANDEM_C_API tandem_status tandem_verify_replay_with(tandem_replay_id replay, const tandem_verify_options* options,
                                                     tandem_verify_report* out_report);

/** Options of the diffs (DiffOptions): payload handlers per side, progress.
 * All-zero (or a NULL pointer) means none. */
typedef struct tandem_diff_options {
  tandem_payload_fn payloads_a;
  void* context_a;
  tandem_payload_fn payloads_b;
  void* context_b;
  tandem_progress_fn progress;
  void* progress_context;
} tandem_diff_options;
/** tandem_diff_replays with options (may be NULL). */
TANDEM_C_API tandem_status tandem_diff_replays_with(tandem_replay_id a, tandem_replay_id b,
                                                    const tandem_diff_options* options,
                                                    tandem_diff_report* out_report);
/** The first difference between a replay (a) and a live run (b): `live` is
 * in the state of the replay's tick 0; `advance` runs one live tick.
 * Compares up to `ticks` ticks (capped at the replay's). Options may be NULL
 * (payloads_b is not used). */
TANDEM_C_API tandem_status tandem_diff_replay_live(tandem_replay_id replay, tandem_world_id live,
                                                   tandem_live_tick_fn advance, void* context, int64_t ticks,
                                                   const tandem_diff_options* options,
                                                   tandem_diff_report* out_report);
/** tandem_replay_seek and tandem_replay_create_world_at with a payload
 * handler (NULL: payloads skipped). */
TANDEM_C_API tandem_status tandem_replay_seek_with(tandem_replay_id replay, tandem_world_id world, int64_t tick,
                                                   tandem_payload_fn payloads, void* context);
TANDEM_C_API tandem_status tandem_replay_create_world_at_with(tandem_replay_id replay, int64_t tick,
                                                              tandem_payload_fn payloads, void* context,
                                                              tandem_world_id* out_world);

/** Frees a verify report's texts and zeroes it (NULL: nothing happens). */
TANDEM_C_API void tandem_free_verify_report(tandem_verify_report* report);
/** The first difference between two replays. */
TANDEM_C_API tandem_status tandem_diff_replays(tandem_replay_id a, tandem_replay_id b, tandem_diff_report* out_report);

/* ------------------------------------------------------------------------ */
/* Sync test (replay/synctest.h)                                             */
/* ------------------------------------------------------------------------ */

/** Called before every step of the sync test (first pass and resimulation):
 * must make the same changes for the same tick. */
typedef void (*tandem_synctest_input_fn)(tandem_world_id world, int64_t tick, void* context);

/** Sync test settings. */
typedef struct tandem_synctest_options {
  int64_t ticks;          /**< ticks to run, ≥ 0 */
  int64_t rollback;       /**< ticks rolled back after each tick, 1…1024; default 8 */
  tandem_q32 time_step;   /**< default 1/60 s */
} tandem_synctest_options;

/** What the sync test found. Free with tandem_free_synctest_report. */
typedef struct tandem_synctest_report {
  bool passed;
  int64_t ticks_run, resimulated_ticks, first_mismatch_tick, detected_at_tick;
  uint64_t expected_hash, actual_hash;
  char* message;  /**< one line; owned */
} tandem_synctest_report;

/** Default sync test options (0 ticks, rollback 8, 1/60 s). */
TANDEM_C_API tandem_synctest_options tandem_default_synctest_options(void);
/** Runs the sync test on `world` (inputs may be NULL). A mismatch is
 * reported in *out_report (passed = false), not as an error. */
TANDEM_C_API tandem_status tandem_run_synctest(tandem_world_id world, const tandem_synctest_options* options,
                                               tandem_synctest_input_fn inputs, void* context,
                                               tandem_synctest_report* out_report);
/** Frees a sync test report's message and zeroes it. */
TANDEM_C_API void tandem_free_synctest_report(tandem_synctest_report* report);

/* ------------------------------------------------------------------------ */
/* Scenes (JSON scene files, docs/scene-format.md)                           */
/* ------------------------------------------------------------------------ */

/** What a loaded scene holds. */
typedef struct tandem_scene_info {
  int32_t step_hz;        /**< steps per simulated second */
  tandem_q32 time_step;   /**< 1/step_hz s */
  int64_t ticks;          /**< suggested run length */
  int32_t body_count;     /**< bodies the scene creates */
  int32_t input_count;    /**< scripted inputs */
} tandem_scene_info;

/** Loads a scene file (path UTF-8). TANDEM_ERROR_PARSE for an unreadable
 * or malformed file (the message names the file, the JSON pointer and what
 * was expected); TANDEM_ERROR_UNSUPPORTED in a build without the scene
 * loader (TANDEM_BUILD_TOOLS=OFF). */
TANDEM_C_API tandem_status tandem_scene_load_file(const char* path, tandem_scene_id* out_scene);
/** Parses scene JSON text of `size` bytes; `name` (may be NULL) prefixes errors. */
TANDEM_C_API tandem_status tandem_scene_load_text(const char* text, size_t size, const char* name, tandem_scene_id* out_scene);
/** Frees a loaded scene (worlds built from it stay alive). */
TANDEM_C_API tandem_status tandem_scene_destroy(tandem_scene_id scene);
/** The scene's step rate, time step, length and counts. */
TANDEM_C_API tandem_status tandem_scene_get_info(tandem_scene_id scene, tandem_scene_info* out_info);
/** Builds a new world from the scene (the caller owns it). */
TANDEM_C_API tandem_status tandem_scene_build(tandem_scene_id scene, tandem_world_id* out_world);
/** The handle of scene body `index` in a world built by tandem_scene_build. */
TANDEM_C_API tandem_status tandem_scene_body(tandem_scene_id scene, tandem_world_id world, int32_t index,
                                             tandem_body_id* out_body);
/** Applies the scene's scripted inputs for `tick` (before step tick + 1) to
 * a world built from it. */
TANDEM_C_API tandem_status tandem_scene_apply_inputs(tandem_scene_id scene, tandem_world_id world, int64_t tick);

/* ------------------------------------------------------------------------ */
/* Compact rollback snapshots (replay/rollback.h)                            */
/* ------------------------------------------------------------------------ */

/** The version of the compact rollback image (same build only: no
 * compatibility promise across versions; use tandem_world_snapshot for
 * files and other machines). */
#define TANDEM_ROLLBACK_FORMAT_VERSION 1

/** A reusable compact rollback snapshot (RollbackBuffer): a canonical image
 * of only what the next step cannot recompute, a few hundred bytes per
 * moving body, for netcode that saves every tick. Library-owned; made by
 * tandem_rollback_buffer_create, freed by tandem_rollback_buffer_free. Not
 * thread-safe: one thread at a time per buffer. */
typedef struct tandem_rollback_buffer tandem_rollback_buffer;

/** Creates an empty buffer (*out_buffer; hash 0, size 0). */
TANDEM_C_API tandem_status tandem_rollback_buffer_create(tandem_rollback_buffer** out_buffer);
/** Frees a buffer (NULL: nothing happens). */
TANDEM_C_API void tandem_rollback_buffer_free(tandem_rollback_buffer* buffer);
/** Copies src into dst (a ring of saved ticks; dst's capacity is reused). */
TANDEM_C_API tandem_status tandem_rollback_buffer_copy(tandem_rollback_buffer* dst, const tandem_rollback_buffer* src);
/** Saves the world's state into the buffer (replaced; no allocation after
 * the first save of the same scene). Refuses an invalid or locked world;
 * the buffer is unchanged then. */
TANDEM_C_API tandem_status tandem_rollback_save(tandem_world_id world, tandem_rollback_buffer* buffer);
/** Replaces the world's state with the buffer's; every later step is
 * bit-identical to the run it was saved from. Refuses an invalid or locked
 * world and an empty or inconsistent buffer (the message names the byte
 * offset and field); a refused restore changes nothing. Before the next
 * step tandem_world_state_hash of the restored world may differ from the
 * saved tick's (omitted manifold geometry); tandem_rollback_hash does not. */
TANDEM_C_API tandem_status tandem_rollback_restore(tandem_world_id world, const tandem_rollback_buffer* buffer);
/** XXH3-64 of the buffer's image (0 for an empty or NULL buffer); equal
 * states give equal hashes, whatever the broad phase. */
TANDEM_C_API uint64_t tandem_rollback_hash(const tandem_rollback_buffer* buffer);
/** The image's size in bytes (what a peer would store per tick; 0 for an
 * empty or NULL buffer). */
TANDEM_C_API size_t tandem_rollback_image_size(const tandem_rollback_buffer* buffer);

#ifdef __cplusplus
}  /* extern "C" */
#endif

#endif /* TANDEM_C_REPLAY_H */

/* tandem_c.h — the C API of Tandem (C11; also valid C++). One header, one
 * shared library (libtandem.so), callable from any language with a C FFI:
 * Python (ctypes), C# (P/Invoke, as a Unity project would), Rust, Go, Lua...
 *
 * DESIGN. The C layer mirrors the C++ API (physics/tandem.h, replay/ headers, the
 * scene loader) one to one and adds no arithmetic: every function converts
 * its arguments field by field, calls the C++ function and converts the
 * result back, so a world driven through this header computes exactly the
 * same bits, tick for tick, as one driven from C++ (a test checks this).
 *
 * NUMBERS. Every physical quantity crosses the boundary as the raw Q32.32
 * integer (tandem_q32 = int64_t, value = raw / 2^32), in SI units (m, s, kg,
 * rad, N). Helpers convert raw values to and from Q16.16, exact decimal text
 * and — for display only — double; there is deliberately no conversion from
 * floating point (write "0.1", not 0.1, to get the same bits everywhere).
 *
 * HANDLES. Worlds, bodies and shapes are small POD structs (index + 1 and a
 * generation, plus the world for bodies and shapes); the all-zero handle is
 * null. A stale handle (its object destroyed) is detected, never
 * dereferenced. Recorders, loaded replays and loaded scenes are handles of
 * the same kind, owned by this library until tandem_*_destroy().
 *
 * ERRORS. A function that can fail returns a tandem_status (TANDEM_OK = 0).
 * Every such function records the outcome as the CALLING THREAD's last error:
 * tandem_last_error_code() and tandem_last_error_message() (a UTF-8 message
 * naming the function and the culprit, e.g. "body_set_linear_velocity: body
 * {index 3, generation 2} was destroyed"; "" after a success). The message
 * stays valid until the next status-returning call on the same thread.
 * Value getters (tandem_body_position, ...) return the value directly; given
 * an invalid handle they return the documented default (zero, the identity,
 * false, a null handle) and do not touch the last error — call
 * tandem_body_check() and friends for a status. No C++ exception ever leaves
 * this library: anything thrown inside (out of memory included) becomes a
 * status.
 *
 * BUFFERS. Functions that return a list take (out, capacity, out_count):
 * *out_count (required) receives the number of elements of the full result.
 * Pass out = NULL and capacity = 0 to ask only for the size (TANDEM_OK). With
 * a non-zero capacity smaller than the result nothing is written and the
 * status is TANDEM_ERROR_BUFFER_TOO_SMALL, its message naming both sizes.
 * Memory this library allocates for a caller (report texts) is freed by the
 * matching tandem_free_*() function and by nothing else.
 *
 * THREADS. As the C++ API: worlds are independent, one world is used by one
 * thread at a time; the last error is per thread.
 *
 * NOT COVERED YET (see README "From other languages"): joints, the world
 * profile, the session; their handles and functions will be added here in
 * the same style.
 */
#ifndef TANDEM_C_H
#define TANDEM_C_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#if defined(_WIN32)
#if defined(TANDEM_C_BUILDING)
#define TANDEM_C_API __declspec(dllexport)
#else
#define TANDEM_C_API __declspec(dllimport)
#endif
#elif defined(__GNUC__)
#define TANDEM_C_API __attribute__((visibility("default")))
#else
#define TANDEM_C_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/** The version of this header's ABI (bumped on any incompatible change). */
#define TANDEM_C_ABI_VERSION 1

/* ------------------------------------------------------------------------ */
/* Scalars, status                                                           */
/* ------------------------------------------------------------------------ */

/** A Q32.32 fixed-point value as its raw integer: value = raw / 2^32. */
typedef int64_t tandem_q32;
/** A Q16.16 fixed-point value as its raw integer: value = raw / 2^16. */
typedef int32_t tandem_q16;
/** A status code: TANDEM_OK or one of TANDEM_ERROR_*. */
typedef int32_t tandem_status;

#define TANDEM_OK 0                          /**< success */
#define TANDEM_ERROR_NULL_HANDLE 1           /**< the handle is null */
#define TANDEM_ERROR_INVALID_HANDLE 2        /**< stale, of a destroyed world, or never valid */
#define TANDEM_ERROR_FOREIGN_HANDLE 3        /**< a handle of another world where one world was expected */
#define TANDEM_ERROR_WORLD_LOCKED 4          /**< changes are refused inside tandem_world_step */
#define TANDEM_ERROR_INVALID_DEFINITION 5    /**< a definition not made by tandem_default_*_def */
#define TANDEM_ERROR_INVALID_ARGUMENT 6      /**< a value outside its range or of the wrong kind */
#define TANDEM_ERROR_CAPACITY_EXCEEDED 7     /**< too many worlds, bodies or shapes */
#define TANDEM_ERROR_NULL_POINTER 8          /**< a required pointer argument is NULL */
#define TANDEM_ERROR_BUFFER_TOO_SMALL 9      /**< the caller's buffer is smaller than the result */
#define TANDEM_ERROR_PARSE 10                /**< text, a scene, a state image or a replay is malformed */
#define TANDEM_ERROR_IO 11                   /**< a file could not be read or written */
#define TANDEM_ERROR_UNSUPPORTED 12          /**< not available in this build */
#define TANDEM_ERROR_OUT_OF_MEMORY 13        /**< an allocation failed */
#define TANDEM_ERROR_INTERNAL 14             /**< an unexpected exception inside the library */

/** The short name of a status code ("ok", "stale handle", ...; "unknown"
 * for a value not listed above). The string is static. */
TANDEM_C_API const char* tandem_status_name(tandem_status status);
/** The status of the calling thread's last status-returning call. */
TANDEM_C_API tandem_status tandem_last_error_code(void);
/** The message of the calling thread's last status-returning call: UTF-8,
 * "" after a success; valid until the next status-returning call on this
 * thread. Never NULL. */
TANDEM_C_API const char* tandem_last_error_message(void);
/** The library's version as "major.minor.patch" (static string). */
TANDEM_C_API const char* tandem_version_string(void);
/** TANDEM_C_ABI_VERSION of the library actually loaded (compare with the
 * header's to detect a mismatched library). */
TANDEM_C_API int32_t tandem_abi_version(void);

/* ------------------------------------------------------------------------ */
/* Number conversions (exact unless stated)                                  */
/* ------------------------------------------------------------------------ */

/** An integer as Q32.32 (exact; every int32_t fits). */
TANDEM_C_API tandem_q32 tandem_q32_from_int(int32_t value);
/** num / den rounded to nearest, ties away from zero (the engine's
 * Q32::from_ratio, e.g. (1, 60) for a 60 Hz step). Fails with
 * TANDEM_ERROR_INVALID_ARGUMENT for den = 0 or a result out of range. */
TANDEM_C_API tandem_status tandem_q32_from_ratio(int64_t num, int64_t den, tandem_q32* out_value);
/** Q16.16 → Q32.32 (exact). */
TANDEM_C_API tandem_q32 tandem_q32_from_q16(tandem_q16 value);
/** Q32.32 → Q16.16 rounded to nearest, ties away from zero. Fails with
 * TANDEM_ERROR_INVALID_ARGUMENT (nothing written) outside ±32768. */
TANDEM_C_API tandem_status tandem_q32_to_q16(tandem_q32 value, tandem_q16* out_value);
/** Parses decimal text ("1.5", "-0.1", "2.5e-3"; JSON number grammar, plus a
 * leading '+') exactly to the nearest Q32.32, ties away from zero, never
 * through floating point. Errors name the offending character. */
TANDEM_C_API tandem_status tandem_q32_from_text(const char* text, tandem_q32* out_value);
/** Exact decimal text of a Q32.32 value ("-1.5", "0.0000000002328306436538696289062").
 * Buffer rule (file comment) over chars: *out_length receives the length
 * without the terminating NUL; capacity must be at least length + 1. */
TANDEM_C_API tandem_status tandem_q32_to_text(tandem_q32 value, char* out_text, size_t capacity, size_t* out_length);
/** The value as a double — FOR DISPLAY ONLY: never feed it back into a world. */
TANDEM_C_API double tandem_q32_to_double(tandem_q32 value);

/* ------------------------------------------------------------------------ */
/* Value types (all quantities raw Q32.32)                                   */
/* ------------------------------------------------------------------------ */

/** A 2D vector (m, m/s, N... the caller's unit). */
typedef struct tandem_vec2 { tandem_q32 x, y; } tandem_vec2;
/** A rotation as cosine and sine, near unit length; identity = (2^32, 0). */
typedef struct tandem_rot { tandem_q32 c, s; } tandem_rot;
/** A pose: position (m) and rotation. */
typedef struct tandem_transform { tandem_vec2 p; tandem_rot q; } tandem_transform;
/** An axis-aligned box, m; lower ≤ upper. */
typedef struct tandem_aabb { tandem_vec2 lower, upper; } tandem_aabb;
/** Mass properties: mass (kg), centre of mass (body frame, m), rotational
 * inertia about it (kg·m²). */
typedef struct tandem_mass_data { tandem_q32 mass; tandem_vec2 center; tandem_q32 rotational_inertia; } tandem_mass_data;

/** The identity rotation. */
TANDEM_C_API tandem_rot tandem_rot_identity(void);
/** The rotation by `angle` radians (the engine's integer sine and cosine). */
TANDEM_C_API tandem_rot tandem_rot_from_angle(tandem_q32 angle);
/** The angle of a rotation, radians in [−π, π]. */
TANDEM_C_API tandem_q32 tandem_rot_angle(tandem_rot rotation);

/* ------------------------------------------------------------------------ */
/* Handles                                                                   */
/* ------------------------------------------------------------------------ */

/** A world: registry slot + 1 (0 = null) and the slot's generation. */
typedef struct tandem_world_id { uint16_t index1, generation; } tandem_world_id;
/** A body: slot + 1 in its world (0 = null), generation, and the world. */
typedef struct tandem_body_id { uint32_t index1, generation; tandem_world_id world; } tandem_body_id;
/** A shape: slot + 1 in its world (0 = null), generation, and the world. */
typedef struct tandem_shape_id { uint32_t index1, generation; tandem_world_id world; } tandem_shape_id;
/** A joint: slot + 1 in its world (0 = null), generation, and the world.
 * Reserved: the joint functions arrive with the C++ joint API. */
typedef struct tandem_joint_id { uint32_t index1, generation; tandem_world_id world; } tandem_joint_id;
/** A replay recorder owned by this library (0 = null). */
typedef struct tandem_recorder_id { uint32_t index1, generation; } tandem_recorder_id;
/** A replay loaded into memory, owned by this library (0 = null). */
typedef struct tandem_replay_id { uint32_t index1, generation; } tandem_replay_id;
/** A scene file loaded into memory, owned by this library (0 = null). */
typedef struct tandem_scene_id { uint32_t index1, generation; } tandem_scene_id;

/* ------------------------------------------------------------------------ */
/* Definitions                                                               */
/* ------------------------------------------------------------------------ */

/** Broad phases (every kind gives the same results; only speed differs). */
#define TANDEM_BROAD_PHASE_NAIVE 0
#define TANDEM_BROAD_PHASE_SWEEP_AND_PRUNE 1
#define TANDEM_BROAD_PHASE_GRID 2
#define TANDEM_BROAD_PHASE_TREE 3

/** Body types. */
#define TANDEM_BODY_STATIC 0
#define TANDEM_BODY_KINEMATIC 1
#define TANDEM_BODY_DYNAMIC 2

/** Shape types. */
#define TANDEM_SHAPE_CIRCLE 0
#define TANDEM_SHAPE_CAPSULE 1
#define TANDEM_SHAPE_SEGMENT 2
#define TANDEM_SHAPE_POLYGON 3
#define TANDEM_SHAPE_CHAIN_SEGMENT 4

/** Flags raised by tandem_world_step. */
#define TANDEM_STEP_FLAG_BODY_LEFT_BOUNDS 1u

/** Settings of a world (physics/defs.h WorldDef). Make with
 * tandem_default_world_def(), then change fields. */
typedef struct tandem_world_def {
  tandem_vec2 gravity;                /**< m/s²; default (0, −10) */
  int32_t sub_step_count;             /**< default 4; 1…64 */
  tandem_q32 contact_hertz;           /**< Hz; default 30 */
  tandem_q32 contact_damping_ratio;   /**< default 10 */
  tandem_q32 max_contact_push_speed;  /**< m/s; default 3 */
  tandem_q32 joint_hertz;             /**< Hz; default 60 */
  tandem_q32 joint_damping_ratio;     /**< default 2 */
  tandem_q32 restitution_threshold;   /**< m/s; default 1 */
  tandem_q32 hit_event_threshold;     /**< m/s; default 1 */
  tandem_q32 max_linear_speed;        /**< m/s; default 400 */
  tandem_aabb bounds;                 /**< m; bodies must stay inside */
  bool enable_sleep;                  /**< default true */
  bool enable_continuous;             /**< default true */
  int32_t broad_phase;                /**< TANDEM_BROAD_PHASE_*; default naive */
  uint64_t user_data;                 /**< any integer; default 0 */
  int32_t internal_cookie;            /**< set by tandem_default_world_def; do not touch */
} tandem_world_def;

/** Settings of a new body (BodyDef). Make with tandem_default_body_def(). */
typedef struct tandem_body_def {
  int32_t type;                  /**< TANDEM_BODY_*; default static */
  tandem_vec2 position;          /**< m; default (0, 0) */
  tandem_rot rotation;           /**< default identity */
  tandem_vec2 linear_velocity;   /**< m/s; default 0 */
  tandem_q32 angular_velocity;   /**< rad/s; default 0 */
  tandem_q32 linear_damping;     /**< 1/s; default 0 */
  tandem_q32 angular_damping;    /**< 1/s; default 0 */
  tandem_q32 gravity_scale;      /**< default 1 */
  uint64_t user_data;            /**< default 0 */
  bool enable_sleep;             /**< default true */
  bool is_awake;                 /**< default true */
  bool fixed_rotation;           /**< default false */
  bool is_bullet;                /**< default false */
  bool is_enabled;               /**< default true */
  int32_t internal_cookie;       /**< set by tandem_default_body_def; do not touch */
} tandem_body_def;

/** Collision filter (see physics/defs.h Filter). */
typedef struct tandem_filter {
  uint64_t category_bits;  /**< default 1 */
  uint64_t mask_bits;      /**< default all */
  int32_t group_index;     /**< default 0 */
} tandem_filter;

/** Settings of a new shape (ShapeDef). Make with tandem_default_shape_def(). */
typedef struct tandem_shape_def {
  tandem_q32 friction;       /**< default 0.6; [0, 100] */
  tandem_q32 restitution;    /**< default 0; [0, 1] */
  tandem_q32 density;        /**< kg/m²; default 1 */
  tandem_filter filter;      /**< default category 1, mask all, group 0 */
  uint64_t user_data;        /**< default 0 */
  bool is_sensor;            /**< default false */
  bool enable_hit_events;    /**< default false */
  int32_t internal_cookie;   /**< set by tandem_default_shape_def; do not touch */
} tandem_shape_def;

/** A world definition with every default filled in. */
TANDEM_C_API tandem_world_def tandem_default_world_def(void);
/** A body definition with every default filled in. */
TANDEM_C_API tandem_body_def tandem_default_body_def(void);
/** A shape definition with every default filled in. */
TANDEM_C_API tandem_shape_def tandem_default_shape_def(void);
/** The default collision filter (category 1, mask all, group 0). */
TANDEM_C_API tandem_filter tandem_default_filter(void);

/* ------------------------------------------------------------------------ */
/* Geometry                                                                  */
/* ------------------------------------------------------------------------ */

#define TANDEM_MAX_POLYGON_VERTICES 8

/** A solid circle, body frame. */
typedef struct tandem_circle { tandem_vec2 center; tandem_q32 radius; } tandem_circle;
/** A solid capsule, body frame. */
typedef struct tandem_capsule { tandem_vec2 center1, center2; tandem_q32 radius; } tandem_capsule;
/** A two-sided segment, body frame. */
typedef struct tandem_segment { tandem_vec2 point1, point2; } tandem_segment;
/** A convex polygon (CCW), body frame; make with tandem_make_box & co. */
typedef struct tandem_polygon {
  tandem_vec2 vertices[TANDEM_MAX_POLYGON_VERTICES];
  tandem_vec2 normals[TANDEM_MAX_POLYGON_VERTICES];
  tandem_vec2 centroid;
  tandem_q32 radius;
  int32_t count;  /**< 3…8 */
} tandem_polygon;
/** One one-sided chain segment with its ghost vertices. */
typedef struct tandem_chain_segment {
  tandem_vec2 ghost1;
  tandem_segment segment;
  tandem_vec2 ghost2;
  int32_t chain_id;
} tandem_chain_segment;
/** Any shape's geometry: `type` (TANDEM_SHAPE_*) says which member is set. */
typedef struct tandem_shape_geometry {
  int32_t type;
  tandem_circle circle;
  tandem_capsule capsule;
  tandem_segment segment;
  tandem_polygon polygon;
  tandem_chain_segment chain_segment;
} tandem_shape_geometry;

/** An axis-aligned box centred on the origin (half widths in m). */
TANDEM_C_API tandem_status tandem_make_box(tandem_q32 half_width, tandem_q32 half_height, tandem_polygon* out_polygon);
/** A box centred at `center`, rotated by `angle` rad, rounded by `radius`. */
TANDEM_C_API tandem_status tandem_make_offset_box(tandem_q32 half_width, tandem_q32 half_height, tandem_vec2 center,
                                                  tandem_q32 angle, tandem_q32 radius, tandem_polygon* out_polygon);
/** The convex hull of 3…64 points as a polygon, rounded by `radius`
 * (degenerate input is refused with a message). */
TANDEM_C_API tandem_status tandem_make_polygon(const tandem_vec2* points, int32_t count, tandem_q32 radius,
                                               tandem_polygon* out_polygon);

/* ------------------------------------------------------------------------ */
/* World                                                                     */
/* ------------------------------------------------------------------------ */

/** Counts of a world. */
typedef struct tandem_world_counters {
  int32_t body_count, shape_count, solver_body_count;
  uint64_t step_count;
  int64_t arena_capacity;  /**< bytes */
} tandem_world_counters;

/** Broad-phase figures of the last step. */
typedef struct tandem_broad_phase_stats {
  int32_t proxies, candidate_pairs, pairs, touching_pairs;
  uint64_t update_nanoseconds;  /**< timing only */
} tandem_broad_phase_stats;

/** A deterministic user collision filter (see tandem.h CustomFilterFn):
 * return false to keep shapes a and b apart. Called inside the step. */
typedef bool (*tandem_custom_filter_fn)(tandem_shape_id a, tandem_shape_id b, void* context);

/** Creates a world from a definition made by tandem_default_world_def. */
TANDEM_C_API tandem_status tandem_create_world(const tandem_world_def* def, tandem_world_id* out_world);
/** Destroys a world and everything in it. */
TANDEM_C_API tandem_status tandem_destroy_world(tandem_world_id world);
/** True when the handle names a live world. */
TANDEM_C_API bool tandem_world_is_valid(tandem_world_id world);
/** TANDEM_OK for a live world, otherwise why not. */
TANDEM_C_API tandem_status tandem_world_check(tandem_world_id world);
/** Advances the world by time_step s (raw Q32.32, 0…1 s). *out_flags
 * (may be NULL) receives TANDEM_STEP_FLAG_* bits. */
TANDEM_C_API tandem_status tandem_world_step(tandem_world_id world, tandem_q32 time_step, uint32_t* out_flags);
/** True while the world is inside tandem_world_step. */
TANDEM_C_API bool tandem_world_is_locked(tandem_world_id world);
/** The world's settings as a definition (default def for an invalid handle). */
TANDEM_C_API tandem_world_def tandem_world_get_def(tandem_world_id world);
/** Gravity, m/s² (zero for an invalid handle). */
TANDEM_C_API tandem_vec2 tandem_world_gravity(tandem_world_id world);
/** Sets gravity, m/s². */
TANDEM_C_API tandem_status tandem_world_set_gravity(tandem_world_id world, tandem_vec2 gravity);
/** Sets the solver sub-steps per step, 1…64. */
TANDEM_C_API tandem_status tandem_world_set_sub_step_count(tandem_world_id world, int32_t sub_step_count);
/** Sets contact stiffness (Hz), damping ratio and push speed (m/s). */
TANDEM_C_API tandem_status tandem_world_set_contact_tuning(tandem_world_id world, tandem_q32 hertz,
                                                           tandem_q32 damping_ratio, tandem_q32 push_speed);
/** Sets joint stiffness (Hz) and damping ratio. */
TANDEM_C_API tandem_status tandem_world_set_joint_tuning(tandem_world_id world, tandem_q32 hertz, tandem_q32 damping_ratio);
/** Sets the restitution threshold, m/s. */
TANDEM_C_API tandem_status tandem_world_set_restitution_threshold(tandem_world_id world, tandem_q32 threshold);
/** Sets the hit event threshold, m/s. */
TANDEM_C_API tandem_status tandem_world_set_hit_event_threshold(tandem_world_id world, tandem_q32 threshold);
/** Sets the maximum linear speed, m/s. */
TANDEM_C_API tandem_status tandem_world_set_max_linear_speed(tandem_world_id world, tandem_q32 max_linear_speed);
/** Turns sleeping on or off. */
TANDEM_C_API tandem_status tandem_world_enable_sleep(tandem_world_id world, bool enable);
/** Turns continuous collision on or off. */
TANDEM_C_API tandem_status tandem_world_enable_continuous(tandem_world_id world, bool enable);
/** Sets the world's user data. */
TANDEM_C_API tandem_status tandem_world_set_user_data(tandem_world_id world, uint64_t user_data);
/** The world's user data (0 for an invalid handle). */
TANDEM_C_API uint64_t tandem_world_user_data(tandem_world_id world);
/** Counts (zeroes for an invalid handle). */
TANDEM_C_API tandem_world_counters tandem_world_get_counters(tandem_world_id world);
/** Live bodies in ascending index (buffer rule). */
TANDEM_C_API tandem_status tandem_world_bodies(tandem_world_id world, tandem_body_id* out_bodies, int32_t capacity,
                                               int32_t* out_count);
/** Selects the broad phase (TANDEM_BROAD_PHASE_*) from the next step on. */
TANDEM_C_API tandem_status tandem_world_set_broad_phase(tandem_world_id world, int32_t kind);
/** The broad phase in use (naive for an invalid handle). */
TANDEM_C_API int32_t tandem_world_get_broad_phase(tandem_world_id world);
/** The last step's broad-phase figures (zeroes for an invalid handle). */
TANDEM_C_API tandem_broad_phase_stats tandem_world_get_broad_phase_stats(tandem_world_id world);
/** Installs a custom filter (NULL removes it); `context` is passed back. */
TANDEM_C_API tandem_status tandem_world_set_custom_filter(tandem_world_id world, tandem_custom_filter_fn filter,
                                                          void* context);

/* ------------------------------------------------------------------------ */
/* Bodies                                                                    */
/* ------------------------------------------------------------------------ */

/** Creates a body from a definition made by tandem_default_body_def. */
TANDEM_C_API tandem_status tandem_create_body(tandem_world_id world, const tandem_body_def* def, tandem_body_id* out_body);
/** Destroys a body and its shapes. */
TANDEM_C_API tandem_status tandem_destroy_body(tandem_body_id body);
/** True when the handle names a live body. */
TANDEM_C_API bool tandem_body_is_valid(tandem_body_id body);
/** TANDEM_OK for a live body (of expected_world unless that is null). */
TANDEM_C_API tandem_status tandem_body_check(tandem_body_id body, tandem_world_id expected_world);
/** The body's world (the handle's world field). */
TANDEM_C_API tandem_world_id tandem_body_world(tandem_body_id body);
/** TANDEM_BODY_* (static for an invalid handle). */
TANDEM_C_API int32_t tandem_body_type(tandem_body_id body);
/** Changes the body type (TANDEM_BODY_*). */
TANDEM_C_API tandem_status tandem_body_set_type(tandem_body_id body, int32_t type);
/** Origin position, m (zero for an invalid handle). */
TANDEM_C_API tandem_vec2 tandem_body_position(tandem_body_id body);
/** Rotation (identity for an invalid handle). */
TANDEM_C_API tandem_rot tandem_body_rotation(tandem_body_id body);
/** Angle, rad in [−π, π] (0 for an invalid handle). */
TANDEM_C_API tandem_q32 tandem_body_angle(tandem_body_id body);
/** Origin pose (identity for an invalid handle). */
TANDEM_C_API tandem_transform tandem_body_transform(tandem_body_id body);
/** Teleports the body: origin (m) and rotation. */
TANDEM_C_API tandem_status tandem_body_set_transform(tandem_body_id body, tandem_vec2 position, tandem_rot rotation);
/** Centre of mass in the world, m. */
TANDEM_C_API tandem_vec2 tandem_body_world_center(tandem_body_id body);
/** Centre of mass in the body frame, m. */
TANDEM_C_API tandem_vec2 tandem_body_local_center(tandem_body_id body);
/** Velocity of the centre of mass, m/s. */
TANDEM_C_API tandem_vec2 tandem_body_linear_velocity(tandem_body_id body);
/** Sets the velocity of the centre of mass, m/s. */
TANDEM_C_API tandem_status tandem_body_set_linear_velocity(tandem_body_id body, tandem_vec2 velocity);
/** Angular velocity, rad/s. */
TANDEM_C_API tandem_q32 tandem_body_angular_velocity(tandem_body_id body);
/** Sets the angular velocity, rad/s. */
TANDEM_C_API tandem_status tandem_body_set_angular_velocity(tandem_body_id body, tandem_q32 angular_velocity);
/** Velocity of a world point moving with the body, m/s. */
TANDEM_C_API tandem_vec2 tandem_body_point_velocity(tandem_body_id body, tandem_vec2 world_point);
/** Adds a force (N) at a world point (m) for the next step. */
TANDEM_C_API tandem_status tandem_body_apply_force(tandem_body_id body, tandem_vec2 force, tandem_vec2 world_point, bool wake);
/** Adds a force (N) at the centre of mass. */
TANDEM_C_API tandem_status tandem_body_apply_force_to_center(tandem_body_id body, tandem_vec2 force, bool wake);
/** Adds a torque (N·m). */
TANDEM_C_API tandem_status tandem_body_apply_torque(tandem_body_id body, tandem_q32 torque, bool wake);
/** Applies an impulse (N·s) at a world point (m) now. */
TANDEM_C_API tandem_status tandem_body_apply_linear_impulse(tandem_body_id body, tandem_vec2 impulse,
                                                            tandem_vec2 world_point, bool wake);
/** Applies an impulse (N·s) at the centre of mass. */
TANDEM_C_API tandem_status tandem_body_apply_linear_impulse_to_center(tandem_body_id body, tandem_vec2 impulse, bool wake);
/** Applies an angular impulse (N·m·s). */
TANDEM_C_API tandem_status tandem_body_apply_angular_impulse(tandem_body_id body, tandem_q32 impulse, bool wake);
/** Mass, kg (0 for static, kinematic and invalid). */
TANDEM_C_API tandem_q32 tandem_body_mass(tandem_body_id body);
/** Rotational inertia about the centre of mass, kg·m². */
TANDEM_C_API tandem_q32 tandem_body_rotational_inertia(tandem_body_id body);
/** Mass, local centre and inertia (zeroes for an invalid handle). */
TANDEM_C_API tandem_mass_data tandem_body_mass_data(tandem_body_id body);
/** Linear damping, 1/s. */
TANDEM_C_API tandem_q32 tandem_body_linear_damping(tandem_body_id body);
/** Sets linear damping, 1/s. */
TANDEM_C_API tandem_status tandem_body_set_linear_damping(tandem_body_id body, tandem_q32 damping);
/** Angular damping, 1/s. */
TANDEM_C_API tandem_q32 tandem_body_angular_damping(tandem_body_id body);
/** Sets angular damping, 1/s. */
TANDEM_C_API tandem_status tandem_body_set_angular_damping(tandem_body_id body, tandem_q32 damping);
/** Gravity scale. */
TANDEM_C_API tandem_q32 tandem_body_gravity_scale(tandem_body_id body);
/** Sets the gravity scale. */
TANDEM_C_API tandem_status tandem_body_set_gravity_scale(tandem_body_id body, tandem_q32 scale);
/** True when the body never rotates. */
TANDEM_C_API bool tandem_body_is_fixed_rotation(tandem_body_id body);
/** Fixes or frees the rotation. */
TANDEM_C_API tandem_status tandem_body_set_fixed_rotation(tandem_body_id body, bool fixed);
/** True for a bullet. */
TANDEM_C_API bool tandem_body_is_bullet(tandem_body_id body);
/** Marks the body as a bullet or not. */
TANDEM_C_API tandem_status tandem_body_set_bullet(tandem_body_id body, bool bullet);
/** True when the body takes part in the simulation. */
TANDEM_C_API bool tandem_body_is_enabled(tandem_body_id body);
/** Adds the body back to the simulation. */
TANDEM_C_API tandem_status tandem_body_enable(tandem_body_id body);
/** Takes the body out of the simulation. */
TANDEM_C_API tandem_status tandem_body_disable(tandem_body_id body);
/** True when a non-static body is awake. */
TANDEM_C_API bool tandem_body_is_awake(tandem_body_id body);
/** Wakes the body or puts it to sleep. */
TANDEM_C_API tandem_status tandem_body_set_awake(tandem_body_id body, bool awake);
/** True when the body may sleep. */
TANDEM_C_API bool tandem_body_is_sleep_enabled(tandem_body_id body);
/** Lets the body sleep or keeps it awake. */
TANDEM_C_API tandem_status tandem_body_enable_sleep(tandem_body_id body, bool enable);
/** The body's user data. */
TANDEM_C_API uint64_t tandem_body_user_data(tandem_body_id body);
/** Sets the body's user data. */
TANDEM_C_API tandem_status tandem_body_set_user_data(tandem_body_id body, uint64_t user_data);
/** Body frame point → world point, m. */
TANDEM_C_API tandem_vec2 tandem_body_world_point(tandem_body_id body, tandem_vec2 local_point);
/** World point → body frame point, m. */
TANDEM_C_API tandem_vec2 tandem_body_local_point(tandem_body_id body, tandem_vec2 world_point);
/** Body frame direction → world direction. */
TANDEM_C_API tandem_vec2 tandem_body_world_vector(tandem_body_id body, tandem_vec2 local_vector);
/** World direction → body frame direction. */
TANDEM_C_API tandem_vec2 tandem_body_local_vector(tandem_body_id body, tandem_vec2 world_vector);
/** Number of shapes on the body (0 for an invalid handle). */
TANDEM_C_API int32_t tandem_body_shape_count(tandem_body_id body);
/** The body's shapes in ascending index (buffer rule). */
TANDEM_C_API tandem_status tandem_body_shapes(tandem_body_id body, tandem_shape_id* out_shapes, int32_t capacity,
                                              int32_t* out_count);

/* ------------------------------------------------------------------------ */
/* Shapes                                                                    */
/* ------------------------------------------------------------------------ */

/** Attaches a circle (body frame, m) to a body. */
TANDEM_C_API tandem_status tandem_create_circle_shape(tandem_body_id body, const tandem_shape_def* def,
                                                      const tandem_circle* circle, tandem_shape_id* out_shape);
/** Attaches a capsule. */
TANDEM_C_API tandem_status tandem_create_capsule_shape(tandem_body_id body, const tandem_shape_def* def,
                                                       const tandem_capsule* capsule, tandem_shape_id* out_shape);
/** Attaches a convex polygon (made by tandem_make_box & co). */
TANDEM_C_API tandem_status tandem_create_polygon_shape(tandem_body_id body, const tandem_shape_def* def,
                                                       const tandem_polygon* polygon, tandem_shape_id* out_shape);
/** Attaches a two-sided segment. */
TANDEM_C_API tandem_status tandem_create_segment_shape(tandem_body_id body, const tandem_shape_def* def,
                                                       const tandem_segment* segment, tandem_shape_id* out_shape);
/** Attaches a chain (see tandem.h create_chain_shapes): an open chain of
 * count ≥ 4 points gives count − 3 one-sided segments, a loop of count ≥ 3
 * gives count. out_shapes follows the buffer rule, checked BEFORE anything
 * is created (NULL with capacity 0: create and report only the count). */
TANDEM_C_API tandem_status tandem_create_chain_shapes(tandem_body_id body, const tandem_shape_def* def,
                                                      const tandem_vec2* points, int32_t count, bool loop,
                                                      tandem_shape_id* out_shapes, int32_t capacity, int32_t* out_count);
/** Destroys a shape and updates its body's mass. */
TANDEM_C_API tandem_status tandem_destroy_shape(tandem_shape_id shape);
/** True when the handle names a live shape. */
TANDEM_C_API bool tandem_shape_is_valid(tandem_shape_id shape);
/** TANDEM_OK for a live shape (of expected_world unless that is null). */
TANDEM_C_API tandem_status tandem_shape_check(tandem_shape_id shape, tandem_world_id expected_world);
/** TANDEM_SHAPE_* (circle for an invalid handle). */
TANDEM_C_API int32_t tandem_shape_type(tandem_shape_id shape);
/** The shape's body (null for an invalid handle). */
TANDEM_C_API tandem_body_id tandem_shape_body(tandem_shape_id shape);
/** The shape's geometry in its body's frame (a default circle for an
 * invalid handle). */
TANDEM_C_API tandem_shape_geometry tandem_shape_geometry_of(tandem_shape_id shape);
/** World bounds, m. */
TANDEM_C_API tandem_aabb tandem_shape_aabb(tandem_shape_id shape);
/** The shape's own mass data. */
TANDEM_C_API tandem_mass_data tandem_shape_mass_data(tandem_shape_id shape);
/** Friction coefficient. */
TANDEM_C_API tandem_q32 tandem_shape_friction(tandem_shape_id shape);
/** Sets the friction coefficient, [0, 100]. */
TANDEM_C_API tandem_status tandem_shape_set_friction(tandem_shape_id shape, tandem_q32 friction);
/** Restitution. */
TANDEM_C_API tandem_q32 tandem_shape_restitution(tandem_shape_id shape);
/** Sets restitution, [0, 1]. */
TANDEM_C_API tandem_status tandem_shape_set_restitution(tandem_shape_id shape, tandem_q32 restitution);
/** Density, kg/m². */
TANDEM_C_API tandem_q32 tandem_shape_density(tandem_shape_id shape);
/** Sets density, kg/m², and updates the body's mass. */
TANDEM_C_API tandem_status tandem_shape_set_density(tandem_shape_id shape, tandem_q32 density);
/** True for a sensor. */
TANDEM_C_API bool tandem_shape_is_sensor(tandem_shape_id shape);
/** The collision filter (default filter for an invalid handle). */
TANDEM_C_API tandem_filter tandem_shape_filter(tandem_shape_id shape);
/** Sets the collision filter. */
TANDEM_C_API tandem_status tandem_shape_set_filter(tandem_shape_id shape, tandem_filter filter);
/** The shape's user data. */
TANDEM_C_API uint64_t tandem_shape_user_data(tandem_shape_id shape);
/** Sets the shape's user data. */
TANDEM_C_API tandem_status tandem_shape_set_user_data(tandem_shape_id shape, uint64_t user_data);

/* ------------------------------------------------------------------------ */
/* Queries (physics/query.h)                                                 */
/* ------------------------------------------------------------------------ */

/** Which shapes a query sees. */
typedef struct tandem_query_filter {
  uint64_t category_bits;  /**< default 1 */
  uint64_t mask_bits;      /**< default all */
  bool include_sensors;    /**< default false */
} tandem_query_filter;

/** One ray hit. */
typedef struct tandem_ray_hit {
  tandem_shape_id shape;  /**< null when no hit */
  tandem_vec2 point;      /**< m */
  tandem_vec2 normal;     /**< unit */
  tandem_q32 fraction;    /**< of the translation, [0, 1] */
  bool hit;
} tandem_ray_hit;

/** The default query filter. */
TANDEM_C_API tandem_query_filter tandem_default_query_filter(void);
/** The closest hit of origin → origin + translation (m). filter may be NULL
 * (default). *out_hit.hit is false when nothing is hit. */
TANDEM_C_API tandem_status tandem_world_cast_ray_closest(tandem_world_id world, tandem_vec2 origin, tandem_vec2 translation,
                                                         const tandem_query_filter* filter, tandem_ray_hit* out_hit);
/** Every hit, by fraction then shape index (buffer rule). */
TANDEM_C_API tandem_status tandem_world_cast_ray_all(tandem_world_id world, tandem_vec2 origin, tandem_vec2 translation,
                                                     const tandem_query_filter* filter, tandem_ray_hit* out_hits,
                                                     int32_t capacity, int32_t* out_count);
/** Shapes whose AABB overlaps `box`, ascending index (buffer rule). */
TANDEM_C_API tandem_status tandem_world_overlap_aabb(tandem_world_id world, tandem_aabb box, const tandem_query_filter* filter,
                                                     tandem_shape_id* out_shapes, int32_t capacity, int32_t* out_count);
/** Shapes containing `point` (buffer rule). */
TANDEM_C_API tandem_status tandem_world_overlap_point(tandem_world_id world, tandem_vec2 point,
                                                      const tandem_query_filter* filter, tandem_shape_id* out_shapes,
                                                      int32_t capacity, int32_t* out_count);
/** Shapes overlapping a circle placed at `transform` (buffer rule). */
TANDEM_C_API tandem_status tandem_world_overlap_circle(tandem_world_id world, const tandem_circle* circle,
                                                       tandem_transform transform, const tandem_query_filter* filter,
                                                       tandem_shape_id* out_shapes, int32_t capacity, int32_t* out_count);
/** Shapes overlapping a capsule placed at `transform` (buffer rule). */
TANDEM_C_API tandem_status tandem_world_overlap_capsule(tandem_world_id world, const tandem_capsule* capsule,
                                                        tandem_transform transform, const tandem_query_filter* filter,
                                                        tandem_shape_id* out_shapes, int32_t capacity, int32_t* out_count);
/** Shapes overlapping a polygon placed at `transform` (buffer rule). */
TANDEM_C_API tandem_status tandem_world_overlap_polygon(tandem_world_id world, const tandem_polygon* polygon,
                                                        tandem_transform transform, const tandem_query_filter* filter,
                                                        tandem_shape_id* out_shapes, int32_t capacity, int32_t* out_count);

/* ------------------------------------------------------------------------ */
/* Events of the last step (physics/events.h; sorted by data keys)           */
/* ------------------------------------------------------------------------ */

/** One contact point. */
typedef struct tandem_manifold_point {
  tandem_vec2 point, anchor_a, anchor_b;
  tandem_q32 separation;
  uint16_t id;
} tandem_manifold_point;
/** Up to two contact points sharing a normal (from shape A to shape B). */
typedef struct tandem_manifold {
  tandem_vec2 normal;
  tandem_manifold_point points[2];
  int32_t point_count;
} tandem_manifold;
/** Two shapes began touching. */
typedef struct tandem_contact_begin_event { tandem_shape_id shape_a, shape_b; tandem_manifold manifold; } tandem_contact_begin_event;
/** Two shapes stopped touching (handles may be stale). */
typedef struct tandem_contact_end_event { tandem_shape_id shape_a, shape_b; } tandem_contact_end_event;
/** Two shapes hit faster than the threshold. */
typedef struct tandem_contact_hit_event {
  tandem_shape_id shape_a, shape_b;
  tandem_vec2 point, normal;
  tandem_q32 approach_speed;
} tandem_contact_hit_event;
/** A shape began or stopped overlapping a sensor. */
typedef struct tandem_sensor_event { tandem_shape_id sensor, visitor; } tandem_sensor_event;
/** A body moved during the step. */
typedef struct tandem_body_move_event { tandem_body_id body; tandem_transform transform; bool fell_asleep; } tandem_body_move_event;

/** Contact begin events of the last step (buffer rule). */
TANDEM_C_API tandem_status tandem_world_contact_begin_events(tandem_world_id world, tandem_contact_begin_event* out_events,
                                                             int32_t capacity, int32_t* out_count);
/** Contact end events of the last step (buffer rule). */
TANDEM_C_API tandem_status tandem_world_contact_end_events(tandem_world_id world, tandem_contact_end_event* out_events,
                                                           int32_t capacity, int32_t* out_count);
/** Contact hit events of the last step (buffer rule). */
TANDEM_C_API tandem_status tandem_world_contact_hit_events(tandem_world_id world, tandem_contact_hit_event* out_events,
                                                           int32_t capacity, int32_t* out_count);
/** Sensor begin events of the last step (buffer rule). */
TANDEM_C_API tandem_status tandem_world_sensor_begin_events(tandem_world_id world, tandem_sensor_event* out_events,
                                                            int32_t capacity, int32_t* out_count);
/** Sensor end events of the last step (buffer rule). */
TANDEM_C_API tandem_status tandem_world_sensor_end_events(tandem_world_id world, tandem_sensor_event* out_events,
                                                          int32_t capacity, int32_t* out_count);
/** Body move events of the last step (buffer rule). */
TANDEM_C_API tandem_status tandem_world_body_move_events(tandem_world_id world, tandem_body_move_event* out_events,
                                                         int32_t capacity, int32_t* out_count);

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
  uint64_t tick;            /**< first tick whose states differ */
  uint64_t hash_a, hash_b;
  bool located;             /**< difference_text names the record and field */
  uint64_t located_tick;
  char* difference_text;    /**< "body 3 (generation 1) linear_velocity.x: a = ..., b = ..."; owned */
  char* text;               /**< the full human-readable report; owned */
} tandem_diff_report;

/** Compares two state images: the first differing record and field. */
TANDEM_C_API tandem_status tandem_diff_snapshots(const uint8_t* a, size_t a_size, const uint8_t* b, size_t b_size,
                                                 tandem_diff_report* out_report);
/** Frees the texts of a report filled by a tandem_diff_* function and
 * zeroes it (NULL or an already freed report: nothing happens). */
TANDEM_C_API void tandem_free_diff_report(tandem_diff_report* report);

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
} tandem_command;

/** A command of `type` with defaults (at_center and flag true, identity
 * rotation, default body def). */
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
TANDEM_C_API uint64_t tandem_recorder_tick_count(tandem_recorder_id recorder);
/** The hash recorded after the last step (0 for an invalid handle). */
TANDEM_C_API uint64_t tandem_recorder_last_hash(tandem_recorder_id recorder);
/** The bytes of a memory recorder so far (buffer rule over bytes). */
TANDEM_C_API tandem_status tandem_recorder_memory(tandem_recorder_id recorder, uint8_t* out_bytes, size_t capacity,
                                                  size_t* out_size);

/** Loads a replay image from memory (copied). */
TANDEM_C_API tandem_status tandem_replay_load_memory(const uint8_t* bytes, size_t size, tandem_replay_id* out_replay);
/** Loads a replay file (path UTF-8). */
TANDEM_C_API tandem_status tandem_replay_load_file(const char* path, tandem_replay_id* out_replay);
/** Frees a loaded replay. */
TANDEM_C_API tandem_status tandem_replay_destroy(tandem_replay_id replay);
/** Ticks in the replay (0 for an invalid handle). */
TANDEM_C_API uint64_t tandem_replay_tick_count(tandem_replay_id replay);
/** The recorded hash after `tick` (1-based); TANDEM_ERROR_INVALID_ARGUMENT
 * if the tick is out of range or has no hash. */
TANDEM_C_API tandem_status tandem_replay_tick_hash(tandem_replay_id replay, uint64_t tick, uint64_t* out_hash);
/** A new world in the state after `tick` ticks. */
TANDEM_C_API tandem_status tandem_replay_create_world_at(tandem_replay_id replay, uint64_t tick, tandem_world_id* out_world);

/** Puts an existing world into the replay's state after `tick` ticks
 * (restores the nearest keyframe, then re-runs the recorded ticks). */
TANDEM_C_API tandem_status tandem_replay_seek(tandem_replay_id replay, tandem_world_id world, uint64_t tick);

/** The outcome of tandem_verify_replay. Free with tandem_free_verify_report. */
typedef struct tandem_verify_report {
  tandem_status error;       /**< not TANDEM_OK: the check could not run */
  bool ok;                   /**< every check passed */
  uint64_t ticks_run, hashes_checked, keyframes_checked;
  bool mismatch;
  uint64_t mismatch_tick, expected_hash, actual_hash;
  bool located;
  uint64_t located_tick;
  bool self_consistent;
  char* difference_text;     /**< owned; "" when not located */
  char* text;                /**< the full human-readable report; owned */
} tandem_verify_report;

/** Re-simulates a replay and compares every recorded hash and keyframe
 * (max_ticks: UINT64_MAX for all). The returned status is TANDEM_OK when
 * the check ran (a mismatch is reported in the report, not as an error). */
TANDEM_C_API tandem_status tandem_verify_replay(tandem_replay_id replay, uint64_t max_ticks, bool locate,
                                                tandem_verify_report* out_report);
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
  int32_t ticks;          /**< ticks to run */
  int32_t rollback;       /**< ticks rolled back after each tick, 1…1024; default 8 */
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

#ifdef __cplusplus
}  /* extern "C" */
#endif

#endif /* TANDEM_C_H */

/* tandem_c_base.h — the C API's scalars, status codes, number conversions,
 * value types, handles, definitions and geometry. Part of the C API; include
 * tandem_c.h (the umbrella) or this file alone. The conventions (numbers,
 * handles, errors, buffers) are in tandem_c.h. */
#ifndef TANDEM_C_BASE_H
#define TANDEM_C_BASE_H

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

/* Marks a function kept for one release under its old name; the message
 * names the replacement (see "Naming and deprecations" in README.md). */
#if defined(TANDEM_C_BUILDING) || defined(TANDEM_C_NO_DEPRECATION_WARNINGS)
#define TANDEM_C_DEPRECATED(message)
#elif defined(__GNUC__)
#define TANDEM_C_DEPRECATED(message) __attribute__((deprecated(message)))
#elif defined(_MSC_VER)
#define TANDEM_C_DEPRECATED(message) __declspec(deprecated(message))
#else
#define TANDEM_C_DEPRECATED(message)
#endif

#ifdef __cplusplus
extern "C" {
#endif

/** The version of this header's ABI (bumped on any incompatible change). */
#define TANDEM_C_ABI_VERSION 4  /* 2: joints, profile, session; joint_count and joint commands appended;
                                   3: tandem_world_def gained worker_count and the task callbacks;
                                   4: every tick is int64_t (tandem_synctest_options.ticks and .rollback
                                      widened from int32_t; the uint64_t ticks keep their size) */

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
/** |v|, m (fixed/vec2.h length: the engine's integer square root). */
TANDEM_C_API tandem_q32 tandem_vec2_length(tandem_vec2 v);
/** |b − a|, m (fixed/vec2.h distance). */
TANDEM_C_API tandem_q32 tandem_vec2_distance(tandem_vec2 a, tandem_vec2 b);

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
/** The user task system (tandem_world_def.enqueue_task / finish_task)
 * misbehaved in this step; tandem_step_result.task_status says how. The step
 * was still completed in full, with the same bits as a correct task system. */
#define TANDEM_STEP_FLAG_TASK_FAILURE 2u

/** Most worker threads a world may use (tandem_world_def.worker_count). */
#define TANDEM_MAX_WORKERS 16

/** One piece of a step's parallel work (physics/defs.h TaskFunction): call
 * it with a sub-range [begin, end) of the items [0, item_count) that
 * enqueue_task received, and the task_context it received, from any thread.
 * Every item must be covered by exactly one call between enqueue_task and the
 * return of finish_task; the order and the threads do not change any bit. */
typedef void (*tandem_task_fn)(int32_t begin, int32_t end, void* task_context);
/** A user task system's enqueue: start running `task` over [0, item_count)
 * (item_count >= 1) in ranges of at least min_range items (a hint) and return
 * a non-NULL handle for finish_task. `user_context` is
 * tandem_world_def.user_task_context. NULL is reported as a task failure
 * (the items then run on the stepping thread; finish_task is not called). */
typedef void* (*tandem_enqueue_task_fn)(tandem_task_fn task, int32_t item_count, int32_t min_range,
                                        void* task_context, void* user_context);
/** A user task system's finish: return only when every item of the task
 * behind `user_task` has run. Called once per successful enqueue_task, on the
 * stepping thread, before the step goes on. */
typedef void (*tandem_finish_task_fn)(void* user_task, void* user_context);

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
  /** Threads that run a step, 1…TANDEM_MAX_WORKERS; default 1. Results are
   * bit-identical for every value. Without task callbacks the world owns a
   * pool of worker_count − 1 threads. */
  int32_t worker_count;
  /** Optional user task system (both or neither), used when worker_count > 1:
   * each parallel stage is one enqueue_task / finish_task pair. */
  tandem_enqueue_task_fn enqueue_task;
  tandem_finish_task_fn finish_task;  /**< see enqueue_task; default NULL */
  void* user_task_context;            /**< passed to enqueue_task and finish_task; default NULL */
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

#ifdef __cplusplus
}  /* extern "C" */
#endif

#endif /* TANDEM_C_BASE_H */

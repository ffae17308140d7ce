/* tandem_c_world.h — worlds, bodies, shapes, queries and events (physics/tandem.h).
 * Part of the C API; include tandem_c.h (the umbrella) or this file alone.
 * The conventions (numbers, handles, errors, buffers) are in tandem_c.h. */
#ifndef TANDEM_C_WORLD_H
#define TANDEM_C_WORLD_H

#include "tandem_c_base.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------------ */
/* World                                                                     */
/* ------------------------------------------------------------------------ */

/** Counts of a world. */
typedef struct tandem_world_counters {
  int32_t body_count, shape_count, solver_body_count;
  uint64_t step_count;
  int64_t arena_capacity;  /**< bytes */
  int32_t joint_count;     /**< live joints */
} tandem_world_counters;

/** Broad-phase figures of the last step. */
typedef struct tandem_broad_phase_stats {
  int32_t proxies, candidate_pairs, pairs, touching_pairs;
  uint64_t update_nanoseconds;  /**< timing only */
} tandem_broad_phase_stats;

/** A deterministic user collision filter (see tandem.h CustomFilterFn):
 * return false to keep shapes a and b apart. Called inside the step. */
typedef bool (*tandem_custom_filter_fn)(tandem_shape_id a, tandem_shape_id b, void* context);

/** Wall-clock nanoseconds of each stage of the last non-empty step
 * (WorldProfile, physics/tandem.h). Timing only: never hashed, never read by
 * the step. Sub-step stages are summed over the sub-steps; the stages sum to
 * at most total_ns. */
typedef struct tandem_world_profile {
  int64_t broad_phase_ns, narrow_phase_ns, islands_ns, events_ns, prepare_ns;
  int64_t integrate_velocities_ns, warm_start_ns, solve_ns, integrate_positions_ns, relax_ns;
  int64_t restitution_ns, store_impulses_ns, continuous_ns, finalize_ns;
  int64_t total_ns;
} tandem_world_profile;

/* The C++ RAII wrappers make_unique_world / UniqueWorld (physics/tandem.h)
 * have no C counterpart on purpose: in C, pair tandem_create_world with
 * tandem_destroy_world (bindings wrap them in their own owners). */

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
/** The outcome of tandem_world_step_ex (physics/tandem.h StepResult). */
typedef struct tandem_step_result {
  uint32_t flags;             /**< TANDEM_STEP_FLAG_* bits */
  tandem_status task_status;  /**< TANDEM_OK, or with TANDEM_STEP_FLAG_TASK_FAILURE what the task system did wrong */
  /** task_status's message ("" when TANDEM_OK), NUL-terminated, cut to fit. */
  char task_message[512];
} tandem_step_result;

/** tandem_world_step with the full result: *out_result (may be NULL) is
 * filled when the step was accepted (zeroed otherwise). The returned status
 * is the step's; a task failure does not make it fail (see task_status). */
TANDEM_C_API tandem_status tandem_world_step_ex(tandem_world_id world, tandem_q32 time_step,
                                                tandem_step_result* out_result);
/** Sets the number of threads that run the next steps, 1…TANDEM_MAX_WORKERS
 * (results stay bit-identical). Refused inside a step and out of range. */
TANDEM_C_API tandem_status tandem_world_set_worker_count(tandem_world_id world, int32_t worker_count);
/** The world's worker count (1 for an invalid handle). */
TANDEM_C_API int32_t tandem_world_worker_count(tandem_world_id world);
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
/** The per-stage timing of the last non-empty step (zeroes before the first
 * step and for an invalid handle). */
TANDEM_C_API tandem_world_profile tandem_world_get_profile(tandem_world_id world);
/** Live bodies in ascending index (buffer rule). */
TANDEM_C_API tandem_status tandem_world_bodies(tandem_world_id world, tandem_body_id* out_bodies, int32_t capacity,
                                               int32_t* out_count);
/** Selects the broad phase (TANDEM_BROAD_PHASE_*) from the next step on. */
TANDEM_C_API tandem_status tandem_world_set_broad_phase(tandem_world_id world, int32_t kind);
/** The broad phase in use (naive for an invalid handle). */
TANDEM_C_API int32_t tandem_world_broad_phase(tandem_world_id world);
/** The last step's broad-phase figures (zeroes for an invalid handle). */
TANDEM_C_API tandem_broad_phase_stats tandem_world_broad_phase_stats(tandem_world_id world);
/** Deprecated (removed next release): use tandem_world_broad_phase. */
TANDEM_C_API TANDEM_C_DEPRECATED("use tandem_world_broad_phase") int32_t
tandem_world_get_broad_phase(tandem_world_id world);
/** Deprecated (removed next release): use tandem_world_broad_phase_stats. */
TANDEM_C_API TANDEM_C_DEPRECATED("use tandem_world_broad_phase_stats") tandem_broad_phase_stats
tandem_world_get_broad_phase_stats(tandem_world_id world);
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
/** Adds the body to the simulation (true) or takes it out (false). */
TANDEM_C_API tandem_status tandem_body_set_enabled(tandem_body_id body, bool enabled);
/** Deprecated (removed next release): tandem_body_set_enabled(body, true). */
TANDEM_C_API TANDEM_C_DEPRECATED("use tandem_body_set_enabled(body, true)") tandem_status
tandem_body_enable(tandem_body_id body);
/** Deprecated (removed next release): tandem_body_set_enabled(body, false). */
TANDEM_C_API TANDEM_C_DEPRECATED("use tandem_body_set_enabled(body, false)") tandem_status
tandem_body_disable(tandem_body_id body);
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

#ifdef __cplusplus
}  /* extern "C" */
#endif

#endif /* TANDEM_C_WORLD_H */

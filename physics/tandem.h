// tandem.h — the one public header of the physics module: worlds, bodies and
// shapes as value handles, driven by free functions.
//
// Units: SI throughout (m, s, kg, rad, N), every quantity Q32.32 (Q32). The
// time step is an exact Q32.32 value passed to world_step(), for example
// Q32::from_ratio(1, 60) (the raw value nearest 1/60 s).
//
// ERROR SCHEME (one rule for every function here):
//   * A function that creates, destroys or changes something returns a Status
//     (creators return Result<Handle>). On failure nothing at all has changed,
//     and the message names the function, the culprit and why, e.g.
//       "body_set_linear_velocity: body {index 3, generation 2} was destroyed"
//       "create_body: position (2000000, 0) m is outside the world bounds ...".
//     Handle failures: null handle, a handle whose object was destroyed
//     (stale), a handle of a destroyed world, a handle that never named
//     anything, a handle of another world where one world was expected
//     (StatusCode::foreign_handle), and any change while the world is inside
//     world_step() (StatusCode::world_locked).
//   * A getter returns its value directly. Given an invalid handle it returns
//     the documented default — zero, the identity, false, a null handle — and
//     never crashes; nothing is recorded. Where a handle may be stale, call
//     body_check() / shape_check() / world_check() first for a Status that
//     says what is wrong, or *_is_valid() for a bool.
//   * Values are checked where they enter (definitions, setters, forces,
//     impulses) against the limits below and in limits.h, so that nothing a
//     user passes can make a step saturate. Refused values name the field,
//     the value and the allowed range.
//   * Nothing throws. Running out of memory is not handled (std::bad_alloc
//     from the standard containers, outside step only).
//
// NAMES AND OUTPUTS: getters are noun_property (no get_), setters
// noun_set_property, predicates noun_is_x, feature toggles noun_enable_x(bool).
// Lists of existing objects are written to (T* out_ids, int32_t capacity)
// and the full count is returned (world_bodies, body_shapes, ...); results a
// call computes go to a std::vector<T>* out, last (queries, chains); event
// lists are spans into world-owned buffers. Deprecated names are listed in
// README.md ("Naming and deprecations") and go in the next release.
//
// THREADS: worlds are independent; one world must be used by one thread at a
// time. create_world / destroy_world may be called from any thread. Inside
// world_step() a world may use worker threads (WorldDef::worker_count, its
// own pool or the application's task system); the results are bit-identical
// for every worker count and every order in which the tasks run.
//
// DETERMINISM: ids are allocated lowest-free-index first (id_pool.h), bodies
// are simulated in ascending body index, a body's shapes are kept in
// ascending shape index. The same calls in the same order give the same
// handles and the same bits on every machine.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "fixed/fixed.h"
#include "fixed/fixed_math.h"
#include "fixed/vec2.h"
#include "physics/collision.h"
#include "physics/status.h"
#include "physics/defs.h"
#include "physics/ids.h"
#include "physics/limits.h"

namespace tandem {

using namespace tandem::literals;

// ---------------------------------------------------------------------------
// Limits checked by this API, beyond limits.h
// ---------------------------------------------------------------------------

/// Most worlds alive at once in one process.
inline constexpr int32_t k_max_worlds = 128;
/// Most bodies, and most shapes, in one world.
inline constexpr int32_t k_max_bodies = 1 << 24;
inline constexpr int32_t k_max_shapes = 1 << 24;
/// Most solver sub-steps per step.
inline constexpr int32_t k_max_sub_steps = 64;
/// Longest time step, s.
inline constexpr Q32 k_max_time_step = 1_q32;
/// Largest |gravity| component, m/s².
inline constexpr Q32 k_max_gravity = 10000_q32;
/// Largest |gravity scale|, dimensionless.
inline constexpr Q32 k_max_gravity_scale = 100_q32;
/// Largest linear or angular damping, 1/s.
inline constexpr Q32 k_max_damping = 10000_q32;
/// Largest contact or joint stiffness, Hz.
inline constexpr Q32 k_max_hertz = 10000_q32;
/// Largest contact or joint damping ratio, dimensionless.
inline constexpr Q32 k_max_damping_ratio = 10000_q32;
/// Largest friction coefficient, dimensionless.
inline constexpr Q32 k_max_friction = 100_q32;
/// Largest |component| of the force accumulated on a body in one step, N
/// (k_max_body_mass × 1000 m/s²), and of the torque, N·m.
inline constexpr Q32 k_max_force = 100000000_q32;
inline constexpr Q32 k_max_torque = 100000000_q32;
/// Largest |component| of the acceleration a force may give a body, m/s²,
/// and of the angular acceleration from a torque, rad/s². Checked when the
/// force is applied; the step also clamps to these (quietly), in case the
/// body's mass changed after the force was applied.
inline constexpr Q32 k_max_linear_acceleration = 1000000_q32;
inline constexpr Q32 k_max_angular_acceleration = 1000000_q32;
/// Largest rotation of a body in one sub-step, radians: π/16 (Box2D's
/// quarter turn per step at its default 4 sub-steps). The step clamps |ω| to
/// min(k_max_angular_speed, k_max_rotation_per_sub_step / sub-step): 47 rad/s
/// at 60 Hz with 4 sub-steps.
inline constexpr Q32 k_max_rotation_per_sub_step = Q32::from_raw((k_pi.raw + 8) / 16);  // π/16 rounded to nearest

// ---------------------------------------------------------------------------
// Status
// ---------------------------------------------------------------------------


/// "world {index 0, generation 1}" (index is index1 − 1; "null world" for null).
std::string describe(WorldId id);
/// "body {index 3, generation 2}" ("null body" for null).
std::string describe(BodyId id);
/// "shape {index 5, generation 1}" ("null shape" for null).
std::string describe(ShapeId id);

// ---------------------------------------------------------------------------
// World
// ---------------------------------------------------------------------------

/// Flags world_step() raises (a bit set). Work that cannot be done is dropped
/// in id order, so two peers degrade identically.
inline constexpr uint32_t k_step_flag_body_left_bounds = 1u << 0;  ///< a body left the world bounds; it was disabled
/// The user task system (WorldDef::enqueue_task / finish_task) misbehaved in
/// this step: StepResult::task_status says how. The step was still completed
/// in full, with the same bits as a correct task system (see TaskFunction).
inline constexpr uint32_t k_step_flag_task_failure = 1u << 1;

/// The outcome of world_step(): a Status (refused steps change nothing) and
/// flags raised during an accepted step.
struct StepResult {
  Status status;
  uint32_t flags = 0;  ///< k_step_flag_* bits
  /// Ok, or (with k_step_flag_task_failure) StatusCode::invalid_argument and
  /// a message naming the stage and the first misuse of the user task system
  /// with counts of each kind, e.g. "world_step: task system: stage 'solve':
  /// enqueue_task returned null (null handles 3, ...)". The step itself was
  /// accepted (status is ok).
  Status task_status;
  /// True when the step was accepted.
  bool ok() const { return status.ok(); }
};

/// Counts and memory of a world.
struct WorldCounters {
  int32_t body_count = 0;           ///< live bodies
  int32_t shape_count = 0;          ///< live shapes
  int32_t joint_count = 0;          ///< live joints
  int32_t solver_body_count = 0;    ///< bodies simulated in the last step
  uint64_t step_count = 0;          ///< accepted non-empty steps so far
  int64_t arena_capacity = 0;       ///< bytes of the per-step stack
};

/// Creates a world from a definition made by default_world_def(). Refuses a
/// definition without the cookie or with a value out of range (the message
/// names the field), and more than k_max_worlds live worlds.
Result<WorldId> create_world(const WorldDef& def);

/// Destroys a world with all its bodies and shapes. Every handle of the world
/// becomes invalid. Refused inside world_step().
Status destroy_world(WorldId world);

/// True when the handle names a live world.
bool world_is_valid(WorldId world);

/// Ok when the handle names a live world; otherwise says why not.
Status world_check(WorldId world);

/// Owns a world and destroys it when it goes out of scope (RAII, move-only),
/// so a world cannot leak on an early return. `id` is the handle, usable with
/// every world_* function; a null `id` owns nothing.
///
///   UniqueWorld world = make_unique_world(default_world_def()).value;
///   BodyId body = create_body(world.id, default_body_def()).value;
struct UniqueWorld {
  WorldId id{};  ///< the owned world (null: none)

  UniqueWorld() = default;
  /// Takes ownership of `world` (which may be null).
  explicit UniqueWorld(WorldId world) : id(world) {}
  ~UniqueWorld() { reset(); }
  UniqueWorld(UniqueWorld&& other) noexcept : id(other.release()) {}
  UniqueWorld& operator=(UniqueWorld&& other) noexcept {
    if (this != &other) reset(other.release());
    return *this;
  }
  UniqueWorld(const UniqueWorld&) = delete;
  UniqueWorld& operator=(const UniqueWorld&) = delete;

  /// Destroys the owned world (if it is still live) and owns `world` instead.
  void reset(WorldId world = {}) {
    // A world destroyed through the handle elsewhere is stale here: nothing to do.
    if (world_is_valid(id)) (void)destroy_world(id);
    id = world;
  }
  /// Gives up ownership without destroying the world; returns its handle.
  WorldId release() {
    const WorldId world = id;
    id = WorldId{};
    return world;
  }
};

/// create_world(def) wrapped in a UniqueWorld; the status says why not (and
/// the UniqueWorld is then null).
inline Result<UniqueWorld> make_unique_world(const WorldDef& def) {
  Result<WorldId> created = create_world(def);
  return Result<UniqueWorld>{std::move(created.status), UniqueWorld{created.value}};
}

/// Advances the world by time_step seconds (Q32.32, 0 ≤ time_step ≤
/// k_max_time_step; 0 does nothing) in sub_step_count sub-steps of
/// time_step / sub_step_count (rounded to nearest, ties away from zero). Stages,
/// in order: update contacts (contact task), prepare bodies, then per
/// sub-step: integrate velocities (gravity × gravity scale, forces, damping
/// v ← v/(1 + h·c), speed clamps), warm start, solve (contact task),
/// integrate positions, relax (contact task); then restitution and store
/// impulses (contact task), and finalize (write back, clear forces, disable
/// bodies that left the bounds, update shape bounds). Makes no heap
/// allocation once the world has warmed up.
StepResult world_step(WorldId world, Q32 time_step);

/// True while the world is inside world_step() (changes are refused then).
/// False for an invalid handle.
bool world_is_locked(WorldId world);

/// The world's current settings as a definition (with the cookie set), so a
/// copy can be made with create_world(world_def(w)). Default def for an
/// invalid handle.
WorldDef world_def(WorldId world);

/// Gravity, m/s². Zero for an invalid handle.
Vec2 world_gravity(WorldId world);
/// Sets gravity, m/s²; each component |g| ≤ k_max_gravity.
Status world_set_gravity(WorldId world, Vec2 gravity);
/// Sets the number of solver sub-steps per step, 1…k_max_sub_steps.
Status world_set_sub_step_count(WorldId world, int32_t sub_step_count);
/// Sets contact stiffness (Hz, (0, k_max_hertz]), damping ratio
/// (dimensionless, [0, k_max_damping_ratio]) and the fastest overlap recovery
/// (m/s, [0, max linear speed]).
Status world_set_contact_tuning(WorldId world, Q32 hertz, Q32 damping_ratio, Q32 push_speed);
/// Sets joint stiffness (Hz, (0, k_max_hertz]) and damping ratio
/// (dimensionless, [0, k_max_damping_ratio]).
Status world_set_joint_tuning(WorldId world, Q32 hertz, Q32 damping_ratio);
/// Sets the restitution threshold, m/s, [0, max linear speed].
Status world_set_restitution_threshold(WorldId world, Q32 threshold);
/// Sets the maximum linear speed, m/s, (0, k_max_linear_speed]. Bodies now
/// faster are slowed by the next step. Refused below the contact push speed
/// or the restitution threshold.
Status world_set_max_linear_speed(WorldId world, Q32 max_linear_speed);
/// Turns sleeping on or off for the whole world.
Status world_enable_sleep(WorldId world, bool enable);
/// Turns continuous collision (WorldDef::enable_continuous) on or off.
Status world_enable_continuous(WorldId world, bool enable);
/// Sets the number of threads that run the next steps, 1…k_max_workers
/// (WorldDef::worker_count); results stay bit-identical across the change.
/// Starts or stops built-in pool threads here, never inside a step. Refused
/// inside world_step() and outside 1…k_max_workers (the message names the
/// value and the range); nothing changes then.
Status world_set_worker_count(WorldId world, int32_t worker_count);
/// The world's worker count (WorldDef::worker_count); 1 for an invalid handle.
int32_t world_worker_count(WorldId world);
/// Sets the world's user data (any integer).
Status world_set_user_data(WorldId world, uint64_t user_data);
/// The world's user data; 0 for an invalid handle.
uint64_t world_user_data(WorldId world);
/// Counts and memory; zeroes for an invalid handle.
WorldCounters world_counters(WorldId world);
/// Wall-clock time of each stage of the last non-empty world_step(), in
/// nanoseconds (std::chrono::steady_clock, integers; like Box2D's b2Profile).
/// Timing only: it is not simulation state — never hashed, never in a
/// snapshot, never read by the step — so reading it (or not) changes no
/// result. Sub-step stages are summed over the sub-steps. Every field is
/// ≥ 0 and the stages sum to at most total_ns (the rest is the step's
/// bookkeeping: arena growth, buffer headroom).
struct WorldProfile {
  int64_t broad_phase_ns = 0;           ///< broad-phase pair update (part of update_contacts)
  int64_t narrow_phase_ns = 0;          ///< the rest of update_contacts: contact merge and manifolds
  int64_t islands_ns = 0;               ///< wake_touched before the solve + update_sleep after it
  int64_t events_ns = 0;                ///< events_after_contacts + events_after_step
  int64_t prepare_ns = 0;               ///< prepare_bodies + prepare_contacts (constraints, colouring)
  int64_t integrate_velocities_ns = 0;  ///< summed over sub-steps
  int64_t warm_start_ns = 0;            ///< summed over sub-steps
  int64_t solve_ns = 0;                 ///< summed over sub-steps
  int64_t integrate_positions_ns = 0;   ///< summed over sub-steps
  int64_t relax_ns = 0;                 ///< summed over sub-steps
  int64_t restitution_ns = 0;           ///< approach-velocity records per sub-step + the restitution stage
  int64_t store_impulses_ns = 0;        ///< impulses back to the contacts for warm starting
  int64_t continuous_ns = 0;            ///< continuous collision (time of impact)
  int64_t finalize_ns = 0;              ///< write back, clear forces, bounds check, shape AABBs
  int64_t total_ns = 0;                 ///< the whole world_step(), validation to unlock
};

/// The per-stage timing of the last non-empty world_step() (see
/// WorldProfile); zeroes before the first step and for an invalid handle. A
/// refused step or one of 0 s leaves it unchanged.
WorldProfile world_profile(WorldId world);

/// Writes up to `capacity` handles of live bodies, in ascending body index,
/// to out_ids (may be null when capacity is 0); returns the number of live
/// bodies (0 for an invalid handle).
int32_t world_bodies(WorldId world, BodyId* out_ids, int32_t capacity);

/// Broad-phase figures of the last step (broad_phase.h). Every broad phase
/// reports the same `pairs` for the same world; the others describe its work.
struct BroadPhaseStats {
  int32_t proxies = 0;          ///< shapes that took part (live, not sensors, on enabled bodies)
  int32_t candidate_pairs = 0;  ///< pairs the structure tested with the exact fattened-bounds test
  int32_t pairs = 0;            ///< pairs emitted to the contact stage (≤ candidate_pairs for all but naive)
  int32_t touching_pairs = 0;   ///< emitted pairs whose manifold has ≥ 1 point (false-positive ratio
                                ///< = 1 − touching_pairs / pairs)
  uint64_t update_nanoseconds = 0;  ///< wall time of the broad phase (steady clock); timing only, it never
                                    ///< feeds back into the simulation
  /// Contacts with a simulated body at the start of the last step (the rest
  /// belong to sleeping islands or lie between bodies that cannot move).
  int32_t awake_contacts = 0;
  /// Contact records the last step read after its contact update (prepare and
  /// colouring, the wake scan and waking, islands, events), counted per pass;
  /// with a sleeping pile and nothing waking it, a few times awake_contacts,
  /// never the whole list. A work counter, not state.
  int64_t contacts_read_after_update = 0;
  /// Proxies whose pairs the last update searched for: every proxy, or, when
  /// few changed (box, kind or filter) since the update before, only those —
  /// the pairs between unchanged proxies are carried over. With a sleeping
  /// pile and nothing moving, 0. A work counter, not state.
  int32_t proxies_searched = 0;
  /// Pairs the last update kept from the update before without a search.
  int32_t pairs_carried = 0;
};

/// Selects the broad phase used from the next step on (any BroadPhaseKind).
/// Every kind gives the same pairs, so results are bit-identical whichever
/// is used; only speed differs. Refused inside world_step() and for an
/// unknown kind.
Status world_set_broad_phase(WorldId world, BroadPhaseKind kind);
/// The broad phase in use; naive for an invalid handle.
BroadPhaseKind world_broad_phase(WorldId world);
/// The last step's broad-phase figures; zeroes before the first step and for
/// an invalid handle.
BroadPhaseStats world_broad_phase_stats(WorldId world);
/// Deprecated (removed next release): the getters drop `get_`.
[[deprecated("use world_broad_phase")]] inline BroadPhaseKind world_get_broad_phase(WorldId world) {
  return world_broad_phase(world);
}
[[deprecated("use world_broad_phase_stats")]] inline BroadPhaseStats world_get_broad_phase_stats(WorldId world) {
  return world_broad_phase_stats(world);
}

/// A user collision filter: return false to keep shapes a and b (a's index
/// below b's) from forming a contact. Called inside world_step() — by the
/// broad phase and by continuous collision, always on the thread that called
/// world_step(), never on a worker — for pairs that passed the
/// category/mask/group test. It MUST be deterministic — a pure function of
/// its arguments and of data that every peer holds identically — and must not
/// change the world (changes are refused while the step runs).
using CustomFilterFn = bool (*)(ShapeId a, ShapeId b, void* context);
/// Installs a custom filter (null removes it); `context` is passed back
/// unchanged. Refused inside world_step().
Status world_set_custom_filter(WorldId world, CustomFilterFn filter, void* context);

// ---------------------------------------------------------------------------
// Bodies
// ---------------------------------------------------------------------------

/// Creates a body from a definition made by default_body_def(). Refuses: no
/// cookie, position outside the world bounds, a zero rotation, speed above
/// the world's maximum, |ω| > k_max_angular_speed, velocity on a static body,
/// damping or gravity scale out of range. A dynamic body without shapes has
/// mass 1 kg and no rotational inertia until shapes give it mass.
Result<BodyId> create_body(WorldId world, const BodyDef& def);

/// Destroys a body and all its shapes. Refused inside world_step().
Status destroy_body(BodyId body);

/// True when the handle names a live body.
bool body_is_valid(BodyId body);

/// Ok when the handle names a live body — and, if expected_world is not null,
/// one of that world (else StatusCode::foreign_handle); otherwise says why not.
Status body_check(BodyId body, WorldId expected_world = {});

/// The world of a body (the handle's world field; null for a null handle).
WorldId body_world(BodyId body);

/// The body's type; static for an invalid handle.
BodyType body_type(BodyId body);
/// Changes the type. To dynamic: mass comes from the shapes (refused if it
/// breaks the mass limits). To static: velocity and forces are cleared. To
/// kinematic: forces are cleared, velocity kept. Wakes the body.
Status body_set_type(BodyId body, BodyType type);

/// World position of the body origin, m; zero for an invalid handle.
Vec2 body_position(BodyId body);
/// World rotation; identity for an invalid handle.
Rot body_rotation(BodyId body);
/// World angle in radians, in [−π, π]; 0 for an invalid handle.
Q32 body_angle(BodyId body);
/// The origin pose; identity for an invalid handle.
Transform body_transform(BodyId body);
/// Moves the body (teleport): origin position (m, inside the world bounds)
/// and rotation (any non-zero (c, s), normalised). Velocity is kept; shape
/// bounds are updated at once.
Status body_set_transform(BodyId body, Vec2 position, Rot rotation);
/// World position of the centre of mass, m; zero for an invalid handle.
Vec2 body_world_center(BodyId body);
/// Centre of mass in the body frame, m; zero for an invalid handle.
Vec2 body_local_center(BodyId body);

/// Velocity of the centre of mass, m/s; zero for an invalid handle.
Vec2 body_linear_velocity(BodyId body);
/// Sets the velocity of the centre of mass, m/s: |v| ≤ the world's maximum
/// linear speed. Refused (unless zero) on a static body. Wakes the body if
/// non-zero.
Status body_set_linear_velocity(BodyId body, Vec2 velocity);
/// Angular velocity, rad/s (counter-clockwise positive); 0 for an invalid
/// handle.
Q32 body_angular_velocity(BodyId body);
/// Sets the angular velocity, rad/s, |ω| ≤ k_max_angular_speed. Refused
/// (unless zero) on a static or fixed-rotation body. The step may clamp it
/// further (see k_max_rotation_per_sub_step). Wakes the body if non-zero.
Status body_set_angular_velocity(BodyId body, Q32 angular_velocity);
/// Velocity of a world point moving with the body, m/s; zero for an invalid
/// handle.
Vec2 body_point_velocity(BodyId body, Vec2 world_point);

/// Adds a force (N) at a world point (m) for the next step; also adds the
/// torque (point − centre) × force; the point must be inside the world
/// bounds. Only enabled dynamic bodies take forces (others: ok, no effect). A
/// sleeping body takes it only with wake = true (and wakes); otherwise the
/// call does nothing. Refused when the accumulated force or
/// torque would exceed k_max_force / k_max_torque, or the acceleration
/// k_max_linear_acceleration / k_max_angular_acceleration.
Status body_apply_force(BodyId body, Vec2 force, Vec2 world_point, bool wake);
/// Adds a force (N) at the centre of mass; as body_apply_force otherwise.
Status body_apply_force_to_center(BodyId body, Vec2 force, bool wake);
/// Adds a torque (N·m) for the next step; as body_apply_force otherwise.
Status body_apply_torque(BodyId body, Q32 torque, bool wake);
/// Applies an impulse (N·s) at a world point (m) now: v += J/m (J × 1/m,
/// rounded once per component), ω += (1/I)·((point − centre) × J). Enabled
/// dynamic bodies only (others: ok, no effect); sleeping bodies only with
/// wake; the point must be inside the world bounds. Refused
/// when the new speed would exceed the world's maximum or |ω| would exceed
/// k_max_angular_speed.
Status body_apply_linear_impulse(BodyId body, Vec2 impulse, Vec2 world_point, bool wake);
/// Applies an impulse (N·s) at the centre of mass: v += J/m. As
/// body_apply_linear_impulse otherwise.
Status body_apply_linear_impulse_to_center(BodyId body, Vec2 impulse, bool wake);
/// Applies an angular impulse (N·m·s): ω += L/I. As body_apply_linear_impulse
/// otherwise.
Status body_apply_angular_impulse(BodyId body, Q32 impulse, bool wake);

/// Mass, kg (0 for static and kinematic bodies and an invalid handle).
Q32 body_mass(BodyId body);
/// Rotational inertia about the centre of mass, kg·m² (0 if none or invalid).
Q32 body_rotational_inertia(BodyId body);
/// Mass, local centre of mass and rotational inertia about it; zeroes for an
/// invalid handle. Recomputed whenever shapes are added, removed or change
/// density, and when the type changes.
MassData body_mass_data(BodyId body);

/// Linear damping, 1/s; 0 for an invalid handle.
Q32 body_linear_damping(BodyId body);
/// Sets linear damping, 1/s, [0, k_max_damping]: each sub-step v ← v/(1 + h·c).
Status body_set_linear_damping(BodyId body, Q32 damping);
/// Angular damping, 1/s; 0 for an invalid handle.
Q32 body_angular_damping(BodyId body);
/// Sets angular damping, 1/s, [0, k_max_damping]: each sub-step ω ← ω/(1 + h·c).
Status body_set_angular_damping(BodyId body, Q32 damping);
/// Gravity scale, dimensionless; 0 for an invalid handle.
Q32 body_gravity_scale(BodyId body);
/// Sets the gravity scale, |s| ≤ k_max_gravity_scale.
Status body_set_gravity_scale(BodyId body, Q32 scale);

/// True when the body never rotates; false for an invalid handle.
bool body_is_fixed_rotation(BodyId body);
/// Fixes or frees the rotation. Fixing zeroes ω and the inverse inertia.
Status body_set_fixed_rotation(BodyId body, bool fixed);
/// True when the body is a bullet; false for an invalid handle.
bool body_is_bullet(BodyId body);
/// Marks the body as a bullet (continuous collision against dynamic bodies,
/// in the continuous-collision task).
Status body_set_bullet(BodyId body, bool bullet);

/// True when the body takes part in the simulation; false for an invalid
/// handle.
bool body_is_enabled(BodyId body);
/// Adds the body to the simulation (enabled = true; velocity as it was when
/// disabled) or takes it out (false): a disabled body keeps its pose and
/// velocity, does not move and does not collide; its forces are cleared and
/// the bodies it touched are woken. No change when already so.
Status body_set_enabled(BodyId body, bool enabled);
/// Deprecated (removed next release): body_set_enabled(body, true / false).
[[deprecated("use body_set_enabled(body, true)")]] inline Status body_enable(BodyId body) {
  return body_set_enabled(body, true);
}
[[deprecated("use body_set_enabled(body, false)")]] inline Status body_disable(BodyId body) {
  return body_set_enabled(body, false);
}

/// True when a non-static body is awake; false for static bodies and an
/// invalid handle.
bool body_is_awake(BodyId body);
/// Wakes the body, or puts it to sleep (velocity and forces zeroed; it does
/// not move until woken). No effect on static bodies.
Status body_set_awake(BodyId body, bool awake);
/// True when the body may sleep; false for an invalid handle.
bool body_is_sleep_enabled(BodyId body);
/// Lets the body sleep (default) or keeps it, and so its island, always awake;
/// disabling wakes it.
Status body_enable_sleep(BodyId body, bool enable);

/// The body's user data; 0 for an invalid handle.
uint64_t body_user_data(BodyId body);
/// Sets the body's user data (any integer).
Status body_set_user_data(BodyId body, uint64_t user_data);

/// A point from the body frame to the world frame, m; zero for an invalid
/// handle.
Vec2 body_world_point(BodyId body, Vec2 local_point);
/// A point from the world frame to the body frame, m; zero for an invalid
/// handle.
Vec2 body_local_point(BodyId body, Vec2 world_point);
/// A direction from the body frame to the world frame; zero for an invalid
/// handle.
Vec2 body_world_vector(BodyId body, Vec2 local_vector);
/// A direction from the world frame to the body frame; zero for an invalid
/// handle.
Vec2 body_local_vector(BodyId body, Vec2 world_vector);

/// Number of shapes on the body (0 for an invalid handle).
int32_t body_shape_count(BodyId body);
/// Writes up to `capacity` of the body's shape handles, in ascending shape
/// index, to out_ids; returns the number of shapes on the body.
int32_t body_shapes(BodyId body, ShapeId* out_ids, int32_t capacity);

// ---------------------------------------------------------------------------
// Shapes
// ---------------------------------------------------------------------------

/// Attaches a circle (body frame, m) to a body. Refuses: no cookie, friction,
/// restitution or density out of range, geometry rejected by
/// validate_circle(), a shape reaching farther than k_max_shape_size from the
/// body origin, and — on a dynamic body — a shape mass below
/// k_min_body_mass or a body mass or inertia beyond limits.h. Updates the
/// body's mass.
Result<ShapeId> create_circle_shape(BodyId body, const ShapeDef& def, const Circle& circle);
/// Attaches a capsule (body frame, m); as create_circle_shape.
Result<ShapeId> create_capsule_shape(BodyId body, const ShapeDef& def, const Capsule& capsule);
/// Attaches a convex polygon (body frame, m; made by make_polygon / make_box*,
/// checked with validate_polygon); as create_circle_shape.
Result<ShapeId> create_polygon_shape(BodyId body, const ShapeDef& def, const Polygon& polygon);
/// Attaches a two-sided segment (body frame, m). Segments have no area and
/// add no mass; as create_circle_shape otherwise.
Result<ShapeId> create_segment_shape(BodyId body, const ShapeDef& def, const Segment& segment);

/// Attaches a chain (body frame, m) as one chain-segment shape per segment,
/// built by make_chain_segments() (collision.h): an open chain of count ≥ 4
/// points gives count − 3 segments (points[0] and points[count − 1] are ghost
/// vertices only), a loop of count ≥ 3 gives count. Chain segments are
/// one-sided — they collide only on the right of point[i] → point[i+1], so a
/// clockwise loop holds bodies inside and a counter-clockwise loop is solid
/// inside — have no mass, and let bodies slide across inner vertices without
/// catching. Every point must be within ±k_max_shape_size of the body origin.
/// The shapes are created in segment order (so in ascending shape index, each
/// taking the lowest free one) and share chain_id = the first segment's shape
/// index.
/// On success *out_shapes (may be null) receives their handles in segment
/// order; on refusal (make_chain_segments' message, or as
/// create_circle_shape) no shape is created and *out_shapes is unchanged.
/// Each segment is a shape of its own for destroy_shape() and the setters.
Status create_chain_shapes(BodyId body, const ShapeDef& def, const Vec2* points, int32_t count, bool loop,
                           std::vector<ShapeId>* out_shapes);

/// Detaches and destroys a shape and updates its body's mass.
Status destroy_shape(ShapeId shape);

/// True when the handle names a live shape.
bool shape_is_valid(ShapeId shape);
/// Ok when the handle names a live shape — and, if expected_world is not
/// null, one of that world; otherwise says why not.
Status shape_check(ShapeId shape, WorldId expected_world = {});

/// The shape's kind; circle for an invalid handle.
ShapeType shape_type(ShapeId shape);
/// The body the shape is attached to; null for an invalid handle.
BodyId shape_body(ShapeId shape);
/// The shape's geometry in its body's frame; a default geometry for an
/// invalid handle.
ShapeGeometry shape_geometry(ShapeId shape);
/// World bounds at the last step or transform change, m; zero box for an
/// invalid handle.
AABB shape_aabb(ShapeId shape);
/// The shape's own mass data (body frame) from its density; zeroes for an
/// invalid handle or a segment.
MassData shape_mass_data(ShapeId shape);

// Material mixing for a contact between shapes A and B (recomputed every
// step, so the setters below apply at once):
//   friction    = sqrt(friction_A · friction_B)  (rounded to nearest; a
//                 frictionless shape makes the pair frictionless)
//   restitution = max(restitution_A, restitution_B); it applies only to
//                 approaches faster than the world's restitution threshold.
// Sensor shapes never form contacts; a pair forms one only when at least one
// body is dynamic and the filters agree (see Filter).

/// Friction coefficient; 0 for an invalid handle.
Q32 shape_friction(ShapeId shape);
/// Sets the friction coefficient, [0, k_max_friction].
Status shape_set_friction(ShapeId shape, Q32 friction);
/// Restitution; 0 for an invalid handle.
Q32 shape_restitution(ShapeId shape);
/// Sets restitution, [0, 1].
Status shape_set_restitution(ShapeId shape, Q32 restitution);
/// Density, kg/m²; 0 for an invalid handle.
Q32 shape_density(ShapeId shape);
/// Sets density, (0, k_max_density] kg/m², and updates the body's mass
/// (refused if the body's mass would break the limits).
Status shape_set_density(ShapeId shape, Q32 density);
/// True for a sensor shape; false for an invalid handle.
bool shape_is_sensor(ShapeId shape);
/// The collision filter; the default filter for an invalid handle.
Filter shape_filter(ShapeId shape);
/// Sets the collision filter.
Status shape_set_filter(ShapeId shape, Filter filter);
/// The shape's user data; 0 for an invalid handle.
uint64_t shape_user_data(ShapeId shape);
/// Sets the shape's user data (any integer).
Status shape_set_user_data(ShapeId shape, uint64_t user_data);

}  // namespace tandem

// The event and query APIs live in their own headers, part of this one.
#include "physics/events.h"
#include "physics/joint.h"
#include "physics/query.h"

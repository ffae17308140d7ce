// defs.h — definition structs for worlds, bodies and shapes, and the
// default_*_def() functions that make them. Nothing else lives here.
//
// Every field has a default and a unit. Get a definition only from its
// default_*_def() function, then change the fields you need: the function
// stamps `internal_cookie`, and create_world / create_body / create_*_shape
// refuse (with a Status naming the struct) a definition whose cookie is
// missing — a definition made as `BodyDef def{}` would otherwise silently
// carry zeroes where the defaults below were meant (Box2D types.c does the
// same with an assert; here it is a checked error in every build).
//
// All quantities are Q32.32 in SI units: metres, seconds, kilograms, radians.
// Where a value must lie in a range, the range is stated; create_* checks it
// and refuses values outside (see tandem.h for the limits).
#pragma once

#include <cstdint>

#include "fixed/fixed.h"
#include "fixed/vec2.h"
#include "physics/limits.h"

namespace tandem {

/// The value default_*_def() writes into internal_cookie ("TAND").
inline constexpr int32_t k_def_cookie = 0x54414E44;

/// Which broad phase a world uses. Every kind reports exactly the same pair
/// list (broad_phase.h), so the choice changes speed, never results.
enum class BroadPhaseKind : int32_t {
  naive = 0,            ///< every shape AABB against every other, in shape id order (O(n²))
  sweep_and_prune = 1,  ///< persistent sorted end points on x, insertion sort (still scenes)
  grid = 2,             ///< uniform hash grid sized by the largest moving proxy (many similar shapes)
  tree = 3,             ///< dynamic AABB tree with fattened boxes (mixed sizes)
};

/// How a body moves.
enum class BodyType : int32_t {
  static_body = 0,     ///< never moves; zero velocity; infinite mass
  kinematic_body = 1,  ///< moves at its set velocity; ignores forces, gravity and contacts; infinite mass
  dynamic_body = 2,    ///< moved by gravity, forces, impulses and contacts; positive mass
};

/// Most worker threads a world may use (WorldDef::worker_count).
inline constexpr int32_t k_max_workers = 16;

/// One piece of a step's parallel work, handed to a user task system (see
/// WorldDef::enqueue_task). Call it with a sub-range [begin, end) of the
/// item range [0, item_count) that enqueue_task received, and the
/// task_context it received, from any thread. Every item must be covered by
/// exactly one call between enqueue_task and the return of finish_task;
/// calls may come in any order and on any threads, and the results do not
/// depend on which. Misuse is caught, never fatal: an item passed twice runs
/// once (the second call skips it), a range outside [0, item_count) or with
/// begin > end is ignored, an item never passed runs on the stepping thread
/// after finish_task returns, and a call after finish_task returned — or
/// after the world was destroyed — does nothing; each is reported by
/// world_step (k_step_flag_task_failure, StepResult::task_status), and the
/// step's results stay bit-identical. (A call that races with
/// destroy_world() is not detected: finish every task before destroying.)
using TaskFunction = void (*)(int32_t begin, int32_t end, void* task_context);

/// A user task system's enqueue: start running `task` over the items
/// [0, item_count) (item_count ≥ 1), in ranges of at least min_range items
/// (a hint; smaller ranges are correct too), and return a non-null handle
/// that finish_task will receive. `user_context` is WorldDef::user_task_context.
/// Returning null is reported as a task failure (the items not yet run then
/// run on the stepping thread; finish_task is not called for it).
using EnqueueTaskFunction = void* (*)(TaskFunction task, int32_t item_count, int32_t min_range, void* task_context,
                                      void* user_context);

/// A user task system's finish: return only when every item of the task
/// behind `user_task` (a handle enqueue_task returned) has run. Called once
/// per successful enqueue_task, on the stepping thread, before world_step()
/// goes on.
using FinishTaskFunction = void (*)(void* user_task, void* user_context);

/// Settings of a world. Make with default_world_def().
struct WorldDef {
  Vec2 gravity;                    ///< m/s²; default (0, −10); each component |g| ≤ k_max_gravity
  int32_t sub_step_count = 0;      ///< solver sub-steps per step; default 4; 1…k_max_sub_steps
  Q32 contact_hertz;               ///< contact stiffness, Hz; default 30 (as Box2D v3); (0, k_max_hertz]
  Q32 contact_damping_ratio;       ///< contact damping, dimensionless; default 10; [0, k_max_damping_ratio]
  Q32 max_contact_push_speed;      ///< fastest overlap recovery, m/s; default 3; [0, max_linear_speed]
  Q32 joint_hertz;                 ///< joint stiffness, Hz; default 60; (0, k_max_hertz]
  Q32 joint_damping_ratio;         ///< joint damping, dimensionless; default 2; [0, k_max_damping_ratio]
  Q32 restitution_threshold;       ///< approach speed below which restitution is ignored, m/s; default 1;
                                   ///< [0, max_linear_speed]
  Q32 hit_event_threshold;         ///< approach speed above which a contact reports a hit event, m/s;
                                   ///< default 1; [0, max_linear_speed] (events.h)
  Q32 max_linear_speed;            ///< bodies are slowed to this speed each sub-step, m/s; default 400;
                                   ///< (0, k_max_linear_speed]
  AABB bounds;                     ///< bodies must start and stay inside, m; default ±k_max_world_coordinate;
                                   ///< must lie within ±k_max_world_coordinate with lower < upper
  bool enable_sleep = true;        ///< let resting islands sleep (0.5 s below 0.05 m/s and 2°/s); default true
  bool enable_continuous = true;   ///< stop fast dynamic bodies at their time of impact against static and
                                   ///< kinematic shapes (bullets: all shapes); default true (continuous.cpp)
  BroadPhaseKind broad_phase = BroadPhaseKind::naive;  ///< default naive
  uint64_t user_data = 0;          ///< any integer, for the application; default 0
  /// Threads that run a step, 1…k_max_workers; default 1 (everything on the
  /// thread that calls world_step). Results are bit-identical for every
  /// value: work is split into blocks fixed by the data (never by the worker
  /// count), each block's result does not depend on the thread or order that
  /// ran it, and shared effects are merged in a fixed order. With more than 1
  /// and no task callbacks, the world owns a pool of worker_count − 1
  /// std::threads (started by create_world or world_set_worker_count, never
  /// inside a step; idle ones sleep), and the stepping thread works too. In a
  /// build without threads (CMake TANDEM_THREADS=OFF, the default for wasm)
  /// a value above 1 is accepted and the blocks run on the stepping thread,
  /// with the same bits. Not saved in snapshots (it is not simulation state).
  /// Use at most the cores the application can spare: a stage waits for
  /// every block, so a worker thread that the system preempts stalls it.
  int32_t worker_count = 1;
  /// Optional user task system (game engines bring their own job system):
  /// both null (default) for the built-in pool, or both set. Used only when
  /// worker_count > 1; each parallel stage then is one enqueue_task /
  /// finish_task pair. See TaskFunction for what a task system must do and
  /// how misuse is reported. Set both or neither, else create_world refuses.
  EnqueueTaskFunction enqueue_task = nullptr;
  FinishTaskFunction finish_task = nullptr;  ///< see enqueue_task
  void* user_task_context = nullptr;         ///< passed to enqueue_task and finish_task; default null
  int32_t internal_cookie = 0;     ///< set by default_world_def(); do not touch
};

/// Settings of a new body. Make with default_body_def().
struct BodyDef {
  BodyType type = BodyType::static_body;  ///< default static
  Vec2 position;                          ///< world position of the body origin, m; default (0, 0);
                                          ///< inside the world bounds
  Rot rotation;                           ///< world rotation; default identity; any non-zero (c, s),
                                          ///< normalised on creation
  Vec2 linear_velocity;                   ///< of the centre of mass, m/s; default 0;
                                          ///< |v| ≤ world max_linear_speed; must be 0 for static bodies
  Q32 angular_velocity;                   ///< rad/s; default 0; |ω| ≤ k_max_angular_speed; 0 for static
  Q32 linear_damping;                     ///< 1/s; default 0; [0, k_max_damping]
  Q32 angular_damping;                    ///< 1/s; default 0; [0, k_max_damping]
  Q32 gravity_scale;                      ///< dimensionless; default 1; |s| ≤ k_max_gravity_scale
  uint64_t user_data = 0;                 ///< any integer, for the application; default 0
  bool enable_sleep = true;               ///< may this body sleep; default true
  bool is_awake = true;                   ///< start awake (a body created asleep starts at rest: its
                                          ///< velocity is ignored); default true
  bool fixed_rotation = false;            ///< never rotate (infinite rotational inertia); default false
  bool is_bullet = false;                 ///< when fast, also swept against dynamic bodies, not only
                                          ///< static and kinematic ones (continuous.cpp); default false
  bool is_enabled = true;                 ///< take part in the simulation; default true
  int32_t internal_cookie = 0;            ///< set by default_body_def(); do not touch
};

/// Collision filtering: shapes A and B may collide when
/// (A.category & B.mask) != 0 and (B.category & A.mask) != 0, unless both
/// share a non-zero group: a positive shared group always collides, a negative
/// one never does (applied by the contact task).
struct Filter {
  uint64_t category_bits = 1;        ///< the layers this shape is on; default layer 1
  uint64_t mask_bits = UINT64_MAX;   ///< the layers it collides with; default all
  int32_t group_index = 0;           ///< default 0 (no group)
};

/// Settings of a new shape. Make with default_shape_def().
struct ShapeDef {
  Q32 friction;                 ///< Coulomb coefficient, dimensionless; default 0.6; [0, k_max_friction]
  Q32 restitution;              ///< bounciness, dimensionless; default 0; [0, 1]
  Q32 density;                  ///< kg/m²; default 1; (0, k_max_density]
  Filter filter;                ///< default: category 1, mask all, group 0
  uint64_t user_data = 0;       ///< any integer, for the application; default 0
  bool is_sensor = false;       ///< detects overlap, never pushes; reports sensor events (events.h); default false
  bool enable_hit_events = false;  ///< report hit events for this shape's contacts (events.h); default false
  int32_t internal_cookie = 0;  ///< set by default_shape_def(); do not touch
};

/// A world definition with every default filled in (see WorldDef).
WorldDef default_world_def();
/// A body definition with every default filled in (see BodyDef).
BodyDef default_body_def();
/// A shape definition with every default filled in (see ShapeDef).
ShapeDef default_shape_def();

}  // namespace tandem

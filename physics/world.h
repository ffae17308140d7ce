// world.h — the World record, the world registry and the step stages
// (internal).
//
// A World owns every record of its simulation in arrays indexed by id index
// (bodies, body sims, shapes, shape geometry), the id pools that hand out
// those indices, and the per-step arena. The process-wide registry maps a
// WorldId's slot to its World; slots are taken lowest-first, and each slot's
// generation is bumped when its world is destroyed.
//
// The step is a fixed list of stages (world.cpp, world_step), each a function
// of (World*, StepContext*). The contact stages call contact.cpp and
// contact_solver.cpp:
//
//   update_contacts            broad-phase pairs → contacts → manifolds (contact.cpp)
//   wake_touched               wake sleeping islands touched by awake bodies (island.cpp)
//   prepare_bodies             gather simulated bodies into solver arrays (arena)
//   prepare_contacts           contact constraints from manifolds (contact_prepare.cpp)
//   for each sub-step (h = dt / n):
//     record_approach          each contact point's normal velocity before gravity (bounce reference)
//     integrate_velocities     v ← v/(1 + h·c) + h·(s·g + F/m); ω likewise; clamp speeds
//     warm_start               apply the accumulated impulses
//     solve                    soft contact constraints with bias, bounces latched
//     integrate_positions      c ← c + h·v; q ← integrate_rotation(q, h·ω)
//     relax                    constraints without bias (+2 passes where a bounce latched)
//   restitution                empty: bounces are solved inside the sub-steps (contact_solver.cpp)
//   store_impulses             for warm starting; frees the constraints
//   continuous                 fast bodies stop at their first time of impact (continuous.cpp)
//   project_joints             revolute joint gaps beyond 3 mm closed by moving poses (joint_solver.cpp)
//   finalize_bodies            write back, clear forces, leave-bounds check, shape AABBs
//   update_sleep               sleep timers, union-find islands, islands to sleep (island.cpp)
//
// The issue lists "integrate velocities → update contacts → solve → ...": with
// sub-steps, velocity integration happens inside the sub-step loop, so
// contacts are updated once, before it, from the poses at the start of the
// step (as Box2D v3's b2Collide precedes b2Solve).
#pragma once

#include <cstdint>
#include <vector>

#include "physics/arena.h"
#include "physics/body.h"
#include "physics/broad_phase.h"
#include "physics/contact.h"
#include "physics/contact_solver.h"
#include "physics/event_state.h"
#include "physics/defs.h"
#include "physics/id_pool.h"
#include "physics/island.h"
#include "physics/joint_state.h"
#include "physics/ids.h"
#include "physics/shape.h"
#include "physics/tandem.h"
#include "physics/task.h"

namespace tandem {

/// What one step computes and shares between stages. Arrays come from the
/// world's arena and live until finalize_bodies, which frees them; a stage
/// that allocates after prepare_bodies must free its arrays before finalize
/// (the arena is a stack), and update_contacts must free before
/// prepare_bodies or keep its arrays below the body arrays for the whole
/// step.
struct StepContext {
  Q32 dt;                          ///< the step, s
  Q32 h;                           ///< the sub-step dt / n, s, rounded to nearest
  int32_t sub_step_count = 0;      ///< n
  Q32 max_linear_speed;            ///< m/s
  Q32 max_angular_speed;           ///< rad/s: min(k_max_angular_speed, k_max_rotation_per_sub_step / h)
  int32_t solver_body_count = 0;
  int32_t* solver_to_body = nullptr;   ///< body index of each solver body, ascending
  int32_t* body_to_solver = nullptr;   ///< solver index of each body index, or k_null_index
  BodyState* states = nullptr;         ///< per solver index
  SolverBodyParams* params = nullptr;  ///< per solver index
  uint32_t flags = 0;                  ///< k_step_flag_* raised so far
  TaskSystem* tasks = nullptr;         ///< the world's workers (task.h); parallel stages go through it

  // Contact solver (contact_solver.cpp); arena arrays freed by store_impulses.
  int32_t sub_step_index = 0;          ///< the current sub-step, 0…n−1
  Q32 inv_h;                           ///< 1/h, 1/s, rounded to nearest
  Q32 max_push_speed;                  ///< m/s (WorldDef::max_contact_push_speed)
  Q32 restitution_threshold;           ///< m/s
  Softness contact_softness;           ///< dynamic–dynamic contacts
  Softness static_softness;            ///< contacts with a body of zero inverse mass (twice the stiffness)
  int32_t constraint_count = 0;
  ContactConstraint* constraints = nullptr;  ///< by graph colour, then contact order
  int32_t colour_count = 0;            ///< colours used by the last prepare, overflow included
  int32_t overflow_constraint_count = 0;  ///< constraints in the overflow group
  /// First constraint of each colour (the overflow colour is k_contact_colour_count), and one past the last.
  int32_t colour_offsets[k_contact_colour_count + 2] = {};
  int32_t* bounce_marks = nullptr;     ///< per solver index: last sub-step with a latched bounce, or −1
  /// The colours' constraints in lane blocks (contact_lanes.h), or null on the scalar path.
  ContactLanes* lanes = nullptr;
  /// First lane block of each colour, and one past the last (colours only; the overflow stays scalar).
  int32_t lane_offsets[k_contact_colour_count + 1] = {};
  bool bounced_this_sub_step = false;  ///< some point latched a bounce in the current sub-step

  // Continuous collision (continuous.cpp).
  int32_t fast_body_count = 0;         ///< bodies that moved more than half their thinnest extent
  int32_t continuous_hits = 0;         ///< fast bodies stopped at a time of impact
};

/// A simulation world.
struct World {
  WorldId id;                        ///< this world's handle
  WorldDef def;                      ///< current settings (cookie set)

  IdPool body_pool;
  std::vector<Body> bodies;          ///< by body index (dead slots keep stale data)
  std::vector<BodySim> body_sims;    ///< by body index

  IdPool shape_pool;
  std::vector<Shape> shapes;                    ///< by shape index
  std::vector<ShapeGeometry> shape_geometries;  ///< by shape index

  BroadPhase broad_phase;            ///< pair buffers (broad_phase.h)
  std::vector<Contact> contacts;     ///< sorted by (shape_a, shape_b) (contact.h)
  std::vector<Contact> contact_scratch;  ///< the next list is built here, then swapped
  /// Derived each step by update_contacts, never state (not hashed, saved or
  /// restored; a restored world rebuilds it in its next step): indices into
  /// `contacts`, ascending, of the contacts with a simulated body (awake,
  /// enabled, not static) at the start of the step — every contact that is
  /// not carried over asleep (contact.cpp, "Awake contacts"). Left empty
  /// while awake_contacts_all (every contact has a simulated body).
  std::vector<int32_t> awake_contacts;
  /// Derived with awake_contacts: true when every contact has a simulated
  /// body, so the index is the whole list and is left empty (not written;
  /// awake_contact_count, for_each_awake_contact).
  bool awake_contacts_all = false;
  /// Counts calls that may wake a body (wake_body_island, wake_all_bodies;
  /// island.cpp). Not state; only compared with awake_contacts_wake_count.
  uint64_t wake_count = 0;
  /// wake_count when awake_contacts was built: while they are equal no body
  /// became simulated since (within a step bodies only wake, until finalize
  /// may disable some), so the index still lists every contact with a
  /// simulated body. Cleared to ~0 by a restore.
  uint64_t awake_contacts_wake_count = ~uint64_t{0};
  /// This step's update_contacts kept the contact list as it was — same keys
  /// and generations, no touching flag changed — so the touching set is last
  /// step's (events_after_step skips its diff when that set is in sync).
  bool contact_set_unchanged = false;
  /// Contact records read by the stages after update_contacts in the current
  /// or last step, counted per pass (BroadPhaseStats); a work counter, not
  /// state, never read by the step.
  int64_t contacts_read_after_update = 0;
  EventState events;                 ///< the last step's events and their buffers (events.h)
  IdPool joint_pool;                 ///< joint slots (joint.h)
  JointWorld joints;                 ///< joints, their collision filter and events (joint.h)

  Arena arena;                       ///< per-step scratch
  StepContext context;               ///< the current / last step
  uint64_t step_count = 0;           ///< accepted non-empty steps
  int32_t last_solver_body_count = 0;
  WorldProfile profile;              ///< timing of the last step; not state (never hashed or saved)
  TaskSystem tasks;                  ///< worker count, pool or user task system (task.h); not state
  bool locked = false;               ///< true inside world_step(); changes are refused
};

/// Calls visit(contact index) in ascending index for every contact that may
/// have a simulated body: the awake index (World::awake_contacts) while it is
/// complete — no body woke since update_contacts built it (wake_count) — and
/// shorter than the list (not awake_contacts_all), otherwise every contact. The visitor applies its
/// own test either way (a contact left out has no simulated body), so both
/// give the same results; only the number of contacts read differs. One call
/// site for the visitor, so it is inlined.
template <typename Visit>
void for_each_awake_contact(World& world, Visit&& visit) {
  const bool use_index = world.wake_count == world.awake_contacts_wake_count && !world.awake_contacts_all &&
                         world.awake_contacts.size() < world.contacts.size();
  const int32_t* index = use_index ? world.awake_contacts.data() : nullptr;
  const int32_t count = static_cast<int32_t>(use_index ? world.awake_contacts.size() : world.contacts.size());
  world.contacts_read_after_update += count;
  for (int32_t k = 0; k < count; ++k) visit(index != nullptr ? index[k] : k);
}

/// The number of contacts with a simulated body at the start of the step
/// (World::awake_contacts, or every contact while awake_contacts_all).
inline int32_t awake_contact_count(const World& world) {
  return static_cast<int32_t>(world.awake_contacts_all ? world.contacts.size() : world.awake_contacts.size());
}

/// The live world of a handle, or null.
World* find_world(WorldId id);

/// Resolves a world handle for `function` (named in messages); `mutating`
/// also refuses a locked world.
Status resolve_world(WorldId id, const char* function, bool mutating, World** out_world);

/// Resolves an object handle's parts against one of the world's pools (the
/// shared path of resolve_body / resolve_shape). Refuses, in this order: a
/// null handle, a world other than expected_world (when not null), a world
/// that is gone, an index never allocated, a destroyed or otherwise dead
/// generation, and (when mutating) a locked world. `kind` ("body") names the
/// handle in the message as describe() does ("body {index 3, generation 1}");
/// the text is built only on a refusal (a resolved handle allocates nothing).
Status resolve_handle(const char* function, const char* kind, uint32_t index1, uint32_t generation, WorldId world_id,
                      WorldId expected_world, bool mutating, IdPool World::*pool, World** out_world,
                      int32_t* out_index);

/// The shared path of the simple setters of a body or shape handle: resolve
/// it for `function` with `resolve` (resolve_body or resolve_shape, mutating,
/// any world), then run set(World*, index).
template <typename Id, typename Resolve, typename Set>
Status set_resolved(Id id, const char* function, Resolve resolve, Set set) {
  World* w = nullptr;
  int32_t i = 0;
  Status s = resolve(id, function, true, WorldId{}, &w, &i);
  if (!s.ok()) return s;
  return set(w, i);
}

/// The shared path of the getters of a body or shape handle: look it up with
/// `find` (find_body or find_shape), get(const World&, index), or `fallback`
/// for an invalid handle.
template <typename T, typename Id, typename Find, typename Get>
T get_found(Id id, T fallback, Find find, Get get) {
  World* w = nullptr;
  int32_t i = 0;
  if (!find(id, &w, &i)) return fallback;
  return get(*w, i);
}

/// The quiet version of resolve_handle for getters: true and the world and
/// index when the handle names a live object.
bool find_handle(uint32_t index1, uint32_t generation, WorldId world_id, IdPool World::*pool, World** out_world,
                 int32_t* out_index);

/// A Status with a code and message.
Status make_status(StatusCode code, std::string message);

// ---------------------------------------------------------------------------
// Step stages (solver.cpp)
// ---------------------------------------------------------------------------

/// The thinnest dimension and farthest point (from local_center) of a body's
/// shapes, m; both 0 without shapes (continuous.cpp).
void compute_body_extents(const World& world, int32_t body_index, Vec2 local_center, Q32* out_min, Q32* out_max);
/// Continuous collision: fast bodies (bullets also against dynamic bodies)
/// stop at their first time of impact (continuous.cpp).
void stage_continuous(World* world, StepContext* context);
/// Continuous collision's first filter: true when (|d.x| + |d.y| + turn)·2 ≤
/// min_extent with fixed.h's saturating operators, decided on exact
/// integers (the body moved too little to be fast; d is the centre's move, a
/// saturating difference; turn ≥ 0). False for a negative turn or
/// min_extent, leaving the decision to the exact test (continuous.cpp).
bool continuous_surely_slow(Vec2 d, Q32 turn, Q32 min_extent);

/// Contacts from broad-phase pairs and narrow phase. Empty until the contact
/// task.
void stage_update_contacts(World* world, StepContext* context);
/// Gathers simulated bodies (non-static, enabled, awake; ascending body index)
/// into the arena's solver arrays and computes their per-step constants.
void stage_prepare_bodies(World* world, StepContext* context);
/// Contact constraints from manifolds. Empty until the contact task.
void stage_prepare_contacts(World* world, StepContext* context);
/// Records each contact point's approach velocity (before gravity).
void stage_record_approach(World* world, StepContext* context);
/// One sub-step of velocity integration with damping and speed clamps.
void stage_integrate_velocities(World* world, StepContext* context);
/// Warm starting. Empty until the contact task.
void stage_warm_start(World* world, StepContext* context);
/// Constraint solve with bias. Empty until the contact task.
void stage_solve(World* world, StepContext* context);
/// One sub-step of position integration.
void stage_integrate_positions(World* world, StepContext* context);
/// Constraint relax without bias. Empty until the contact task.
void stage_relax(World* world, StepContext* context);
/// Restitution. Empty until the contact task.
void stage_restitution(World* world, StepContext* context);
/// Stores impulses for warm starting. Empty until the contact task.
void stage_store_impulses(World* world, StepContext* context);
/// Writes solver state back to the body sims, clears forces, disables bodies
/// that left the world bounds, updates shape bounds, and frees the arena
/// arrays.
void stage_finalize_bodies(World* world, StepContext* context);

}  // namespace tandem

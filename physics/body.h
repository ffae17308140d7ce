// body.h — body records (internal).
//
// Three records, split by who reads them how often (Box2D's b2Body /
// b2BodySim / b2BodyState split, re-derived for Q32.32 and one awake set):
//
//   Body       cold bookkeeping: type, flags, shape list, mass, user data.
//              World::bodies, indexed by body index.
//   BodySim    the persistent hot record: pose, centre of mass, velocity,
//              inverse mass and inertia, accumulated force and torque,
//              damping. World::body_sims, a contiguous array indexed by body
//              index. Authoritative between steps.
//   BodyState  the solver's per-step copy, indexed by SOLVER index: one entry
//              per simulated body (non-static, enabled, awake) in ascending
//              body index, gathered from BodySim at the start of the step and
//              written back at the end. This is what the sub-step loops
//              stream: velocity and pose in one 56-byte record, contiguous.
//   SolverBodyParams  per solver index, read-only during the sub-steps: the
//              per-sub-step velocity change from gravity and forces, the
//              damping factors and the inverse mass and inertia.
//
// Why a solver index: contact constraints (contact task) will refer to their
// two bodies by solver index (static bodies: no index, a shared zero-velocity
// dummy), precompute inverse masses from SolverBodyParams into the
// constraint, and then touch only BodyState in the inner loops. Graph
// colouring can then batch constraints whose solver indices are disjoint, and
// a wide (SoA) solver can transpose BodyState by solver index.
//
// Sizes on x86-64 (asserted as upper bounds below, printed by
// tests/physics/test_body.cpp): Body 64 bytes (with the sleep fields),
// BodySim 152, BodyState 56, SolverBodyParams 56.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "fixed/fixed.h"
#include "fixed/vec2.h"
#include "fixed/wide.h"
#include "physics/collision.h"
#include "physics/defs.h"
#include "physics/ids.h"
#include "physics/tandem.h"

namespace tandem {

struct World;

/// The null index for bodies, shapes, solver bodies.
inline constexpr int32_t k_null_index = -1;

/// Cold per-body bookkeeping, indexed by body index.
struct Body {
  BodyType type = BodyType::static_body;
  int32_t head_shape = k_null_index;  ///< first shape; the list is in ascending shape index
  int32_t shape_count = 0;
  Q32 mass;                           ///< kg; 0 for static and kinematic bodies
  Q32 rotational_inertia;             ///< kg·m² about the centre of mass (before fixed rotation)
  Q32 sleep_time;                     ///< s still, Q32.32, capped at k_time_to_sleep (island.h)
  int32_t sleep_island = k_null_index;  ///< while asleep: the island's root body index (island.h)
  uint64_t user_data = 0;
  bool enable_sleep = true;
  bool awake = true;                  ///< meaningless for static bodies
  bool enabled = true;
  bool fixed_rotation = false;
  bool bullet = false;
  Q32 min_extent;                     ///< thinnest shape dimension, m (derived from the shapes; continuous.cpp)
  Q32 max_extent;                     ///< farthest shape point from the centre of mass, m (derived)
};

/// Persistent hot state, indexed by body index.
struct BodySim {
  Transform transform;       ///< origin pose: position m, rotation
  Vec2 center;               ///< world centre of mass, m
  Vec2 local_center;         ///< centre of mass in the body frame, m
  Vec2 linear_velocity;      ///< of the centre of mass, m/s
  Q32 angular_velocity;      ///< rad/s
  Vec2 force;                ///< accumulated for the next step, N
  Q32 torque;                ///< accumulated for the next step, N·m
  Q32 inv_mass;              ///< 1/kg; 0 for static and kinematic bodies
  Q32 inv_inertia;           ///< 1/(kg·m²); 0 without rotational inertia or with fixed rotation
  Q32 linear_damping;        ///< 1/s
  Q32 angular_damping;       ///< 1/s
  Q32 gravity_scale;         ///< dimensionless
};

/// The solver's per-step body state, indexed by solver index.
struct BodyState {
  Vec2 linear_velocity;   ///< m/s
  Q32 angular_velocity;   ///< rad/s
  Vec2 center;            ///< world centre of mass, m
  Rot rotation;           ///< world rotation
};

/// Per-step constants of a solver body, indexed by solver index.
struct SolverBodyParams {
  Vec2 delta_linear_velocity;   ///< added each sub-step: h·(s·g + F/m), m/s
  Q32 delta_angular_velocity;   ///< added each sub-step: h·τ/I, rad/s
  Q32 linear_damping_factor;    ///< 1/(1 + h·c_linear), dimensionless, exactly 1 without damping
  Q32 angular_damping_factor;   ///< 1/(1 + h·c_angular)
  Q32 inv_mass;                 ///< 1/kg
  Q32 inv_inertia;              ///< 1/(kg·m²)
};

static_assert(sizeof(Body) <= 80);
static_assert(sizeof(BodySim) <= 160);
static_assert(sizeof(BodyState) <= 56);
static_assert(sizeof(SolverBodyParams) <= 56);

// ---------------------------------------------------------------------------
// Handle resolution (body.cpp)
// ---------------------------------------------------------------------------

/// Resolves a body handle for `function` (named in messages). On success
/// writes the world and the body index. `mutating` also refuses a locked
/// world; a non-null expected_world refuses a body of another world.
Status resolve_body(BodyId id, const char* function, bool mutating, WorldId expected_world, World** out_world,
                    int32_t* out_index);

/// The live body's world and index, or false (no message; for getters).
bool find_body(BodyId id, World** out_world, int32_t* out_index);

/// The handle of the live body at `index` in `world`.
BodyId make_body_id(const World& world, int32_t index);

/// True when the body is simulated by the next step: non-static, enabled,
/// awake.
inline bool body_is_simulated(const Body& body) {
  // Inline: the step's loops over bodies and contacts call it per element.
  return body.type != BodyType::static_body && body.enabled && body.awake;
}

/// Recomputes the body's mass data from its shapes (or sets the static /
/// kinematic / default values) and moves its world centre, keeping the
/// velocity of the body at the new centre consistent (v += ω × Δc). Fails
/// (changing nothing) when a dynamic body's mass or inertia breaks limits.h.
Status update_body_mass(World* world, int32_t body_index, const char* function);

/// Recomputes the world bounds of every shape of the body from its transform
/// and marks the broad phase stale for queries.
void update_body_shape_bounds(World* world, int32_t body_index);

/// update_body_shape_bounds without marking the broad phase stale: writes
/// only the body's own shapes' bounds, so blocks of bodies may run on
/// different threads (the caller marks the broad phase stale once).
void compute_body_shape_bounds(World* world, int32_t body_index);

/// Mass data of a body combined from shape masses: mass, local centre and
/// inertia about it, with inverses.
struct BodyMass {
  Q32 mass;
  Q32 rotational_inertia;
  Q32 inv_mass;
  Q32 inv_inertia;
  Vec2 local_center;
};

/// Appends the mass data of each massive shape of a dynamic body, in
/// ascending shape index; `replace_shape` (if not k_null_index) is taken at
/// `replace_density` instead of its own. Fails (see shape_mass_for_body) when
/// a shape is too light or too heavy for a dynamic body; `what` names the
/// body in messages.
Status gather_shape_masses(const World& world, int32_t body_index, int32_t replace_shape, Q32 replace_density,
                           const std::string& what, std::vector<MassData>* out);

/// Applies computed mass data to a body: inverses, local and world centre;
/// the velocity of the new centre becomes v + ω × Δc (clamped to the world's
/// maximum speed), so the body's motion is unchanged.
void apply_body_mass(World* world, int32_t body_index, const BodyMass& mass);

/// Checks, without changing anything, that the body's mass stays within
/// limits.h with one shape's density replaced and/or an extra shape's mass
/// added (either may be absent: k_null_index / null).
Status check_body_mass_with(const World& world, int32_t body_index, int32_t replace_shape, Q32 replace_density,
                            const MassData* extra, const std::string& what);

/// Combines shape mass data (any order: every sum is exact) into a body's
/// mass, refusing a total mass above k_max_body_mass or an inertia above
/// k_max_rotational_inertia. Zero mass gives the 1 kg default. `what` names
/// the body in messages.
Status combine_masses(const MassData* items, int32_t count, BodyType type, bool fixed_rotation,
                      const std::string& what, BodyMass* out_mass);

// ---------------------------------------------------------------------------
// Quiet checked arithmetic for entry checks and the step's clamps
// ---------------------------------------------------------------------------
// These round exactly like Q32 operations but saturate WITHOUT a fault
// report: they compute values that are then checked against limits (entry)
// or clamped (step), so an out-of-range intermediate is expected, not a bug.

/// a·b rounded once (nearest, ties away from zero), saturated quietly.
inline Q32 mul_quiet(Q32 a, Q32 b) {
  bool overflow = false;
  return Q32::from_raw(wide::round_shift_saturate(wide::mul_s64(a.raw, b.raw), 32, &overflow));
}

/// a + b saturated quietly to the symmetric range.
inline Q32 add_quiet(Q32 a, Q32 b) {
  int64_t r = 0;
  if (__builtin_add_overflow(a.raw, b.raw, &r) || r == INT64_MIN) return a.raw > 0 ? Q32::max() : Q32::min();
  return Q32::from_raw(r);
}

/// a × b (2D cross) rounded once, saturated quietly.
inline Q32 cross_quiet(Vec2 a, Vec2 b) {
  bool overflow = false;
  const wide::U128 p = wide::sub(wide::mul_s64(a.x.raw, b.y.raw), wide::mul_s64(a.y.raw, b.x.raw));
  return Q32::from_raw(wide::round_shift_saturate(p, 32, &overflow));
}

/// True when |v| > limit (limit ≥ 0), decided exactly on 128-bit squares.
inline bool length_exceeds(Vec2 v, Q32 limit) {
  const wide::U128 vv = wide::add(wide::mul_s64(v.x.raw, v.x.raw), wide::mul_s64(v.y.raw, v.y.raw));
  const wide::U128 ll = wide::mul_s64(limit.raw, limit.raw);
  return wide::less_u(ll, vv);  // both non-negative; vv ≤ 2^127
}

/// "(x, y)" with exact decimals, for messages.
std::string format_vec2(Vec2 v);

}  // namespace tandem

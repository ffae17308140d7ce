// island.h — sleep islands and body sleep/wake (internal).
//
// DESIGN. Islands are rebuilt every step by union-find over body indices
// (Box2D v2's per-step islands, not v3's persistent ones: one array pass, no
// island bookkeeping to keep consistent under create/destroy, and nothing to
// snapshot beyond two fields per body). Two awake dynamic bodies are in one
// island when a touching contact joins them; static and kinematic bodies
// never join islands (Box2D's rule: a floor must not tie every box on it into
// one island). The root of a set is always its lowest body index, so island
// membership and ids are functions of body indices and contact order only.
//
// Per-body timer (Body::sleep_time, s, Q32.32): after each step a simulated
// body whose linear speed is at most k_linear_sleep_tolerance and whose
// angular speed is at most k_angular_sleep_tolerance adds the step's dt
// (capped at k_time_to_sleep, so it never grows without bound); any faster
// body, a body with enable_sleep off, or any body of a world with sleep off
// resets it to 0. An island whose every body has reached k_time_to_sleep
// sleeps: each body gets awake = false, velocities and forces zeroed, and
// Body::sleep_island = the island's root index. A lone kinematic body is its
// own island.
//
// While asleep a body is not simulated: not integrated, no constraints for
// its contacts with other sleeping or static bodies, and (contact.cpp) no
// narrow phase for such contacts — they keep their manifold and impulses, so
// the island wakes warm started.
//
// Waking (Body::sleep_island names the set to wake together):
//   - after update_contacts, a touching contact between a sleeping body and
//     an awake dynamic body, or an awake kinematic body that moved in the
//     last step or was just woken (sleep_time == 0), wakes the sleeper's
//     island (stage_wake_touched; contact order, so deterministic);
//   - the body API wakes a body's island on force, torque, impulse, velocity,
//     transform, type change, shape added / removed / re-massed
//     (update_body_mass), body_set_awake(true), body_enable_sleep(false);
//   - destroying a body or changing its shapes or transform also wakes every
//     body touching it (wake_touching), static bodies included; a transform
//     also wakes every sleeper whose shape AABBs overlap the body's new ones
//     (wake_overlapping_sleepers), so a teleported wall cannot end up inside
//     sleeping bodies that never notice it;
//   - world_enable_sleep(false) wakes every body.
// A body put to sleep by hand (body_set_awake(false), BodyDef::is_awake =
// false) is an island of its own; touching sleepers of other islands are
// woken a step later, by the contact rule.
//
// Waking an island scans the body array for its members (O(bodies), only
// when a sleeping island is woken), rejected against a per-island member
// list: fewer fields to keep consistent and to snapshot.
#pragma once

#include <cstdint>

#include "fixed/fixed.h"

namespace tandem {

struct World;
struct StepContext;

/// Linear speed at or below which a body counts as still, m/s (0.05).
inline constexpr Q32 k_linear_sleep_tolerance = Q32::from_raw(214748365);  // round(0.05 · 2^32)
/// Angular speed at or below which a body counts as still, rad/s (2°/s =
/// π/90 ≈ 0.0349066).
inline constexpr Q32 k_angular_sleep_tolerance = Q32::from_raw(149922641);  // round(π/90 · 2^32)
/// Time an island's bodies must all be still before it sleeps, s (0.5).
inline constexpr Q32 k_time_to_sleep = Q32::from_raw(int64_t{1} << 31);

/// Wakes the body (non-static, asleep) and every body of its sleep island:
/// awake = true, sleep_time = 0, sleep_island = null. An awake body only has
/// its timer reset. Static bodies: nothing.
void wake_body_island(World* world, int32_t body_index);

/// Wakes the islands of every body that touches `body_index` through a
/// touching contact (either side; the body itself is not woken).
void wake_touching(World* world, int32_t body_index);

/// Wakes the island of every sleeping body with a shape whose AABB overlaps
/// one of this body's shape AABBs (a teleport can move a body, a static one
/// included, into sleepers it had no contact with). O(shapes × the body's
/// shapes); only on teleport.
void wake_overlapping_sleepers(World* world, int32_t body_index);

/// Wakes the body's island and the islands of every body touching it. With
/// wake_lone_sleeper false, a sleeping body with no touching contact stays
/// asleep (its neighbours, if any, are still woken): update_body_mass uses
/// that, so a body created asleep may get its shapes without waking.
void wake_body_and_touching(World* world, int32_t body_index, bool wake_lone_sleeper);

/// Puts one body to sleep as an island of its own (body_set_awake(false),
/// BodyDef::is_awake = false): velocities and forces zeroed.
void put_body_to_sleep(World* world, int32_t body_index);

/// Wakes every body of the world (world_enable_sleep(false)).
void wake_all_bodies(World* world);

/// Step stage after update_contacts: wakes the islands of sleeping bodies
/// touched by awake ones (see the file comment).
void stage_wake_touched(World* world, StepContext* context);

/// Step stage after finalize_bodies: updates sleep timers, builds islands by
/// union-find over touching contacts and puts islands whose bodies have all
/// been still for k_time_to_sleep to sleep. Uses (and frees) arena memory.
void stage_update_sleep(World* world, StepContext* context);

}  // namespace tandem

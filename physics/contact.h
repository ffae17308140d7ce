// contact.h — persistent contacts between shape pairs (internal).
//
// A Contact exists while the fattened AABBs of its two shapes overlap (the
// broad phase's pair list, broad_phase.h). It is keyed by (lower shape index,
// higher shape index) and World::contacts is kept sorted by that key, so the
// order in which contacts are updated, solved and (later) reported is a
// function of the shape ids alone (contact.cpp spells out the chain).
//
// Each step update_contacts() recomputes every contact's manifold from the
// start-of-step poses — with collide_persistent() for a contact that was
// touching (a polygon pair re-clips last step's edges while they still face
// each other, manifold.cpp), collide() otherwise — and carries the previous step's
// impulses over to the new points whose feature id matches an old point's
// (warm starting). A contact is "touching" when its manifold has points
// (which includes speculative points up to k_speculative_distance apart).
//
// A shape slot reused by a new shape (same index, new generation) must not
// inherit the old shape's contact: the contact remembers both shapes'
// generations and is recreated from zero when either differs.
//
// Material mixing (documented for users in tandem.h):
//   friction    = sqrt(friction_a · friction_b)   (Box2D's rule: a zero-friction
//                                                   shape makes the pair frictionless)
//   restitution = max(restitution_a, restitution_b)
// recomputed every update, so shape_set_friction / _restitution apply at once.
//
// Sizes on x86-64 (printed by tests/physics/test_contact.cpp): Contact 232
// bytes; ContactConstraint 384 bytes per step for each touching contact
// with a simulated body (ContactConstraintPoint 136).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "fixed/fixed.h"
#include "physics/collision.h"

namespace tandem {

struct World;

/// Contact flag: the manifold has at least one point.
inline constexpr uint32_t k_contact_touching = 1u << 0;

/// A persistent contact between two shapes, in World::contacts.
struct Contact {
  int32_t shape_a = 0;                  ///< lower shape index
  int32_t shape_b = 0;                  ///< higher shape index
  uint32_t generation_a = 0;            ///< shape_a's generation when the contact was made
  uint32_t generation_b = 0;            ///< shape_b's generation when the contact was made
  int32_t body_a = 0;                   ///< body index of shape_a
  int32_t body_b = 0;                   ///< body index of shape_b
  uint32_t flags = 0;                   ///< k_contact_* bits
  Q32 friction;                         ///< mixed, dimensionless
  Q32 restitution;                      ///< mixed, dimensionless
  Manifold manifold;                    ///< normal from shape_a to shape_b, world frame
  std::array<Q32, 2> normal_impulse{};  ///< per manifold point, N·s (last step's, for warm starting)
  std::array<Q32, 2> tangent_impulse{}; ///< per manifold point, N·s
};

/// The sort key of a contact (see shape_pair_key).
uint64_t contact_key(const Contact& contact);

/// Mixed friction of two shapes: sqrt(a·b), rounded to nearest.
Q32 mix_friction(Q32 a, Q32 b);
/// Mixed restitution of two shapes: max(a, b).
Q32 mix_restitution(Q32 a, Q32 b);

/// The contact stage: broad-phase pairs → World::contacts (created for new
/// pairs, destroyed for vanished ones, sorted by key) → manifolds and warm
/// start impulses matched by feature id. No heap allocation once the buffers
/// have grown to the scene.
void update_contacts(World* world);

/// Called at the end of world_step, after the arena is empty: when a contact
/// or broad-phase buffer is more than 3/4 full (the proxy buffers measured
/// against the shape capacity), grows it to twice its use plus 64 entries,
/// so the next steps of a slowly changing scene do not allocate.
void reserve_contact_headroom(World* world);

}  // namespace tandem

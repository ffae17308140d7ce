// peers.h — the peer engines' harnesses (tools only; Box2D 2.4 and
// Chipmunk2D, linked only with TANDEM_BUILD_BENCH; Box2D v3, optional, only
// with TANDEM_BOX2D_V3_DIR as well — see peer_box2d3.cpp). Each builds the scene
// from the same SceneSpec as Tandem, its doubles being the exact values of
// the spec's Q32.32 numbers (scenes.h).
//
// Matching choices:
// * Box2D 2.4: its defaults — 8 velocity / 3 position iterations, b2World
//   warm starting and continuous collision on, restitution threshold 1 m/s —
//   sleeping off. It has no capsule shape: a capsule is one body with three
//   fixtures (a box of half extents (half length, radius) and two circles at
//   the segment ends), whose union is exactly the capsule, with SetMassData
//   giving it the exact capsule mass and inertia.
// * Chipmunk2D 7: its defaults (10 iterations, collision slop 0.1 m, BB tree
//   broad phase), sleeping off (its default). Chipmunk multiplies the two
//   shapes' friction and elasticity, so every shape gets the square root of
//   the scene's value and a pair gets exactly the scene's value. A capsule is
//   a segment shape with a radius. Masses and moments are the exact
//   analytic values for each shape (the same formulas as Box2D's capsule).
#pragma once

#include "harness.h"

namespace tandem::bench {

/// Box2D 2.4 (libbox2d, as Debian builds it: Release).
Engine box2d24_engine();
/// Chipmunk2D 7 (libchipmunk, as Debian builds it: debug checks on).
Engine chipmunk_engine();
/// Box2D v3 with `workers` workers of its built-in scheduler (only when the
/// build has TANDEM_BOX2D_V3_DIR: peer_box2d3.cpp; the engine is named
/// "box2d3-w<workers>").
Engine box2d3_engine(int32_t workers);

/// Exact mass (kg) and rotational inertia about the centre (kg·m²) of a
/// spec's shape, in binary64.
void spec_mass(const BodySpec& b, double* mass, double* inertia);

}  // namespace tandem::bench

// shape.h — the shape record attached to a body (internal). The geometry
// itself (Circle, Capsule, Polygon, Segment; mass, bounds, manifolds) is
// collision.h's; this is the world's bookkeeping around it.
//
// Two arrays by shape index: Shape (what the broad phase, contact creation
// and filtering read: body, material, filter, bounds) and ShapeGeometry (read
// only by the narrow phase, mass and queries). ShapeGeometry holds every
// variant side by side (464 bytes on x86-64, 288 of them the polygon), so
// keeping it out of Shape keeps the streamed record small. A tagged union in
// collision.h would save ~170 bytes per shape (suggested to its owner).
//
// A body's shapes form a doubly linked list in ascending shape index
// (prev_shape / next_shape), so mass, bounds and (later) contact creation
// visit them in id order.
//
// Sizes on x86-64 (printed by tests/physics/test_body.cpp): Shape 112 bytes,
// ShapeGeometry 464 bytes.
#pragma once

#include <cstdint>
#include <string>

#include "fixed/vec2.h"
#include "physics/collision.h"
#include "physics/defs.h"
#include "physics/ids.h"
#include "physics/tandem.h"

namespace tandem {

struct World;

/// A shape's world bookkeeping, indexed by shape index.
struct Shape {
  int32_t body_index = -1;   ///< the body it is attached to
  int32_t prev_shape = -1;   ///< previous shape of the body (lower index) or −1
  int32_t next_shape = -1;   ///< next shape of the body (higher index) or −1
  ShapeType type = ShapeType::circle;
  Q32 friction;              ///< dimensionless
  Q32 restitution;           ///< dimensionless
  Q32 density;               ///< kg/m²
  Filter filter;
  uint64_t user_data = 0;
  AABB aabb;                 ///< world bounds, m; updated at the end of each step and on teleport
  bool is_sensor = false;
  bool enable_hit_events = false;  ///< events.h
};

static_assert(sizeof(Shape) <= 120);

/// Resolves a shape handle for `function` (named in messages); see
/// resolve_body.
Status resolve_shape(ShapeId id, const char* function, bool mutating, WorldId expected_world, World** out_world,
                     int32_t* out_index);

/// The live shape's world and index, or false (no message; for getters).
bool find_shape(ShapeId id, World** out_world, int32_t* out_index);

/// The handle of the live shape at `index` in `world`.
ShapeId make_shape_id(const World& world, int32_t index);

/// World bounds of any geometry under a transform (dispatches to
/// compute_*_aabb).
AABB compute_shape_aabb(const ShapeGeometry& geometry, Transform transform);

/// The GJK proxy of any geometry (chain segments: their segment); the
/// queries, sensor events and continuous collision use it (query.cpp).
ShapeProxy make_shape_proxy(const ShapeGeometry& geometry);

/// True when every point of the geometry, grown by its radius, lies within
/// ±k_max_shape_size of the body origin on each axis (and a polygon has 3 to
/// k_max_polygon_vertices vertices): the check create_*_shape applies, for
/// snapshot restore.
bool shape_geometry_within_reach(const ShapeGeometry& geometry);

/// Mass data of any geometry at a density (segments and chain segments: zero).
MassData compute_shape_mass(const ShapeGeometry& geometry, Q32 density);

/// The mass data of a shape on a dynamic body, refusing (with `what` naming
/// it) a shape whose mass or inertia could not be computed without saturating
/// and a massive shape lighter than k_min_body_mass. "Could not be computed":
/// with A the area of its local bounding box and r² the largest squared
/// distance of a bounding corner from the body origin, A·r² > 2^30 m⁴,
/// density·A > 2^30 kg or density·A·r² > 2^30 kg·m² (bounds on the polar
/// moment compute_*_mass forms; each is ~1000× beyond what limits.h lets a
/// body have, e.g. a 200 m square still passes). Zero-area shapes (segments)
/// give zero mass. Static and kinematic bodies never compute shape mass, so
/// their shapes may be as large as k_max_shape_size allows.
Status shape_mass_for_body(const ShapeGeometry& geometry, Q32 density, const std::string& what, MassData* out_mass);

/// Destroys a shape without touching its body's mass (destroy_body uses it).
void remove_shape(World* world, int32_t shape_index);

}  // namespace tandem

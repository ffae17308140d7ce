// query.h — world queries between steps: ray casts (closest and all hits),
// AABB overlap, point query and shape overlap. Public API (included by
// tandem.h).
//
// WHAT IS SEARCHED. Live shapes on enabled bodies whose filter passes the
// QueryFilter (shape.category & query.mask and query.category & shape.mask
// both non-zero). Sensor shapes only with QueryFilter::include_sensors.
// Bounds are the shapes' current AABBs (updated at the end of each step and
// on teleport). Candidates come from the world's broad phase (whichever kind
// is selected), brought up to date with those bounds first; the results are
// exactly those of visiting every shape (tests compare the two on random
// worlds). A query may update the broad phase's cached structure, never the
// simulation state: stepping after a query gives the same bits as without it.
// Queries on one world are not safe to run concurrently with each other.
//
// EXACTNESS. AABB overlap reports shapes whose AABB overlaps the box (edges
// touching count) — a bounds test, as in Box2D. Point query: the point is
// inside or on the shape (segments never contain a point). Shape overlap:
// AABBs overlap and the GJK distance (shape_distance with radii) is 0.
// Ray casts use ray_cast_* in the shape's frame: a ray starting inside a
// solid shape does not hit it; chain segments are one-sided.
//
// ORDER. Overlap results are in ascending shape index. All ray hits are
// sorted by fraction, then shape index; the closest hit is the lowest
// fraction, the lowest shape index on a tie.
//
// ERRORS. Every query returns a Status: an invalid (null, stale, destroyed)
// world handle, a locked world (inside world_step), or a bad argument
// (a ray translation or AABB outside ±k_max_world_coordinate, an inverted
// AABB, a geometry failing validate_*) give an error and empty results.
#pragma once

#include <cstdint>
#include <vector>

#include "physics/tandem.h"

namespace tandem {

/// Which shapes a query sees (see the file comment).
struct QueryFilter {
  uint64_t category_bits = 1;       ///< the query's layers; default layer 1
  uint64_t mask_bits = UINT64_MAX;  ///< the layers it sees; default all
  bool include_sensors = false;     ///< default false
};

/// One ray hit.
struct RayHit {
  ShapeId shape;   ///< the shape hit (null when no hit)
  Vec2 point;      ///< world hit point, m
  Vec2 normal;     ///< unit world surface normal at the hit
  Q32 fraction;    ///< of the translation, in [0, 1]
  bool hit = false;
};

/// The closest hit of the ray origin → origin + translation (m, world); a
/// RayHit with hit = false when nothing is hit.
Result<RayHit> world_cast_ray_closest(WorldId world, Vec2 origin, Vec2 translation, QueryFilter filter = {});
/// Every hit of the ray, sorted by fraction then shape index, into *out
/// (cleared first).
Status world_cast_ray_all(WorldId world, Vec2 origin, Vec2 translation, QueryFilter filter,
                          std::vector<RayHit>* out);
/// Shapes whose AABB overlaps `box` (m, world), ascending shape index, into
/// *out (cleared first).
Status world_overlap_aabb(WorldId world, AABB box, QueryFilter filter, std::vector<ShapeId>* out);
/// Shapes containing `point` (m, world), ascending shape index.
Status world_overlap_point(WorldId world, Vec2 point, QueryFilter filter, std::vector<ShapeId>* out);
/// Shapes overlapping a circle / capsule / polygon placed at `transform`
/// (geometry in its own frame, m), ascending shape index.
Status world_overlap_circle(WorldId world, const Circle& circle, Transform transform, QueryFilter filter,
                            std::vector<ShapeId>* out);
Status world_overlap_capsule(WorldId world, const Capsule& capsule, Transform transform, QueryFilter filter,
                             std::vector<ShapeId>* out);
Status world_overlap_polygon(WorldId world, const Polygon& polygon, Transform transform, QueryFilter filter,
                             std::vector<ShapeId>* out);

}  // namespace tandem

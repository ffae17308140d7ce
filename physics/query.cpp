// query.cpp — world queries (see query.h for the contract).
//
// Every query resolves the world (refusing a locked one), checks its
// arguments, then asks the world's current broad phase for candidates
// (broad_phase_query_box / _ray, which first re-sync it with the shapes'
// current bounds; broad_phase.h "Queries"). Each candidate goes through the
// same tests the reference path applies to every shape: visible to the
// filter, its AABB against the query's box (the ray's bounds), then the exact
// test. Results never depend on the visiting order: overlaps are sorted by
// shape index, all ray hits by the unique key (fraction, shape index), and the
// closest hit is the minimum of that key (so farther boxes can be skipped).
//
// The reference path — every shape slot in ascending index, the queries as
// they were before the broad phase took part — stays behind
// BroadPhase::query_brute_force for tests that compare the two.
#include "physics/query.h"

#include <algorithm>
#include <string>

#include "physics/broad_phase.h"
#include "physics/world.h"

namespace tandem {

ShapeProxy make_shape_proxy(const ShapeGeometry& g) {
  switch (g.type) {
    case ShapeType::circle: return make_proxy(g.circle);
    case ShapeType::capsule: return make_proxy(g.capsule);
    case ShapeType::polygon: return make_proxy(g.polygon);
    case ShapeType::segment: return make_proxy(g.segment);
    case ShapeType::chain_segment: return make_proxy(g.chain_segment.segment);
    case ShapeType::count: break;
  }
  return make_proxy(g.circle);
}

namespace {

bool coordinate_ok(Q32 v, Q32 limit) { return -limit <= v && v <= limit; }

bool vec_ok(Vec2 v, Q32 limit) { return coordinate_ok(v.x, limit) && coordinate_ok(v.y, limit); }

Status bad_argument(const char* function, const std::string& what) {
  return make_status(StatusCode::invalid_argument, std::string(function) + ": " + what);
}

/// Whether shape `i` of `w` takes part in a query with `filter`.
bool shape_visible(const World& w, int32_t i, const QueryFilter& filter) {
  if (!id_pool_is_alive(w.shape_pool, i)) return false;
  const Shape& s = w.shapes[static_cast<size_t>(i)];
  if (s.is_sensor && !filter.include_sensors) return false;
  if (!w.bodies[static_cast<size_t>(s.body_index)].enabled) return false;
  return (s.filter.category_bits & filter.mask_bits) != 0 && (filter.category_bits & s.filter.mask_bits) != 0;
}

Transform shape_transform(const World& w, int32_t i) {
  return w.body_sims[static_cast<size_t>(w.shapes[static_cast<size_t>(i)].body_index)].transform;
}

/// Casts a world ray against shape i; the hit in world frame.
CastOutput cast_shape(const World& w, int32_t i, Vec2 origin, Vec2 translation) {
  const Transform xf = shape_transform(w, i);
  RayCastInput input;
  input.origin = inv_transform_point(xf, origin);
  input.translation = inv_rotate(xf.q, translation);
  input.max_fraction = Q32::one();
  const ShapeGeometry& g = w.shape_geometries[static_cast<size_t>(i)];
  CastOutput out;
  switch (g.type) {
    case ShapeType::circle: out = ray_cast_circle(input, g.circle); break;
    case ShapeType::capsule: out = ray_cast_capsule(input, g.capsule); break;
    case ShapeType::polygon: out = ray_cast_polygon(input, g.polygon); break;
    case ShapeType::segment: out = ray_cast_segment(input, g.segment, false); break;
    case ShapeType::chain_segment: out = ray_cast_segment(input, g.chain_segment.segment, true); break;
    case ShapeType::count: break;
  }
  if (out.hit) {
    out.point = transform_point(xf, out.point);
    out.normal = rotate(xf.q, out.normal);
  }
  return out;
}

Status check_ray(const char* function, Vec2 origin, Vec2 translation) {
  if (!vec_ok(origin, k_max_world_coordinate)) {
    return bad_argument(function, "origin " + format_vec2(origin) + " m is outside ±" +
                                      to_string(k_max_world_coordinate) + " m");
  }
  const Q32 t_limit = k_max_world_coordinate + k_max_world_coordinate;
  if (!vec_ok(translation, t_limit)) {
    return bad_argument(function, "translation " + format_vec2(translation) + " m is outside ±" +
                                      to_string(t_limit) + " m");
  }
  return Status{};
}

/// What a candidate visitor needs (one record for every query kind).
struct Visit {
  World* world = nullptr;
  QueryFilter filter;
  AABB box;                        ///< the query box, or the whole ray's bounds
  Vec2 origin;                     ///< ray, m
  Vec2 translation;                ///< ray, m
  const ShapeProxy* proxy = nullptr;  ///< shape overlap
  Transform transform;             ///< shape overlap
  std::vector<RayHit>* hits = nullptr;
  std::vector<ShapeId>* shapes = nullptr;
  RayHit best;                     ///< closest hit so far
  int32_t best_index = -1;         ///< its shape index
};

/// Casts the ray at shape i when it is visible and its bounds meet the ray's;
/// false when it misses.
bool cast_candidate(const Visit& v, int32_t i, CastOutput* out) {
  if (!shape_visible(*v.world, i, v.filter)) return false;
  if (!aabb_overlaps(v.box, v.world->shapes[static_cast<size_t>(i)].aabb)) return false;
  *out = cast_shape(*v.world, i, v.origin, v.translation);
  return out->hit;
}

RayHit make_hit(const World& w, int32_t i, const CastOutput& out) {
  RayHit hit;
  hit.shape = make_shape_id(w, i);
  hit.point = out.point;
  hit.normal = out.normal;
  hit.fraction = out.fraction;
  hit.hit = true;
  return hit;
}

/// Closest hit: keeps the lowest (fraction, shape index), a unique key, so the
/// visiting order cannot matter; farther candidates need not be offered.
Q32 visit_closest(void* context, int32_t i) {
  Visit& v = *static_cast<Visit*>(context);
  CastOutput out;
  if (cast_candidate(v, i, &out)) {
    const bool better = v.best_index == -1 || out.fraction < v.best.fraction ||
                        (out.fraction == v.best.fraction && i < v.best_index);
    if (better) {
      v.best = make_hit(*v.world, i, out);
      v.best_index = i;
    }
  }
  return v.best_index == -1 ? Q32::one() : v.best.fraction;
}

/// All hits, unsorted.
Q32 visit_all_hits(void* context, int32_t i) {
  Visit& v = *static_cast<Visit*>(context);
  CastOutput out;
  if (cast_candidate(v, i, &out)) v.hits->push_back(make_hit(*v.world, i, out));
  return Q32::one();
}

Q32 visit_box(void* context, int32_t i) {
  Visit& v = *static_cast<Visit*>(context);
  if (shape_visible(*v.world, i, v.filter) && aabb_overlaps(v.box, v.world->shapes[static_cast<size_t>(i)].aabb)) {
    v.shapes->push_back(make_shape_id(*v.world, i));
  }
  return Q32::one();
}

/// The point is v.box.lower (= upper).
Q32 visit_point(void* context, int32_t i) {
  Visit& v = *static_cast<Visit*>(context);
  const World& w = *v.world;
  const Vec2 point = v.box.lower;
  if (!shape_visible(w, i, v.filter)) return Q32::one();
  if (!aabb_contains_point(w.shapes[static_cast<size_t>(i)].aabb, point)) return Q32::one();
  const Vec2 local = inv_transform_point(shape_transform(w, i), point);
  const ShapeGeometry& g = w.shape_geometries[static_cast<size_t>(i)];
  bool inside = false;
  switch (g.type) {
    case ShapeType::circle: inside = point_in_circle(local, g.circle); break;
    case ShapeType::capsule: inside = point_in_capsule(local, g.capsule); break;
    case ShapeType::polygon: inside = point_in_polygon(local, g.polygon); break;
    case ShapeType::segment:
    case ShapeType::chain_segment:
    case ShapeType::count: inside = false; break;
  }
  if (inside) v.shapes->push_back(make_shape_id(w, i));
  return Q32::one();
}

Q32 visit_proxy(void* context, int32_t i) {
  Visit& v = *static_cast<Visit*>(context);
  const World& w = *v.world;
  if (!shape_visible(w, i, v.filter)) return Q32::one();
  if (!aabb_overlaps(v.box, w.shapes[static_cast<size_t>(i)].aabb)) return Q32::one();
  DistanceInput input;
  input.proxy_a = make_shape_proxy(w.shape_geometries[static_cast<size_t>(i)]);
  input.proxy_b = *v.proxy;
  input.transform_a = shape_transform(w, i);
  input.transform_b = v.transform;
  input.use_radii = true;
  if (shape_distance(input).distance == Q32::zero()) v.shapes->push_back(make_shape_id(w, i));
  return Q32::one();
}

/// The reference path (WorldDef-independent): every shape slot, ascending.
void visit_every_shape(Visit* v, BroadPhaseVisit visit) {
  const int32_t n = id_pool_capacity(v->world->shape_pool);
  for (int32_t i = 0; i < n; ++i) (void)visit(v, i);
}

/// Offers the candidates of box v->box (broad phase, or every shape).
void visit_box_candidates(Visit* v, BroadPhaseVisit visit) {
  if (v->world->broad_phase.query_brute_force) {
    visit_every_shape(v, visit);
  } else {
    broad_phase_query_box(v->world, v->box, v->filter.include_sensors, visit, v);
  }
}

/// Offers the candidates of the ray v->origin, v->translation.
void visit_ray_candidates(Visit* v, BroadPhaseVisit visit) {
  if (v->world->broad_phase.query_brute_force) {
    visit_every_shape(v, visit);
  } else {
    broad_phase_query_ray(v->world, v->origin, v->translation, v->filter.include_sensors, visit, v);
  }
}

/// Shape ids in ascending index (unique key), whatever the visiting order.
void sort_shape_ids(std::vector<ShapeId>* ids) {
  std::sort(ids->begin(), ids->end(), [](const ShapeId& a, const ShapeId& b) { return a.index1 < b.index1; });
}

/// Shapes overlapping a proxy at a transform (bounds `box`), ascending index.
Status overlap_proxy(WorldId id, const char* function, const ShapeProxy& proxy, Transform transform, AABB box,
                     const QueryFilter& filter, std::vector<ShapeId>* out) {
  out->clear();
  World* w = nullptr;
  Status s = resolve_world(id, function, true, &w);
  if (!s.ok()) return s;
  Visit v;
  v.world = w;
  v.filter = filter;
  v.box = box;
  v.proxy = &proxy;
  v.transform = transform;
  v.shapes = out;
  visit_box_candidates(&v, visit_proxy);
  sort_shape_ids(out);
  return s;
}

Status check_transform(const char* function, Transform transform) {
  if (!vec_ok(transform.p, k_max_world_coordinate)) {
    return bad_argument(function, "transform position " + format_vec2(transform.p) + " m is outside ±" +
                                      to_string(k_max_world_coordinate) + " m");
  }
  return Status{};
}

/// A ray's Visit record.
Visit ray_visit(World* w, Vec2 origin, Vec2 translation, const QueryFilter& filter) {
  Visit v;
  v.world = w;
  v.filter = filter;
  v.origin = origin;
  v.translation = translation;
  const Vec2 end = origin + translation;
  v.box = AABB{min(origin, end), max(origin, end)};
  return v;
}

}  // namespace

Result<RayHit> world_cast_ray_closest(WorldId id, Vec2 origin, Vec2 translation, QueryFilter filter) {
  const char* fn = "world_cast_ray_closest";
  Result<RayHit> result;
  World* w = nullptr;
  result.status = resolve_world(id, fn, true, &w);
  if (!result.ok()) return result;
  result.status = check_ray(fn, origin, translation);
  if (!result.ok()) return result;
  Visit v = ray_visit(w, origin, translation, filter);
  visit_ray_candidates(&v, visit_closest);
  if (v.best_index != -1) result.value = v.best;
  return result;
}

Status world_cast_ray_all(WorldId id, Vec2 origin, Vec2 translation, QueryFilter filter, std::vector<RayHit>* out) {
  const char* fn = "world_cast_ray_all";
  out->clear();
  World* w = nullptr;
  Status s = resolve_world(id, fn, true, &w);
  if (!s.ok()) return s;
  s = check_ray(fn, origin, translation);
  if (!s.ok()) return s;
  Visit v = ray_visit(w, origin, translation, filter);
  v.hits = out;
  visit_ray_candidates(&v, visit_all_hits);
  std::sort(out->begin(), out->end(), [](const RayHit& a, const RayHit& b) {
    if (a.fraction != b.fraction) return a.fraction < b.fraction;
    return a.shape.index1 < b.shape.index1;  // unique within a world
  });
  return s;
}

Status world_overlap_aabb(WorldId id, AABB box, QueryFilter filter, std::vector<ShapeId>* out) {
  const char* fn = "world_overlap_aabb";
  out->clear();
  World* w = nullptr;
  Status s = resolve_world(id, fn, true, &w);
  if (!s.ok()) return s;
  if (!aabb_is_valid(box) || !vec_ok(box.lower, k_max_world_coordinate) ||
      !vec_ok(box.upper, k_max_world_coordinate)) {
    return bad_argument(fn, "box [" + format_vec2(box.lower) + ", " + format_vec2(box.upper) +
                                "] m must have lower ≤ upper and lie within ±" + to_string(k_max_world_coordinate) +
                                " m");
  }
  Visit v;
  v.world = w;
  v.filter = filter;
  v.box = box;
  v.shapes = out;
  visit_box_candidates(&v, visit_box);
  sort_shape_ids(out);
  return s;
}

Status world_overlap_point(WorldId id, Vec2 point, QueryFilter filter, std::vector<ShapeId>* out) {
  const char* fn = "world_overlap_point";
  out->clear();
  World* w = nullptr;
  Status s = resolve_world(id, fn, true, &w);
  if (!s.ok()) return s;
  if (!vec_ok(point, k_max_world_coordinate)) {
    return bad_argument(fn, "point " + format_vec2(point) + " m is outside ±" + to_string(k_max_world_coordinate) +
                                " m");
  }
  Visit v;
  v.world = w;
  v.filter = filter;
  v.box = AABB{point, point};
  v.shapes = out;
  visit_box_candidates(&v, visit_point);
  sort_shape_ids(out);
  return s;
}

Status world_overlap_circle(WorldId id, const Circle& circle, Transform transform, QueryFilter filter,
                            std::vector<ShapeId>* out) {
  const char* fn = "world_overlap_circle";
  out->clear();
  const Status g = validate_circle(circle);
  if (!g.ok()) return bad_argument(fn, g.message);
  Status s = check_transform(fn, transform);
  if (!s.ok()) return s;
  return overlap_proxy(id, fn, make_proxy(circle), transform, compute_circle_aabb(circle, transform), filter, out);
}

Status world_overlap_capsule(WorldId id, const Capsule& capsule, Transform transform, QueryFilter filter,
                             std::vector<ShapeId>* out) {
  const char* fn = "world_overlap_capsule";
  out->clear();
  const Status g = validate_capsule(capsule);
  if (!g.ok()) return bad_argument(fn, g.message);
  Status s = check_transform(fn, transform);
  if (!s.ok()) return s;
  return overlap_proxy(id, fn, make_proxy(capsule), transform, compute_capsule_aabb(capsule, transform), filter,
                       out);
}

Status world_overlap_polygon(WorldId id, const Polygon& polygon, Transform transform, QueryFilter filter,
                             std::vector<ShapeId>* out) {
  const char* fn = "world_overlap_polygon";
  out->clear();
  const Status g = validate_polygon(polygon);
  if (!g.ok()) return bad_argument(fn, g.message);
  Status s = check_transform(fn, transform);
  if (!s.ok()) return s;
  return overlap_proxy(id, fn, make_proxy(polygon), transform, compute_polygon_aabb(polygon, transform), filter,
                       out);
}

}  // namespace tandem

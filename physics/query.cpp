// query.cpp — world queries (see query.h for the contract).
//
// Every query resolves the world (refusing a locked one), checks its
// arguments, then visits live shapes in ascending index: the candidate test
// is the shape's AABB, then the exact test. Ray hits are collected and, for
// the all-hits query, sorted on the unique key (fraction, shape index).
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

/// Collects every hit (unsorted, shape index order) into *hits.
void collect_ray_hits(const World& w, Vec2 origin, Vec2 translation, const QueryFilter& filter,
                      std::vector<RayHit>* hits) {
  const Vec2 end = origin + translation;
  const AABB ray_box{min(origin, end), max(origin, end)};
  const int32_t n = id_pool_capacity(w.shape_pool);
  for (int32_t i = 0; i < n; ++i) {
    if (!shape_visible(w, i, filter)) continue;
    if (!aabb_overlaps(ray_box, w.shapes[static_cast<size_t>(i)].aabb)) continue;
    const CastOutput out = cast_shape(w, i, origin, translation);
    if (!out.hit) continue;
    RayHit hit;
    hit.shape = make_shape_id(w, i);
    hit.point = out.point;
    hit.normal = out.normal;
    hit.fraction = out.fraction;
    hit.hit = true;
    hits->push_back(hit);
  }
}

/// Shapes overlapping a proxy at a transform (bounds `box`), ascending index.
Status overlap_proxy(WorldId id, const char* function, const ShapeProxy& proxy, Transform transform, AABB box,
                     const QueryFilter& filter, std::vector<ShapeId>* out) {
  out->clear();
  World* w = nullptr;
  Status s = resolve_world(id, function, true, &w);
  if (!s.ok()) return s;
  const int32_t n = id_pool_capacity(w->shape_pool);
  for (int32_t i = 0; i < n; ++i) {
    if (!shape_visible(*w, i, filter)) continue;
    if (!aabb_overlaps(box, w->shapes[static_cast<size_t>(i)].aabb)) continue;
    DistanceInput input;
    input.proxy_a = make_shape_proxy(w->shape_geometries[static_cast<size_t>(i)]);
    input.proxy_b = proxy;
    input.transform_a = shape_transform(*w, i);
    input.transform_b = transform;
    input.use_radii = true;
    if (shape_distance(input).distance == Q32::zero()) out->push_back(make_shape_id(*w, i));
  }
  return s;
}

Status check_transform(const char* function, Transform transform) {
  if (!vec_ok(transform.p, k_max_world_coordinate)) {
    return bad_argument(function, "transform position " + format_vec2(transform.p) + " m is outside ±" +
                                      to_string(k_max_world_coordinate) + " m");
  }
  return Status{};
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
  const Vec2 end = origin + translation;
  const AABB ray_box{min(origin, end), max(origin, end)};
  const int32_t n = id_pool_capacity(w->shape_pool);
  for (int32_t i = 0; i < n; ++i) {
    if (!shape_visible(*w, i, filter)) continue;
    if (!aabb_overlaps(ray_box, w->shapes[static_cast<size_t>(i)].aabb)) continue;
    const CastOutput out = cast_shape(*w, i, origin, translation);
    // Strictly closer only: the lowest shape index wins a tie.
    if (!out.hit || (result.value.hit && !(out.fraction < result.value.fraction))) continue;
    result.value.shape = make_shape_id(*w, i);
    result.value.point = out.point;
    result.value.normal = out.normal;
    result.value.fraction = out.fraction;
    result.value.hit = true;
  }
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
  collect_ray_hits(*w, origin, translation, filter, out);
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
  const int32_t n = id_pool_capacity(w->shape_pool);
  for (int32_t i = 0; i < n; ++i) {
    if (!shape_visible(*w, i, filter)) continue;
    if (aabb_overlaps(box, w->shapes[static_cast<size_t>(i)].aabb)) out->push_back(make_shape_id(*w, i));
  }
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
  const int32_t n = id_pool_capacity(w->shape_pool);
  for (int32_t i = 0; i < n; ++i) {
    if (!shape_visible(*w, i, filter)) continue;
    if (!aabb_contains_point(w->shapes[static_cast<size_t>(i)].aabb, point)) continue;
    const Vec2 local = inv_transform_point(shape_transform(*w, i), point);
    const ShapeGeometry& g = w->shape_geometries[static_cast<size_t>(i)];
    bool inside = false;
    switch (g.type) {
      case ShapeType::circle: inside = point_in_circle(local, g.circle); break;
      case ShapeType::capsule: inside = point_in_capsule(local, g.capsule); break;
      case ShapeType::polygon: inside = point_in_polygon(local, g.polygon); break;
      case ShapeType::segment:
      case ShapeType::chain_segment:
      case ShapeType::count: inside = false; break;
    }
    if (inside) out->push_back(make_shape_id(*w, i));
  }
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

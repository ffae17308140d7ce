// shape_api.cpp — shapes attached to bodies: creation, destruction, the shape
// API, and dispatch from ShapeGeometry to collision.h's per-type mass and
// bounds functions.
//
// Checks on creation, in order (each refusal names the function and the
// culprit; nothing changes on refusal): the body handle, the ShapeDef (cookie,
// friction, restitution, density), the geometry's reach from the body origin
// (every point within ±k_max_shape_size, checked before any geometry function
// runs, so none of them can saturate), collision.h's validate_*(), and — on a
// dynamic body — the shape's and the body's mass limits.
//
// create_chain_shapes checks every point's reach, then make_chain_segments()
// (its message, nothing created on refusal), then adds one massless
// chain-segment shape per segment in segment order.
//
// A body's shapes stay in ascending shape index (a doubly linked list), so a
// new shape whose index was freed earlier is inserted in the middle.
#include <string>
#include <utility>
#include <vector>

#include "physics/body.h"
#include "physics/fast_math.h"
#include "physics/shape.h"
#include "physics/world.h"

namespace tandem {

namespace {

std::string q32_text(Q32 v) { return to_string(v); }

Shape& shape_at(World* w, int32_t i) { return w->shapes[static_cast<size_t>(i)]; }
const Shape& shape_at(const World* w, int32_t i) { return w->shapes[static_cast<size_t>(i)]; }
const ShapeGeometry& geometry_at(const World* w, int32_t i) { return w->shape_geometries[static_cast<size_t>(i)]; }

Status invalid_argument(const std::string& message) { return make_status(StatusCode::invalid_argument, message); }

bool check_closed(const char* fn, const char* field, Q32 v, Q32 lo, Q32 hi, const char* unit, Status* out) {
  if (lo <= v && v <= hi) return true;
  *out = invalid_argument(std::string(fn) + ": " + field + " " + q32_text(v) + " " + unit + " is outside [" +
                          q32_text(lo) + ", " + q32_text(hi) + "] " + unit);
  return false;
}

bool check_density(const char* fn, Q32 density, Status* out) {
  if (Q32::zero() < density && density <= k_max_density) return true;
  *out = invalid_argument(std::string(fn) + ": density " + q32_text(density) + " kg/m² is outside (0, " +
                          q32_text(k_max_density) + "] kg/m²");
  return false;
}

Status validate_shape_def(const ShapeDef& def, const char* fn) {
  Status s;
  if (def.internal_cookie != k_def_cookie) {
    return make_status(StatusCode::invalid_definition,
                       std::string(fn) + ": the ShapeDef was not made by default_shape_def()");
  }
  if (!check_closed(fn, "friction", def.friction, Q32::zero(), k_max_friction, "", &s)) return s;
  if (!check_closed(fn, "restitution", def.restitution, Q32::zero(), Q32::one(), "", &s)) return s;
  check_density(fn, def.density, &s);
  return s;
}

/// The points and radius that bound a geometry (the polygon's count must
/// already be in range).
struct Reach {
  std::array<Vec2, k_max_polygon_vertices + 1> points{};
  int32_t count = 0;
  Q32 radius;
};

Reach reach_of(const ShapeGeometry& g) {
  Reach r;
  switch (g.type) {
    case ShapeType::circle:
      r.points[0] = g.circle.center;
      r.count = 1;
      r.radius = g.circle.radius;
      break;
    case ShapeType::capsule:
      r.points[0] = g.capsule.center1;
      r.points[1] = g.capsule.center2;
      r.count = 2;
      r.radius = g.capsule.radius;
      break;
    case ShapeType::segment:
      r.points[0] = g.segment.point1;
      r.points[1] = g.segment.point2;
      r.count = 2;
      break;
    case ShapeType::polygon:
      for (int32_t k = 0; k < g.polygon.count; ++k) r.points[static_cast<size_t>(k)] = g.polygon.vertices[static_cast<size_t>(k)];
      r.points[static_cast<size_t>(g.polygon.count)] = g.polygon.centroid;
      r.count = g.polygon.count + 1;
      r.radius = g.polygon.radius;
      break;
    case ShapeType::chain_segment:
      r.points[0] = g.chain_segment.segment.point1;
      r.points[1] = g.chain_segment.segment.point2;
      r.count = 2;
      break;
    case ShapeType::count: break;
  }
  return r;
}

/// Every point of the geometry within ±k_max_shape_size of the body origin.
bool check_reach(const ShapeGeometry& g, const char* fn, Status* out) {
  if (g.type == ShapeType::polygon && (g.polygon.count < 3 || g.polygon.count > k_max_polygon_vertices)) {
    *out = invalid_argument(std::string(fn) + ": polygon vertex count " + std::to_string(g.polygon.count) +
                            " is outside [3, " + std::to_string(k_max_polygon_vertices) + "]");
    return false;
  }
  const Reach r = reach_of(g);
  const Q32 radius = abs(r.radius);
  bool ok = radius <= k_max_shape_size;
  for (int32_t k = 0; ok && k < r.count; ++k) {
    const Vec2 p = r.points[static_cast<size_t>(k)];
    ok = add_quiet(abs(p.x), radius) <= k_max_shape_size && add_quiet(abs(p.y), radius) <= k_max_shape_size;
  }
  if (!ok) {
    *out = invalid_argument(std::string(fn) + ": the shape reaches farther than k_max_shape_size " +
                            q32_text(k_max_shape_size) + " m from the body origin (on an axis)");
  }
  return ok;
}

/// True when the bounding-box area times the squared reach ≤ 2^30 m⁴, density
/// × area ≤ 2^30 kg and that times the squared reach ≤ 2^30 kg·m² (see
/// shape_mass_for_body). Requires check_reach to have
/// passed, so every intermediate here is far inside Q32.32.
bool mass_is_computable(const ShapeGeometry& g, Q32 density) {
  if (g.type == ShapeType::segment || g.type == ShapeType::chain_segment) return true;
  const Reach r = reach_of(g);
  const Q32 radius = abs(r.radius);
  Vec2 lo = r.points[0], hi = r.points[0];
  Q32 reach2;
  for (int32_t k = 0; k < r.count; ++k) {
    const Vec2 p = r.points[static_cast<size_t>(k)];
    lo = min(lo, p);
    hi = max(hi, p);
    const Q32 ex = abs(p.x) + radius, ey = abs(p.y) + radius;  // ≤ 1e4 each
    reach2 = max(reach2, ex * ex + ey * ey);                  // ≤ 2e8
  }
  const Q32 width = hi.x - lo.x + radius * 2, height = hi.y - lo.y + radius * 2;  // ≤ 2e4 + ...
  const Q32 limit = Q32::from_int(int64_t{1} << 30);
  const Q32 area_bound = mul_quiet(width, height);
  const Q32 mass_bound = mul_quiet(density, area_bound);
  // The polar moment is formed before the density multiplies it, so the
  // geometry alone must also stay in range.
  return mul_quiet(area_bound, reach2) <= limit && mass_bound <= limit && mul_quiet(mass_bound, reach2) <= limit;
}

Status validate_geometry(const ShapeGeometry& g) {
  switch (g.type) {
    case ShapeType::circle: return validate_circle(g.circle);
    case ShapeType::capsule: return validate_capsule(g.capsule);
    case ShapeType::segment: return validate_segment(g.segment);
    case ShapeType::polygon: return validate_polygon(g.polygon);
    case ShapeType::chain_segment:
    case ShapeType::count: break;
  }
  Status s;
  s.code = StatusCode::invalid_argument;
  s.message = "this shape type cannot be created here";
  return s;
}

/// Links a shape into its body's list, keeping ascending shape index.
void link_shape(World* w, Body* body, int32_t index) {
  Shape& shape = shape_at(w, index);
  int32_t prev = k_null_index;
  int32_t next = body->head_shape;
  while (next != k_null_index && next < index) {
    prev = next;
    next = shape_at(w, next).next_shape;
  }
  shape.prev_shape = prev;
  shape.next_shape = next;
  if (prev == k_null_index) {
    body->head_shape = index;
  } else {
    shape_at(w, prev).next_shape = index;
  }
  if (next != k_null_index) shape_at(w, next).prev_shape = index;
  ++body->shape_count;
}

/// Allocates a shape index, fills the record and links it into body b's list
/// (every check already passed); returns the index. The body's mass is not
/// updated here.
int32_t insert_shape(World* w, int32_t b, const ShapeDef& def, const ShapeGeometry& geometry) {
  const int32_t index = id_pool_allocate(&w->shape_pool);
  broad_phase_mark_stale(w);  // queries re-sync (broad_phase.h)
  if (static_cast<size_t>(index) >= w->shapes.size()) {
    w->shapes.resize(static_cast<size_t>(index) + 1);
    w->shape_geometries.resize(static_cast<size_t>(index) + 1);
  }
  Shape& shape = shape_at(w, index);
  shape = Shape{};
  shape.body_index = b;
  shape.type = geometry.type;
  shape.friction = def.friction;
  shape.restitution = def.restitution;
  shape.density = def.density;
  shape.filter = def.filter;
  shape.user_data = def.user_data;
  shape.is_sensor = def.is_sensor;
  shape.enable_hit_events = def.enable_hit_events;
  w->shape_geometries[static_cast<size_t>(index)] = geometry;
  link_shape(w, &w->bodies[static_cast<size_t>(b)], index);
  shape.aabb = compute_shape_aabb(geometry, w->body_sims[static_cast<size_t>(b)].transform);
  return index;
}

Result<ShapeId> create_shape(BodyId body_id, const ShapeDef& def, const ShapeGeometry& geometry, const char* fn) {
  Result<ShapeId> result;
  Status& s = result.status;
  World* w = nullptr;
  int32_t b = 0;
  s = resolve_body(body_id, fn, true, WorldId{}, &w, &b);
  if (!s.ok()) return result;
  s = validate_shape_def(def, fn);
  if (!s.ok()) return result;
  if (!check_reach(geometry, fn, &s)) return result;
  const Status gs = validate_geometry(geometry);
  if (!gs.ok()) {
    s = invalid_argument(std::string(fn) + ": " + gs.message);
    return result;
  }
  if (w->bodies[static_cast<size_t>(b)].type == BodyType::dynamic_body) {
    MassData md{};
    s = shape_mass_for_body(geometry, def.density, std::string(fn) + ": the new shape", &md);
    if (!s.ok()) return result;
    s = check_body_mass_with(*w, b, k_null_index, Q32::zero(), md.mass > Q32::zero() ? &md : nullptr,
                             std::string(fn) + ": " + describe(body_id));
    if (!s.ok()) return result;
  }
  if (w->shape_pool.alive_count >= k_max_shapes) {
    s = make_status(StatusCode::capacity_exceeded, std::string(fn) + ": " + describe(body_id.world) +
                                                       " already has " + std::to_string(k_max_shapes) + " shapes");
    return result;
  }

  const int32_t index = insert_shape(w, b, def, geometry);
  const Status mass = update_body_mass(w, b, fn);  // checked above: cannot fail
  TANDEM_ASSERT(mass.ok());
  result.value = make_shape_id(*w, index);
  return result;
}

template <typename Set>
Status set_shape(ShapeId id, const char* fn, Set set) {
  return set_resolved(id, fn, resolve_shape, set);
}

template <typename T, typename Get>
T get_shape(ShapeId id, T fallback, Get get) {
  return get_found(id, fallback, find_shape, get);
}

}  // namespace

bool shape_geometry_within_reach(const ShapeGeometry& geometry) {
  Status ignored;
  return check_reach(geometry, "", &ignored);
}

// ---------------------------------------------------------------------------
// Internal helpers (shape.h)
// ---------------------------------------------------------------------------

Status resolve_shape(ShapeId id, const char* function, bool mutating, WorldId expected_world, World** out_world,
                     int32_t* out_index) {
  return resolve_handle(function, "shape", id.index1, id.generation, id.world, expected_world, mutating,
                        &World::shape_pool, out_world, out_index);
}

bool find_shape(ShapeId id, World** out_world, int32_t* out_index) {
  return find_handle(id.index1, id.generation, id.world, &World::shape_pool, out_world, out_index);
}

ShapeId make_shape_id(const World& world, int32_t index) {
  ShapeId id;
  id.index1 = static_cast<uint32_t>(index) + 1u;
  id.generation = id_pool_generation(world.shape_pool, index);
  id.world = world.id;
  return id;
}

namespace {

/// The bounds of points p_i (body frame) under xf, grown by r: the same bits
/// as collision.h's compute_*_aabb (which take any transform and report
/// faults), through fast_math.h. Range: a shape's points lie within
/// k_max_shape_size (10^4 m) of its body's origin and xf's rotation is a unit
/// vector, so a rotated coordinate is below 1.5·10^4 m and adding a position
/// within the world's range (≤ 2·10^6 m) cannot saturate. Where fast_math.h
/// is unchecked (release builds with __int128), the position is added once,
/// to the extremes of the rotated points: the saturating add is monotone, so
/// min_i(a_i + p) = min_i(a_i) + p bit for bit, saturated or not
/// (transform_point(xf, v) is rotate(xf.q, v) + xf.p); builds that report
/// faults add it to every point, so a crafted geometry reports as before.
#if TANDEM_FAST_MATH_UNCHECKED
/// Whether the points are make_box's: (−a, −b), (a, −b), (a, b), (−a, b), in
/// that order, with a, b ≠ INT64_MIN (so every product below is below 2^126).
bool is_centred_box(const Vec2* v, int32_t count) {
  if (count != 4) return false;
  const int64_t a = v[1].x.raw;
  const int64_t b = v[2].y.raw;
  return a != INT64_MIN && b != INT64_MIN && v[0].x.raw == -a && v[0].y.raw == -b && v[1].y.raw == -b &&
         v[2].x.raw == a && v[3].x.raw == -a && v[3].y.raw == b;
}

fast::s128 abs128(fast::s128 x) { return x < 0 ? -x : x; }
#endif

AABB transformed_bounds(const Vec2* points, int32_t count, Q32 r, Transform xf) {
#if TANDEM_FAST_MATH_UNCHECKED
  Vec2 lo, hi;
  if (is_centred_box(points, count)) {
    // The box's rotated coordinates, exact before rounding, are
    // x = ±c·a ± s·b and y = ±s·a ± c·b, all four sign pairs each (one per
    // corner). Their least and greatest are ∓(|c·a| + |s·b|) and
    // ∓(|s·a| + |c·b|), and rounding is monotone, so rounding those gives the
    // least and greatest of the rounded corners: the loop's bits, from 4
    // products instead of 16.
    const int64_t a = points[1].x.raw;
    const int64_t b = points[2].y.raw;
    const fast::s128 tx = abs128(fast::s128{xf.q.c.raw} * a) + abs128(fast::s128{xf.q.s.raw} * b);
    const fast::s128 ty = abs128(fast::s128{xf.q.s.raw} * a) + abs128(fast::s128{xf.q.c.raw} * b);
    lo = {fast::round_shift(static_cast<fast::u128>(-tx)), fast::round_shift(static_cast<fast::u128>(-ty))};
    hi = {fast::round_shift(static_cast<fast::u128>(tx)), fast::round_shift(static_cast<fast::u128>(ty))};
  } else {
    lo = fast::rotate(xf.q, points[0]);
    hi = lo;
    for (int32_t i = 1; i < count; ++i) {
      const Vec2 v = fast::rotate(xf.q, points[i]);
      lo = min(lo, v);
      hi = max(hi, v);
    }
  }
  // lo + p − r and hi + p + r. When every operand is below 2^61 in
  // magnitude no partial sum can reach 2^63 (nor INT64_MIN), so plain adds
  // give the saturating adds' bits; otherwise the saturating adds below.
  constexpr uint64_t k_bias = uint64_t{1} << 61;
  const auto biased = [](Q32 v) { return static_cast<uint64_t>(v.raw) + k_bias; };
  if (((biased(lo.x) | biased(lo.y) | biased(hi.x) | biased(hi.y) | biased(xf.p.x) | biased(xf.p.y) | biased(r)) >>
       62) == 0) {
    const auto add3 = [](Q32 a, Q32 b, Q32 c) { return Q32::from_raw(a.raw + b.raw + c.raw); };
    const auto add_sub = [](Q32 a, Q32 b, Q32 c) { return Q32::from_raw(a.raw + b.raw - c.raw); };
    return {{add_sub(lo.x, xf.p.x, r), add_sub(lo.y, xf.p.y, r)}, {add3(hi.x, xf.p.x, r), add3(hi.y, xf.p.y, r)}};
  }
  lo = fast::add(lo, xf.p);
  hi = fast::add(hi, xf.p);
#else
  Vec2 lo = fast::transform_point(xf, points[0]);
  Vec2 hi = lo;
  for (int32_t i = 1; i < count; ++i) {
    const Vec2 v = fast::transform_point(xf, points[i]);
    lo = min(lo, v);
    hi = max(hi, v);
  }
#endif
  const Vec2 rr{r, r};
  return {fast::sub(lo, rr), fast::add(hi, rr)};
}

}  // namespace

AABB compute_shape_aabb(const ShapeGeometry& g, Transform xf) {
  switch (g.type) {
    case ShapeType::circle: {
      // transformed_bounds of one point, written out (the same operations in
      // every build: its bounds are transform_point(xf, c) ∓ r). For a
      // circle at its body's origin (the common case) the rotation is skipped:
      // rotating (0, 0) gives (0, 0) exactly, whatever xf.q holds.
      const Vec2 c = g.circle.center == Vec2{} ? fast::add(Vec2{}, xf.p) : fast::transform_point(xf, g.circle.center);
      const Vec2 rr{g.circle.radius, g.circle.radius};
      return {fast::sub(c, rr), fast::add(c, rr)};
    }
    case ShapeType::capsule: {
      const Vec2 centres[2] = {g.capsule.center1, g.capsule.center2};
      return transformed_bounds(centres, 2, g.capsule.radius, xf);
    }
    case ShapeType::segment: {
      const Vec2 ends[2] = {g.segment.point1, g.segment.point2};
      return transformed_bounds(ends, 2, Q32::zero(), xf);
    }
    case ShapeType::polygon: return transformed_bounds(g.polygon.vertices.data(), g.polygon.count, g.polygon.radius, xf);
    case ShapeType::chain_segment: {
      const Vec2 ends[2] = {g.chain_segment.segment.point1, g.chain_segment.segment.point2};
      return transformed_bounds(ends, 2, Q32::zero(), xf);
    }
    case ShapeType::count: break;
  }
  return AABB{};
}

MassData compute_shape_mass(const ShapeGeometry& g, Q32 density) {
  switch (g.type) {
    case ShapeType::circle: return compute_circle_mass(g.circle, density);
    case ShapeType::capsule: return compute_capsule_mass(g.capsule, density);
    case ShapeType::polygon: return compute_polygon_mass(g.polygon, density);
    case ShapeType::segment:
    case ShapeType::chain_segment:
    case ShapeType::count: break;
  }
  return MassData{};
}

Status shape_mass_for_body(const ShapeGeometry& g, Q32 density, const std::string& what, MassData* out_mass) {
  *out_mass = MassData{};
  if (!mass_is_computable(g, density)) {
    return invalid_argument(what + " is far too large or heavy for a dynamic body (density " + q32_text(density) +
                            " kg/m² over its extent); its inertia would leave the number range");
  }
  const MassData md = compute_shape_mass(g, density);
  if (md.mass > Q32::zero() && md.mass < k_min_body_mass) {
    return invalid_argument(what + " has mass " + q32_text(md.mass) + " kg, below k_min_body_mass " +
                            q32_text(k_min_body_mass) + " kg");
  }
  *out_mass = md;
  return Status{};
}

void remove_shape(World* w, int32_t index) {
  Shape& shape = shape_at(w, index);
  Body& body = w->bodies[static_cast<size_t>(shape.body_index)];
  if (shape.prev_shape == k_null_index) {
    body.head_shape = shape.next_shape;
  } else {
    shape_at(w, shape.prev_shape).next_shape = shape.next_shape;
  }
  if (shape.next_shape != k_null_index) shape_at(w, shape.next_shape).prev_shape = shape.prev_shape;
  --body.shape_count;
  shape = Shape{};
  w->shape_geometries[static_cast<size_t>(index)] = ShapeGeometry{};
  id_pool_free(&w->shape_pool, index);
  broad_phase_mark_stale(w);  // queries re-sync (broad_phase.h)
}

// ---------------------------------------------------------------------------
// Creation and destruction
// ---------------------------------------------------------------------------

Result<ShapeId> create_circle_shape(BodyId body, const ShapeDef& def, const Circle& circle) {
  ShapeGeometry g{};
  g.type = ShapeType::circle;
  g.circle = circle;
  return create_shape(body, def, g, "create_circle_shape");
}

Result<ShapeId> create_capsule_shape(BodyId body, const ShapeDef& def, const Capsule& capsule) {
  ShapeGeometry g{};
  g.type = ShapeType::capsule;
  g.capsule = capsule;
  return create_shape(body, def, g, "create_capsule_shape");
}

Result<ShapeId> create_polygon_shape(BodyId body, const ShapeDef& def, const Polygon& polygon) {
  ShapeGeometry g{};
  g.type = ShapeType::polygon;
  g.polygon = polygon;
  return create_shape(body, def, g, "create_polygon_shape");
}

Result<ShapeId> create_segment_shape(BodyId body, const ShapeDef& def, const Segment& segment) {
  ShapeGeometry g{};
  g.type = ShapeType::segment;
  g.segment = segment;
  return create_shape(body, def, g, "create_segment_shape");
}

Status create_chain_shapes(BodyId body_id, const ShapeDef& def, const Vec2* points, int32_t count, bool loop,
                           std::vector<ShapeId>* out_shapes) {
  const char* fn = "create_chain_shapes";
  World* w = nullptr;
  int32_t b = 0;
  Status s = resolve_body(body_id, fn, true, WorldId{}, &w, &b);
  if (!s.ok()) return s;
  s = validate_shape_def(def, fn);
  if (!s.ok()) return s;
  // Too many points for the shape limit: refused before anything is sized
  // by count.
  if (count > k_max_shapes) {
    return make_status(StatusCode::capacity_exceeded, std::string(fn) + ": " + std::to_string(count) +
                                                          " points exceed k_max_shapes " +
                                                          std::to_string(k_max_shapes));
  }
  // Every point (ghosts included) within ±k_max_shape_size of the body origin
  // before make_chain_segments measures distances, so nothing can saturate.
  if (points != nullptr) {
    for (int32_t k = 0; k < count; ++k) {
      const Vec2 p = points[k];
      if (abs(p.x) > k_max_shape_size || abs(p.y) > k_max_shape_size) {
        return invalid_argument(std::string(fn) + ": point " + std::to_string(k) + " (" + q32_text(p.x) + ", " +
                                q32_text(p.y) + ") m is farther than k_max_shape_size " +
                                q32_text(k_max_shape_size) + " m from the body origin (on an axis)");
      }
    }
  }
  std::vector<ChainSegment> segments(static_cast<size_t>(count > 0 ? count : 0));
  int32_t segment_count = 0;
  const Status gs = make_chain_segments(points, count, loop, -1, segments.data(), count, &segment_count);
  if (!gs.ok()) return invalid_argument(std::string(fn) + ": " + gs.message);
  if (w->bodies[static_cast<size_t>(b)].type == BodyType::dynamic_body) {
    // Chain segments add no mass; the body's own mass must still be valid.
    s = check_body_mass_with(*w, b, k_null_index, Q32::zero(), nullptr, std::string(fn) + ": " + describe(body_id));
    if (!s.ok()) return s;
  }
  if (w->shape_pool.alive_count > k_max_shapes - segment_count) {
    return make_status(StatusCode::capacity_exceeded, std::string(fn) + ": " + describe(body_id.world) + " has " +
                                                          std::to_string(w->shape_pool.alive_count) +
                                                          " shapes; " + std::to_string(segment_count) +
                                                          " more would exceed " + std::to_string(k_max_shapes));
  }
  std::vector<ShapeId> ids;
  ids.reserve(static_cast<size_t>(segment_count));
  int32_t chain_id = -1;  // the first segment's shape index names the chain
  for (int32_t k = 0; k < segment_count; ++k) {
    ShapeGeometry g{};
    g.type = ShapeType::chain_segment;
    g.chain_segment = segments[static_cast<size_t>(k)];
    const int32_t index = insert_shape(w, b, def, g);
    if (chain_id < 0) chain_id = index;
    w->shape_geometries[static_cast<size_t>(index)].chain_segment.chain_id = chain_id;
    ids.push_back(make_shape_id(*w, index));
  }
  const Status mass = update_body_mass(w, b, fn);  // no mass added: cannot fail
  TANDEM_ASSERT(mass.ok());
  if (out_shapes != nullptr) *out_shapes = std::move(ids);
  return Status{};
}

Status destroy_shape(ShapeId id) {
  const char* fn = "destroy_shape";
  return set_shape(id, fn, [&](World* w, int32_t i) {
    const int32_t b = shape_at(w, i).body_index;
    remove_shape(w, i);
    // Fewer shapes: mass and inertia about the new centre only shrink, and
    // every remaining massive shape is ≥ k_min_body_mass, so this holds.
    const Status mass = update_body_mass(w, b, fn);
    TANDEM_ASSERT(mass.ok());
    return Status{};
  });
}

bool shape_is_valid(ShapeId id) {
  World* w = nullptr;
  int32_t i = 0;
  return find_shape(id, &w, &i);
}

Status shape_check(ShapeId id, WorldId expected_world) {
  World* w = nullptr;
  int32_t i = 0;
  return resolve_shape(id, "shape_check", false, expected_world, &w, &i);
}

// ---------------------------------------------------------------------------
// Getters and setters
// ---------------------------------------------------------------------------

ShapeType shape_type(ShapeId id) {
  return get_shape(id, ShapeType::circle, [](const World& w, int32_t i) { return shape_at(&w, i).type; });
}

BodyId shape_body(ShapeId id) {
  return get_shape(id, BodyId{}, [](const World& w, int32_t i) { return make_body_id(w, shape_at(&w, i).body_index); });
}

ShapeGeometry shape_geometry(ShapeId id) {
  return get_shape(id, ShapeGeometry{}, [](const World& w, int32_t i) { return geometry_at(&w, i); });
}

AABB shape_aabb(ShapeId id) {
  return get_shape(id, AABB{}, [](const World& w, int32_t i) { return shape_at(&w, i).aabb; });
}

MassData shape_mass_data(ShapeId id) {
  return get_shape(id, MassData{}, [](const World& w, int32_t i) {
    const ShapeGeometry& g = geometry_at(&w, i);
    const Q32 density = shape_at(&w, i).density;
    return mass_is_computable(g, density) ? compute_shape_mass(g, density) : MassData{};
  });
}

Q32 shape_friction(ShapeId id) {
  return get_shape(id, Q32{}, [](const World& w, int32_t i) { return shape_at(&w, i).friction; });
}

Status shape_set_friction(ShapeId id, Q32 friction) {
  const char* fn = "shape_set_friction";
  return set_shape(id, fn, [&](World* w, int32_t i) {
    Status s;
    if (check_closed(fn, "friction", friction, Q32::zero(), k_max_friction, "", &s)) shape_at(w, i).friction = friction;
    return s;
  });
}

Q32 shape_restitution(ShapeId id) {
  return get_shape(id, Q32{}, [](const World& w, int32_t i) { return shape_at(&w, i).restitution; });
}

Status shape_set_restitution(ShapeId id, Q32 restitution) {
  const char* fn = "shape_set_restitution";
  return set_shape(id, fn, [&](World* w, int32_t i) {
    Status s;
    if (check_closed(fn, "restitution", restitution, Q32::zero(), Q32::one(), "", &s)) {
      shape_at(w, i).restitution = restitution;
    }
    return s;
  });
}

Q32 shape_density(ShapeId id) {
  return get_shape(id, Q32{}, [](const World& w, int32_t i) { return shape_at(&w, i).density; });
}

Status shape_set_density(ShapeId id, Q32 density) {
  const char* fn = "shape_set_density";
  return set_shape(id, fn, [&](World* w, int32_t i) {
    Status s;
    if (!check_density(fn, density, &s)) return s;
    const int32_t b = shape_at(w, i).body_index;
    s = check_body_mass_with(*w, b, i, density, nullptr, std::string(fn) + ": " + describe(make_body_id(*w, b)));
    if (!s.ok()) return s;
    shape_at(w, i).density = density;
    const Status mass = update_body_mass(w, b, fn);
    TANDEM_ASSERT(mass.ok());
    return s;
  });
}

bool shape_is_sensor(ShapeId id) {
  return get_shape(id, false, [](const World& w, int32_t i) { return shape_at(&w, i).is_sensor; });
}

Filter shape_filter(ShapeId id) {
  return get_shape(id, Filter{}, [](const World& w, int32_t i) { return shape_at(&w, i).filter; });
}

Status shape_set_filter(ShapeId id, Filter filter) {
  return set_shape(id, "shape_set_filter", [&](World* w, int32_t i) {
    shape_at(w, i).filter = filter;
    return Status{};
  });
}

uint64_t shape_user_data(ShapeId id) {
  return get_shape(id, uint64_t{0}, [](const World& w, int32_t i) { return shape_at(&w, i).user_data; });
}

Status shape_set_user_data(ShapeId id, uint64_t user_data) {
  return set_shape(id, "shape_set_user_data", [&](World* w, int32_t i) {
    shape_at(w, i).user_data = user_data;
    return Status{};
  });
}

}  // namespace tandem

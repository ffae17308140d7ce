// tandem_c_body.cpp — the C API of bodies, shapes, queries and events.
// (design and how to add a function: tandem_c_core.cpp's top comment).
#include "tandem_c_internal.h"

using namespace tandem_c_internal;

// --- bodies -------------------------------------------------------------------------
tandem_status tandem_create_body(tandem_world_id world, const tandem_body_def* def, tandem_body_id* out_body) {
  static const char* fn = "tandem_create_body";
  if (def == nullptr) return null_pointer(fn, "def");
  if (out_body == nullptr) return null_pointer(fn, "out_body");
  return guard(fn, [&] {
    const Result<BodyId> r = create_body(to_cpp(world), to_cpp(*def));
    if (r.ok()) *out_body = to_c(r.value);
    return status(r.status);
  });
}

tandem_status tandem_destroy_body(tandem_body_id body) {
  return guard("tandem_destroy_body", [&] { return status(destroy_body(to_cpp(body))); });
}
bool tandem_body_is_valid(tandem_body_id body) { return body_is_valid(to_cpp(body)); }
tandem_status tandem_body_check(tandem_body_id body, tandem_world_id expected_world) {
  return guard("tandem_body_check", [&] { return status(body_check(to_cpp(body), to_cpp(expected_world))); });
}
tandem_world_id tandem_body_world(tandem_body_id body) { return to_c(body_world(to_cpp(body))); }
int32_t tandem_body_type(tandem_body_id body) { return static_cast<int32_t>(body_type(to_cpp(body))); }
tandem_status tandem_body_set_type(tandem_body_id body, int32_t type) {
  return guard("tandem_body_set_type", [&] { return status(body_set_type(to_cpp(body), static_cast<BodyType>(type))); });
}
tandem_vec2 tandem_body_position(tandem_body_id body) { return to_c(body_position(to_cpp(body))); }
tandem_rot tandem_body_rotation(tandem_body_id body) { return to_c(body_rotation(to_cpp(body))); }
tandem_q32 tandem_body_angle(tandem_body_id body) { return body_angle(to_cpp(body)).raw; }
tandem_transform tandem_body_transform(tandem_body_id body) { return to_c(body_transform(to_cpp(body))); }
tandem_status tandem_body_set_transform(tandem_body_id body, tandem_vec2 position, tandem_rot rotation) {
  return guard("tandem_body_set_transform",
               [&] { return status(body_set_transform(to_cpp(body), to_cpp(position), to_cpp(rotation))); });
}
tandem_vec2 tandem_body_world_center(tandem_body_id body) { return to_c(body_world_center(to_cpp(body))); }
tandem_vec2 tandem_body_local_center(tandem_body_id body) { return to_c(body_local_center(to_cpp(body))); }
tandem_vec2 tandem_body_linear_velocity(tandem_body_id body) { return to_c(body_linear_velocity(to_cpp(body))); }
tandem_status tandem_body_set_linear_velocity(tandem_body_id body, tandem_vec2 velocity) {
  return guard("tandem_body_set_linear_velocity",
               [&] { return status(body_set_linear_velocity(to_cpp(body), to_cpp(velocity))); });
}
tandem_q32 tandem_body_angular_velocity(tandem_body_id body) { return body_angular_velocity(to_cpp(body)).raw; }
tandem_status tandem_body_set_angular_velocity(tandem_body_id body, tandem_q32 w) {
  return guard("tandem_body_set_angular_velocity", [&] { return status(body_set_angular_velocity(to_cpp(body), q(w))); });
}
tandem_vec2 tandem_body_point_velocity(tandem_body_id body, tandem_vec2 p) {
  return to_c(body_point_velocity(to_cpp(body), to_cpp(p)));
}
tandem_status tandem_body_apply_force(tandem_body_id body, tandem_vec2 force, tandem_vec2 point, bool wake) {
  return guard("tandem_body_apply_force",
               [&] { return status(body_apply_force(to_cpp(body), to_cpp(force), to_cpp(point), wake)); });
}
tandem_status tandem_body_apply_force_to_center(tandem_body_id body, tandem_vec2 force, bool wake) {
  return guard("tandem_body_apply_force_to_center",
               [&] { return status(body_apply_force_to_center(to_cpp(body), to_cpp(force), wake)); });
}
tandem_status tandem_body_apply_torque(tandem_body_id body, tandem_q32 torque, bool wake) {
  return guard("tandem_body_apply_torque", [&] { return status(body_apply_torque(to_cpp(body), q(torque), wake)); });
}
tandem_status tandem_body_apply_linear_impulse(tandem_body_id body, tandem_vec2 impulse, tandem_vec2 point, bool wake) {
  return guard("tandem_body_apply_linear_impulse",
               [&] { return status(body_apply_linear_impulse(to_cpp(body), to_cpp(impulse), to_cpp(point), wake)); });
}
tandem_status tandem_body_apply_linear_impulse_to_center(tandem_body_id body, tandem_vec2 impulse, bool wake) {
  return guard("tandem_body_apply_linear_impulse_to_center",
               [&] { return status(body_apply_linear_impulse_to_center(to_cpp(body), to_cpp(impulse), wake)); });
}
tandem_status tandem_body_apply_angular_impulse(tandem_body_id body, tandem_q32 impulse, bool wake) {
  return guard("tandem_body_apply_angular_impulse",
               [&] { return status(body_apply_angular_impulse(to_cpp(body), q(impulse), wake)); });
}
tandem_q32 tandem_body_mass(tandem_body_id body) { return body_mass(to_cpp(body)).raw; }
tandem_q32 tandem_body_rotational_inertia(tandem_body_id body) { return body_rotational_inertia(to_cpp(body)).raw; }
tandem_mass_data tandem_body_mass_data(tandem_body_id body) { return to_c(body_mass_data(to_cpp(body))); }
tandem_q32 tandem_body_linear_damping(tandem_body_id body) { return body_linear_damping(to_cpp(body)).raw; }
tandem_status tandem_body_set_linear_damping(tandem_body_id body, tandem_q32 d) {
  return guard("tandem_body_set_linear_damping", [&] { return status(body_set_linear_damping(to_cpp(body), q(d))); });
}
tandem_q32 tandem_body_angular_damping(tandem_body_id body) { return body_angular_damping(to_cpp(body)).raw; }
tandem_status tandem_body_set_angular_damping(tandem_body_id body, tandem_q32 d) {
  return guard("tandem_body_set_angular_damping", [&] { return status(body_set_angular_damping(to_cpp(body), q(d))); });
}
tandem_q32 tandem_body_gravity_scale(tandem_body_id body) { return body_gravity_scale(to_cpp(body)).raw; }
tandem_status tandem_body_set_gravity_scale(tandem_body_id body, tandem_q32 s) {
  return guard("tandem_body_set_gravity_scale", [&] { return status(body_set_gravity_scale(to_cpp(body), q(s))); });
}
bool tandem_body_is_fixed_rotation(tandem_body_id body) { return body_is_fixed_rotation(to_cpp(body)); }
tandem_status tandem_body_set_fixed_rotation(tandem_body_id body, bool fixed) {
  return guard("tandem_body_set_fixed_rotation", [&] { return status(body_set_fixed_rotation(to_cpp(body), fixed)); });
}
bool tandem_body_is_bullet(tandem_body_id body) { return body_is_bullet(to_cpp(body)); }
tandem_status tandem_body_set_bullet(tandem_body_id body, bool bullet) {
  return guard("tandem_body_set_bullet", [&] { return status(body_set_bullet(to_cpp(body), bullet)); });
}
bool tandem_body_is_enabled(tandem_body_id body) { return body_is_enabled(to_cpp(body)); }
tandem_status tandem_body_set_enabled(tandem_body_id body, bool enabled) {
  return guard("tandem_body_set_enabled", [&] { return status(body_set_enabled(to_cpp(body), enabled)); });
}
tandem_status tandem_body_enable(tandem_body_id body) {
  return guard("tandem_body_enable", [&] { return status(body_set_enabled(to_cpp(body), true)); });
}
tandem_status tandem_body_disable(tandem_body_id body) {
  return guard("tandem_body_disable", [&] { return status(body_set_enabled(to_cpp(body), false)); });
}
bool tandem_body_is_awake(tandem_body_id body) { return body_is_awake(to_cpp(body)); }
tandem_status tandem_body_set_awake(tandem_body_id body, bool awake) {
  return guard("tandem_body_set_awake", [&] { return status(body_set_awake(to_cpp(body), awake)); });
}
bool tandem_body_is_sleep_enabled(tandem_body_id body) { return body_is_sleep_enabled(to_cpp(body)); }
tandem_status tandem_body_enable_sleep(tandem_body_id body, bool enable) {
  return guard("tandem_body_enable_sleep", [&] { return status(body_enable_sleep(to_cpp(body), enable)); });
}
uint64_t tandem_body_user_data(tandem_body_id body) { return body_user_data(to_cpp(body)); }
tandem_status tandem_body_set_user_data(tandem_body_id body, uint64_t user_data) {
  return guard("tandem_body_set_user_data", [&] { return status(body_set_user_data(to_cpp(body), user_data)); });
}
tandem_vec2 tandem_body_world_point(tandem_body_id body, tandem_vec2 p) { return to_c(body_world_point(to_cpp(body), to_cpp(p))); }
tandem_vec2 tandem_body_local_point(tandem_body_id body, tandem_vec2 p) { return to_c(body_local_point(to_cpp(body), to_cpp(p))); }
tandem_vec2 tandem_body_world_vector(tandem_body_id body, tandem_vec2 v) {
  return to_c(body_world_vector(to_cpp(body), to_cpp(v)));
}
tandem_vec2 tandem_body_local_vector(tandem_body_id body, tandem_vec2 v) {
  return to_c(body_local_vector(to_cpp(body), to_cpp(v)));
}
int32_t tandem_body_shape_count(tandem_body_id body) { return body_shape_count(to_cpp(body)); }

tandem_status tandem_body_shapes(tandem_body_id body, tandem_shape_id* out_shapes, int32_t capacity, int32_t* out_count) {
  static const char* fn = "tandem_body_shapes";
  return guard(fn, [&] {
    const BodyId b = to_cpp(body);
    if (const Status s = body_check(b); !s.ok()) return status(s);
    std::vector<ShapeId> ids(static_cast<size_t>(body_shape_count(b)));
    body_shapes(b, ids.data(), static_cast<int32_t>(ids.size()));
    return fill(fn, std::span<const ShapeId>(ids), out_shapes, capacity, out_count, [](ShapeId s) { return to_c(s); });
  });
}

// --- shapes --------------------------------------------------------------------------
namespace {
using tandem_c_internal::to_c;
using tandem_c_internal::to_cpp;
template <typename CGeom, typename Create>
tandem_status create_shape(const char* fn, const tandem_shape_def* def, const CGeom* geom, tandem_shape_id* out,
                           Create&& create) {
  if (def == nullptr) return null_pointer(fn, "def");
  if (geom == nullptr) return null_pointer(fn, "the geometry");
  if (out == nullptr) return null_pointer(fn, "out_shape");
  return guard(fn, [&] {
    const Result<ShapeId> r = create(to_cpp(*def), to_cpp(*geom));
    if (r.ok()) *out = to_c(r.value);
    return status(r.status);
  });
}
}  // namespace

tandem_status tandem_create_circle_shape(tandem_body_id body, const tandem_shape_def* def, const tandem_circle* circle,
                                         tandem_shape_id* out_shape) {
  return create_shape("tandem_create_circle_shape", def, circle, out_shape,
                      [&](const ShapeDef& d, const Circle& g) { return create_circle_shape(to_cpp(body), d, g); });
}
tandem_status tandem_create_capsule_shape(tandem_body_id body, const tandem_shape_def* def, const tandem_capsule* capsule,
                                          tandem_shape_id* out_shape) {
  return create_shape("tandem_create_capsule_shape", def, capsule, out_shape,
                      [&](const ShapeDef& d, const Capsule& g) { return create_capsule_shape(to_cpp(body), d, g); });
}
tandem_status tandem_create_polygon_shape(tandem_body_id body, const tandem_shape_def* def, const tandem_polygon* polygon,
                                          tandem_shape_id* out_shape) {
  return create_shape("tandem_create_polygon_shape", def, polygon, out_shape,
                      [&](const ShapeDef& d, const Polygon& g) { return create_polygon_shape(to_cpp(body), d, g); });
}
tandem_status tandem_create_segment_shape(tandem_body_id body, const tandem_shape_def* def, const tandem_segment* segment,
                                          tandem_shape_id* out_shape) {
  return create_shape("tandem_create_segment_shape", def, segment, out_shape,
                      [&](const ShapeDef& d, const Segment& g) { return create_segment_shape(to_cpp(body), d, g); });
}

tandem_status tandem_create_chain_shapes(tandem_body_id body, const tandem_shape_def* def, const tandem_vec2* points,
                                         int32_t count, bool loop, tandem_shape_id* out_shapes, int32_t capacity,
                                         int32_t* out_count) {
  static const char* fn = "tandem_create_chain_shapes";
  if (def == nullptr) return null_pointer(fn, "def");
  if (points == nullptr && count != 0) return null_pointer(fn, "points");
  if (out_count == nullptr) return null_pointer(fn, "out_count");
  if (count < 0) return fail(TANDEM_ERROR_INVALID_ARGUMENT, std::string(fn) + ": count is negative");
  if (capacity < 0) return fail(TANDEM_ERROR_INVALID_ARGUMENT, std::string(fn) + ": capacity is negative");
  if (out_shapes == nullptr && capacity != 0) return null_pointer(fn, "out_shapes (with a non-zero capacity)");
  return guard(fn, [&] {
    // The segment count make_chain_segments will produce (checked there too).
    const int32_t needed = loop ? count : (count >= 3 ? count - 3 : 0);
    if (out_shapes != nullptr && capacity < needed) {
      *out_count = needed;
      return fail(TANDEM_ERROR_BUFFER_TOO_SMALL, std::string(fn) + ": the buffer holds " + std::to_string(capacity) +
                                                     " shapes, the chain has " + std::to_string(needed) +
                                                     " segments; nothing was created");
    }
    std::vector<Vec2> pts;
    pts.reserve(static_cast<size_t>(count));
    for (int32_t i = 0; i < count; ++i) pts.push_back(to_cpp(points[i]));
    std::vector<ShapeId> ids;
    const Status s = create_chain_shapes(to_cpp(body), to_cpp(*def), pts.data(), count, loop, &ids);
    if (!s.ok()) return status(s);
    *out_count = static_cast<int32_t>(ids.size());
    if (out_shapes != nullptr)
      for (size_t i = 0; i < ids.size(); ++i) out_shapes[i] = to_c(ids[i]);
    return succeed();
  });
}

tandem_status tandem_destroy_shape(tandem_shape_id shape) {
  return guard("tandem_destroy_shape", [&] { return status(destroy_shape(to_cpp(shape))); });
}
bool tandem_shape_is_valid(tandem_shape_id shape) { return shape_is_valid(to_cpp(shape)); }
tandem_status tandem_shape_check(tandem_shape_id shape, tandem_world_id expected_world) {
  return guard("tandem_shape_check", [&] { return status(shape_check(to_cpp(shape), to_cpp(expected_world))); });
}
int32_t tandem_shape_type(tandem_shape_id shape) { return static_cast<int32_t>(shape_type(to_cpp(shape))); }
tandem_body_id tandem_shape_body(tandem_shape_id shape) { return to_c(shape_body(to_cpp(shape))); }
tandem_shape_geometry tandem_shape_geometry_of(tandem_shape_id shape) { return to_c(shape_geometry(to_cpp(shape))); }
tandem_aabb tandem_shape_aabb(tandem_shape_id shape) { return to_c(shape_aabb(to_cpp(shape))); }
tandem_mass_data tandem_shape_mass_data(tandem_shape_id shape) { return to_c(shape_mass_data(to_cpp(shape))); }
tandem_q32 tandem_shape_friction(tandem_shape_id shape) { return shape_friction(to_cpp(shape)).raw; }
tandem_status tandem_shape_set_friction(tandem_shape_id shape, tandem_q32 v) {
  return guard("tandem_shape_set_friction", [&] { return status(shape_set_friction(to_cpp(shape), q(v))); });
}
tandem_q32 tandem_shape_restitution(tandem_shape_id shape) { return shape_restitution(to_cpp(shape)).raw; }
tandem_status tandem_shape_set_restitution(tandem_shape_id shape, tandem_q32 v) {
  return guard("tandem_shape_set_restitution", [&] { return status(shape_set_restitution(to_cpp(shape), q(v))); });
}
tandem_q32 tandem_shape_density(tandem_shape_id shape) { return shape_density(to_cpp(shape)).raw; }
tandem_status tandem_shape_set_density(tandem_shape_id shape, tandem_q32 v) {
  return guard("tandem_shape_set_density", [&] { return status(shape_set_density(to_cpp(shape), q(v))); });
}
bool tandem_shape_is_sensor(tandem_shape_id shape) { return shape_is_sensor(to_cpp(shape)); }
tandem_filter tandem_shape_filter(tandem_shape_id shape) { return to_c(shape_filter(to_cpp(shape))); }
tandem_status tandem_shape_set_filter(tandem_shape_id shape, tandem_filter filter) {
  return guard("tandem_shape_set_filter", [&] { return status(shape_set_filter(to_cpp(shape), to_cpp(filter))); });
}
uint64_t tandem_shape_user_data(tandem_shape_id shape) { return shape_user_data(to_cpp(shape)); }
tandem_status tandem_shape_set_user_data(tandem_shape_id shape, uint64_t user_data) {
  return guard("tandem_shape_set_user_data", [&] { return status(shape_set_user_data(to_cpp(shape), user_data)); });
}

// --- queries ----------------------------------------------------------------------------
tandem_query_filter tandem_default_query_filter(void) {
  const QueryFilter f;
  tandem_query_filter o;
  std::memset(&o, 0, sizeof o);
  o.category_bits = f.category_bits;
  o.mask_bits = f.mask_bits;
  o.include_sensors = f.include_sensors;
  return o;
}

tandem_status tandem_world_cast_ray_closest(tandem_world_id world, tandem_vec2 origin, tandem_vec2 translation,
                                            const tandem_query_filter* filter, tandem_ray_hit* out_hit) {
  static const char* fn = "tandem_world_cast_ray_closest";
  if (out_hit == nullptr) return null_pointer(fn, "out_hit");
  return guard(fn, [&] {
    const Result<RayHit> r = world_cast_ray_closest(to_cpp(world), to_cpp(origin), to_cpp(translation), to_cpp(filter));
    if (r.ok()) *out_hit = to_c(r.value);
    return status(r.status);
  });
}

tandem_status tandem_world_cast_ray_all(tandem_world_id world, tandem_vec2 origin, tandem_vec2 translation,
                                        const tandem_query_filter* filter, tandem_ray_hit* out_hits, int32_t capacity,
                                        int32_t* out_count) {
  static const char* fn = "tandem_world_cast_ray_all";
  return guard(fn, [&] {
    std::vector<RayHit> hits;
    const Status s = world_cast_ray_all(to_cpp(world), to_cpp(origin), to_cpp(translation), to_cpp(filter), &hits);
    if (!s.ok()) return status(s);
    return fill(fn, std::span<const RayHit>(hits), out_hits, capacity, out_count, [](const RayHit& h) { return to_c(h); });
  });
}

namespace {
using tandem_c_internal::to_c;
using tandem_c_internal::to_cpp;
// Runs a shape-list query and copies the result (buffer rule).
template <typename Query>
tandem_status shape_query(const char* fn, tandem_shape_id* out, int32_t capacity, int32_t* out_count, Query&& query) {
  return guard(fn, [&] {
    std::vector<ShapeId> ids;
    const Status s = query(&ids);
    if (!s.ok()) return status(s);
    return fill(fn, std::span<const ShapeId>(ids), out, capacity, out_count, [](ShapeId id) { return to_c(id); });
  });
}
}  // namespace

tandem_status tandem_world_overlap_aabb(tandem_world_id world, tandem_aabb box, const tandem_query_filter* filter,
                                        tandem_shape_id* out_shapes, int32_t capacity, int32_t* out_count) {
  return shape_query("tandem_world_overlap_aabb", out_shapes, capacity, out_count, [&](std::vector<ShapeId>* ids) {
    return world_overlap_aabb(to_cpp(world), to_cpp(box), to_cpp(filter), ids);
  });
}
tandem_status tandem_world_overlap_point(tandem_world_id world, tandem_vec2 point, const tandem_query_filter* filter,
                                         tandem_shape_id* out_shapes, int32_t capacity, int32_t* out_count) {
  return shape_query("tandem_world_overlap_point", out_shapes, capacity, out_count, [&](std::vector<ShapeId>* ids) {
    return world_overlap_point(to_cpp(world), to_cpp(point), to_cpp(filter), ids);
  });
}
tandem_status tandem_world_overlap_circle(tandem_world_id world, const tandem_circle* circle, tandem_transform transform,
                                          const tandem_query_filter* filter, tandem_shape_id* out_shapes, int32_t capacity,
                                          int32_t* out_count) {
  if (circle == nullptr) return null_pointer("tandem_world_overlap_circle", "circle");
  return shape_query("tandem_world_overlap_circle", out_shapes, capacity, out_count, [&](std::vector<ShapeId>* ids) {
    return world_overlap_circle(to_cpp(world), to_cpp(*circle), to_cpp(transform), to_cpp(filter), ids);
  });
}
tandem_status tandem_world_overlap_capsule(tandem_world_id world, const tandem_capsule* capsule, tandem_transform transform,
                                           const tandem_query_filter* filter, tandem_shape_id* out_shapes, int32_t capacity,
                                           int32_t* out_count) {
  if (capsule == nullptr) return null_pointer("tandem_world_overlap_capsule", "capsule");
  return shape_query("tandem_world_overlap_capsule", out_shapes, capacity, out_count, [&](std::vector<ShapeId>* ids) {
    return world_overlap_capsule(to_cpp(world), to_cpp(*capsule), to_cpp(transform), to_cpp(filter), ids);
  });
}
tandem_status tandem_world_overlap_polygon(tandem_world_id world, const tandem_polygon* polygon, tandem_transform transform,
                                           const tandem_query_filter* filter, tandem_shape_id* out_shapes, int32_t capacity,
                                           int32_t* out_count) {
  if (polygon == nullptr) return null_pointer("tandem_world_overlap_polygon", "polygon");
  return shape_query("tandem_world_overlap_polygon", out_shapes, capacity, out_count, [&](std::vector<ShapeId>* ids) {
    return world_overlap_polygon(to_cpp(world), to_cpp(*polygon), to_cpp(transform), to_cpp(filter), ids);
  });
}

// --- events --------------------------------------------------------------------------------
tandem_status tandem_world_contact_begin_events(tandem_world_id world, tandem_contact_begin_event* out, int32_t capacity,
                                                int32_t* out_count) {
  static const char* fn = "tandem_world_contact_begin_events";
  return guard(fn, [&] {
    const Result<ContactEvents> r = world_contact_events(to_cpp(world));
    if (!r.ok()) return status(r.status);
    return fill(fn, r.value.begin, out, capacity, out_count, [](const ContactBeginEvent& e) {
      return tandem_contact_begin_event{to_c(e.shape_a), to_c(e.shape_b), to_c(e.manifold)};
    });
  });
}
tandem_status tandem_world_contact_end_events(tandem_world_id world, tandem_contact_end_event* out, int32_t capacity,
                                              int32_t* out_count) {
  static const char* fn = "tandem_world_contact_end_events";
  return guard(fn, [&] {
    const Result<ContactEvents> r = world_contact_events(to_cpp(world));
    if (!r.ok()) return status(r.status);
    return fill(fn, r.value.end, out, capacity, out_count, [](const ContactEndEvent& e) {
      return tandem_contact_end_event{to_c(e.shape_a), to_c(e.shape_b)};
    });
  });
}
tandem_status tandem_world_contact_hit_events(tandem_world_id world, tandem_contact_hit_event* out, int32_t capacity,
                                              int32_t* out_count) {
  static const char* fn = "tandem_world_contact_hit_events";
  return guard(fn, [&] {
    const Result<ContactEvents> r = world_contact_events(to_cpp(world));
    if (!r.ok()) return status(r.status);
    return fill(fn, r.value.hit, out, capacity, out_count, [](const ContactHitEvent& e) {
      return tandem_contact_hit_event{to_c(e.shape_a), to_c(e.shape_b), to_c(e.point), to_c(e.normal),
                                      e.approach_speed.raw};
    });
  });
}
tandem_status tandem_world_sensor_begin_events(tandem_world_id world, tandem_sensor_event* out, int32_t capacity,
                                               int32_t* out_count) {
  static const char* fn = "tandem_world_sensor_begin_events";
  return guard(fn, [&] {
    const Result<SensorEvents> r = world_sensor_events(to_cpp(world));
    if (!r.ok()) return status(r.status);
    return fill(fn, r.value.begin, out, capacity, out_count,
                [](const SensorEvent& e) { return tandem_sensor_event{to_c(e.sensor), to_c(e.visitor)}; });
  });
}
tandem_status tandem_world_sensor_end_events(tandem_world_id world, tandem_sensor_event* out, int32_t capacity,
                                             int32_t* out_count) {
  static const char* fn = "tandem_world_sensor_end_events";
  return guard(fn, [&] {
    const Result<SensorEvents> r = world_sensor_events(to_cpp(world));
    if (!r.ok()) return status(r.status);
    return fill(fn, r.value.end, out, capacity, out_count,
                [](const SensorEvent& e) { return tandem_sensor_event{to_c(e.sensor), to_c(e.visitor)}; });
  });
}
tandem_status tandem_world_body_move_events(tandem_world_id world, tandem_body_move_event* out, int32_t capacity,
                                            int32_t* out_count) {
  static const char* fn = "tandem_world_body_move_events";
  return guard(fn, [&] {
    const Result<BodyEvents> r = world_body_events(to_cpp(world));
    if (!r.ok()) return status(r.status);
    return fill(fn, r.value.move, out, capacity, out_count, [](const BodyMoveEvent& e) {
      tandem_body_move_event o;
      std::memset(&o, 0, sizeof o);
      o.body = to_c(e.body);
      o.transform = to_c(e.transform);
      o.fell_asleep = e.fell_asleep;
      return o;
    });
  });
}

// tandem_c_geometry.cpp — the C API of single-shape geometry
// (include/tandem_c_geometry.h over physics/collision.h).
// (design and how to add a function: tandem_c_core.cpp's top comment).
#include "tandem_c_internal.h"

using namespace tandem_c_internal;

namespace {
using tandem_c_internal::to_c;
using tandem_c_internal::to_cpp;

// A C shape geometry as C++, refusing an unknown type.
tandem_status geometry_of(const char* fn, const char* name, const tandem_shape_geometry* g, ShapeGeometry* out) {
  if (g == nullptr) return null_pointer(fn, name);
  if (g->type < TANDEM_SHAPE_CIRCLE || g->type > TANDEM_SHAPE_CHAIN_SEGMENT) {
    return fail(TANDEM_ERROR_INVALID_ARGUMENT, std::string(fn) + ": " + name + ".type " + std::to_string(g->type) +
                                                   " is not 0…4 (TANDEM_SHAPE_*)");
  }
  out->type = static_cast<ShapeType>(g->type);
  out->circle = to_cpp(g->circle);
  out->capsule = to_cpp(g->capsule);
  out->segment = to_cpp(g->segment);
  out->polygon = to_cpp(g->polygon);
  out->chain_segment = to_cpp(g->chain_segment);
  return TANDEM_OK;
}

template <typename C, typename Validate>
tandem_status validate(const char* fn, const C* shape, Validate&& check) {
  if (shape == nullptr) return null_pointer(fn, "shape");
  return guard(fn, [&] { return geometry(fn, check(to_cpp(*shape))); });
}

template <typename C, typename Mass>
tandem_status mass(const char* fn, const C* shape, tandem_q32 density, tandem_mass_data* out, Mass&& compute) {
  if (shape == nullptr) return null_pointer(fn, "shape");
  if (out == nullptr) return null_pointer(fn, "out_mass");
  return guard(fn, [&] {
    *out = to_c(compute(to_cpp(*shape), q(density)));
    return succeed();
  });
}

ShapeProxy to_cpp(const tandem_shape_proxy& p) {
  ShapeProxy o;
  for (size_t i = 0; i < o.points.size(); ++i) o.points[i] = to_cpp(p.points[i]);
  o.count = p.count;
  o.radius = q(p.radius);
  return o;
}
tandem_shape_proxy to_c(const ShapeProxy& p) {
  tandem_shape_proxy o;
  std::memset(&o, 0, sizeof o);
  for (size_t i = 0; i < p.points.size(); ++i) o.points[i] = to_c(p.points[i]);
  o.count = p.count;
  o.radius = p.radius.raw;
  return o;
}
Sweep to_cpp(const tandem_sweep& s) {
  return {to_cpp(s.local_center), to_cpp(s.c1), to_cpp(s.c2), to_cpp(s.q1), to_cpp(s.q2)};
}
tandem_cast_output to_c(const CastOutput& o) {
  tandem_cast_output c;
  std::memset(&c, 0, sizeof c);
  c.normal = to_c(o.normal);
  c.point = to_c(o.point);
  c.fraction = o.fraction.raw;
  c.iterations = o.iterations;
  c.hit = o.hit;
  return c;
}
// A proxy's count must index its points array.
tandem_status check_proxy(const char* fn, const char* name, const tandem_shape_proxy& p) {
  if (p.count < 1 || p.count > TANDEM_MAX_POLYGON_VERTICES) {
    return fail(TANDEM_ERROR_INVALID_ARGUMENT,
                std::string(fn) + ": " + name + ".count " + std::to_string(p.count) + " is outside 1…8");
  }
  return TANDEM_OK;
}

}  // namespace

tandem_status tandem_validate_circle(const tandem_circle* circle) {
  return validate("tandem_validate_circle", circle, [](const Circle& c) { return validate_circle(c); });
}
tandem_status tandem_validate_capsule(const tandem_capsule* capsule) {
  return validate("tandem_validate_capsule", capsule, [](const Capsule& c) { return validate_capsule(c); });
}
tandem_status tandem_validate_segment(const tandem_segment* segment) {
  return validate("tandem_validate_segment", segment, [](const Segment& s) { return validate_segment(s); });
}
tandem_status tandem_validate_polygon(const tandem_polygon* polygon) {
  return validate("tandem_validate_polygon", polygon, [](const Polygon& p) { return validate_polygon(p); });
}

tandem_status tandem_compute_circle_mass(const tandem_circle* circle, tandem_q32 density, tandem_mass_data* out) {
  return mass("tandem_compute_circle_mass", circle, density, out,
              [](const Circle& c, Q32 d) { return compute_circle_mass(c, d); });
}
tandem_status tandem_compute_capsule_mass(const tandem_capsule* capsule, tandem_q32 density, tandem_mass_data* out) {
  return mass("tandem_compute_capsule_mass", capsule, density, out,
              [](const Capsule& c, Q32 d) { return compute_capsule_mass(c, d); });
}
tandem_status tandem_compute_polygon_mass(const tandem_polygon* polygon, tandem_q32 density, tandem_mass_data* out) {
  return mass("tandem_compute_polygon_mass", polygon, density, out,
              [](const Polygon& p, Q32 d) { return compute_polygon_mass(p, d); });
}

tandem_status tandem_compute_shape_aabb(const tandem_shape_geometry* shape, tandem_transform transform,
                                        tandem_aabb* out_aabb) {
  static const char* fn = "tandem_compute_shape_aabb";
  if (out_aabb == nullptr) return null_pointer(fn, "out_aabb");
  ShapeGeometry g;
  if (const tandem_status s = geometry_of(fn, "shape", shape, &g); s != TANDEM_OK) return s;
  return guard(fn, [&] {
    const Transform xf = to_cpp(transform);
    switch (g.type) {
      case ShapeType::circle: *out_aabb = to_c(compute_circle_aabb(g.circle, xf)); break;
      case ShapeType::capsule: *out_aabb = to_c(compute_capsule_aabb(g.capsule, xf)); break;
      case ShapeType::segment: *out_aabb = to_c(compute_segment_aabb(g.segment, xf)); break;
      case ShapeType::polygon: *out_aabb = to_c(compute_polygon_aabb(g.polygon, xf)); break;
      default: *out_aabb = to_c(compute_chain_segment_aabb(g.chain_segment, xf)); break;
    }
    return succeed();
  });
}

tandem_status tandem_point_in_shape(const tandem_shape_geometry* shape, tandem_vec2 point, bool* out_inside) {
  static const char* fn = "tandem_point_in_shape";
  if (out_inside == nullptr) return null_pointer(fn, "out_inside");
  ShapeGeometry g;
  if (const tandem_status s = geometry_of(fn, "shape", shape, &g); s != TANDEM_OK) return s;
  return guard(fn, [&] {
    const Vec2 p = to_cpp(point);
    switch (g.type) {
      case ShapeType::circle: *out_inside = point_in_circle(p, g.circle); break;
      case ShapeType::capsule: *out_inside = point_in_capsule(p, g.capsule); break;
      case ShapeType::polygon: *out_inside = point_in_polygon(p, g.polygon); break;
      default: *out_inside = false; break;  // segments have no inside
    }
    return succeed();
  });
}

tandem_status tandem_ray_cast_shape(const tandem_shape_geometry* shape, const tandem_ray_cast_input* input,
                                    tandem_cast_output* out) {
  static const char* fn = "tandem_ray_cast_shape";
  if (input == nullptr) return null_pointer(fn, "input");
  if (out == nullptr) return null_pointer(fn, "out");
  ShapeGeometry g;
  if (const tandem_status s = geometry_of(fn, "shape", shape, &g); s != TANDEM_OK) return s;
  return guard(fn, [&] {
    const RayCastInput in{to_cpp(input->origin), to_cpp(input->translation), q(input->max_fraction)};
    CastOutput o;
    switch (g.type) {
      case ShapeType::circle: o = ray_cast_circle(in, g.circle); break;
      case ShapeType::capsule: o = ray_cast_capsule(in, g.capsule); break;
      case ShapeType::segment: o = ray_cast_segment(in, g.segment, false); break;
      case ShapeType::polygon: o = ray_cast_polygon(in, g.polygon); break;
      default: o = ray_cast_segment(in, g.chain_segment.segment, true); break;
    }
    *out = to_c(o);
    return succeed();
  });
}

tandem_status tandem_collide(const tandem_shape_geometry* a, tandem_transform transform_a,
                             const tandem_shape_geometry* b, tandem_transform transform_b,
                             tandem_manifold* out_manifold) {
  static const char* fn = "tandem_collide";
  if (out_manifold == nullptr) return null_pointer(fn, "out_manifold");
  ShapeGeometry ga, gb;
  if (const tandem_status s = geometry_of(fn, "a", a, &ga); s != TANDEM_OK) return s;
  if (const tandem_status s = geometry_of(fn, "b", b, &gb); s != TANDEM_OK) return s;
  return guard(fn, [&] {
    *out_manifold = to_c(collide(ga, to_cpp(transform_a), gb, to_cpp(transform_b)));
    return succeed();
  });
}

tandem_status tandem_make_proxy(const tandem_vec2* points, int32_t count, tandem_q32 radius,
                                tandem_shape_proxy* out_proxy) {
  static const char* fn = "tandem_make_proxy";
  if (out_proxy == nullptr) return null_pointer(fn, "out_proxy");
  if (points == nullptr && count > 0) return null_pointer(fn, "points");
  return guard(fn, [&] {
    std::vector<Vec2> p;
    for (int32_t i = 0; i < count && i < TANDEM_MAX_POLYGON_VERTICES; ++i) p.push_back(to_cpp(points[i]));
    *out_proxy = to_c(make_proxy(p.data(), static_cast<int32_t>(p.size()), q(radius)));
    return succeed();
  });
}

tandem_status tandem_make_shape_proxy(const tandem_shape_geometry* shape, tandem_shape_proxy* out_proxy) {
  static const char* fn = "tandem_make_shape_proxy";
  if (out_proxy == nullptr) return null_pointer(fn, "out_proxy");
  ShapeGeometry g;
  if (const tandem_status s = geometry_of(fn, "shape", shape, &g); s != TANDEM_OK) return s;
  return guard(fn, [&] {
    switch (g.type) {
      case ShapeType::circle: *out_proxy = to_c(make_proxy(g.circle)); break;
      case ShapeType::capsule: *out_proxy = to_c(make_proxy(g.capsule)); break;
      case ShapeType::segment: *out_proxy = to_c(make_proxy(g.segment)); break;
      case ShapeType::polygon: *out_proxy = to_c(make_proxy(g.polygon)); break;
      default:
        return fail(TANDEM_ERROR_INVALID_ARGUMENT,
                    std::string(fn) + ": a chain segment has no proxy (use its segment)");
    }
    return succeed();
  });
}

tandem_status tandem_shape_distance(const tandem_distance_input* input, tandem_distance_output* out) {
  static const char* fn = "tandem_shape_distance";
  if (input == nullptr) return null_pointer(fn, "input");
  if (out == nullptr) return null_pointer(fn, "out");
  if (const tandem_status s = check_proxy(fn, "proxy_a", input->proxy_a); s != TANDEM_OK) return s;
  if (const tandem_status s = check_proxy(fn, "proxy_b", input->proxy_b); s != TANDEM_OK) return s;
  return guard(fn, [&] {
    const DistanceOutput d = shape_distance(DistanceInput{to_cpp(input->proxy_a), to_cpp(input->proxy_b),
                                                          to_cpp(input->transform_a), to_cpp(input->transform_b),
                                                          input->use_radii});
    *out = tandem_distance_output{to_c(d.point_a), to_c(d.point_b), to_c(d.normal), d.distance.raw, d.iterations,
                                  d.simplex_count};
    return succeed();
  });
}

tandem_status tandem_shape_cast(const tandem_shape_cast_input* input, tandem_cast_output* out) {
  static const char* fn = "tandem_shape_cast";
  if (input == nullptr) return null_pointer(fn, "input");
  if (out == nullptr) return null_pointer(fn, "out");
  if (const tandem_status s = check_proxy(fn, "proxy_a", input->proxy_a); s != TANDEM_OK) return s;
  if (const tandem_status s = check_proxy(fn, "proxy_b", input->proxy_b); s != TANDEM_OK) return s;
  return guard(fn, [&] {
    *out = to_c(shape_cast(ShapeCastInput{to_cpp(input->proxy_a), to_cpp(input->proxy_b), to_cpp(input->transform_a),
                                          to_cpp(input->transform_b), to_cpp(input->translation_b),
                                          q(input->max_fraction), input->can_encroach}));
    return succeed();
  });
}

tandem_status tandem_sweep_transform(const tandem_sweep* sweep, tandem_q32 t, tandem_transform* out_transform) {
  static const char* fn = "tandem_sweep_transform";
  if (sweep == nullptr) return null_pointer(fn, "sweep");
  if (out_transform == nullptr) return null_pointer(fn, "out_transform");
  return guard(fn, [&] {
    *out_transform = to_c(sweep_transform(to_cpp(*sweep), q(t)));
    return succeed();
  });
}

tandem_status tandem_time_of_impact(const tandem_toi_input* input, tandem_toi_output* out) {
  static const char* fn = "tandem_time_of_impact";
  if (input == nullptr) return null_pointer(fn, "input");
  if (out == nullptr) return null_pointer(fn, "out");
  if (const tandem_status s = check_proxy(fn, "proxy_a", input->proxy_a); s != TANDEM_OK) return s;
  if (const tandem_status s = check_proxy(fn, "proxy_b", input->proxy_b); s != TANDEM_OK) return s;
  return guard(fn, [&] {
    const ToiOutput o = time_of_impact(ToiInput{to_cpp(input->proxy_a), to_cpp(input->proxy_b),
                                                to_cpp(input->sweep_a), to_cpp(input->sweep_b),
                                                q(input->max_fraction)});
    *out = tandem_toi_output{static_cast<int32_t>(o.state), o.fraction.raw, o.iterations};
    return succeed();
  });
}

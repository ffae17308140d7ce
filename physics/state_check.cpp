// state_check.cpp — checks of a decoded state image before it may replace a
// world's state (state_access.h check_image): cross references first, then
// every value against the engine's limits and every cached value against
// the value derived from the others.
//
// Every restored value is held to the limits the public API enforces when the
// value enters a world (limits.h, tandem.h), widened only where a legal
// simulation can carry a value past the entry limit (speeds after a contact
// solve, say), and every cached value that the engine derives from others is
// recomputed here and must match bit for bit: shape bounds from geometry and
// pose, body mass, inertia, their inverses and the centre of mass from the
// shapes, the world centre from the pose, the continuous-collision extents.
// So an image can only hold states the API could have produced (or states
// as safe), and no build's unchecked in-range arithmetic (contact_solver.cpp)
// ever sees a value that would make it wrap where another build saturates.
// A refusal names the record and field; replay turns that into a byte offset.
#include <array>
#include <string>
#include <vector>

#include "fixed/str_cat.h"
#include "physics/body.h"
#include "physics/broad_phase.h"
#include "physics/contact.h"
#include "physics/event_state.h"
#include "physics/id_pool.h"
#include "physics/joint_state.h"
#include "physics/shape.h"
#include "physics/state_fields.h"
#include "physics/state_image.h"
#include "physics/world.h"

namespace tandem::state_access {

namespace {

using state_fields::first_joint_field_out_of_range;
using state_fields::FieldRangeFailure;
using state_fields::point_name;
using state_fields::polygon_name;

/// Largest |linear velocity| component restored for a moving body, m/s: the
/// entry limit leaves room for what one contact solve can add after the
/// sub-step's speed clamp (the next step clamps again).
constexpr Q32 k_max_restored_linear_speed = k_max_linear_speed * 4;
/// |ω| always accepted for a moving body, rad/s; above it the rim speed
/// |ω|·max_extent must stay within k_max_restored_linear_speed (small bodies
/// legitimately spin fast after a glancing contact).
constexpr Q32 k_max_restored_angular_speed = k_max_angular_speed * 4;
/// Largest |stored contact impulse| per point, N·s: the momentum of the
/// heaviest body at the restored speed limit.
constexpr Q32 k_max_restored_impulse = Q32::from_raw(int64_t{400000000} << 32);
/// Largest velocity change (m/s, and rim speed change m/s) that a body's
/// stored contact impulses may apply in the warm start, summed over its
/// contacts: 2^27, 16× inside the Q32.32 range.
constexpr Q32 k_max_warm_start_velocity_change = Q32::from_raw(int64_t{1} << 59);
/// Tolerance on |rotation| and |normal| = 1: 2^-16.
constexpr int64_t k_unit_tolerance_raw = int64_t{1} << 16;
/// Largest |coordinate| of a stored body or contact point, m: a body that
/// left the bounds (then disabled) may stand a little outside them.
constexpr Q32 k_max_restored_coordinate = k_max_world_coordinate * 2;
/// Largest |anchor| or |separation| of a stored contact point, m.
constexpr Q32 k_max_restored_anchor = k_max_shape_size * 4;

/// A record being checked: names it in messages; the offset of a refused
/// field is found by replay (state_access.h, StateRefusal).
struct RecordRef {
  enum Kind { world, body, shape, contact, joint } kind;
  size_t index = 0;
  const World* img = nullptr;

  std::string who() const {
    switch (kind) {
      case world: return "world";
      case body: return "body " + std::to_string(index);
      case shape: return "shape " + std::to_string(index);
      case joint: return "joint " + std::to_string(index);
      case contact: {
        const Contact& c = img->contacts[index];
        return "contact " + std::to_string(index) + " (shapes " + std::to_string(c.shape_a) + ", " +
               std::to_string(c.shape_b) + ")";
      }
    }
    return "?";
  }
  RecordKind record_kind() const {
    switch (kind) {
      case world: return RecordKind::world;
      case body: return RecordKind::body;
      case shape: return RecordKind::shape;
      case contact: return RecordKind::contact;
      case joint: return RecordKind::joint;
    }
    return RecordKind::world;
  }
};

struct ImageChecker {
  World& img;
  StateRefusal* out;
  bool refused = false;

  bool failed() const { return refused; }
  /// Refuses at `field` of `r` (offset_field: where the offset points, when
  /// the message names a group of fields).
  void refuse(const RecordRef& r, const char* field, const std::string& what, const char* offset_field = nullptr) {
    if (failed()) return;
    refused = true;
    out->where = StateRefusal::Where::field;
    out->kind = r.record_kind();
    out->index = static_cast<int64_t>(r.index);
    out->field = offset_field ? offset_field : field;
    out->message = r.who() + " " + field + " " + what;
  }
  static std::string text(Q32 v, const char* unit) { return to_string(v) + (*unit ? std::string(" ") + unit : ""); }
  /// lo ≤ v ≤ hi (lo_open: lo < v). The test is inline; the message is
  /// built out of line, only on failure.
  void range(const RecordRef& r, const char* field, Q32 v, Q32 lo, Q32 hi, const char* unit, bool lo_open = false) {
    if ((lo_open ? lo < v : lo <= v) && v <= hi) return;
    refuse_range(r, field, v, lo, hi, unit, lo_open);
  }
  [[gnu::noinline, gnu::cold]] void refuse_range(const RecordRef& r, const char* field, Q32 v, Q32 lo, Q32 hi,
                                                 const char* unit, bool lo_open) {
    refuse(r, field,
           text(v, unit) + " is outside " + (lo_open ? "(" : "[") + to_string(lo) + ", " + to_string(hi) + "]" +
               (*unit ? std::string(" ") + unit : ""));
  }
  void equal(const RecordRef& r, const char* field, Q32 v, Q32 expected, const char* unit, const char* from) {
    if (v == expected) return;
    refuse_equal(r, field, v, expected, unit, from);
  }
  [[gnu::noinline, gnu::cold]] void refuse_equal(const RecordRef& r, const char* field, Q32 v, Q32 expected,
                                                 const char* unit, const char* from) {
    refuse(r, field,
           text(v, unit) + " does not match the value derived from " + from + " (" + text(expected, unit) +
               "); restore refuses inconsistent cached state");
  }
  /// (x, y) with each component in [−1 − 2^-16, 1 + 2^-16] and x² + y²
  /// within 2^-16 of 1 (normalisation rounds to a few raw units either way).
  void unit(const RecordRef& r, const char* fx, const char* fy, Vec2 v) {
    const Q32 lim = Q32::from_raw(Q32::one().raw + k_unit_tolerance_raw);
    range(r, fx, v.x, -lim, lim, "");
    range(r, fy, v.y, -lim, lim, "");
    if (failed()) return;
    const Q32 n = v.x * v.x + v.y * v.y;  // components ≤ 1 + 2^-16: no saturation
    if ((n - Q32::one()).raw > k_unit_tolerance_raw || (Q32::one() - n).raw > k_unit_tolerance_raw) {
      refuse_unit(r, fx, v, n);
    }
  }
  /// Out of line: the error path only.
  [[gnu::noinline, gnu::cold]] void refuse_unit(const RecordRef& r, const char* fx, Vec2 v, Q32 n) {
    refuse(r, fx,
           str_cat("(", to_string(v.x), ", ", to_string(v.y), ") has squared length ", to_string(n),
                   ", expected 1 ± 2^-16 (a unit vector)"));
  }
};

void check_world(ImageChecker& c) {
  const WorldDef& d = c.img.def;
  const RecordRef r{RecordRef::world, 0, &c.img};
  c.range(r, "gravity.x", d.gravity.x, -k_max_gravity, k_max_gravity, "m/s²");
  c.range(r, "gravity.y", d.gravity.y, -k_max_gravity, k_max_gravity, "m/s²");
  c.range(r, "contact_hertz", d.contact_hertz, Q32::zero(), k_max_hertz, "Hz", true);
  c.range(r, "contact_damping_ratio", d.contact_damping_ratio, Q32::zero(), k_max_damping_ratio, "");
  c.range(r, "max_linear_speed", d.max_linear_speed, Q32::zero(), k_max_linear_speed, "m/s", true);
  if (c.failed()) return;
  c.range(r, "max_contact_push_speed", d.max_contact_push_speed, Q32::zero(), d.max_linear_speed, "m/s");
  c.range(r, "joint_hertz", d.joint_hertz, Q32::zero(), k_max_hertz, "Hz", true);
  c.range(r, "joint_damping_ratio", d.joint_damping_ratio, Q32::zero(), k_max_damping_ratio, "");
  c.range(r, "restitution_threshold", d.restitution_threshold, Q32::zero(), d.max_linear_speed, "m/s");
  c.range(r, "hit_event_threshold", d.hit_event_threshold, Q32::zero(), d.max_linear_speed, "m/s");
  const Q32 m = k_max_world_coordinate;
  c.range(r, "bounds.lower.x", d.bounds.lower.x, -m, m, "m");
  c.range(r, "bounds.lower.y", d.bounds.lower.y, -m, m, "m");
  c.range(r, "bounds.upper.x", d.bounds.upper.x, -m, m, "m");
  c.range(r, "bounds.upper.y", d.bounds.upper.y, -m, m, "m");
  if (!c.failed() && !(d.bounds.lower.x < d.bounds.upper.x && d.bounds.lower.y < d.bounds.upper.y)) {
    c.refuse(r, "bounds", "must have lower < upper on both axes", "bounds.lower.x");
  }
}

/// Per-thread scratch of the checks (grown once, reused by warm restores).
struct CheckScratch {
  std::vector<MassData> masses;
  std::vector<Q32> impulse_sum;
};

CheckScratch& check_scratch() {
  thread_local CheckScratch scratch;
  return scratch;
}

/// Shape fields that need no body: materials, geometry reach, normals.
void check_shapes(ImageChecker& c) {
  World& img = c.img;
  const int32_t shape_cap = static_cast<int32_t>(img.shapes.size());
  for (size_t i = 0; i < img.shapes.size() && !c.failed(); ++i) {
    if (img.shape_pool.alive[i] == 0) continue;
    const Shape& shape = img.shapes[i];
    const ShapeGeometry& g = img.shape_geometries[i];
    const RecordRef r{RecordRef::shape, i, &img};
    c.range(r, "friction", shape.friction, Q32::zero(), k_max_friction, "");
    c.range(r, "restitution", shape.restitution, Q32::zero(), Q32::one(), "");
    c.range(r, "density", shape.density, Q32::zero(), k_max_density, "kg/m²");
    // Reach: every point, grown by the radius, within ±k_max_shape_size of
    // the body origin on each axis (create_*_shape's check), named by field.
    struct Point {
      const char* x;
      const char* y;
      Vec2 p;
    };
    std::array<Point, k_max_polygon_vertices + 1> points{};
    int32_t n = 0;
    const char* radius_name = nullptr;
    Q32 radius;
    switch (g.type) {
      case ShapeType::circle:
        points[0] = {"circle.center.x", "circle.center.y", g.circle.center};
        n = 1;
        radius_name = "circle.radius";
        radius = g.circle.radius;
        break;
      case ShapeType::capsule:
        points[0] = {"capsule.center1.x", "capsule.center1.y", g.capsule.center1};
        points[1] = {"capsule.center2.x", "capsule.center2.y", g.capsule.center2};
        n = 2;
        radius_name = "capsule.radius";
        radius = g.capsule.radius;
        break;
      case ShapeType::segment:
        points[0] = {"segment.point1.x", "segment.point1.y", g.segment.point1};
        points[1] = {"segment.point2.x", "segment.point2.y", g.segment.point2};
        n = 2;
        break;
      case ShapeType::polygon:
        for (int32_t k = 0; k < g.polygon.count; ++k) {
          points[static_cast<size_t>(k)] = {polygon_name(k, 0), polygon_name(k, 1),
                                            g.polygon.vertices[static_cast<size_t>(k)]};
        }
        points[static_cast<size_t>(g.polygon.count)] = {"polygon.centroid.x", "polygon.centroid.y",
                                                        g.polygon.centroid};
        n = g.polygon.count + 1;
        radius_name = "polygon.radius";
        radius = g.polygon.radius;
        break;
      case ShapeType::chain_segment:
        points[0] = {"chain.ghost1.x", "chain.ghost1.y", g.chain_segment.ghost1};
        points[1] = {"chain.point1.x", "chain.point1.y", g.chain_segment.segment.point1};
        points[2] = {"chain.point2.x", "chain.point2.y", g.chain_segment.segment.point2};
        points[3] = {"chain.ghost2.x", "chain.ghost2.y", g.chain_segment.ghost2};
        n = 4;
        break;
      case ShapeType::count: break;
    }
    const Q32 m = k_max_shape_size;
    if (radius_name != nullptr) c.range(r, radius_name, radius, Q32::zero(), m, "m");
    if (c.failed()) return;
    const Q32 reach = m - radius;  // radius ∈ [0, m]: exact
    for (int32_t k = 0; k < n && !c.failed(); ++k) {
      const Point& pt = points[static_cast<size_t>(k)];
      c.range(r, pt.x, pt.p.x, -reach, reach, "m");
      c.range(r, pt.y, pt.p.y, -reach, reach, "m");
    }
    if (c.failed()) return;
    if (!shape_geometry_within_reach(g)) {  // the API's own check, as a backstop
      c.refuse(r, "geometry",
               "reaches farther than k_max_shape_size " + to_string(k_max_shape_size) +
                   " m from the body origin (on an axis)",
               "type");
      return;
    }
    if (g.type == ShapeType::polygon) {
      for (int32_t k = 0; k < g.polygon.count && !c.failed(); ++k) {
        c.unit(r, polygon_name(k, 2), polygon_name(k, 3), g.polygon.normals[static_cast<size_t>(k)]);
      }
    }
    if (g.type == ShapeType::chain_segment) {
      const int32_t id = g.chain_segment.chain_id;
      if (!c.failed() && (id < -1 || id >= shape_cap)) {
        c.refuse(r, "chain.chain_id", std::to_string(id) + " is outside [-1, " + std::to_string(shape_cap - 1) + "]");
      }
    }
  }
}

void check_bodies(ImageChecker& c) {
  World& img = c.img;
  std::vector<MassData>& masses = check_scratch().masses;
  static const std::string k_unnamed;  // messages name the body themselves
  for (size_t b = 0; b < img.bodies.size() && !c.failed(); ++b) {
    if (img.body_pool.alive[b] == 0) continue;
    const Body& body = img.bodies[b];
    const BodySim& sim = img.body_sims[b];
    const RecordRef r{RecordRef::body, b, &img};
    const bool moving = body.type != BodyType::static_body;
    // Pose first: the derived values below depend on it.
    const Q32 wmax = k_max_restored_coordinate;
    c.range(r, "position.x", sim.transform.p.x, -wmax, wmax, "m");
    c.range(r, "position.y", sim.transform.p.y, -wmax, wmax, "m");
    c.unit(r, "rotation.c", "rotation.s", Vec2{sim.transform.q.c, sim.transform.q.s});
    c.range(r, "sleep_time", body.sleep_time, Q32::zero(), k_time_to_sleep, "s");
    c.range(r, "linear_damping", sim.linear_damping, Q32::zero(), k_max_damping, "1/s");
    c.range(r, "angular_damping", sim.angular_damping, Q32::zero(), k_max_damping, "1/s");
    c.range(r, "gravity_scale", sim.gravity_scale, -k_max_gravity_scale, k_max_gravity_scale, "");
    c.range(r, "force.x", sim.force.x, -k_max_force, k_max_force, "N");
    c.range(r, "force.y", sim.force.y, -k_max_force, k_max_force, "N");
    c.range(r, "torque", sim.torque, -k_max_torque, k_max_torque, "N·m");
    const Q32 vmax = moving ? k_max_restored_linear_speed : Q32::zero();
    c.range(r, "linear_velocity.x", sim.linear_velocity.x, -vmax, vmax, "m/s");
    c.range(r, "linear_velocity.y", sim.linear_velocity.y, -vmax, vmax, "m/s");
    if (c.failed()) return;
    // Mass data, derived from the shapes exactly as create and update do
    // (gather_shape_masses + combine_masses, without building names).
    BodyMass m{};
    if (body.type == BodyType::dynamic_body) {
      masses.clear();
      Status st;
      for (int32_t s = body.head_shape; s != k_null_index && st.ok();
           s = img.shapes[static_cast<size_t>(s)].next_shape) {
        MassData md{};
        st = shape_mass_for_body(img.shape_geometries[static_cast<size_t>(s)], img.shapes[static_cast<size_t>(s)].density,
                                 k_unnamed, &md);
        if (st.ok() && md.mass > Q32::zero()) masses.push_back(md);
      }
      if (st.ok()) {
        st = combine_masses(masses.data(), static_cast<int32_t>(masses.size()), body.type, body.fixed_rotation,
                            k_unnamed, &m);
      }
      if (!st.ok()) {
        c.refuse(r, "mass", "cannot be derived from its shapes (" + st.message + ")");
        return;
      }
    }
    c.equal(r, "mass", body.mass, m.mass, "kg", "its shapes");
    c.equal(r, "rotational_inertia", body.rotational_inertia, m.rotational_inertia, "kg·m²", "its shapes");
    c.equal(r, "inv_mass", sim.inv_mass, m.inv_mass, "1/kg", "its shapes");
    c.equal(r, "inv_inertia", sim.inv_inertia, m.inv_inertia, "1/(kg·m²)", "its shapes");
    c.equal(r, "local_center.x", sim.local_center.x, m.local_center.x, "m", "its shapes");
    c.equal(r, "local_center.y", sim.local_center.y, m.local_center.y, "m", "its shapes");
    if (c.failed()) return;
    const Vec2 center = transform_point(sim.transform, sim.local_center);
    c.equal(r, "center.x", sim.center.x, center.x, "m", "its pose and local centre");
    c.equal(r, "center.y", sim.center.y, center.y, "m", "its pose and local centre");
    Q32 min_extent, max_extent;
    compute_body_extents(img, static_cast<int32_t>(b), sim.local_center, &min_extent, &max_extent);
    c.equal(r, "min_extent", body.min_extent, min_extent, "m", "its shapes");
    c.equal(r, "max_extent", body.max_extent, max_extent, "m", "its shapes");
    if (c.failed()) return;
    const Q32 w = sim.angular_velocity;
    if (!moving) {
      c.range(r, "angular_velocity", w, Q32::zero(), Q32::zero(), "rad/s");
    } else if (abs(w) > k_max_restored_angular_speed &&
               mul_quiet(abs(w), max(max_extent, k_min_shape_size)) > k_max_restored_linear_speed) {
      c.refuse(r, "angular_velocity",
               to_string(w) + " rad/s is outside [" + to_string(-k_max_restored_angular_speed) + ", " +
                   to_string(k_max_restored_angular_speed) + "] rad/s and its rim speed |angular_velocity| · " +
                   "max_extent (" + to_string(max_extent) + " m) exceeds " + to_string(k_max_restored_linear_speed) +
                   " m/s");
    }
  }
}

/// Shape bounds, after the bodies' poses have been checked.
void check_shape_bounds(ImageChecker& c) {
  World& img = c.img;
  for (size_t i = 0; i < img.shapes.size() && !c.failed(); ++i) {
    if (img.shape_pool.alive[i] == 0) continue;
    const Shape& shape = img.shapes[i];
    const RecordRef r{RecordRef::shape, i, &img};
    // Derived from the geometry and the body's pose (finalize, teleports and
    // creation all store exactly this).
    const AABB box = compute_shape_aabb(img.shape_geometries[i],
                                        img.body_sims[static_cast<size_t>(shape.body_index)].transform);
    const char* from = "its geometry and body pose";
    c.equal(r, "aabb.lower.x", shape.aabb.lower.x, box.lower.x, "m", from);
    c.equal(r, "aabb.lower.y", shape.aabb.lower.y, box.lower.y, "m", from);
    c.equal(r, "aabb.upper.x", shape.aabb.upper.x, box.upper.x, "m", from);
    c.equal(r, "aabb.upper.y", shape.aabb.upper.y, box.upper.y, "m", from);
  }
}

void check_contacts(ImageChecker& c) {
  World& img = c.img;
  // Per body: the sum of |stored impulse| over its contact points, N·s.
  std::vector<Q32>& impulse_sum = check_scratch().impulse_sum;
  impulse_sum.assign(img.bodies.size(), Q32::zero());
  const Q32 unit_lim = Q32::from_raw(Q32::one().raw + k_unit_tolerance_raw);
  for (size_t i = 0; i < img.contacts.size() && !c.failed(); ++i) {
    const Contact& ct = img.contacts[i];
    const RecordRef r{RecordRef::contact, i, &img};
    // A contact whose shapes are alive with the stored generations is kept by
    // the next update: its bodies must be those shapes' bodies.
    const auto current = [&](int32_t s, uint32_t generation) {
      return img.shape_pool.alive[static_cast<size_t>(s)] != 0 &&
             img.shape_pool.generations[static_cast<size_t>(s)] == generation;
    };
    if (current(ct.shape_a, ct.generation_a) && current(ct.shape_b, ct.generation_b)) {
      const int32_t ba = img.shapes[static_cast<size_t>(ct.shape_a)].body_index;
      const int32_t bb = img.shapes[static_cast<size_t>(ct.shape_b)].body_index;
      if (ct.body_a != ba) {
        c.refuse(r, "body_a", std::to_string(ct.body_a) + " is not shape_a's body " + std::to_string(ba));
      }
      if (ct.body_b != bb) {
        c.refuse(r, "body_b", std::to_string(ct.body_b) + " is not shape_b's body " + std::to_string(bb));
      }
    }
    const bool touching = ct.manifold.point_count > 0;
    const uint32_t flags = touching ? k_contact_touching : 0u;
    if (ct.flags != flags) {
      c.refuse(r, "flags",
               std::to_string(ct.flags) + " is not " + std::to_string(flags) +
                   " (the touching bit set exactly when the manifold has points)");
    }
    c.range(r, "friction", ct.friction, Q32::zero(), k_max_friction, "");
    c.range(r, "restitution", ct.restitution, Q32::zero(), Q32::one(), "");
    if (touching) {
      c.unit(r, "normal.x", "normal.y", ct.manifold.normal);
    } else {
      c.range(r, "normal.x", ct.manifold.normal.x, -unit_lim, unit_lim, "");
      c.range(r, "normal.y", ct.manifold.normal.y, -unit_lim, unit_lim, "");
    }
    for (int32_t k = 0; k < ct.manifold.point_count && !c.failed(); ++k) {
      const ManifoldPoint& p = ct.manifold.points[static_cast<size_t>(k)];
      const Q32 wmax = k_max_restored_coordinate;
      const Q32 amax = k_max_restored_anchor;
      // (Field names are looked up only on failure.)
      const auto check = [&](int32_t which, Q32 v, Q32 lim, const char* unit) {
        if (-lim <= v && v <= lim) return;
        c.refuse_range(r, point_name(k, which), v, -lim, lim, unit, false);
      };
      check(0, p.point.x, wmax, "m");
      check(1, p.point.y, wmax, "m");
      check(2, p.anchor_a.x, amax, "m");
      check(3, p.anchor_a.y, amax, "m");
      check(4, p.anchor_b.x, amax, "m");
      check(5, p.anchor_b.y, amax, "m");
      check(6, p.separation, amax, "m");
      const Q32 jmax = k_max_restored_impulse;
      const Q32 jn = ct.normal_impulse[static_cast<size_t>(k)];
      const Q32 jt = ct.tangent_impulse[static_cast<size_t>(k)];
      check(8, jn, jmax, "N·s");
      check(9, jt, jmax, "N·s");
      if (c.failed()) return;
      // What the warm start applies to each body, summed over its contacts
      // (checked after each impulse, so the one that crosses is named).
      for (int32_t which = 0; which < 2; ++which) {
        const Q32 j = abs(which == 0 ? jn : jt);
        for (const int32_t b : {ct.body_a, ct.body_b}) {
          const size_t bi = static_cast<size_t>(b);
          if (img.body_pool.alive[bi] == 0) continue;
          Q32& sum = impulse_sum[bi];
          sum = add_quiet(sum, j);
          const BodySim& sim = img.body_sims[bi];
          const Q32 lever = add_quiet(img.bodies[bi].max_extent, k_speculative_distance * 2);
          const Q32 dv = mul_quiet(sum, sim.inv_mass);
          const Q32 dw = mul_quiet(mul_quiet(sum, sim.inv_inertia), lever);
          if (dv > k_max_warm_start_velocity_change || dw > k_max_warm_start_velocity_change) {
            c.refuse(r, point_name(k, which == 0 ? 8 : 9),
                     "brings the stored impulses on body " + std::to_string(b) + " to " + to_string(sum) +
                         " N·s, a warm-start velocity change of " + to_string(max(dv, dw)) + " m/s, above " +
                         to_string(k_max_warm_start_velocity_change) + " m/s");
            return;
          }
        }
      }
    }
  }
}

/// Joint records: every setting against the limits the joint API enforces
/// (limits.h; the union over the joint kinds of each field's range, as a
/// field keeps its default 0 in the kinds that do not use it), unit axes for
/// prismatic and wheel joints, accumulated impulses as contact impulses.
void check_joints(ImageChecker& c) {
  World& img = c.img;
  const Q32 unit_lim = Q32::from_raw(Q32::one().raw + k_unit_tolerance_raw);
  for (size_t i = 0; i < img.joints.joints.size() && !c.failed(); ++i) {
    if (img.joint_pool.alive[i] == 0) continue;
    const Joint& j = img.joints.joints[i];
    const RecordRef r{RecordRef::joint, i, &img};
    FieldRangeFailure bad;
    if (first_joint_field_out_of_range(j, &bad)) {
      c.range(r, bad.field, bad.value, bad.lo, bad.hi, bad.unit);
      continue;
    }
    if (j.lower > j.upper) {
      c.refuse(r, "lower", to_string(j.lower) + " is above upper " + to_string(j.upper));
      continue;
    }
    if (j.type == JointType::prismatic || j.type == JointType::wheel) {
      c.unit(r, "local_axis_a.x", "local_axis_a.y", j.local_axis_a);
    } else {
      c.range(r, "local_axis_a.x", j.local_axis_a.x, -unit_lim, unit_lim, "");
      c.range(r, "local_axis_a.y", j.local_axis_a.y, -unit_lim, unit_lim, "");
    }
  }
}


/// Cross references of a structurally decoded image: shape lists, pool
/// indices, sort orders, live joint bodies, non-degenerate geometry.
bool check_structure(const World& img, StateRefusal* out) {
  const auto bad = [&](const std::string& msg) {
    out->where = StateRefusal::Where::none;
    out->message = msg;
    return false;
  };
  const auto at = [&](RecordKind kind, int64_t index, const std::string& msg) {
    out->where = StateRefusal::Where::record;
    out->kind = kind;
    out->index = index;
    out->message = msg;
    return false;
  };
  const int32_t body_cap = static_cast<int32_t>(img.bodies.size());
  const int32_t shape_cap = static_cast<int32_t>(img.shapes.size());
  if (img.body_pool.alive_count > k_max_bodies || img.shape_pool.alive_count > k_max_shapes) {
    return bad("too many live bodies or shapes");
  }
  if (img.last_solver_body_count < 0 || img.last_solver_body_count > body_cap) {
    return bad("last_solver_body_count " + std::to_string(img.last_solver_body_count) + " outside [0, " +
               std::to_string(body_cap) + "]");
  }
  if (!(img.def.bounds.lower.x < img.def.bounds.upper.x && img.def.bounds.lower.y < img.def.bounds.upper.y)) {
    return bad("world bounds must have lower < upper");
  }
  int64_t listed_shapes = 0;
  for (int32_t b = 0; b < body_cap; ++b) {
    if (img.body_pool.alive[static_cast<size_t>(b)] == 0) continue;
    const Body& body = img.bodies[static_cast<size_t>(b)];
    const std::string who = "body " + std::to_string(b);
    if (body.sleep_island != k_null_index && (body.sleep_island < 0 || body.sleep_island >= body_cap ||
                                              img.body_pool.alive[static_cast<size_t>(body.sleep_island)] == 0)) {
      return at(RecordKind::body, b, who + " sleep_island " + std::to_string(body.sleep_island) + " is not a live body");
    }
    int32_t count = 0;
    int32_t prev = k_null_index;
    for (int32_t s = body.head_shape; s != k_null_index;) {
      if (s < 0 || s >= shape_cap || img.shape_pool.alive[static_cast<size_t>(s)] == 0) {
        return at(RecordKind::body, b, who + " shape list names shape " + std::to_string(s) + ", which is not a live shape");
      }
      const Shape& shape = img.shapes[static_cast<size_t>(s)];
      if (shape.body_index != b || shape.prev_shape != prev || s <= prev) {
        return at(RecordKind::shape, s,
                  "shape " + std::to_string(s) + " is inconsistent with " + who +
                      "'s shape list (body, prev_shape or order)");
      }
      if (++count > body.shape_count) break;
      prev = s;
      s = shape.next_shape;
    }
    if (count != body.shape_count) {
      return at(RecordKind::body, b, who + " shape_count " + std::to_string(body.shape_count) + " but its list holds " +
                                         (count > body.shape_count ? "more" : std::to_string(count)));
    }
    listed_shapes += count;
  }
  if (listed_shapes != img.shape_pool.alive_count) {
    return bad("bodies list " + std::to_string(listed_shapes) + " shapes but " +
               std::to_string(img.shape_pool.alive_count) + " shapes are alive");
  }
  // Geometry the narrow phase divides by or takes roots of.
  for (int32_t i = 0; i < shape_cap; ++i) {
    if (img.shape_pool.alive[static_cast<size_t>(i)] == 0) continue;
    const ShapeGeometry& g = img.shape_geometries[static_cast<size_t>(i)];
    bool valid = true;
    switch (g.type) {
      case ShapeType::circle: valid = g.circle.radius > Q32::zero(); break;
      case ShapeType::capsule: valid = g.capsule.radius > Q32::zero() && g.capsule.center1 != g.capsule.center2; break;
      case ShapeType::segment: valid = g.segment.point1 != g.segment.point2; break;
      case ShapeType::polygon: valid = g.polygon.radius >= Q32::zero(); break;
      case ShapeType::chain_segment:
        valid = g.chain_segment.segment.point1 != g.chain_segment.segment.point2;
        break;
      case ShapeType::count: valid = false; break;
    }
    if (!valid) {
      return at(RecordKind::shape, i,
                "shape " + std::to_string(i) + " has degenerate geometry (zero or negative radius, or coincident points)");
    }
  }
  uint64_t prev_key = 0;
  for (size_t i = 0; i < img.contacts.size(); ++i) {
    const Contact& c = img.contacts[i];
    const int64_t ii = static_cast<int64_t>(i);
    if (c.shape_a < 0 || c.shape_b >= shape_cap || c.shape_a >= c.shape_b || c.body_a < 0 || c.body_a >= body_cap ||
        c.body_b < 0 || c.body_b >= body_cap) {
      return at(RecordKind::contact, ii, "contact " + std::to_string(i) + " names shapes (" + std::to_string(c.shape_a) + ", " +
                         std::to_string(c.shape_b) + ") / bodies (" + std::to_string(c.body_a) + ", " +
                         std::to_string(c.body_b) + ") outside the pools or out of order");
    }
    const uint64_t key = contact_key(c);
    if (i > 0 && key <= prev_key) return at(RecordKind::contact, ii, "contact " + std::to_string(i) + " is not sorted by shape pair");
    prev_key = key;
  }
  const auto check_pairs = [&](const std::vector<PairRecord>& pairs, const char* what) {
    for (size_t i = 0; i < pairs.size(); ++i) {
      const PairRecord& p = pairs[i];
      if (p.shape_a < 0 || p.shape_a >= shape_cap || p.shape_b < 0 || p.shape_b >= shape_cap) {
        return bad(std::string(what) + " " + std::to_string(i) + " names a shape outside the pool");
      }
      if (i > 0 && shape_pair_key(p.shape_a, p.shape_b) <=
                       shape_pair_key(pairs[i - 1].shape_a, pairs[i - 1].shape_b)) {
        return bad(std::string(what) + " " + std::to_string(i) + " is not sorted");
      }
    }
    return true;
  };
  if (!check_pairs(img.events.touching, "touching pair")) return false;
  if (!check_pairs(img.events.sensor_overlaps, "sensor overlap")) return false;
  for (size_t i = 0; i < img.joints.joints.size(); ++i) {
    if (img.joint_pool.alive[i] == 0) continue;
    const Joint& j = img.joints.joints[i];
    const auto live = [&](int32_t b) {
      return b >= 0 && b < body_cap && img.body_pool.alive[static_cast<size_t>(b)] != 0;
    };
    if (!live(j.body_a) || !live(j.body_b) || j.body_a == j.body_b) {
      return at(RecordKind::joint, static_cast<int64_t>(i), "joint " + std::to_string(i) + " joins bodies (" + std::to_string(j.body_a) +
                                           ", " + std::to_string(j.body_b) + "), which are not two live bodies");
    }
  }
  return true;
}

}  // namespace

bool check_image(StateImage& image, StateRefusal* out) {
  World& img = image.world;
  if (!check_structure(img, out)) return false;
  ImageChecker c{img, out};
  check_world(c);
  if (!c.failed()) check_shapes(c);
  if (!c.failed()) check_bodies(c);
  if (!c.failed()) check_shape_bounds(c);
  if (!c.failed()) check_contacts(c);
  if (!c.failed()) check_joints(c);
  return !c.failed();
}

}  // namespace tandem::state_access

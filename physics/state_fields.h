// state_fields.h — the canonical field list of every persistent physics
// record (internal, not installed): one visit function per record lists its
// fields in canonical order with their names, and every consumer of the
// canonical state walks them — replay/'s encoder, decoder, size, hash and
// field diff (through physics/state_access.h: FieldsOf below adapts its
// FieldVisitor), the restore checks (state_check.cpp) and the compact
// rollback image's full records — so adding a field to a record is one line
// here (plus a format version bump when the bytes change;
// tests/replay/test_state_fields.cpp fails when a record's size changes
// without this list being revisited). A bounded field (q32_in, vec2_in)
// carries the range a restored value must lie in, next to the field.
//
// A visitor V provides: k_reading (true when fields are being filled from
// bytes), q32(name, Q32&), q32_in(name, Q32&, lo, hi, unit),
// vec2(name_x, name_y, Vec2&), vec2_in(..., lo, hi, unit), i32, u32, u16,
// u64, boolean (name, T&), enum8(name, E&, max), ranged_i32(name, int32_t&,
// lo, hi) and ok() (false after a failed read: stop).
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "fixed/fixed_math.h"
#include "physics/body.h"
#include "physics/contact.h"
#include "physics/event_state.h"
#include "physics/joint.h"
#include "physics/joint_state.h"
#include "physics/limits.h"
#include "physics/shape.h"
#include "physics/state_access.h"

namespace tandem::state_fields {

/// Largest |accumulated joint impulse| restored, N·s (as contact impulses).
inline constexpr Q32 k_max_restored_joint_impulse = Q32::from_raw(int64_t{400000000} << 32);

// ---------------------------------------------------------------------------
// Visitors
// ---------------------------------------------------------------------------

/// Runs the field lists below with a state_access::FieldVisitor (the
/// interface replay implements): enums pass as their int32 values, and the
/// ranges of bounded fields are for the checks, not the bytes.
template <bool Reading>
struct FieldsOf {
  static constexpr bool k_reading = Reading;
  state_access::FieldVisitor& v;
  void q32(const char* n, Q32& x) { v.q32(n, x); }
  void q32_in(const char* n, Q32& x, Q32, Q32, const char*) { v.q32(n, x); }
  void vec2(const char* nx, const char* ny, Vec2& x) { v.vec2(nx, ny, x); }
  void vec2_in(const char* nx, const char* ny, Vec2& x, Q32, Q32, const char*) { v.vec2(nx, ny, x); }
  void i32(const char* n, int32_t& x) { v.i32(n, x); }
  void u32(const char* n, uint32_t& x) { v.u32(n, x); }
  void u16(const char* n, uint16_t& x) { v.u16(n, x); }
  void u64(const char* n, uint64_t& x) { v.u64(n, x); }
  void boolean(const char* n, bool& x) { v.boolean(n, x); }
  template <typename E>
  void enum8(const char* n, E& e, int32_t max) {
    int32_t x = static_cast<int32_t>(e);
    v.enum8(n, x, max);
    if constexpr (Reading) e = static_cast<E>(x);
  }
  void ranged_i32(const char* n, int32_t& x, int32_t lo, int32_t hi) { v.ranged_i32(n, x, lo, hi); }
  bool ok() const { return v.ok(); }
  // The structure between records.
  void record(const char* kind, int64_t index, int64_t index2, uint32_t generation) {
    v.record(kind, index, index2, generation);
  }
  void begin_read(const char* kind, int64_t position) { v.begin_read(kind, position); }
  void tag(const char* t) { v.tag(t); }
  void count(state_access::StateList list, const char* context, const char* name, uint32_t& n, uint32_t max) {
    v.count(list, context, name, n, max);
  }
  void slot(const char* kind, uint32_t index, uint32_t& generation, bool& alive) {
    v.slot(kind, index, generation, alive);
  }
};

/// The first bounded field of a record outside its range.
struct FieldRangeFailure {
  const char* field = nullptr;
  Q32 value, lo, hi;
  const char* unit = "";
};

/// Finds the first bounded field outside its range (q32_in, vec2_in); the
/// other fields are not looked at.
struct RangeCheck {
  static constexpr bool k_reading = false;
  FieldRangeFailure* failure;
  void q32_in(const char* n, Q32& x, Q32 lo, Q32 hi, const char* unit) {
    if (failure->field != nullptr || (lo <= x && x <= hi)) return;
    *failure = FieldRangeFailure{n, x, lo, hi, unit};
  }
  void vec2_in(const char* nx, const char* ny, Vec2& x, Q32 lo, Q32 hi, const char* unit) {
    q32_in(nx, x.x, lo, hi, unit);
    q32_in(ny, x.y, lo, hi, unit);
  }
  void q32(const char*, Q32&) {}
  void vec2(const char*, const char*, Vec2&) {}
  void i32(const char*, int32_t&) {}
  void u32(const char*, uint32_t&) {}
  void u16(const char*, uint16_t&) {}
  void u64(const char*, uint64_t&) {}
  void boolean(const char*, bool&) {}
  template <typename E>
  void enum8(const char*, E&, int32_t) {}
  void ranged_i32(const char*, int32_t&, int32_t, int32_t) {}
  bool ok() const { return true; }
};

// ---------------------------------------------------------------------------
// Field names that carry an index (built once)
// ---------------------------------------------------------------------------

inline const char* polygon_name(int32_t i, int32_t which) {
  // which: 0 vertices.x, 1 vertices.y, 2 normals.x, 3 normals.y
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (int32_t k = 0; k < k_max_polygon_vertices; ++k) {
      const std::string s = std::to_string(k);
      n.push_back("vertices[" + s + "].x");
      n.push_back("vertices[" + s + "].y");
      n.push_back("normals[" + s + "].x");
      n.push_back("normals[" + s + "].y");
    }
    return n;
  }();
  return names[static_cast<size_t>(i * 4 + which)].c_str();
}

inline constexpr int32_t k_point_field_count = 10;

inline const char* point_name(int32_t i, int32_t which) {
  // Literals, so a visitor that ignores names costs nothing for them.
  static constexpr const char* k_names[2][k_point_field_count] = {
      {"points[0].point.x", "points[0].point.y", "points[0].anchor_a.x", "points[0].anchor_a.y", "points[0].anchor_b.x",
       "points[0].anchor_b.y", "points[0].separation", "points[0].id", "points[0].normal_impulse", "points[0].tangent_impulse"},
      {"points[1].point.x", "points[1].point.y", "points[1].anchor_a.x", "points[1].anchor_a.y", "points[1].anchor_b.x",
       "points[1].anchor_b.y", "points[1].separation", "points[1].id", "points[1].normal_impulse", "points[1].tangent_impulse"},
  };
  return k_names[static_cast<size_t>(i)][static_cast<size_t>(which)];
}


// ---------------------------------------------------------------------------
// Records, in canonical field order
// ---------------------------------------------------------------------------

template <typename V>
void visit_world_def(V& v, WorldDef& d) {
  v.vec2("gravity.x", "gravity.y", d.gravity);
  v.ranged_i32("sub_step_count", d.sub_step_count, 1, k_max_sub_steps);
  v.q32("contact_hertz", d.contact_hertz);
  v.q32("contact_damping_ratio", d.contact_damping_ratio);
  v.q32("max_contact_push_speed", d.max_contact_push_speed);
  v.q32("joint_hertz", d.joint_hertz);
  v.q32("joint_damping_ratio", d.joint_damping_ratio);
  v.q32("restitution_threshold", d.restitution_threshold);
  v.q32("hit_event_threshold", d.hit_event_threshold);
  v.q32("max_linear_speed", d.max_linear_speed);
  v.vec2("bounds.lower.x", "bounds.lower.y", d.bounds.lower);
  v.vec2("bounds.upper.x", "bounds.upper.y", d.bounds.upper);
  v.boolean("enable_sleep", d.enable_sleep);
  v.boolean("enable_continuous", d.enable_continuous);
  v.enum8("broad_phase", d.broad_phase, static_cast<int32_t>(BroadPhaseKind::tree));
  v.u64("user_data", d.user_data);
}

template <typename V>
void visit_body(V& v, Body& b, BodySim& s) {
  v.enum8("type", b.type, static_cast<int32_t>(BodyType::dynamic_body));
  v.i32("head_shape", b.head_shape);
  v.i32("shape_count", b.shape_count);
  v.q32("mass", b.mass);
  v.q32("rotational_inertia", b.rotational_inertia);
  v.q32("sleep_time", b.sleep_time);
  v.i32("sleep_island", b.sleep_island);
  v.u64("user_data", b.user_data);
  v.boolean("enable_sleep", b.enable_sleep);
  v.boolean("awake", b.awake);
  v.boolean("enabled", b.enabled);
  v.boolean("fixed_rotation", b.fixed_rotation);
  v.boolean("bullet", b.bullet);
  v.q32("min_extent", b.min_extent);
  v.q32("max_extent", b.max_extent);
  v.vec2("position.x", "position.y", s.transform.p);
  v.q32("rotation.c", s.transform.q.c);
  v.q32("rotation.s", s.transform.q.s);
  v.vec2("center.x", "center.y", s.center);
  v.vec2("local_center.x", "local_center.y", s.local_center);
  v.vec2("linear_velocity.x", "linear_velocity.y", s.linear_velocity);
  v.q32("angular_velocity", s.angular_velocity);
  v.vec2("force.x", "force.y", s.force);
  v.q32("torque", s.torque);
  v.q32("inv_mass", s.inv_mass);
  v.q32("inv_inertia", s.inv_inertia);
  v.q32("linear_damping", s.linear_damping);
  v.q32("angular_damping", s.angular_damping);
  v.q32("gravity_scale", s.gravity_scale);
}

template <typename V>
void visit_shape(V& v, Shape& s, ShapeGeometry& g) {
  v.i32("body", s.body_index);
  v.i32("prev_shape", s.prev_shape);
  v.i32("next_shape", s.next_shape);
  v.enum8("type", s.type, static_cast<int32_t>(ShapeType::chain_segment));
  v.q32("friction", s.friction);
  v.q32("restitution", s.restitution);
  v.q32("density", s.density);
  v.u64("filter.category_bits", s.filter.category_bits);
  v.u64("filter.mask_bits", s.filter.mask_bits);
  v.i32("filter.group_index", s.filter.group_index);
  v.u64("user_data", s.user_data);
  v.vec2("aabb.lower.x", "aabb.lower.y", s.aabb.lower);
  v.vec2("aabb.upper.x", "aabb.upper.y", s.aabb.upper);
  v.boolean("is_sensor", s.is_sensor);
  v.boolean("enable_hit_events", s.enable_hit_events);
  if (!v.ok()) return;
  if constexpr (V::k_reading) g.type = s.type;
  switch (s.type) {
    case ShapeType::circle:
      v.vec2("circle.center.x", "circle.center.y", g.circle.center);
      v.q32("circle.radius", g.circle.radius);
      break;
    case ShapeType::capsule:
      v.vec2("capsule.center1.x", "capsule.center1.y", g.capsule.center1);
      v.vec2("capsule.center2.x", "capsule.center2.y", g.capsule.center2);
      v.q32("capsule.radius", g.capsule.radius);
      break;
    case ShapeType::segment:
      v.vec2("segment.point1.x", "segment.point1.y", g.segment.point1);
      v.vec2("segment.point2.x", "segment.point2.y", g.segment.point2);
      break;
    case ShapeType::polygon: {
      Polygon& p = g.polygon;
      v.ranged_i32("polygon.count", p.count, 3, k_max_polygon_vertices);
      if (!v.ok()) return;
      const int32_t n = std::clamp(p.count, int32_t{0}, k_max_polygon_vertices);
      for (int32_t i = 0; i < n; ++i) {
        v.vec2(polygon_name(i, 0), polygon_name(i, 1), p.vertices[static_cast<size_t>(i)]);
      }
      for (int32_t i = 0; i < n; ++i) {
        v.vec2(polygon_name(i, 2), polygon_name(i, 3), p.normals[static_cast<size_t>(i)]);
      }
      v.vec2("polygon.centroid.x", "polygon.centroid.y", p.centroid);
      v.q32("polygon.radius", p.radius);
      break;
    }
    case ShapeType::chain_segment:
      v.vec2("chain.ghost1.x", "chain.ghost1.y", g.chain_segment.ghost1);
      v.vec2("chain.point1.x", "chain.point1.y", g.chain_segment.segment.point1);
      v.vec2("chain.point2.x", "chain.point2.y", g.chain_segment.segment.point2);
      v.vec2("chain.ghost2.x", "chain.ghost2.y", g.chain_segment.ghost2);
      v.i32("chain.chain_id", g.chain_segment.chain_id);
      break;
    case ShapeType::count:
      break;
  }
}

template <typename V>
void visit_contact(V& v, Contact& c) {
  v.i32("shape_a", c.shape_a);
  v.i32("shape_b", c.shape_b);
  v.u32("generation_a", c.generation_a);
  v.u32("generation_b", c.generation_b);
  v.i32("body_a", c.body_a);
  v.i32("body_b", c.body_b);
  v.u32("flags", c.flags);
  v.q32("friction", c.friction);
  v.q32("restitution", c.restitution);
  v.vec2("normal.x", "normal.y", c.manifold.normal);
  v.ranged_i32("point_count", c.manifold.point_count, 0, 2);
  if (!v.ok()) return;
  const int32_t n = std::clamp(c.manifold.point_count, int32_t{0}, int32_t{2});
  for (int32_t i = 0; i < n; ++i) {
    ManifoldPoint& p = c.manifold.points[static_cast<size_t>(i)];
    v.vec2(point_name(i, 0), point_name(i, 1), p.point);
    v.vec2(point_name(i, 2), point_name(i, 3), p.anchor_a);
    v.vec2(point_name(i, 4), point_name(i, 5), p.anchor_b);
    v.q32(point_name(i, 6), p.separation);
    v.u16(point_name(i, 7), p.id);
    v.q32(point_name(i, 8), c.normal_impulse[static_cast<size_t>(i)]);
    v.q32(point_name(i, 9), c.tangent_impulse[static_cast<size_t>(i)]);
  }
}

/// A joint record (version 2): settings, accumulated impulses and the last
/// reaction; the per-step scratch is not state.
template <typename V>
void visit_joint(V& v, Joint& j) {
  // The bounded fields carry the range a restored value must lie in: what the
  // joint API accepts for the field (limits.h), over every joint kind (a
  // field keeps its default 0 in the kinds that do not use it); accumulated
  // impulses as contact impulses.
  const Q32 z = Q32::zero();
  const Q32 size = k_max_shape_size;
  const Q32 jmax = k_max_restored_joint_impulse;
  const Q32 speed = max(k_max_linear_speed, k_max_angular_speed);
  const Q32 motor = max(k_max_joint_force, k_max_joint_torque);
  const Q32 coord = k_max_world_coordinate;
  v.enum8("type", j.type, static_cast<int32_t>(JointType::motor));
  v.i32("body_a", j.body_a);
  v.i32("body_b", j.body_b);
  v.vec2_in("local_anchor_a.x", "local_anchor_a.y", j.local_anchor_a, -size, size, "m");
  v.vec2_in("local_anchor_b.x", "local_anchor_b.y", j.local_anchor_b, -size, size, "m");
  v.vec2("local_axis_a.x", "local_axis_a.y", j.local_axis_a);
  v.q32_in("reference_angle", j.reference_angle, -k_pi, k_pi, "rad");
  v.boolean("collide_connected", j.collide_connected);
  v.boolean("enable_spring", j.enable_spring);
  v.boolean("enable_limit", j.enable_limit);
  v.boolean("enable_motor", j.enable_motor);
  v.q32_in("break_force", j.break_force, z, k_max_joint_force, "N");
  v.q32_in("break_torque", j.break_torque, z, k_max_joint_torque, "N·m");
  v.u64("user_data", j.user_data);
  v.q32_in("hertz", j.hertz, z, k_max_joint_hertz, "Hz");
  v.q32_in("damping_ratio", j.damping_ratio, z, k_max_joint_damping_ratio, "");
  v.q32_in("angular_hertz", j.angular_hertz, z, k_max_joint_hertz, "Hz");
  v.q32_in("angular_damping_ratio", j.angular_damping_ratio, z, k_max_joint_damping_ratio, "");
  v.q32_in("length", j.length, z, k_max_joint_length, "m");
  v.q32_in("lower", j.lower, -k_max_joint_length, k_max_joint_length, "rad or m");
  v.q32_in("upper", j.upper, -k_max_joint_length, k_max_joint_length, "rad or m");
  v.q32_in("motor_speed", j.motor_speed, -speed, speed, "rad/s or m/s");
  v.q32_in("max_motor_force", j.max_motor_force, z, motor, "N or N·m");
  v.vec2_in("target.x", "target.y", j.target, -coord, coord, "m");
  v.q32_in("angular_offset", j.angular_offset, -k_pi, k_pi, "rad");
  v.q32_in("max_force", j.max_force, z, k_max_joint_force, "N");
  v.q32_in("max_torque", j.max_torque, z, k_max_joint_torque, "N·m");
  v.q32_in("correction_factor", j.correction_factor, z, Q32::one(), "");
  v.vec2_in("linear_impulse.x", "linear_impulse.y", j.linear_impulse, -jmax, jmax, "N·s");
  v.q32_in("angular_impulse", j.angular_impulse, -jmax, jmax, "N·m·s");
  v.q32_in("axial_impulse", j.axial_impulse, -jmax, jmax, "N·s");
  v.q32_in("spring_impulse", j.spring_impulse, -jmax, jmax, "N·s");
  v.q32_in("motor_impulse", j.motor_impulse, -jmax, jmax, "N·s");
  v.q32_in("lower_impulse", j.lower_impulse, -jmax, jmax, "N·s");
  v.q32_in("upper_impulse", j.upper_impulse, -jmax, jmax, "N·s");
  v.vec2("reaction_force.x", "reaction_force.y", j.reaction_force);
  v.q32("reaction_torque", j.reaction_torque);
}

/// A joint event waiting for the next step (joint destroyed with a body, or
/// broken): its stale handles, kind, reaction and user data. The handles'
/// world is not stored (restore sets the target world's).
template <typename V>
void visit_joint_event(V& v, JointEvent& e) {
  v.u32("joint.index1", e.joint.index1);
  v.u32("joint.generation", e.joint.generation);
  v.u32("body_a.index1", e.body_a.index1);
  v.u32("body_a.generation", e.body_a.generation);
  v.u32("body_b.index1", e.body_b.index1);
  v.u32("body_b.generation", e.body_b.generation);
  v.enum8("kind", e.kind, static_cast<int32_t>(JointEventKind::destroyed_with_body));
  v.vec2("force.x", "force.y", e.force);
  v.q32("torque", e.torque);
  v.u64("user_data", e.user_data);
}

template <typename V>
void visit_pair(V& v, PairRecord& p) {
  v.i32("shape_a", p.shape_a);
  v.i32("shape_b", p.shape_b);
  v.u32("generation_a", p.generation_a);
  v.u32("generation_b", p.generation_b);
}


/// The first field of a joint outside its range (false: none).
inline bool first_joint_field_out_of_range(const Joint& joint, FieldRangeFailure* out) {
  *out = FieldRangeFailure{};
  Joint j = joint;
  RangeCheck check{out};
  visit_joint(check, j);
  return out->field != nullptr;
}

}  // namespace tandem::state_fields

// state.cpp — canonical state encoding, restore, hash, decode and diff
// (state.h describes the format).
//
// DESIGN. Each record kind has ONE visit function (visit_world_def,
// visit_body, visit_shape, visit_contact, visit_pair, visit_pool) that lists
// its fields in canonical order with their names. Four visitors walk them:
//   WriteVisitor     fields → bytes (ByteWriter; a null buffer only counts)
//   ReadVisitor      bytes → fields (ByteReader; names go into messages)
//   DescribeVisitor  fields → DecodedRecord named fields (diffs)
// so encode, decode, size and diff cannot disagree about the order. The
// exact encoded size is computed arithmetically from per-record sizes that
// are themselves measured once by running the WriteVisitor in counting mode
// over default records.
//
// Restore decodes into a WorldImage (thread-local scratch, reused so warm
// rollbacks do not allocate), validates cross references, then copy-assigns
// its vectors into the World (capacity reused).
#include "replay/state.h"

#include <algorithm>
#include <utility>
#include <array>
#include <cstring>
#include <string>
#include <vector>

#define XXH_INLINE_ALL
#include <xxhash.h>

#include "physics/body.h"
#include "physics/broad_phase.h"
#include "physics/contact.h"
#include "physics/events.h"
#include "physics/id_pool.h"
#include "physics/island.h"
#include "physics/limits.h"
#include "physics/shape.h"
#include "physics/world.h"
#include "replay/bytes.h"

namespace tandem {
namespace {

constexpr uint32_t k_state_kind_full = 0;

/// Everything restore replaces, decoded and validated before it touches a
/// world. It is a World (never registered, never stepped) so the physics
/// functions that derive cached values (shape bounds, body mass, extents) can
/// run on the image itself for the consistency checks; restore then swaps its
/// vectors into the target world. Joints are World::joints/joint_pool (empty
/// for a version-1 image).
struct WorldImage : World {
  // Reader only: byte offset of each record, for messages.
  std::vector<size_t> body_offsets;   // by body index
  std::vector<size_t> shape_offsets;  // by shape index
  std::vector<size_t> contact_offsets;
  std::vector<size_t> joint_offsets;  // by joint index
};

std::vector<PairRecord>& touching_of(World& w) { return w.events.touching; }
std::vector<PairRecord>& sensors_of(World& w) { return w.events.sensor_overlaps; }
std::vector<Joint>& joints_of(World& w) { return w.joints.joints; }

/// The smallest encoded contact record (no points), for read_count.
size_t min_contact_record_bytes();

// ---------------------------------------------------------------------------
// Field names that carry an index (built once)
// ---------------------------------------------------------------------------

const char* polygon_name(int32_t i, int32_t which) {
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

constexpr int32_t k_point_field_count = 10;

const char* point_name(int32_t i, int32_t which) {
  static const std::vector<std::string> names = [] {
    static const char* const fields[k_point_field_count] = {
        "point.x",    "point.y",    "anchor_a.x", "anchor_a.y",     "anchor_b.x",
        "anchor_b.y", "separation", "id",         "normal_impulse", "tangent_impulse"};
    std::vector<std::string> n;
    for (int32_t k = 0; k < 2; ++k) {
      for (const char* f : fields) n.push_back("points[" + std::to_string(k) + "]." + f);
    }
    return n;
  }();
  return names[static_cast<size_t>(i * k_point_field_count + which)].c_str();
}

// ---------------------------------------------------------------------------
// Visitors
// ---------------------------------------------------------------------------

/// Fields → bytes.
struct WriteVisitor {
  static constexpr bool k_reading = false;
  ByteWriter* w;
  void record(const char*, int64_t, int64_t = -1, uint32_t = 0) {}
  void tag(const char* t) { w->bytes(reinterpret_cast<const uint8_t*>(t), 4); }
  void q32(const char*, Q32& v) { w->q32(v); }
  void vec2(const char*, const char*, Vec2& v) { w->vec2(v); }
  void i32(const char*, int32_t& v) { w->i32(v); }
  void u32(const char*, uint32_t& v) { w->u32(v); }
  /// A list length (a u32; implied by the records when described).
  void count(const char*, uint32_t& v) { w->u32(v); }
  void u16(const char*, uint16_t& v) { w->u16(v); }
  void u64(const char*, uint64_t& v) { w->u64(v); }
  void boolean(const char*, bool& v) { w->boolean(v); }
  template <typename E>
  void enum8(const char*, E& v, int32_t) {
    w->u8(static_cast<uint8_t>(static_cast<int32_t>(v)));
  }
  /// A value that must lie in [lo, hi] (checked when reading).
  void ranged_i32(const char*, int32_t& v, int32_t, int32_t) { w->i32(v); }
  bool ok() const { return true; }
};

/// Bytes → fields, with checks.
struct ReadVisitor {
  static constexpr bool k_reading = true;
  ByteReader* r;
  void record(const char* kind, int64_t index, int64_t = -1, uint32_t = 0) { r->set_context(kind, index); }
  void tag(const char* t) {
    const size_t at = r->offset();
    const std::span<const uint8_t> b = r->bytes(4, (std::string("section tag ") + t).c_str());
    if (b.size() == 4 && std::memcmp(b.data(), t, 4) != 0) {
      r->fail_at(at, std::string("expected section tag \"") + t + "\"");
    }
  }
  void q32(const char* name, Q32& v) {
    const size_t at = r->offset();
    v = r->q32(name);
    if (v.raw == INT64_MIN) r->fail_at(at, "expected " + r->describe_what(name) + " (Q32.32), got raw INT64_MIN");
  }
  void vec2(const char* nx, const char* ny, Vec2& v) {
    q32(nx, v.x);
    q32(ny, v.y);
  }
  void i32(const char* name, int32_t& v) { v = r->i32(name); }
  void u32(const char* name, uint32_t& v) { v = r->u32(name); }
  void u16(const char* name, uint16_t& v) { v = r->u16(name); }
  void u64(const char* name, uint64_t& v) { v = r->u64(name); }
  void boolean(const char* name, bool& v) { v = r->boolean(name); }
  template <typename E>
  void enum8(const char* name, E& v, int32_t max) {
    const size_t at = r->offset();
    const uint8_t raw = r->u8(name);
    if (!r->ok()) return;
    if (raw > max) {
      r->fail_at(at, "expected " + r->describe_what(name) + " 0.." + std::to_string(max) + ", got " +
                         std::to_string(raw));
      return;
    }
    v = static_cast<E>(raw);
  }
  void ranged_i32(const char* name, int32_t& v, int32_t lo, int32_t hi) {
    const size_t at = r->offset();
    const int32_t x = r->i32(name);
    if (!r->ok()) return;
    if (x < lo || x > hi) {
      r->fail_at(at, "expected " + r->describe_what(name) + " in [" + std::to_string(lo) + ", " +
                         std::to_string(hi) + "], got " + std::to_string(x));
      return;
    }
    v = x;
  }
  bool ok() const { return r->ok(); }
};

/// Fields → named DecodedRecord fields (over an already decoded image).
struct DescribeVisitor {
  static constexpr bool k_reading = false;
  DecodedState* out;
  void record(const char* kind, int64_t index, int64_t index2 = -1, uint32_t generation = 0) {
    DecodedRecord rec;
    rec.kind = kind;
    rec.index = index;
    rec.index2 = index2;
    rec.generation = generation;
    out->records.push_back(std::move(rec));
  }
  void field(const char* name, int64_t v, bool q) { out->records.back().fields.push_back({name, v, q}); }
  void tag(const char*) {}
  void q32(const char* name, Q32& v) { field(name, v.raw, true); }
  void vec2(const char* nx, const char* ny, Vec2& v) {
    field(nx, v.x.raw, true);
    field(ny, v.y.raw, true);
  }
  void i32(const char* name, int32_t& v) { field(name, v, false); }
  void u32(const char* name, uint32_t& v) { field(name, v, false); }
  void count(const char*, uint32_t&) {}
  void u16(const char* name, uint16_t& v) { field(name, v, false); }
  void u64(const char* name, uint64_t& v) { field(name, static_cast<int64_t>(v), false); }
  void boolean(const char* name, bool& v) { field(name, v ? 1 : 0, false); }
  template <typename E>
  void enum8(const char* name, E& v, int32_t) {
    field(name, static_cast<int32_t>(v), false);
  }
  void ranged_i32(const char* name, int32_t& v, int32_t, int32_t) { field(name, v, false); }
  bool ok() const { return true; }
};

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
  v.enum8("type", j.type, static_cast<int32_t>(JointType::motor));
  v.i32("body_a", j.body_a);
  v.i32("body_b", j.body_b);
  v.vec2("local_anchor_a.x", "local_anchor_a.y", j.local_anchor_a);
  v.vec2("local_anchor_b.x", "local_anchor_b.y", j.local_anchor_b);
  v.vec2("local_axis_a.x", "local_axis_a.y", j.local_axis_a);
  v.q32("reference_angle", j.reference_angle);
  v.boolean("collide_connected", j.collide_connected);
  v.boolean("enable_spring", j.enable_spring);
  v.boolean("enable_limit", j.enable_limit);
  v.boolean("enable_motor", j.enable_motor);
  v.q32("break_force", j.break_force);
  v.q32("break_torque", j.break_torque);
  v.u64("user_data", j.user_data);
  v.q32("hertz", j.hertz);
  v.q32("damping_ratio", j.damping_ratio);
  v.q32("angular_hertz", j.angular_hertz);
  v.q32("angular_damping_ratio", j.angular_damping_ratio);
  v.q32("length", j.length);
  v.q32("lower", j.lower);
  v.q32("upper", j.upper);
  v.q32("motor_speed", j.motor_speed);
  v.q32("max_motor_force", j.max_motor_force);
  v.vec2("target.x", "target.y", j.target);
  v.q32("angular_offset", j.angular_offset);
  v.q32("max_force", j.max_force);
  v.q32("max_torque", j.max_torque);
  v.q32("correction_factor", j.correction_factor);
  v.vec2("linear_impulse.x", "linear_impulse.y", j.linear_impulse);
  v.q32("angular_impulse", j.angular_impulse);
  v.q32("axial_impulse", j.axial_impulse);
  v.q32("spring_impulse", j.spring_impulse);
  v.q32("motor_impulse", j.motor_impulse);
  v.q32("lower_impulse", j.lower_impulse);
  v.q32("upper_impulse", j.upper_impulse);
  v.vec2("reaction_force.x", "reaction_force.y", j.reaction_force);
  v.q32("reaction_torque", j.reaction_torque);
}

template <typename V>
void visit_pair(V& v, PairRecord& p) {
  v.i32("shape_a", p.shape_a);
  v.i32("shape_b", p.shape_b);
  v.u32("generation_a", p.generation_a);
  v.u32("generation_b", p.generation_b);
}

constexpr size_t k_slot_bytes = 5;   // generation u32 + alive u8
constexpr size_t k_pair_bytes = 16;

/// Pool slots (generation, alive) after a u32 capacity.
template <typename V>
void visit_pool(V& v, IdPool& pool, const char* kind, int32_t max_capacity, ByteReader* reader) {
  uint32_t capacity = static_cast<uint32_t>(pool.generations.size());
  if constexpr (V::k_reading) {
    reader->set_context(kind);
    capacity = reader->read_count("capacity", k_slot_bytes, static_cast<uint32_t>(max_capacity));
    if (!reader->ok()) return;
    pool.generations.assign(capacity, 0);
    pool.alive.assign(capacity, 0);
  } else {
    v.count("capacity", capacity);
  }
  for (uint32_t i = 0; i < capacity; ++i) {
    v.record(kind, i, -1, pool.generations[i]);
    v.u32("generation", pool.generations[i]);
    bool alive = pool.alive[i] != 0;
    v.boolean("alive", alive);
    if constexpr (V::k_reading) {
      if (!v.ok()) return;
      if (pool.generations[i] == 0) {
        reader->fail_at(reader->offset() - k_slot_bytes, reader->describe_what("generation") + ": expected ≥ 1, got 0");
        return;
      }
      pool.alive[i] = alive ? 1 : 0;
    }
  }
  if constexpr (V::k_reading) {
    // Free slots in ascending order already form a valid min-heap.
    pool.free_heap.clear();
    pool.alive_count = 0;
    for (uint32_t i = 0; i < capacity; ++i) {
      if (pool.alive[i] != 0) {
        ++pool.alive_count;
      } else {
        pool.free_heap.push_back(static_cast<int32_t>(i));
      }
    }
  }
}

/// A sorted pair list after a u32 count.
template <typename V>
void visit_pairs(V& v, std::vector<PairRecord>& pairs, const char* kind, ByteReader* reader) {
  uint32_t n = static_cast<uint32_t>(pairs.size());
  if constexpr (V::k_reading) {
    reader->set_context(kind);
    n = reader->read_count("count", k_pair_bytes);
    if (!reader->ok()) return;
    pairs.resize(n);
  } else {
    v.count("count", n);
  }
  for (uint32_t i = 0; i < n; ++i) {
    v.record(kind, pairs[i].shape_a, pairs[i].shape_b);
    if constexpr (V::k_reading) reader->set_context(kind, i);
    visit_pair(v, pairs[i]);
  }
}

/// The whole state after the header. `W` is World or WorldImage; `reader` is
/// non-null only for the ReadVisitor. with_joints: the version-2 joint
/// sections follow the version-1 ones.
template <typename V, typename W>
void visit_world(V& v, W& w, ByteReader* reader, bool with_joints) {
  v.tag("WRLD");
  v.record("world", 0);
  visit_world_def(v, w.def);
  v.u64("step_count", w.step_count);
  v.i32("last_solver_body_count", w.last_solver_body_count);
  if (!v.ok()) return;

  v.tag("BPOL");
  visit_pool(v, w.body_pool, "body_slot", k_max_bodies, reader);
  if (!v.ok()) return;
  const size_t body_capacity = w.body_pool.generations.size();
  if constexpr (V::k_reading) {
    w.bodies.assign(body_capacity, Body{});
    w.body_sims.assign(body_capacity, BodySim{});
    w.body_offsets.assign(body_capacity, 0);
  }
  v.tag("BODY");
  for (size_t i = 0; i < body_capacity; ++i) {
    if (w.body_pool.alive[i] == 0) continue;
    v.record("body", static_cast<int64_t>(i), -1, w.body_pool.generations[i]);
    if constexpr (V::k_reading) w.body_offsets[i] = reader->offset();
    visit_body(v, w.bodies[i], w.body_sims[i]);
    if (!v.ok()) return;
  }

  v.tag("SPOL");
  visit_pool(v, w.shape_pool, "shape_slot", k_max_shapes, reader);
  if (!v.ok()) return;
  const size_t shape_capacity = w.shape_pool.generations.size();
  if constexpr (V::k_reading) {
    w.shapes.assign(shape_capacity, Shape{});
    w.shape_geometries.assign(shape_capacity, ShapeGeometry{});
    w.shape_offsets.assign(shape_capacity, 0);
  }
  v.tag("SHAP");
  for (size_t i = 0; i < shape_capacity; ++i) {
    if (w.shape_pool.alive[i] == 0) continue;
    v.record("shape", static_cast<int64_t>(i), -1, w.shape_pool.generations[i]);
    if constexpr (V::k_reading) w.shape_offsets[i] = reader->offset();
    visit_shape(v, w.shapes[i], w.shape_geometries[i]);
    if (!v.ok()) return;
  }

  v.tag("CONT");
  uint32_t contact_count = static_cast<uint32_t>(w.contacts.size());
  if constexpr (V::k_reading) {
    reader->set_context("contacts");
    contact_count = reader->read_count("count", min_contact_record_bytes());
    if (!reader->ok()) return;
    w.contacts.assign(contact_count, Contact{});
    w.contact_offsets.assign(contact_count, 0);
  } else {
    v.count("count", contact_count);
  }
  for (uint32_t i = 0; i < contact_count; ++i) {
    Contact& c = w.contacts[i];
    v.record("contact", c.shape_a, c.shape_b);
    if constexpr (V::k_reading) {
      reader->set_context("contact", i);
      w.contact_offsets[i] = reader->offset();
    }
    visit_contact(v, c);
    if (!v.ok()) return;
  }

  v.tag("TUCH");
  visit_pairs(v, touching_of(w), "touching", reader);
  if (!v.ok()) return;
  v.tag("SENS");
  visit_pairs(v, sensors_of(w), "sensor_overlap", reader);
  if (!with_joints || !v.ok()) return;

  v.tag("JPOL");
  visit_pool(v, w.joint_pool, "joint_slot", k_max_bodies, reader);
  if (!v.ok()) return;
  const size_t joint_capacity = w.joint_pool.generations.size();
  std::vector<Joint>& joints = joints_of(w);
  if constexpr (V::k_reading) {
    joints.assign(joint_capacity, Joint{});
    w.joint_offsets.assign(joint_capacity, 0);
  }
  v.tag("JOIN");
  for (size_t i = 0; i < joint_capacity; ++i) {
    if (w.joint_pool.alive[i] == 0) continue;
    v.record("joint", static_cast<int64_t>(i), -1, w.joint_pool.generations[i]);
    if constexpr (V::k_reading) w.joint_offsets[i] = reader->offset();
    visit_joint(v, joints[i]);
    if (!v.ok()) return;
  }
}

/// Worlds that never had a joint are written as version 1 (the format before
/// joints, byte for byte); others as version 2 with the joint sections.
bool writes_joints(const World& w) { return !w.joint_pool.generations.empty(); }

// ---------------------------------------------------------------------------
// Sizes
// ---------------------------------------------------------------------------

constexpr size_t k_header_bytes = 12;  // magic, version, kind

template <typename F>
size_t measure(F&& f) {
  ByteWriter counter(nullptr, 0);
  WriteVisitor v{&counter};
  f(v);
  return counter.size();
}

struct RecordSizes {
  size_t world = 0;           // tag + def + step count + solver count
  size_t body = 0;
  size_t shape[5] = {};       // by ShapeType; polygon: with 0 vertices
  size_t polygon_vertex = 32; // vertex + normal
  size_t contact = 0;         // with no points
  size_t contact_point = 0;
  size_t joint = 0;
};

const RecordSizes& record_sizes() {
  static const RecordSizes sizes = [] {
    RecordSizes s;
    s.world = measure([](WriteVisitor& v) {
      WorldDef d{};
      uint64_t sc = 0;
      int32_t n = 0;
      visit_world_def(v, d);
      v.u64("", sc);
      v.i32("", n);
    });
    s.body = measure([](WriteVisitor& v) {
      Body b{};
      BodySim sim{};
      visit_body(v, b, sim);
    });
    for (int32_t t = 0; t < 5; ++t) {
      s.shape[t] = measure([t](WriteVisitor& v) {
        Shape sh{};
        ShapeGeometry g{};
        sh.type = static_cast<ShapeType>(t);
        g.polygon.count = 0;
        visit_shape(v, sh, g);
      });
    }
    s.contact = measure([](WriteVisitor& v) {
      Contact c{};
      visit_contact(v, c);
    });
    s.contact_point = measure([](WriteVisitor& v) {
                        Contact c{};
                        c.manifold.point_count = 1;
                        visit_contact(v, c);
                      }) -
                      s.contact;
    s.joint = measure([](WriteVisitor& v) {
      Joint j{};
      visit_joint(v, j);
    });
    return s;
  }();
  return sizes;
}

size_t min_contact_record_bytes() { return record_sizes().contact; }

size_t shape_record_size(const Shape& s, const ShapeGeometry& g) {
  const RecordSizes& rs = record_sizes();
  const size_t t = static_cast<size_t>(s.type);
  size_t n = t < 5 ? rs.shape[t] : 0;
  if (s.type == ShapeType::polygon) n += static_cast<size_t>(std::clamp(g.polygon.count, 0, 8)) * rs.polygon_vertex;
  return n;
}

size_t encoded_size(const World& w) {
  const RecordSizes& rs = record_sizes();
  size_t n = k_header_bytes + 4 + rs.world;
  n += 4 + 4 + w.body_pool.generations.size() * k_slot_bytes;
  n += 4 + static_cast<size_t>(w.body_pool.alive_count) * rs.body;
  n += 4 + 4 + w.shape_pool.generations.size() * k_slot_bytes;
  n += 4;
  for (size_t i = 0; i < w.shapes.size() && i < w.shape_pool.alive.size(); ++i) {
    if (w.shape_pool.alive[i] != 0) n += shape_record_size(w.shapes[i], w.shape_geometries[i]);
  }
  n += 4 + 4;
  for (const Contact& c : w.contacts) {
    n += rs.contact + static_cast<size_t>(std::clamp(c.manifold.point_count, 0, 2)) * rs.contact_point;
  }
  n += 4 + 4 + w.events.touching.size() * k_pair_bytes;
  n += 4 + 4 + w.events.sensor_overlaps.size() * k_pair_bytes;
  if (writes_joints(w)) {
    n += 4 + 4 + w.joint_pool.generations.size() * k_slot_bytes;
    n += 4 + static_cast<size_t>(w.joint_pool.alive_count) * rs.joint;
  }
  return n;
}

void write_header(ByteWriter* out, bool with_joints) {
  out->bytes(k_state_magic, 4);
  out->u32(with_joints ? k_state_format_version_joints : k_state_format_version);
  out->u32(k_state_kind_full);
}

/// Encodes into buffer[0, capacity); returns the size (> capacity: nothing
/// past the capacity was written).
size_t encode_into(World* w, uint8_t* buffer, size_t capacity) {
  ByteWriter out(buffer, capacity);
  const bool with_joints = writes_joints(*w);
  write_header(&out, with_joints);
  WriteVisitor v{&out};
  visit_world(v, *w, nullptr, with_joints);
  return out.size();
}

Status resolve_for_state(WorldId id, const char* function, bool mutating, World** out) {
  return resolve_world(id, function, mutating, out);
}

// ---------------------------------------------------------------------------
// Decoding and validation
// ---------------------------------------------------------------------------

// ---------------------------------------------------------------------------
// Range and consistency validation (after the structural checks)
// ---------------------------------------------------------------------------
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

/// Finds the byte offset of a named field inside one record by walking the
/// record's visit function in counting mode.
struct OffsetVisitor {
  static constexpr bool k_reading = false;
  ByteWriter* w;
  const char* target;
  size_t found = SIZE_MAX;
  void mark(const char* name) {
    if (found == SIZE_MAX && std::strcmp(name, target) == 0) found = w->size();
  }
  void record(const char*, int64_t, int64_t = -1, uint32_t = 0) {}
  void tag(const char*) { w->bytes(reinterpret_cast<const uint8_t*>("TAGS"), 4); }
  void q32(const char* n, Q32& v) { mark(n); w->q32(v); }
  void vec2(const char* nx, const char* ny, Vec2& v) {
    mark(nx);
    w->q32(v.x);
    mark(ny);
    w->q32(v.y);
  }
  void i32(const char* n, int32_t& v) { mark(n); w->i32(v); }
  void u32(const char* n, uint32_t& v) { mark(n); w->u32(v); }
  void count(const char* n, uint32_t& v) { mark(n); w->u32(v); }
  void u16(const char* n, uint16_t& v) { mark(n); w->u16(v); }
  void u64(const char* n, uint64_t& v) { mark(n); w->u64(v); }
  void boolean(const char* n, bool& v) { mark(n); w->boolean(v); }
  template <typename E>
  void enum8(const char* n, E& v, int32_t) {
    mark(n);
    w->u8(static_cast<uint8_t>(static_cast<int32_t>(v)));
  }
  void ranged_i32(const char* n, int32_t& v, int32_t, int32_t) { mark(n); w->i32(v); }
  bool ok() const { return true; }
};

template <typename F>
size_t field_offset_in(const char* field, F&& visit) {
  ByteWriter counter(nullptr, 0);
  OffsetVisitor v{&counter, field};
  visit(v);
  return v.found == SIZE_MAX ? 0 : v.found;
}

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

/// A record being checked: names it and finds a field's byte offset, both
/// only when a check fails (the success path allocates nothing and walks no
/// visitor, so a warm rollback's restore stays cheap).
struct RecordRef {
  enum Kind { world, body, shape, contact } kind;
  size_t index = 0;
  const WorldImage* img = nullptr;

  std::string who() const {
    switch (kind) {
      case world: return "world";
      case body: return "body " + std::to_string(index);
      case shape: return "shape " + std::to_string(index);
      case contact: {
        const Contact& c = img->contacts[index];
        return "contact " + std::to_string(index) + " (shapes " + std::to_string(c.shape_a) + ", " +
               std::to_string(c.shape_b) + ")";
      }
    }
    return "?";
  }
  size_t offset(const char* field) const {
    switch (kind) {
      case world: {
        WorldDef d = img->def;
        return 16 + field_offset_in(field, [&](OffsetVisitor& v) { visit_world_def(v, d); });
      }
      case body: {
        Body b = img->bodies[index];
        BodySim s = img->body_sims[index];
        return img->body_offsets[index] + field_offset_in(field, [&](OffsetVisitor& v) { visit_body(v, b, s); });
      }
      case shape: {
        Shape s = img->shapes[index];
        ShapeGeometry g = img->shape_geometries[index];
        return img->shape_offsets[index] + field_offset_in(field, [&](OffsetVisitor& v) { visit_shape(v, s, g); });
      }
      case contact: {
        Contact c = img->contacts[index];
        return img->contact_offsets[index] + field_offset_in(field, [&](OffsetVisitor& v) { visit_contact(v, c); });
      }
    }
    return 0;
  }
};

struct ImageChecker {
  WorldImage& img;
  const char* fn;
  Status status;

  bool failed() const { return !status.ok(); }
  /// Refuses at `field` of `r` (offset_field: where the offset points, when
  /// the message names a group of fields).
  void refuse(const RecordRef& r, const char* field, const std::string& what, const char* offset_field = nullptr) {
    if (failed()) return;
    status = make_status(StatusCode::invalid_argument, std::string(fn) + ": offset " +
                                                           std::to_string(r.offset(offset_field ? offset_field : field)) +
                                                           ": " + r.who() + " " + field + " " + what);
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
      refuse(r, fx, "(" + to_string(v.x) + ", " + to_string(v.y) + ") has squared length " + to_string(n) +
                        ", expected 1 ± 2^-16 (a unit vector)");
    }
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
  WorldImage& img = c.img;
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
  WorldImage& img = c.img;
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
  WorldImage& img = c.img;
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
  WorldImage& img = c.img;
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

/// Range and consistency checks of a structurally valid image (see above).
Status validate_image_values(WorldImage* img, const char* function) {
  ImageChecker c{*img, function, Status{}};
  check_world(c);
  if (!c.failed()) check_shapes(c);
  if (!c.failed()) check_bodies(c);
  if (!c.failed()) check_shape_bounds(c);
  if (!c.failed()) check_contacts(c);
  return c.status;
}

/// Decodes and validates a full image into *img. Returns an error Status
/// (invalid_argument, "<function>: offset N: expected ...").
Status decode_image(const uint8_t* data, size_t size, const char* function, WorldImage* img, uint32_t* out_version) {
  ByteReader r(data, size);
  const auto bad = [&](const std::string& msg) {
    return make_status(StatusCode::invalid_argument, std::string(function) + ": " + msg);
  };
  if (data == nullptr && size != 0) return bad("null data with size " + std::to_string(size));
  const std::span<const uint8_t> magic = r.bytes(4, "magic \"TNDS\"");
  if (!r.ok()) return bad(r.error());
  if (std::memcmp(magic.data(), k_state_magic, 4) != 0) {
    return bad("offset 0: expected magic \"TNDS\" (a Tandem state image), got bytes " + std::to_string(magic[0]) +
               " " + std::to_string(magic[1]) + " " + std::to_string(magic[2]) + " " + std::to_string(magic[3]));
  }
  const uint32_t version = r.u32("format version");
  if (!r.ok()) return bad(r.error());
  if (version != k_state_format_version && version != k_state_format_version_joints) {
    return bad("offset 4: expected format version " + std::to_string(k_state_format_version) + " or " +
               std::to_string(k_state_format_version_joints) + ", got " + std::to_string(version));
  }
  if (out_version != nullptr) *out_version = version;
  const uint32_t kind = r.u32("image kind");
  if (!r.ok()) return bad(r.error());
  if (kind != k_state_kind_full) {
    return bad("offset 8: expected image kind 0 (full state), got " + std::to_string(kind));
  }

  ReadVisitor v{&r};
  const bool with_joints = version == k_state_format_version_joints;
  if (!with_joints) {
    img->joint_pool = IdPool{};
    img->joints.joints.clear();
    img->joint_offsets.clear();
  }
  visit_world(v, *img, &r, with_joints);
  if (!r.ok()) return bad(r.error());
  if (!r.at_end()) {
    return bad("offset " + std::to_string(r.offset()) + ": expected the end of the image, " +
               std::to_string(r.remaining()) + " bytes left over");
  }

  // Cross references.
  const auto at = [&](size_t offset, const std::string& msg) {
    return bad("offset " + std::to_string(offset) + ": " + msg);
  };
  const int32_t body_cap = static_cast<int32_t>(img->bodies.size());
  const int32_t shape_cap = static_cast<int32_t>(img->shapes.size());
  if (img->body_pool.alive_count > k_max_bodies || img->shape_pool.alive_count > k_max_shapes) {
    return bad("too many live bodies or shapes");
  }
  if (img->last_solver_body_count < 0 || img->last_solver_body_count > body_cap) {
    return bad("last_solver_body_count " + std::to_string(img->last_solver_body_count) + " outside [0, " +
               std::to_string(body_cap) + "]");
  }
  if (!(img->def.bounds.lower.x < img->def.bounds.upper.x && img->def.bounds.lower.y < img->def.bounds.upper.y)) {
    return bad("world bounds must have lower < upper");
  }
  int64_t listed_shapes = 0;
  for (int32_t b = 0; b < body_cap; ++b) {
    if (img->body_pool.alive[static_cast<size_t>(b)] == 0) continue;
    const Body& body = img->bodies[static_cast<size_t>(b)];
    const size_t off = img->body_offsets[static_cast<size_t>(b)];
    const std::string who = "body " + std::to_string(b);
    if (body.sleep_island != k_null_index && (body.sleep_island < 0 || body.sleep_island >= body_cap ||
                                              img->body_pool.alive[static_cast<size_t>(body.sleep_island)] == 0)) {
      return at(off, who + " sleep_island " + std::to_string(body.sleep_island) + " is not a live body");
    }
    int32_t count = 0;
    int32_t prev = k_null_index;
    for (int32_t s = body.head_shape; s != k_null_index;) {
      if (s < 0 || s >= shape_cap || img->shape_pool.alive[static_cast<size_t>(s)] == 0) {
        return at(off, who + " shape list names shape " + std::to_string(s) + ", which is not a live shape");
      }
      const Shape& shape = img->shapes[static_cast<size_t>(s)];
      if (shape.body_index != b || shape.prev_shape != prev || s <= prev) {
        return at(img->shape_offsets[static_cast<size_t>(s)],
                  "shape " + std::to_string(s) + " is inconsistent with " + who +
                      "'s shape list (body, prev_shape or order)");
      }
      if (++count > body.shape_count) break;
      prev = s;
      s = shape.next_shape;
    }
    if (count != body.shape_count) {
      return at(off, who + " shape_count " + std::to_string(body.shape_count) + " but its list holds " +
                         (count > body.shape_count ? "more" : std::to_string(count)));
    }
    listed_shapes += count;
  }
  if (listed_shapes != img->shape_pool.alive_count) {
    return bad("bodies list " + std::to_string(listed_shapes) + " shapes but " +
               std::to_string(img->shape_pool.alive_count) + " shapes are alive");
  }
  // Geometry the narrow phase divides by or takes roots of.
  for (int32_t i = 0; i < shape_cap; ++i) {
    if (img->shape_pool.alive[static_cast<size_t>(i)] == 0) continue;
    const ShapeGeometry& g = img->shape_geometries[static_cast<size_t>(i)];
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
      return at(img->shape_offsets[static_cast<size_t>(i)],
                "shape " + std::to_string(i) + " has degenerate geometry (zero or negative radius, or coincident points)");
    }
  }
  uint64_t prev_key = 0;
  for (size_t i = 0; i < img->contacts.size(); ++i) {
    const Contact& c = img->contacts[i];
    const size_t off = img->contact_offsets[i];
    if (c.shape_a < 0 || c.shape_b >= shape_cap || c.shape_a >= c.shape_b || c.body_a < 0 || c.body_a >= body_cap ||
        c.body_b < 0 || c.body_b >= body_cap) {
      return at(off, "contact " + std::to_string(i) + " names shapes (" + std::to_string(c.shape_a) + ", " +
                         std::to_string(c.shape_b) + ") / bodies (" + std::to_string(c.body_a) + ", " +
                         std::to_string(c.body_b) + ") outside the pools or out of order");
    }
    const uint64_t key = contact_key(c);
    if (i > 0 && key <= prev_key) return at(off, "contact " + std::to_string(i) + " is not sorted by shape pair");
    prev_key = key;
  }
  const auto check_pairs = [&](const std::vector<PairRecord>& pairs, const char* what) -> Status {
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
    return Status{};
  };
  Status s = check_pairs(img->events.touching, "touching pair");
  if (!s.ok()) return s;
  s = check_pairs(img->events.sensor_overlaps, "sensor overlap");
  if (!s.ok()) return s;
  for (size_t i = 0; i < img->joints.joints.size(); ++i) {
    if (img->joint_pool.alive[i] == 0) continue;
    const Joint& j = img->joints.joints[i];
    const auto live = [&](int32_t b) {
      return b >= 0 && b < body_cap && img->body_pool.alive[static_cast<size_t>(b)] != 0;
    };
    if (!live(j.body_a) || !live(j.body_b) || j.body_a == j.body_b) {
      return at(img->joint_offsets[i], "joint " + std::to_string(i) + " joins bodies (" + std::to_string(j.body_a) +
                                           ", " + std::to_string(j.body_b) + "), which are not two live bodies");
    }
  }
  return validate_image_values(img, function);
}

/// Replaces the world's state with a validated image. Vectors are swapped,
/// so the scratch image keeps the world's old buffers for the next decode
/// (no allocation in a warm rollback loop).
void commit_image(World* w, WorldImage& img) {
  const int32_t cookie = w->def.internal_cookie;
  w->def = img.def;
  w->def.internal_cookie = cookie;
  w->step_count = img.step_count;
  w->last_solver_body_count = img.last_solver_body_count;
  std::swap(w->body_pool, img.body_pool);
  std::swap(w->bodies, img.bodies);
  std::swap(w->body_sims, img.body_sims);
  std::swap(w->shape_pool, img.shape_pool);
  std::swap(w->shapes, img.shapes);
  std::swap(w->shape_geometries, img.shape_geometries);
  std::swap(w->contacts, img.contacts);
  w->contact_scratch.clear();
  std::swap(w->joint_pool, img.joint_pool);
  std::swap(w->joints.joints, img.joints.joints);
  w->joints.events.clear();
  w->joints.pending.clear();
  rebuild_joint_filter(w);
  EventState& e = w->events;
  std::swap(e.touching, img.events.touching);
  std::swap(e.sensor_overlaps, img.events.sensor_overlaps);
  e.touching_next.clear();
  e.sensor_next.clear();
  e.hit_candidates.clear();
  events_clear_reported(&e);
  broad_phase_reset(w);
  // Buffers sized for the restored scene, so its next step does not allocate.
  reserve_contact_headroom(w);
  events_reserve_headroom(w);
}

WorldImage& scratch_image() {
  thread_local WorldImage image;
  return image;
}

std::vector<uint8_t>& scratch_bytes() {
  thread_local std::vector<uint8_t> bytes;
  return bytes;
}

}  // namespace

// ---------------------------------------------------------------------------
// Public API
// ---------------------------------------------------------------------------

size_t world_snapshot_size(WorldId world) {
  World* w = find_world(world);
  return w == nullptr ? 0 : encoded_size(*w);
}

Status world_snapshot(WorldId world, uint8_t* buffer, size_t capacity, size_t* written) {
  World* w = nullptr;
  Status s = resolve_for_state(world, "world_snapshot", true, &w);
  if (!s.ok()) return s;
  const size_t needed = encoded_size(*w);
  if (written != nullptr) *written = needed;
  if (capacity < needed || (buffer == nullptr && needed != 0)) {
    return make_status(StatusCode::capacity_exceeded, "world_snapshot: the buffer holds " + std::to_string(capacity) +
                                                          " bytes; the snapshot of " + describe(world) + " needs " +
                                                          std::to_string(needed));
  }
  const size_t n = encode_into(w, buffer, capacity);
  TANDEM_ASSERT(n == needed);
  (void)n;
  return s;
}

Status world_snapshot_append(WorldId world, std::vector<uint8_t>* out) {
  World* w = nullptr;
  Status s = resolve_for_state(world, "world_snapshot_append", true, &w);
  if (!s.ok()) return s;
  const size_t needed = encoded_size(*w);
  const size_t old = out->size();
  out->resize(old + needed);
  const size_t n = encode_into(w, out->data() + old, needed);
  TANDEM_ASSERT(n == needed);
  (void)n;
  return s;
}

Status encode_world_state(WorldId world, std::vector<uint8_t>* out) {
  World* w = nullptr;
  Status s = resolve_for_state(world, "encode_world_state", true, &w);
  if (!s.ok()) return s;
  out->clear();
  return world_snapshot_append(world, out);
}

Status world_restore(WorldId world, const uint8_t* data, size_t size) {
  World* w = nullptr;
  Status s = resolve_for_state(world, "world_restore", true, &w);
  if (!s.ok()) return s;
  WorldImage& img = scratch_image();
  s = decode_image(data, size, "world_restore", &img, nullptr);
  if (!s.ok()) return s;
  commit_image(w, img);
  return s;
}

Result<WorldId> create_world_from_snapshot(const uint8_t* data, size_t size) {
  Result<WorldId> result = create_world(default_world_def());
  if (!result.ok()) return result;
  Status s = world_restore(result.value, data, size);
  if (!s.ok()) {
    (void)destroy_world(result.value);  // just created: cannot fail
    result.value = WorldId{};
    result.status = make_status(s.code, "create_world_from_snapshot: " + s.message);
  }
  return result;
}

uint64_t world_state_hash(WorldId world) {
  World* w = find_world(world);
  if (w == nullptr || w->locked) return 0;
  std::vector<uint8_t>& buf = scratch_bytes();
  const size_t needed = encoded_size(*w);
  if (buf.size() < needed) buf.resize(needed);
  // The broad-phase kind is kept in snapshots (a restore brings it back) but
  // by contract changes no result, so the hash sees every world as naive:
  // the same simulation hashes the same whichever broad phase ran it.
  const BroadPhaseKind kind = w->def.broad_phase;
  w->def.broad_phase = BroadPhaseKind::naive;
  const size_t n = encode_into(w, buf.data(), buf.size());
  w->def.broad_phase = kind;
  TANDEM_ASSERT(n == needed);
  return XXH3_64bits(buf.data(), n);
}

namespace {
uint64_t hash_body(World* w, int32_t index) {
  std::vector<uint8_t>& buf = scratch_bytes();
  const RecordSizes& rs = record_sizes();
  const Body& body = w->bodies[static_cast<size_t>(index)];
  size_t needed = rs.body;
  for (int32_t s = body.head_shape; s != k_null_index; s = w->shapes[static_cast<size_t>(s)].next_shape) {
    needed += shape_record_size(w->shapes[static_cast<size_t>(s)], w->shape_geometries[static_cast<size_t>(s)]);
  }
  if (buf.size() < needed) buf.resize(needed);
  ByteWriter out(buf.data(), buf.size());
  WriteVisitor v{&out};
  visit_body(v, w->bodies[static_cast<size_t>(index)], w->body_sims[static_cast<size_t>(index)]);
  for (int32_t s = body.head_shape; s != k_null_index; s = w->shapes[static_cast<size_t>(s)].next_shape) {
    visit_shape(v, w->shapes[static_cast<size_t>(s)], w->shape_geometries[static_cast<size_t>(s)]);
  }
  TANDEM_ASSERT(out.size() == needed);
  return XXH3_64bits(buf.data(), out.size());
}
}  // namespace

uint64_t body_state_hash(BodyId body) {
  World* w = nullptr;
  int32_t index = 0;
  if (!find_body(body, &w, &index) || w->locked) return 0;
  return hash_body(w, index);
}

Status world_body_hashes(WorldId world, std::vector<uint64_t>* out) {
  World* w = nullptr;
  Status s = resolve_for_state(world, "world_body_hashes", true, &w);
  if (!s.ok()) return s;
  const int32_t cap = id_pool_capacity(w->body_pool);
  out->assign(static_cast<size_t>(cap), 0);
  for (int32_t i = 0; i < cap; ++i) {
    if (id_pool_is_alive(w->body_pool, i)) (*out)[static_cast<size_t>(i)] = hash_body(w, i);
  }
  return s;
}

Status decode_world_state(const uint8_t* data, size_t size, DecodedState* out) {
  WorldImage img;
  uint32_t version = 0;
  Status s = decode_image(data, size, "decode_world_state", &img, &version);
  if (!s.ok()) return s;
  out->version = version;
  out->records.clear();
  DescribeVisitor v{out};
  visit_world(v, img, nullptr, version == k_state_format_version_joints);
  return s;
}

Status locate_state_field(const uint8_t* data, size_t size, const std::string& kind, int64_t index,
                          const std::string& field, size_t* out_offset) {
  WorldImage img;
  Status s = decode_image(data, size, "locate_state_field", &img, nullptr);
  if (!s.ok()) return s;
  const auto missing = [&](const std::string& what) {
    return make_status(StatusCode::invalid_argument, "locate_state_field: " + what);
  };
  const char* f = field.c_str();
  size_t base = 0;
  size_t found = SIZE_MAX;
  const auto find = [&](auto&& visit) {
    ByteWriter counter(nullptr, 0);
    OffsetVisitor v{&counter, f};
    visit(v);
    found = v.found;
  };
  if (kind == "world") {
    base = 16;
    find([&](OffsetVisitor& v) { visit_world_def(v, img.def); });
  } else if (kind == "body" || kind == "shape") {
    const bool body = kind == "body";
    const size_t cap = body ? img.bodies.size() : img.shapes.size();
    if (index < 0 || static_cast<size_t>(index) >= cap ||
        (body ? img.body_pool : img.shape_pool).alive[static_cast<size_t>(index)] == 0) {
      return missing(kind + " " + std::to_string(index) + " is not alive in the image");
    }
    const size_t i = static_cast<size_t>(index);
    if (body) {
      base = img.body_offsets[i];
      find([&](OffsetVisitor& v) { visit_body(v, img.bodies[i], img.body_sims[i]); });
    } else {
      base = img.shape_offsets[i];
      find([&](OffsetVisitor& v) { visit_shape(v, img.shapes[i], img.shape_geometries[i]); });
    }
  } else if (kind == "contact") {
    if (index < 0 || static_cast<size_t>(index) >= img.contacts.size()) {
      return missing("contact " + std::to_string(index) + " is not in the image");
    }
    base = img.contact_offsets[static_cast<size_t>(index)];
    find([&](OffsetVisitor& v) { visit_contact(v, img.contacts[static_cast<size_t>(index)]); });
  } else {
    return missing("unknown record kind \"" + kind + "\" (world, body, shape or contact)");
  }
  if (found == SIZE_MAX) return missing(kind + " has no field \"" + field + "\"");
  *out_offset = base + found;
  return s;
}

// ---------------------------------------------------------------------------
// Deltas
// ---------------------------------------------------------------------------

namespace {

constexpr uint8_t k_delta_magic[4] = {'T', 'N', 'D', 'D'};
constexpr uint32_t k_delta_version = 1;

void put_varint(std::vector<uint8_t>* out, uint64_t v) {
  while (v >= 0x80) {
    out->push_back(static_cast<uint8_t>(v | 0x80));
    v >>= 7;
  }
  out->push_back(static_cast<uint8_t>(v));
}

/// LEB128, at most 10 bytes; fails (false) on truncation or overlong input.
bool get_varint(ByteReader* r, const char* what, uint64_t* out) {
  uint64_t v = 0;
  for (int shift = 0; shift < 64; shift += 7) {
    const size_t at = r->offset();
    const uint8_t b = r->u8(what);
    if (!r->ok()) return false;
    if (shift == 63 && b > 1) {
      r->fail_at(at, std::string("expected ") + what + " (a varint below 2^64)");
      return false;
    }
    v |= static_cast<uint64_t>(b & 0x7F) << shift;
    if ((b & 0x80) == 0) {
      *out = v;
      return true;
    }
  }
  r->fail(std::string("expected the end of varint ") + what);
  return false;
}

uint8_t base_byte(const uint8_t* base, size_t base_size, size_t i) { return i < base_size ? base[i] : 0; }

}  // namespace

void encode_state_delta(const uint8_t* base, size_t base_size, const uint8_t* image, size_t image_size,
                        std::vector<uint8_t>* out) {
  out->clear();
  ByteWriter header(out);
  header.bytes(k_delta_magic, 4);
  header.u32(k_delta_version);
  header.u64(image_size);
  header.u64(XXH3_64bits(base, base_size));
  const size_t common = std::min(base_size, image_size);
  size_t i = 0;
  while (i < image_size) {
    // A run of bytes equal to the base (only within the base).
    size_t run = 0;
    while (i + run + 8 <= common && std::memcmp(base + i + run, image + i + run, 8) == 0) run += 8;
    while (i + run < common && base[i + run] == image[i + run]) ++run;
    put_varint(out, run);
    i += run;
    if (i >= image_size) break;
    // Literal bytes until 4 equal bytes in a row (or the end).
    size_t end = i;
    size_t same = 0;
    while (end < image_size) {
      if (end < common && base[end] == image[end]) {
        if (++same == 4) {
          end -= 3;
          break;
        }
      } else {
        same = 0;
      }
      ++end;
    }
    if (end >= image_size) end = image_size;
    put_varint(out, end - i);
    for (size_t k = i; k < end; ++k) out->push_back(static_cast<uint8_t>(image[k] ^ base_byte(base, base_size, k)));
    i = end;
  }
}

Status apply_state_delta(const uint8_t* base, size_t base_size, const uint8_t* delta, size_t delta_size,
                         std::vector<uint8_t>* out_image) {
  const auto bad = [](const std::string& msg) {
    return make_status(StatusCode::invalid_argument, "apply_state_delta: " + msg);
  };
  if (delta == nullptr && delta_size != 0) return bad("null delta with size " + std::to_string(delta_size));
  ByteReader r(delta, delta_size);
  const std::span<const uint8_t> magic = r.bytes(4, "magic \"TNDD\"");
  if (!r.ok()) return bad(r.error());
  if (std::memcmp(magic.data(), k_delta_magic, 4) != 0) return bad("offset 0: expected magic \"TNDD\" (a state delta)");
  const uint32_t version = r.u32("delta version");
  if (r.ok() && version != k_delta_version) {
    return bad("offset 4: expected delta version " + std::to_string(k_delta_version) + ", got " +
               std::to_string(version));
  }
  const uint64_t image_size = r.u64("image size");
  const uint64_t base_hash = r.u64("base hash");
  if (!r.ok()) return bad(r.error());
  if (base_hash != XXH3_64bits(base, base_size)) {
    return bad("offset 16: the delta was made against another base (base hash differs)");
  }
  if (image_size > static_cast<uint64_t>(base_size) + delta_size) {
    return bad("offset 8: expected an image size of at most " + std::to_string(base_size + delta_size) +
               " (base + delta), got " + std::to_string(image_size));
  }
  const size_t n = static_cast<size_t>(image_size);
  out_image->resize(n);
  uint8_t* img = out_image->data();
  size_t i = 0;
  while (i < n) {
    uint64_t run = 0;
    const size_t run_at = r.offset();
    if (!get_varint(&r, "unchanged run", &run)) return bad(r.error());
    if (run > n - i || run > (i < base_size ? base_size - i : 0)) {
      return bad("offset " + std::to_string(run_at) + ": expected an unchanged run within the base and the image (" +
                 std::to_string(std::min(n - i, i < base_size ? base_size - i : 0)) + " bytes), got " +
                 std::to_string(run));
    }
    if (run != 0) std::memcpy(img + i, base + i, static_cast<size_t>(run));
    i += static_cast<size_t>(run);
    if (i >= n) break;
    uint64_t lit = 0;
    const size_t lit_at = r.offset();
    if (!get_varint(&r, "changed run", &lit)) return bad(r.error());
    if (lit == 0 || lit > n - i || lit > r.remaining()) {
      return bad("offset " + std::to_string(lit_at) + ": expected a changed run of 1.." +
                 std::to_string(std::min(n - i, r.remaining())) + " bytes, got " + std::to_string(lit));
    }
    const std::span<const uint8_t> bytes = r.bytes(static_cast<size_t>(lit), "changed bytes");
    for (size_t k = 0; k < bytes.size(); ++k, ++i) img[i] = static_cast<uint8_t>(bytes[k] ^ base_byte(base, base_size, i));
  }
  if (!r.at_end()) {
    return bad("offset " + std::to_string(r.offset()) + ": expected the end of the delta, " +
               std::to_string(r.remaining()) + " bytes left over");
  }
  return Status{};
}

std::string q32_raw_text(int64_t raw) {
  if (raw == INT64_MIN) return "-2147483648";
  return to_string(Q32::from_raw(raw));
}

std::string StateDifference::describe() const {
  if (!differs) return "identical";
  std::string who = kind + " " + std::to_string(index);
  if (index2 >= 0) who = kind + " (" + std::to_string(index) + ", " + std::to_string(index2) + ")";
  if (generation != 0) who += " (generation " + std::to_string(generation) + ")";
  if (missing_in_a) return who + ": only in b";
  if (missing_in_b) return who + ": only in a";
  const auto text = [&](int64_t v) {
    return is_q32 ? q32_raw_text(v) + " (raw " + std::to_string(v) + ")" : std::to_string(v);
  };
  return who + " " + field + ": a = " + text(value_a) + ", b = " + text(value_b);
}

namespace {
/// The position of a record kind's section in canonical order.
int32_t kind_rank(const std::string& kind) {
  static const char* const kinds[] = {"world",   "body_slot", "body",           "shape_slot", "shape",
                                      "contact", "touching",  "sensor_overlap", "joint_slot", "joint"};
  for (int32_t i = 0; i < 10; ++i) {
    if (kind == kinds[i]) return i;
  }
  return 10;
}
}  // namespace

StateDifference diff_world_states(const DecodedState& a, const DecodedState& b) {
  StateDifference d;
  const size_t n = std::min(a.records.size(), b.records.size());
  for (size_t i = 0; i < n; ++i) {
    const DecodedRecord& ra = a.records[i];
    const DecodedRecord& rb = b.records[i];
    if (ra.kind != rb.kind || ra.index != rb.index || ra.index2 != rb.index2) {
      d.differs = true;
      // The record that sorts first in canonical order is the one the other
      // side lacks; kinds differ only at a section boundary, where the
      // shorter section is missing a record.
      const int32_t rank_a = kind_rank(ra.kind);
      const int32_t rank_b = kind_rank(rb.kind);
      const bool a_first = rank_a != rank_b ? rank_a < rank_b
                                            : (ra.index < rb.index || (ra.index == rb.index && ra.index2 < rb.index2));
      const DecodedRecord& r = a_first ? ra : rb;
      d.kind = r.kind;
      d.index = r.index;
      d.index2 = r.index2;
      d.generation = r.generation;
      d.missing_in_b = a_first;
      d.missing_in_a = !a_first;
      return d;
    }
    const size_t fields = std::min(ra.fields.size(), rb.fields.size());
    for (size_t f = 0; f < fields; ++f) {
      const DecodedField& fa = ra.fields[f];
      const DecodedField& fb = rb.fields[f];
      if (fa.name != fb.name || fa.value != fb.value) {
        d.differs = true;
        d.kind = ra.kind;
        d.index = ra.index;
        d.index2 = ra.index2;
        d.generation = ra.generation;
        d.field = fa.name == fb.name ? fa.name : fa.name + " / " + fb.name;
        d.value_a = fa.value;
        d.value_b = fb.value;
        d.is_q32 = fa.is_q32;
        return d;
      }
    }
    if (ra.fields.size() != rb.fields.size()) {
      d.differs = true;
      d.kind = ra.kind;
      d.index = ra.index;
      d.index2 = ra.index2;
      d.generation = ra.generation;
      const bool a_longer = ra.fields.size() > rb.fields.size();
      d.field = (a_longer ? ra.fields[fields] : rb.fields[fields]).name + " (present on one side only)";
      d.value_a = static_cast<int64_t>(ra.fields.size());
      d.value_b = static_cast<int64_t>(rb.fields.size());
      return d;
    }
    if (ra.generation != rb.generation) {
      d.differs = true;
      d.kind = ra.kind;
      d.index = ra.index;
      d.index2 = ra.index2;
      d.generation = ra.generation;
      d.field = "generation";
      d.value_a = ra.generation;
      d.value_b = rb.generation;
      return d;
    }
  }
  if (a.records.size() != b.records.size()) {
    const bool a_longer = a.records.size() > b.records.size();
    const DecodedRecord& r = a_longer ? a.records[n] : b.records[n];
    d.differs = true;
    d.kind = r.kind;
    d.index = r.index;
    d.index2 = r.index2;
    d.generation = r.generation;
    d.missing_in_b = a_longer;
    d.missing_in_a = !a_longer;
  }
  return d;
}

}  // namespace tandem

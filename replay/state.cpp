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
#include "physics/shape.h"
#include "physics/world.h"
#include "replay/bytes.h"

namespace tandem {
namespace {

constexpr uint32_t k_state_kind_full = 0;

/// Everything restore replaces, decoded and validated before it touches a
/// world. Field names match World's so the visit templates serve both.
struct WorldImage {
  WorldDef def;
  uint64_t step_count = 0;
  int32_t last_solver_body_count = 0;
  IdPool body_pool;
  std::vector<Body> bodies;
  std::vector<BodySim> body_sims;
  IdPool shape_pool;
  std::vector<Shape> shapes;
  std::vector<ShapeGeometry> shape_geometries;
  std::vector<Contact> contacts;
  std::vector<PairRecord> touching;
  std::vector<PairRecord> sensor_overlaps;
  IdPool joint_pool;       // empty for a version-1 image
  std::vector<Joint> joints;
  // Reader only: byte offset of each record, for cross-reference messages.
  std::vector<size_t> body_offsets;   // by body index
  std::vector<size_t> shape_offsets;  // by shape index
  std::vector<size_t> contact_offsets;
  std::vector<size_t> joint_offsets;  // by joint index
};

std::vector<PairRecord>& touching_of(World& w) { return w.events.touching; }
std::vector<PairRecord>& touching_of(WorldImage& w) { return w.touching; }
std::vector<PairRecord>& sensors_of(World& w) { return w.events.sensor_overlaps; }
std::vector<PairRecord>& sensors_of(WorldImage& w) { return w.sensor_overlaps; }
std::vector<Joint>& joints_of(World& w) { return w.joints.joints; }
std::vector<Joint>& joints_of(WorldImage& w) { return w.joints; }

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
    contact_count = reader->read_count("count", 16);
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
    img->joints.clear();
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
  Status s = check_pairs(img->touching, "touching pair");
  if (!s.ok()) return s;
  s = check_pairs(img->sensor_overlaps, "sensor overlap");
  if (!s.ok()) return s;
  for (size_t i = 0; i < img->joints.size(); ++i) {
    if (img->joint_pool.alive[i] == 0) continue;
    const Joint& j = img->joints[i];
    const auto live = [&](int32_t b) {
      return b >= 0 && b < body_cap && img->body_pool.alive[static_cast<size_t>(b)] != 0;
    };
    if (!live(j.body_a) || !live(j.body_b) || j.body_a == j.body_b) {
      return at(img->joint_offsets[i], "joint " + std::to_string(i) + " joins bodies (" + std::to_string(j.body_a) +
                                           ", " + std::to_string(j.body_b) + "), which are not two live bodies");
    }
  }
  return s;
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
  std::swap(w->joints.joints, img.joints);
  w->joints.events.clear();
  w->joints.pending.clear();
  rebuild_joint_filter(w);
  EventState& e = w->events;
  std::swap(e.touching, img.touching);
  std::swap(e.sensor_overlaps, img.sensor_overlaps);
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
    destroy_world(result.value);
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

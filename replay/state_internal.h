// state_internal.h — what the canonical-state files share (internal, not
// installed): the WorldImage scratch world, the field visitors and the
// per-record visit functions that define the canonical field order.
//
// Files (state.h describes the format):
//   state_internal.h   visitors, visit_* (field order), shared declarations
//   state_encode.cpp   sizes, encoding, snapshot and hash API
//   state_restore.cpp  structural decoding, commit, restore, decode/locate API
//   state_validate.cpp range and consistency validation of a decoded image
//   state_diff.cpp     deltas against a base image, field-level diffs
//
// DESIGN. Each record kind has ONE visit function (visit_world_def, visit_body,
// visit_shape, visit_contact, visit_pair, visit_pool) that lists
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
#pragma once

#include <algorithm>
#include <array>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "physics/body.h"
#include "physics/broad_phase.h"
#include "physics/contact.h"
#include "physics/events.h"
#include "physics/id_pool.h"
#include "physics/island.h"
#include "physics/joint_state.h"
#include "physics/limits.h"
#include "physics/shape.h"
#include "physics/state_fields.h"
#include "physics/world.h"
#include "replay/bytes.h"
#include "replay/state.h"

namespace tandem::state_detail {

inline constexpr uint32_t k_state_kind_full = 0;

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

inline std::vector<PairRecord>& touching_of(World& w) { return w.events.touching; }
inline std::vector<PairRecord>& sensors_of(World& w) { return w.events.sensor_overlaps; }
inline std::vector<Joint>& joints_of(World& w) { return w.joints.joints; }

/// The smallest encoded contact record (no points), for read_count.
size_t min_contact_record_bytes();

// The field lists (visit_world_def … visit_pair) live in physics/state_fields.h.
using state_fields::k_point_field_count;
using state_fields::point_name;
using state_fields::polygon_name;
using state_fields::visit_body;
using state_fields::visit_contact;
using state_fields::visit_joint;
using state_fields::visit_joint_event;
using state_fields::visit_pair;
using state_fields::visit_shape;
using state_fields::visit_world_def;

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

inline constexpr size_t k_slot_bytes = 5;   // generation u32 + alive u8
inline constexpr size_t k_pair_bytes = 16;

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
/// non-null only for the ReadVisitor. version: the image's format version
/// (2 adds the joint sections, 3 the pending joint events). with_joints:
/// sections follow the version-1 ones.
template <typename V, typename W>
void visit_world(V& v, W& w, ByteReader* reader, uint32_t version) {
  const bool with_joints = version >= k_state_format_version_joints;
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
  if (version < k_state_format_version_joint_events) return;

  v.tag("JEVP");
  std::vector<JointEvent>& pending = w.joints.pending;
  uint32_t pending_count = static_cast<uint32_t>(pending.size());
  if constexpr (V::k_reading) {
    reader->set_context("pending joint events");
    pending_count = reader->read_count("count", 53);
    if (!reader->ok()) return;
    pending.assign(pending_count, JointEvent{});
  } else {
    v.count("count", pending_count);
  }
  for (uint32_t i = 0; i < pending_count; ++i) {
    v.record("joint_event", i);
    if constexpr (V::k_reading) reader->set_context("joint_event", i);
    visit_joint_event(v, pending[i]);
    if (!v.ok()) return;
  }
}

/// The version an image of `w` is written in: 1 for worlds that never had a
/// joint (the format before joints, byte for byte), 3 while joint events wait
/// for the next step (joints destroyed with a body since the last step), 2
/// otherwise (so the images and hashes of every tick after a step are those
/// of version 2).
inline uint32_t image_version(const World& w) {
  if (w.joint_pool.generations.empty() && w.joints.pending.empty()) return k_state_format_version;
  return w.joints.pending.empty() ? k_state_format_version_joints : k_state_format_version_joint_events;
}

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

// ---------------------------------------------------------------------------
// Joint field ranges (restore validation, portable and rollback)
// ---------------------------------------------------------------------------

/// One Q32 field of a joint record and the range a restored value must lie
/// in: what the joint API accepts for it (limits.h), over every joint kind.
struct JointFieldRange {
  const char* field;
  Q32 Joint::*member;  ///< the field, or null for a Vec2 component
  Vec2 Joint::*vector;
  bool y;              ///< the component of `vector`
  Q32 lo, hi;
  const char* unit;
  Q32 get(const Joint& j) const { return member != nullptr ? j.*member : (y ? (j.*vector).y : (j.*vector).x); }
};

/// Largest |accumulated joint impulse| restored, N·s (as contact impulses).
inline constexpr Q32 k_max_restored_joint_impulse = Q32::from_raw(int64_t{400000000} << 32);

/// The range of every bounded Q32 joint field, in canonical order.
inline const std::vector<JointFieldRange>& joint_field_ranges() {
  static const std::vector<JointFieldRange> table = [] {
    const Q32 z = Q32::zero();
    const Q32 jmax = k_max_restored_joint_impulse;
    const Q32 speed = max(k_max_linear_speed, k_max_angular_speed);
    const Q32 motor = max(k_max_joint_force, k_max_joint_torque);
    const auto q = [](const char* f, Q32 Joint::*m, Q32 lo, Q32 hi, const char* unit) {
      return JointFieldRange{f, m, nullptr, false, lo, hi, unit};
    };
    const auto v = [](const char* f, Vec2 Joint::*m, bool y, Q32 lo, Q32 hi, const char* unit) {
      return JointFieldRange{f, nullptr, m, y, lo, hi, unit};
    };
    return std::vector<JointFieldRange>{
        v("local_anchor_a.x", &Joint::local_anchor_a, false, -k_max_shape_size, k_max_shape_size, "m"),
        v("local_anchor_a.y", &Joint::local_anchor_a, true, -k_max_shape_size, k_max_shape_size, "m"),
        v("local_anchor_b.x", &Joint::local_anchor_b, false, -k_max_shape_size, k_max_shape_size, "m"),
        v("local_anchor_b.y", &Joint::local_anchor_b, true, -k_max_shape_size, k_max_shape_size, "m"),
        q("reference_angle", &Joint::reference_angle, -k_pi, k_pi, "rad"),
        q("break_force", &Joint::break_force, z, k_max_joint_force, "N"),
        q("break_torque", &Joint::break_torque, z, k_max_joint_torque, "N·m"),
        q("hertz", &Joint::hertz, z, k_max_joint_hertz, "Hz"),
        q("damping_ratio", &Joint::damping_ratio, z, k_max_joint_damping_ratio, ""),
        q("angular_hertz", &Joint::angular_hertz, z, k_max_joint_hertz, "Hz"),
        q("angular_damping_ratio", &Joint::angular_damping_ratio, z, k_max_joint_damping_ratio, ""),
        q("length", &Joint::length, z, k_max_joint_length, "m"),
        q("lower", &Joint::lower, -k_max_joint_length, k_max_joint_length, "rad or m"),
        q("upper", &Joint::upper, -k_max_joint_length, k_max_joint_length, "rad or m"),
        q("motor_speed", &Joint::motor_speed, -speed, speed, "rad/s or m/s"),
        q("max_motor_force", &Joint::max_motor_force, z, motor, "N or N·m"),
        v("target.x", &Joint::target, false, -k_max_world_coordinate, k_max_world_coordinate, "m"),
        v("target.y", &Joint::target, true, -k_max_world_coordinate, k_max_world_coordinate, "m"),
        q("angular_offset", &Joint::angular_offset, -k_pi, k_pi, "rad"),
        q("max_force", &Joint::max_force, z, k_max_joint_force, "N"),
        q("max_torque", &Joint::max_torque, z, k_max_joint_torque, "N·m"),
        q("correction_factor", &Joint::correction_factor, z, Q32::one(), ""),
        v("linear_impulse.x", &Joint::linear_impulse, false, -jmax, jmax, "N·s"),
        v("linear_impulse.y", &Joint::linear_impulse, true, -jmax, jmax, "N·s"),
        q("angular_impulse", &Joint::angular_impulse, -jmax, jmax, "N·m·s"),
        q("axial_impulse", &Joint::axial_impulse, -jmax, jmax, "N·s"),
        q("spring_impulse", &Joint::spring_impulse, -jmax, jmax, "N·s"),
        q("motor_impulse", &Joint::motor_impulse, -jmax, jmax, "N·s"),
        q("lower_impulse", &Joint::lower_impulse, -jmax, jmax, "N·s"),
        q("upper_impulse", &Joint::upper_impulse, -jmax, jmax, "N·s"),
    };
  }();
  return table;
}

/// The first field of `j` outside its range, or null.
inline const JointFieldRange* first_joint_field_out_of_range(const Joint& j) {
  for (const JointFieldRange& f : joint_field_ranges()) {
    const Q32 x = f.get(j);
    if (x < f.lo || x > f.hi) return &f;
  }
  return nullptr;
}

// ---------------------------------------------------------------------------
// Shared between the files (defined where noted)
// ---------------------------------------------------------------------------

inline constexpr size_t k_header_bytes = 12;  // magic, version, kind

struct RecordSizes {
  size_t world = 0;           // tag + def + step count + solver count
  size_t body = 0;
  size_t shape[5] = {};       // by ShapeType; polygon: with 0 vertices
  size_t polygon_vertex = 32; // vertex + normal
  size_t contact = 0;         // with no points
  size_t contact_point = 0;
  size_t joint = 0;
  size_t joint_event = 0;
};

// state_encode.cpp
const RecordSizes& record_sizes();
size_t shape_record_size(const Shape& s, const ShapeGeometry& g);
size_t encoded_size(const World& w);
/// Encodes into buffer[0, capacity); returns the size (> capacity: nothing
/// past the capacity was written).
size_t encode_into(World* w, uint8_t* buffer, size_t capacity);
Status resolve_for_state(WorldId id, const char* function, bool mutating, World** out);
std::vector<uint8_t>& scratch_bytes();

// state_validate.cpp
/// Range and consistency checks of a structurally valid image.
Status validate_image_values(WorldImage* img, const char* function);

// state_restore.cpp
/// Decodes and validates a full image into *img. Returns an error Status
/// (invalid_argument, "<function>: offset N: expected ...").
Status decode_image(const uint8_t* data, size_t size, const char* function, WorldImage* img, uint32_t* out_version);
/// Replaces the world's state with a validated image (vectors swapped).
void commit_image(World* w, WorldImage& img);
WorldImage& scratch_image();

}  // namespace tandem::state_detail

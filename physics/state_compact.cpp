// state_compact.cpp — writing the records of the compact rollback image
// (replay/rollback.h describes what it holds and why that is enough; replay
// writes the header and calls write_compact_records through
// physics/state_access.h). Physics owns these records as it owns the
// portable ones: each field of a record is either packed here (flags, pose,
// optional groups), carried in the structure beside the image (mass data,
// geometry) or recomputed by restore; the records kept whole (world
// settings, full contacts, joints, joint events) run the field lists of
// state_fields.h. tests/replay/test_state_fields.cpp fails when a record
// grows, so a new field is placed here as well as in state_fields.h.
//
// DESIGN. Save writes the image with explicit little-endian stores into a
// buffer sized for an upper bound (no ByteWriter bookkeeping per field; each
// store is one move on x86-64; replay/rollback.cpp keeps that buffer and
// copies the bytes written into the image). Restore runs the same
// decoder twice over the image (state_compact_restore.cpp): the first pass
// checks every structure, index and range
// without touching the world, the second writes the world and
// cannot fail, so a refused image changes nothing and an accepted one needs
// no scratch copy of the world (the portable restore decodes into a whole
// scratch World and swaps it in, which costs most of its time).
//
// Layout of the image, version 1 (replay writes bytes [0, 8), physics the rest):
//   [0, 4)  magic "TNDR"       [4, 8)  u32 version       [8]  broad-phase kind
//   world   WorldDef (broad phase written as naive), u64 step count,
//           i32 last solver body count
//   pools   body, shape, joint: u32 capacity, then per slot u32 generation
//           and u8 alive
//   bodies  per live body: u8 flags (type, enable_sleep, awake, enabled,
//           fixed_rotation, bullet), u8 presence bits, position, rotation,
//           then the present optional fields (velocity, force and torque,
//           sleep time, sleep island, user data, damping, gravity scale)
//   shapes  per live shape: i32 body, u8 type and flags with presence bits,
//           then materials, filter, user data when not the defaults
//   contacts u32 count; per contact i32 shape_a, i32 shape_b, u8 point count
//           (bit 2: a full record follows, state_fields.h visit_contact);
//           compact: per point u16 feature id, normal and tangent impulse
//   pairs   u8 1 when the touching pairs are exactly the touching contacts
//           (always after a step), else 0, u32 count and the pairs; then the
//           sensor overlaps (u32 count, pairs)
//   joints  joint records (visit_joint), then pending joint events
// rollback_hash hashes bytes [9, end): everything but the broad-phase kind.
#include "physics/state_compact.h"

namespace tandem::state_access {

using namespace compact_detail;

namespace {

/// Explicit little-endian stores into a buffer sized beforehand.
struct Out {
  uint8_t* p;
  void u8(uint8_t v) { *p++ = v; }
  void u16(uint16_t v) {
    store_le16(p, v);
    p += 2;
  }
  void u32(uint32_t v) {
    store_le32(p, v);
    p += 4;
  }
  void u64(uint64_t v) {
    store_le64(p, v);
    p += 8;
  }
  void i32(int32_t v) { u32(static_cast<uint32_t>(v)); }
  void q32(Q32 v) { u64(static_cast<uint64_t>(v.raw)); }
  void vec2(Vec2 v) {
    q32(v.x);
    q32(v.y);
  }
};

/// A contact that the next step recomputes from the poses: both bodies
/// simulated, shapes current, cached fields as update_contacts makes them.
bool contact_is_recomputed(const World& w, const Contact& c) {
  const size_t sa = static_cast<size_t>(c.shape_a);
  const size_t sb = static_cast<size_t>(c.shape_b);
  if (w.shape_pool.alive[sa] == 0 || w.shape_pool.alive[sb] == 0) return false;
  if (w.shape_pool.generations[sa] != c.generation_a || w.shape_pool.generations[sb] != c.generation_b) return false;
  if (w.shapes[sa].body_index != c.body_a || w.shapes[sb].body_index != c.body_b) return false;
  if (c.flags != (c.manifold.point_count > 0 ? k_contact_touching : 0u)) return false;
  return body_is_simulated(w.bodies[static_cast<size_t>(c.body_a)]) &&
         body_is_simulated(w.bodies[static_cast<size_t>(c.body_b)]);
}

/// True when the touching pairs are the touching contacts (then not stored).
bool touching_is_derived(const World& w) {
  const std::vector<PairRecord>& t = w.events.touching;
  size_t k = 0;
  for (const Contact& c : w.contacts) {
    if ((c.flags & k_contact_touching) == 0) continue;
    if (k == t.size()) return false;
    const PairRecord& p = t[k++];
    if (p.shape_a != c.shape_a || p.shape_b != c.shape_b || p.generation_a != c.generation_a ||
        p.generation_b != c.generation_b) {
      return false;
    }
  }
  return k == t.size();
}

/// Bytes of the records kept whole, measured once over default records.
struct RecordSizes {
  size_t world = 0;          ///< WorldDef, step count, solver body count
  size_t contact = 0;        ///< a contact without points
  size_t contact_point = 0;  ///< each manifold point more
  size_t joint = 0;
};

const RecordSizes& record_sizes() {
  static const RecordSizes sizes = [] {
    RecordSizes r;
    r.world = record_bytes([](FieldWriter& f) {
      WorldDef d{};
      uint64_t steps = 0;
      int32_t solver_bodies = 0;
      visit_world_def(f, d);
      f.u64(nullptr, steps);
      f.i32(nullptr, solver_bodies);
    });
    Contact c{};
    r.contact = record_bytes([&](FieldWriter& f) { visit_contact(f, c); });
    c.manifold.point_count = 1;
    r.contact_point = record_bytes([&](FieldWriter& f) { visit_contact(f, c); }) - r.contact;
    Joint j{};
    r.joint = record_bytes([&](FieldWriter& f) { visit_joint(f, j); });
    return r;
  }();
  return sizes;
}

size_t image_bound(const World& w) {
  const RecordSizes& rs = record_sizes();
  size_t n = 1 + rs.world;
  n += 3 * 4 + (w.body_pool.generations.size() + w.shape_pool.generations.size() + w.joint_pool.generations.size()) * 5;
  n += static_cast<size_t>(w.body_pool.alive_count) * k_max_body_bytes;
  n += static_cast<size_t>(w.shape_pool.alive_count) * k_max_shape_bytes;
  n += 4 + w.contacts.size() * (9 + rs.contact + 2 * rs.contact_point);
  n += 1 + 4 + w.events.touching.size() * 16 + 4 + w.events.sensor_overlaps.size() * 16;
  n += static_cast<size_t>(w.joint_pool.alive_count) * rs.joint;
  n += 4 + w.joints.pending.size() * 64;
  return n;
}

void write_pool(Out& o, const IdPool& pool) {
  o.u32(static_cast<uint32_t>(pool.generations.size()));
  for (size_t i = 0; i < pool.generations.size(); ++i) {
    o.u32(pool.generations[i]);
    o.u8(pool.alive[i] != 0 ? 1 : 0);
  }
}

/// Runs a FieldWriter at o.p (the bound of the image covers the record).
template <typename F>
void write_visited(Out& o, F&& f) {
  FieldWriter v{o.p};
  f(v);
  o.p = v.p;
}

}  // namespace

size_t compact_records_bound(const WorldState& state) { return image_bound(as_world(state)); }

size_t write_compact_records(WorldState& state, uint8_t* out, CompactStructure structure) {
  World& w = as_world(state);
  std::vector<RollbackBodyMass>& masses = *structure.masses;
  std::vector<ShapeGeometry>& geometries = *structure.geometries;
  Out o{out};
  o.u8(static_cast<uint8_t>(w.def.broad_phase));
  {
    WorldDef def = w.def;
    def.broad_phase = BroadPhaseKind::naive;  // hashed as naive (byte 8 holds the kind)
    uint64_t steps = w.step_count;
    int32_t solver_bodies = w.last_solver_body_count;
    write_visited(o, [&](auto& v) {
      visit_world_def(v, def);
      v.u64("", steps);
      v.i32("", solver_bodies);
    });
  }

  write_pool(o, w.body_pool);
  const size_t body_cap = w.body_pool.generations.size();
  if (masses.size() < body_cap) masses.resize(body_cap);
  for (size_t i = 0; i < body_cap; ++i) {
    if (w.body_pool.alive[i] == 0) continue;
    const Body& b = w.bodies[i];
    const BodySim& s = w.body_sims[i];
    uint8_t flags = static_cast<uint8_t>(static_cast<uint8_t>(b.type) & k_body_type_mask);
    if (b.enable_sleep) flags |= k_body_enable_sleep;
    if (b.awake) flags |= k_body_awake;
    if (b.enabled) flags |= k_body_enabled;
    if (b.fixed_rotation) flags |= k_body_fixed_rotation;
    if (b.bullet) flags |= k_body_bullet;
    uint8_t present = 0;
    const Vec2 zero{};
    if (s.linear_velocity != zero || s.angular_velocity != Q32::zero()) present |= k_has_velocity;
    if (s.force != zero || s.torque != Q32::zero()) present |= k_has_force;
    if (b.sleep_time != Q32::zero()) present |= k_has_sleep_time;
    if (b.sleep_island != k_null_index) present |= k_has_sleep_island;
    if (b.user_data != 0) present |= k_has_user_data;
    if (s.linear_damping != Q32::zero() || s.angular_damping != Q32::zero()) present |= k_has_damping;
    if (s.gravity_scale != Q32::one()) present |= k_has_gravity_scale;
    o.u8(flags);
    o.u8(present);
    o.vec2(s.transform.p);
    o.q32(s.transform.q.c);
    o.q32(s.transform.q.s);
    if (present & k_has_velocity) {
      o.vec2(s.linear_velocity);
      o.q32(s.angular_velocity);
    }
    if (present & k_has_force) {
      o.vec2(s.force);
      o.q32(s.torque);
    }
    if (present & k_has_sleep_time) o.q32(b.sleep_time);
    if (present & k_has_sleep_island) o.i32(b.sleep_island);
    if (present & k_has_user_data) o.u64(b.user_data);
    if (present & k_has_damping) {
      o.q32(s.linear_damping);
      o.q32(s.angular_damping);
    }
    if (present & k_has_gravity_scale) o.q32(s.gravity_scale);
    masses[i] = RollbackBodyMass{b.mass,         b.rotational_inertia, s.inv_mass,    s.inv_inertia,
                                      s.local_center, b.min_extent,         b.max_extent};
  }

  write_pool(o, w.shape_pool);
  const size_t shape_cap = w.shape_pool.generations.size();
  if (geometries.size() < shape_cap) geometries.resize(shape_cap);
  for (size_t i = 0; i < shape_cap; ++i) {
    if (w.shape_pool.alive[i] == 0) continue;
    const Shape& s = w.shapes[i];
    uint8_t bits = static_cast<uint8_t>(static_cast<uint8_t>(s.type) & k_shape_type_mask);
    if (s.is_sensor) bits |= k_shape_sensor;
    if (s.enable_hit_events) bits |= k_shape_hit_events;
    const bool materials = !default_materials(s);
    const bool filter = !default_filter(s.filter);
    if (materials) bits |= k_shape_has_materials;
    if (filter) bits |= k_shape_has_filter;
    if (s.user_data != 0) bits |= k_shape_has_user_data;
    o.i32(s.body_index);
    o.u8(bits);
    if (materials) {
      o.q32(s.friction);
      o.q32(s.restitution);
      o.q32(s.density);
    }
    if (filter) {
      o.u64(s.filter.category_bits);
      o.u64(s.filter.mask_bits);
      o.i32(s.filter.group_index);
    }
    if (s.user_data != 0) o.u64(s.user_data);
    copy_geometry(w.shape_geometries[i], &geometries[i]);
  }

  o.u32(static_cast<uint32_t>(w.contacts.size()));
  for (Contact& c : w.contacts) {
    o.i32(c.shape_a);
    o.i32(c.shape_b);
    const int32_t n = std::clamp(c.manifold.point_count, int32_t{0}, int32_t{2});
    if (contact_is_recomputed(w, c)) {
      o.u8(static_cast<uint8_t>(n));
      for (int32_t k = 0; k < n; ++k) {
        const size_t kk = static_cast<size_t>(k);
        o.u16(c.manifold.points[kk].id);
        o.q32(c.normal_impulse[kk]);
        o.q32(c.tangent_impulse[kk]);
      }
    } else {
      o.u8(static_cast<uint8_t>(n | k_contact_full));
      write_visited(o, [&](auto& v) { visit_contact(v, c); });
    }
  }

  const bool derived = touching_is_derived(w);
  o.u8(derived ? 1 : 0);
  const auto write_pairs = [&](const std::vector<PairRecord>& pairs) {
    o.u32(static_cast<uint32_t>(pairs.size()));
    for (const PairRecord& p : pairs) {
      o.i32(p.shape_a);
      o.i32(p.shape_b);
      o.u32(p.generation_a);
      o.u32(p.generation_b);
    }
  };
  if (!derived) write_pairs(w.events.touching);
  write_pairs(w.events.sensor_overlaps);

  write_pool(o, w.joint_pool);
  for (size_t i = 0; i < w.joint_pool.generations.size(); ++i) {
    if (w.joint_pool.alive[i] == 0) continue;
    write_visited(o, [&](auto& v) { visit_joint(v, w.joints.joints[i]); });
  }
  o.u32(static_cast<uint32_t>(w.joints.pending.size()));
  for (JointEvent& e : w.joints.pending) {
    write_visited(o, [&](auto& v) { visit_joint_event(v, e); });
  }
  const size_t size = static_cast<size_t>(o.p - out);
  TANDEM_ASSERT(size <= image_bound(w));
  return size;
}

}  // namespace tandem::state_access

// rollback.cpp — the compact rollback snapshot (rollback.h describes what it
// holds and why that is enough).
//
// DESIGN. Save writes the image with explicit little-endian stores into a
// buffer sized once for an upper bound (no ByteWriter bookkeeping per field;
// each store is one move on x86-64), then trims it. Restore runs the same
// decoder twice over the image: the first pass (Apply = false) reads through
// a bounds-checked ByteReader and checks every structure, index and range
// without touching the world, the second (Apply = true) writes the world and
// cannot fail, so a refused image changes nothing and an accepted one needs
// no scratch copy of the world (the portable restore decodes into a whole
// scratch World and swaps it in, which costs most of its time).
//
// Layout of the image, version 1:
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
//           (bit 2: a full record follows, state_internal.h visit_contact);
//           compact: per point u16 feature id, normal and tangent impulse
//   pairs   u8 1 when the touching pairs are exactly the touching contacts
//           (always after a step), else 0, u32 count and the pairs; then the
//           sensor overlaps (u32 count, pairs)
//   joints  joint records (visit_joint), then pending joint events
// rollback_hash hashes bytes [9, end): everything but the broad-phase kind.
#include "replay/rollback.h"

#define XXH_INLINE_ALL
#include <xxhash.h>

#include "replay/state_internal.h"

namespace tandem {

using namespace state_detail;

namespace {

constexpr size_t k_kind_offset = 8;
constexpr size_t k_hashed_from = 9;

// Body flag bits.
constexpr uint8_t k_body_type_mask = 3;
constexpr uint8_t k_body_enable_sleep = 1u << 2;
constexpr uint8_t k_body_awake = 1u << 3;
constexpr uint8_t k_body_enabled = 1u << 4;
constexpr uint8_t k_body_fixed_rotation = 1u << 5;
constexpr uint8_t k_body_bullet = 1u << 6;
// Body presence bits.
constexpr uint8_t k_has_velocity = 1u << 0;
constexpr uint8_t k_has_force = 1u << 1;
constexpr uint8_t k_has_sleep_time = 1u << 2;
constexpr uint8_t k_has_sleep_island = 1u << 3;
constexpr uint8_t k_has_user_data = 1u << 4;
constexpr uint8_t k_has_damping = 1u << 5;
constexpr uint8_t k_has_gravity_scale = 1u << 6;
// Shape bits (type in the low 3).
constexpr uint8_t k_shape_type_mask = 7;
constexpr uint8_t k_shape_sensor = 1u << 3;
constexpr uint8_t k_shape_hit_events = 1u << 4;
constexpr uint8_t k_shape_has_materials = 1u << 5;
constexpr uint8_t k_shape_has_filter = 1u << 6;
constexpr uint8_t k_shape_has_user_data = 1u << 7;
// Contact header bits.
constexpr uint8_t k_contact_count_mask = 3;
constexpr uint8_t k_contact_full = 1u << 2;

constexpr size_t k_max_body_bytes = 2 + 32 + 24 + 24 + 8 + 4 + 8 + 16 + 8;
constexpr size_t k_max_shape_bytes = 4 + 1 + 24 + 20 + 8;
constexpr size_t k_compact_point_bytes = 2 + 8 + 8;

/// Explicit little-endian stores into a buffer sized beforehand.
struct Out {
  uint8_t* p;
  void u8(uint8_t v) { *p++ = v; }
  void u16(uint16_t v) {
    p[0] = static_cast<uint8_t>(v);
    p[1] = static_cast<uint8_t>(v >> 8);
    p += 2;
  }
  void u32(uint32_t v) {
    for (int i = 0; i < 4; ++i) p[i] = static_cast<uint8_t>(v >> (8 * i));
    p += 4;
  }
  void u64(uint64_t v) {
    for (int i = 0; i < 8; ++i) p[i] = static_cast<uint8_t>(v >> (8 * i));
    p += 8;
  }
  void i32(int32_t v) { u32(static_cast<uint32_t>(v)); }
  void q32(Q32 v) { u64(static_cast<uint64_t>(v.raw)); }
  void vec2(Vec2 v) {
    q32(v.x);
    q32(v.y);
  }
};

const ShapeDef& default_shape() {
  static const ShapeDef def = default_shape_def();
  return def;
}

bool default_materials(const Shape& s) {
  const ShapeDef& d = default_shape();
  return s.friction == d.friction && s.restitution == d.restitution && s.density == d.density;
}

bool default_filter(const Filter& f) {
  const Filter d{};
  return f.category_bits == d.category_bits && f.mask_bits == d.mask_bits && f.group_index == d.group_index;
}

/// Copies the active variant only (the others are not state).
void copy_geometry(const ShapeGeometry& from, ShapeGeometry* to) {
  to->type = from.type;
  switch (from.type) {
    case ShapeType::circle: to->circle = from.circle; break;
    case ShapeType::capsule: to->capsule = from.capsule; break;
    case ShapeType::segment: to->segment = from.segment; break;
    case ShapeType::polygon: {
      const Polygon& a = from.polygon;
      Polygon& b = to->polygon;
      const size_t n = static_cast<size_t>(std::clamp(a.count, int32_t{0}, k_max_polygon_vertices));
      std::copy(a.vertices.begin(), a.vertices.begin() + static_cast<std::ptrdiff_t>(n), b.vertices.begin());
      std::copy(a.normals.begin(), a.normals.begin() + static_cast<std::ptrdiff_t>(n), b.normals.begin());
      b.centroid = a.centroid;
      b.radius = a.radius;
      b.count = a.count;
      break;
    }
    case ShapeType::chain_segment: to->chain_segment = from.chain_segment; break;
    case ShapeType::count: break;
  }
}

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

size_t image_bound(const World& w) {
  const RecordSizes& rs = record_sizes();
  size_t n = k_hashed_from + rs.world;
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

/// Runs a WriteVisitor at o.p (the record is at most `bound` bytes).
template <typename F>
void write_visited(Out& o, size_t bound, F&& f) {
  ByteWriter bw(o.p, bound);
  WriteVisitor v{&bw};
  f(v);
  o.p += bw.size();
}

void write_image(World& w, RollbackBuffer* buf) {
  const RecordSizes& rs = record_sizes();
  buf->image.resize(image_bound(w));
  Out o{buf->image.data()};
  o.u8(k_rollback_magic[0]);
  o.u8(k_rollback_magic[1]);
  o.u8(k_rollback_magic[2]);
  o.u8(k_rollback_magic[3]);
  o.u32(k_rollback_format_version);
  o.u8(static_cast<uint8_t>(w.def.broad_phase));
  {
    WorldDef def = w.def;
    def.broad_phase = BroadPhaseKind::naive;  // hashed as naive (byte 8 holds the kind)
    uint64_t steps = w.step_count;
    int32_t solver_bodies = w.last_solver_body_count;
    write_visited(o, rs.world, [&](WriteVisitor& v) {
      visit_world_def(v, def);
      v.u64("", steps);
      v.i32("", solver_bodies);
    });
  }

  write_pool(o, w.body_pool);
  const size_t body_cap = w.body_pool.generations.size();
  if (buf->masses.size() < body_cap) buf->masses.resize(body_cap);
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
    buf->masses[i] = RollbackBodyMass{b.mass,         b.rotational_inertia, s.inv_mass,    s.inv_inertia,
                                      s.local_center, b.min_extent,         b.max_extent};
  }

  write_pool(o, w.shape_pool);
  const size_t shape_cap = w.shape_pool.generations.size();
  if (buf->geometries.size() < shape_cap) buf->geometries.resize(shape_cap);
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
    copy_geometry(w.shape_geometries[i], &buf->geometries[i]);
  }

  o.u32(static_cast<uint32_t>(w.contacts.size()));
  const size_t full_bound = rs.contact + 2 * rs.contact_point;
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
      write_visited(o, full_bound, [&](WriteVisitor& v) { visit_contact(v, c); });
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
    write_visited(o, rs.joint, [&](WriteVisitor& v) { visit_joint(v, w.joints.joints[i]); });
  }
  o.u32(static_cast<uint32_t>(w.joints.pending.size()));
  for (JointEvent& e : w.joints.pending) {
    write_visited(o, 64, [&](WriteVisitor& v) { visit_joint_event(v, e); });
  }
  const size_t size = static_cast<size_t>(o.p - buf->image.data());
  TANDEM_ASSERT(size <= buf->image.size());
  buf->image.resize(size);
}

// ---------------------------------------------------------------------------
// Restore: one decoder, run to check (Apply = false) and then to write
// ---------------------------------------------------------------------------

/// Largest |coordinate|, speed, impulse restored (as state_validate.cpp).
constexpr Q32 k_max_coordinate = k_max_world_coordinate * 2;
constexpr Q32 k_max_speed = k_max_linear_speed * 4;
constexpr Q32 k_max_spin = k_max_angular_speed * 64;
constexpr Q32 k_max_impulse = Q32::from_raw(int64_t{400000000} << 32);
constexpr int64_t k_unit_tolerance = int64_t{1} << 16;

/// Pass-1 knowledge the checks need (per-thread, reused).
struct Scratch {
  std::vector<uint8_t> body_alive;
  std::vector<uint8_t> shape_alive;
  std::vector<uint32_t> shape_generation;
  std::vector<int32_t> shape_body;
  std::vector<uint8_t> body_simulated;
  std::vector<uint8_t> joint_alive;
  std::vector<int32_t> tail;  // pass 2: each body's last listed shape
};

Scratch& scratch() {
  thread_local Scratch s;
  return s;
}

template <bool Apply>
class Decoder {
 public:
  Decoder(const RollbackBuffer& buf, World* w, const char* fn)
      : buf_(buf), r_(buf.image.data(), buf.image.size()), w_(w), fn_(fn), sc_(scratch()) {}

  Status run() {
    if (!Apply) {
      const std::span<const uint8_t> magic = r_.bytes(4, "magic \"TNDR\"");
      if (!r_.ok()) return bad(r_.error());
      if (std::memcmp(magic.data(), k_rollback_magic, 4) != 0) {
        return bad("offset 0: expected magic \"TNDR\" (a compact rollback image)");
      }
      const uint32_t version = r_.u32("format version");
      if (r_.ok() && version != k_rollback_format_version) {
        return bad("offset 4: expected rollback format version " + std::to_string(k_rollback_format_version) +
                   ", got " + std::to_string(version));
      }
    } else {
      r_.bytes(8, "");
    }
    r_.set_context("world");
    BroadPhaseKind kind = BroadPhaseKind::naive;
    {
      ReadVisitor v{&r_};
      v.enum8("broad_phase", kind, static_cast<int32_t>(BroadPhaseKind::tree));
    }
    if (!r_.ok()) return bad(r_.error());
    world(kind);
    if (r_.ok()) pool(Apply ? &w_->body_pool : nullptr, "body_slot", k_max_bodies, &sc_.body_alive, nullptr);
    if (r_.ok()) bodies();
    if (r_.ok()) pool(Apply ? &w_->shape_pool : nullptr, "shape_slot", k_max_shapes, &sc_.shape_alive,
                      &sc_.shape_generation);
    if (r_.ok()) shapes();
    if (r_.ok()) contacts();
    if (r_.ok()) pairs();
    if (r_.ok()) joints();
    if (!r_.ok()) return bad(r_.error());
    if (!r_.at_end()) {
      return bad("offset " + std::to_string(r_.offset()) + ": expected the end of the image, " +
                 std::to_string(r_.remaining()) + " bytes left over");
    }
    if (Apply) finish();
    return Status{};
  }

 private:
  Status bad(const std::string& msg) const {
    return make_status(StatusCode::invalid_argument, std::string(fn_) + ": " + msg);
  }
  /// Refuses at `at` (record context from the reader).
  void refuse(size_t at, const std::string& what) { r_.fail_at(at, r_.describe_what(what.c_str())); }
  void check_range(size_t at, const char* field, Q32 v, Q32 lim, const char* unit) {
    if (Apply || (-lim <= v && v <= lim)) return;
    refuse(at, std::string(field) + " " + to_string(v) + " " + unit + " is outside [" + to_string(-lim) + ", " +
                   to_string(lim) + "] " + unit);
  }
  Q32 q32(const char* field, Q32 lim, const char* unit) {
    const size_t at = r_.offset();
    const Q32 v = r_.q32(field);
    check_range(at, field, v, lim, unit);
    return v;
  }

  void world(BroadPhaseKind kind) {
    WorldDef def{};
    uint64_t steps = 0;
    int32_t solver_bodies = 0;
    ReadVisitor v{&r_};
    r_.set_context("world");
    visit_world_def(v, def);
    v.u64("step_count", steps);
    v.i32("last_solver_body_count", solver_bodies);
    if (!r_.ok() || !Apply) return;
    const int32_t cookie = w_->def.internal_cookie;
    w_->def = def;
    w_->def.internal_cookie = cookie;
    w_->def.broad_phase = kind;
    w_->step_count = steps;
    w_->last_solver_body_count = solver_bodies;
  }

  void pool(IdPool* pool, const char* kind, int32_t max_capacity, std::vector<uint8_t>* alive,
            std::vector<uint32_t>* generations) {
    r_.set_context(kind);
    const uint32_t cap = r_.read_count("capacity", 5, static_cast<uint32_t>(max_capacity));
    if (!r_.ok()) return;
    if (!Apply) {
      alive->assign(cap, 0);
      if (generations != nullptr) generations->assign(cap, 0);
    } else {
      pool->generations.resize(cap);
      pool->alive.resize(cap);
      pool->free_heap.clear();
      pool->alive_count = 0;
    }
    for (uint32_t i = 0; i < cap; ++i) {
      const size_t at = r_.offset();
      const uint32_t g = r_.u32("generation");
      const bool live = r_.boolean("alive");
      if (!r_.ok()) return;
      if (!Apply) {
        if (g == 0) {
          r_.set_context(kind, i);
          refuse(at, "generation: expected ≥ 1, got 0");
          return;
        }
        (*alive)[i] = live ? 1 : 0;
        if (generations != nullptr) (*generations)[i] = g;
      } else {
        pool->generations[i] = g;
        pool->alive[i] = live ? 1 : 0;
        if (live) {
          ++pool->alive_count;
        } else {
          pool->free_heap.push_back(static_cast<int32_t>(i));  // ascending: a valid min-heap
        }
      }
    }
  }

  void bodies() {
    const size_t cap = sc_.body_alive.size();
    if (!Apply) {
      if (buf_.masses.size() < cap) {
        r_.fail_at(r_.offset(), "the buffer's body masses hold " + std::to_string(buf_.masses.size()) +
                                    " entries, the image needs " + std::to_string(cap));
        return;
      }
      sc_.body_simulated.assign(cap, 0);
    } else {
      w_->bodies.resize(cap);
      w_->body_sims.resize(cap);
    }
    for (size_t i = 0; i < cap; ++i) {
      if (sc_.body_alive[i] == 0) {
        if (Apply) {
          w_->bodies[i] = Body{};
          w_->body_sims[i] = BodySim{};
        }
        continue;
      }
      r_.set_context("body", static_cast<int64_t>(i));
      const size_t at = r_.offset();
      const uint8_t flags = r_.u8("flags");
      const uint8_t present = r_.u8("presence bits");
      if (!r_.ok()) return;
      const uint8_t type = flags & k_body_type_mask;
      if (!Apply && (type > static_cast<uint8_t>(BodyType::dynamic_body) || (flags & 0x80) != 0 ||
                     (present & 0x80) != 0)) {
        refuse(at, "flags " + std::to_string(flags) + " / presence " + std::to_string(present) +
                       ": expected a body type 0..2 and defined bits only");
        return;
      }
      Transform xf;
      xf.p.x = q32("position.x", k_max_coordinate, "m");
      xf.p.y = q32("position.y", k_max_coordinate, "m");
      const size_t rot_at = r_.offset();
      xf.q.c = q32("rotation.c", Q32::from_raw(Q32::one().raw + k_unit_tolerance), "");
      xf.q.s = q32("rotation.s", Q32::from_raw(Q32::one().raw + k_unit_tolerance), "");
      if (!Apply && r_.ok()) {
        const Q32 n = xf.q.c * xf.q.c + xf.q.s * xf.q.s;
        if ((n - Q32::one()).raw > k_unit_tolerance || (Q32::one() - n).raw > k_unit_tolerance) {
          refuse(rot_at, "rotation (" + to_string(xf.q.c) + ", " + to_string(xf.q.s) +
                             ") is not a unit vector (squared length " + to_string(n) + ")");
        }
      }
      const bool moving = type != static_cast<uint8_t>(BodyType::static_body);
      Vec2 v{};
      Q32 omega;
      if (present & k_has_velocity) {
        const Q32 vmax = moving ? k_max_speed : Q32::zero();
        v.x = q32("linear_velocity.x", vmax, "m/s");
        v.y = q32("linear_velocity.y", vmax, "m/s");
        omega = q32("angular_velocity", moving ? k_max_spin : Q32::zero(), "rad/s");
      }
      Vec2 force{};
      Q32 torque;
      if (present & k_has_force) {
        force.x = q32("force.x", k_max_force, "N");
        force.y = q32("force.y", k_max_force, "N");
        torque = q32("torque", k_max_torque, "N·m");
      }
      Q32 sleep_time;
      if (present & k_has_sleep_time) {
        const size_t st_at = r_.offset();
        sleep_time = r_.q32("sleep_time");
        if (!Apply && r_.ok() && (sleep_time < Q32::zero() || sleep_time > k_time_to_sleep)) {
          refuse(st_at, "sleep_time " + to_string(sleep_time) + " s is outside [0, " + to_string(k_time_to_sleep) +
                            "] s");
        }
      }
      int32_t island = k_null_index;
      if (present & k_has_sleep_island) {
        const size_t is_at = r_.offset();
        island = r_.i32("sleep_island");
        if (!Apply && r_.ok() &&
            (island < 0 || static_cast<size_t>(island) >= cap || sc_.body_alive[static_cast<size_t>(island)] == 0)) {
          refuse(is_at, "sleep_island " + std::to_string(island) + " is not a live body");
        }
      }
      const uint64_t user = (present & k_has_user_data) ? r_.u64("user_data") : 0;
      Q32 lin_damp, ang_damp;
      if (present & k_has_damping) {
        const size_t d_at = r_.offset();
        lin_damp = r_.q32("linear_damping");
        ang_damp = r_.q32("angular_damping");
        if (!Apply && r_.ok() &&
            (lin_damp < Q32::zero() || lin_damp > k_max_damping || ang_damp < Q32::zero() || ang_damp > k_max_damping)) {
          refuse(d_at, "damping (" + to_string(lin_damp) + ", " + to_string(ang_damp) + ") 1/s is outside [0, " +
                           to_string(k_max_damping) + "] 1/s");
        }
      }
      const Q32 gravity_scale =
          (present & k_has_gravity_scale) ? q32("gravity_scale", k_max_gravity_scale, "") : Q32::one();
      if (!r_.ok()) return;
      const bool awake = (flags & k_body_awake) != 0;
      const bool enabled = (flags & k_body_enabled) != 0;
      if (!Apply) {
        sc_.body_simulated[i] = moving && awake && enabled ? 1 : 0;
        continue;
      }
      const RollbackBodyMass& m = buf_.masses[i];
      Body& b = w_->bodies[i];
      b.type = static_cast<BodyType>(type);
      b.head_shape = k_null_index;
      b.shape_count = 0;
      b.mass = m.mass;
      b.rotational_inertia = m.rotational_inertia;
      b.sleep_time = sleep_time;
      b.sleep_island = island;
      b.user_data = user;
      b.enable_sleep = (flags & k_body_enable_sleep) != 0;
      b.awake = awake;
      b.enabled = enabled;
      b.fixed_rotation = (flags & k_body_fixed_rotation) != 0;
      b.bullet = (flags & k_body_bullet) != 0;
      b.min_extent = m.min_extent;
      b.max_extent = m.max_extent;
      BodySim& s = w_->body_sims[i];
      s.transform = xf;
      s.local_center = m.local_center;
      s.center = transform_point(xf, m.local_center);
      s.linear_velocity = v;
      s.angular_velocity = omega;
      s.force = force;
      s.torque = torque;
      s.inv_mass = m.inv_mass;
      s.inv_inertia = m.inv_inertia;
      s.linear_damping = lin_damp;
      s.angular_damping = ang_damp;
      s.gravity_scale = gravity_scale;
    }
  }

  void shapes() {
    const size_t cap = sc_.shape_alive.size();
    const size_t body_cap = sc_.body_alive.size();
    if (!Apply) {
      if (buf_.geometries.size() < cap) {
        r_.fail_at(r_.offset(), "the buffer's geometries hold " + std::to_string(buf_.geometries.size()) +
                                    " entries, the image needs " + std::to_string(cap));
        return;
      }
      sc_.shape_body.assign(cap, k_null_index);
    } else {
      w_->shapes.resize(cap);
      w_->shape_geometries.resize(cap);
      sc_.tail.assign(body_cap, k_null_index);
    }
    const ShapeDef& d = default_shape();
    for (size_t i = 0; i < cap; ++i) {
      if (sc_.shape_alive[i] == 0) {
        if (Apply) {
          w_->shapes[i] = Shape{};
          w_->shape_geometries[i] = ShapeGeometry{};
        }
        continue;
      }
      r_.set_context("shape", static_cast<int64_t>(i));
      const size_t at = r_.offset();
      const int32_t body = r_.i32("body");
      const uint8_t bits = r_.u8("type and flags");
      if (!r_.ok()) return;
      const uint8_t type = bits & k_shape_type_mask;
      if (!Apply) {
        if (body < 0 || static_cast<size_t>(body) >= body_cap || sc_.body_alive[static_cast<size_t>(body)] == 0) {
          refuse(at, "body " + std::to_string(body) + " is not a live body");
          return;
        }
        const ShapeGeometry& g = buf_.geometries[i];
        if (type > static_cast<uint8_t>(ShapeType::chain_segment) || static_cast<uint8_t>(g.type) != type ||
            (g.type == ShapeType::polygon && (g.polygon.count < 3 || g.polygon.count > k_max_polygon_vertices))) {
          refuse(at + 4, "type " + std::to_string(type) + " does not match the buffer's geometry (type " +
                             std::to_string(static_cast<int32_t>(g.type)) + ")");
          return;
        }
        sc_.shape_body[i] = body;
      }
      Q32 friction = d.friction, restitution = d.restitution, density = d.density;
      if (bits & k_shape_has_materials) {
        const size_t m_at = r_.offset();
        friction = r_.q32("friction");
        restitution = r_.q32("restitution");
        density = r_.q32("density");
        if (!Apply && r_.ok() &&
            (friction < Q32::zero() || friction > k_max_friction || restitution < Q32::zero() ||
             restitution > Q32::one() || density < Q32::zero() || density > k_max_density)) {
          refuse(m_at, "materials (friction " + to_string(friction) + ", restitution " + to_string(restitution) +
                           ", density " + to_string(density) + ") are outside [0, " + to_string(k_max_friction) +
                           "], [0, 1], [0, " + to_string(k_max_density) + "]");
        }
      }
      Filter filter{};
      if (bits & k_shape_has_filter) {
        filter.category_bits = r_.u64("filter.category_bits");
        filter.mask_bits = r_.u64("filter.mask_bits");
        filter.group_index = r_.i32("filter.group_index");
      }
      const uint64_t user = (bits & k_shape_has_user_data) ? r_.u64("user_data") : 0;
      if (!r_.ok() || !Apply) continue;
      Shape& s = w_->shapes[i];
      s.body_index = body;
      s.type = static_cast<ShapeType>(type);
      s.friction = friction;
      s.restitution = restitution;
      s.density = density;
      s.filter = filter;
      s.user_data = user;
      s.is_sensor = (bits & k_shape_sensor) != 0;
      s.enable_hit_events = (bits & k_shape_hit_events) != 0;
      copy_geometry(buf_.geometries[i], &w_->shape_geometries[i]);
      // Shape lists are in ascending shape index.
      Body& b = w_->bodies[static_cast<size_t>(body)];
      int32_t& tail = sc_.tail[static_cast<size_t>(body)];
      s.prev_shape = tail;
      s.next_shape = k_null_index;
      if (tail == k_null_index) {
        b.head_shape = static_cast<int32_t>(i);
      } else {
        w_->shapes[static_cast<size_t>(tail)].next_shape = static_cast<int32_t>(i);
      }
      tail = static_cast<int32_t>(i);
      ++b.shape_count;
      s.aabb = compute_shape_aabb(w_->shape_geometries[i], w_->body_sims[static_cast<size_t>(body)].transform);
    }
  }

  void contacts() {
    r_.set_context("contacts");
    const uint32_t n = r_.read_count("count", 9);
    if (!r_.ok()) return;
    const int32_t shape_cap = static_cast<int32_t>(sc_.shape_alive.size());
    const int32_t body_cap = static_cast<int32_t>(sc_.body_alive.size());
    if (Apply) w_->contacts.resize(n);
    uint64_t prev_key = 0;
    for (uint32_t i = 0; i < n; ++i) {
      r_.set_context("contact", i);
      const size_t at = r_.offset();
      const int32_t a = r_.i32("shape_a");
      const int32_t b = r_.i32("shape_b");
      const uint8_t head = r_.u8("point count and kind");
      if (!r_.ok()) return;
      const int32_t count = head & k_contact_count_mask;
      if (!Apply) {
        if (a < 0 || b >= shape_cap || a >= b || (head & ~(k_contact_count_mask | k_contact_full)) != 0 ||
            count > 2) {
          refuse(at, "shapes (" + std::to_string(a) + ", " + std::to_string(b) + ") / header " +
                         std::to_string(head) + ": expected two shapes of the pool in ascending order and 0..2 points");
          return;
        }
        const uint64_t key = shape_pair_key(a, b);
        if (i > 0 && key <= prev_key) {
          refuse(at, "is not sorted by shape pair");
          return;
        }
        prev_key = key;
      }
      if ((head & k_contact_full) != 0) {
        Contact c{};
        ReadVisitor v{&r_};
        const size_t rec_at = r_.offset();
        visit_contact(v, c);
        if (!r_.ok()) return;
        if (!Apply && (c.shape_a != a || c.shape_b != b || c.manifold.point_count != count || c.body_a < 0 ||
                       c.body_a >= body_cap || c.body_b < 0 || c.body_b >= body_cap)) {
          refuse(rec_at, "full record disagrees with its header or names bodies outside the pool");
          return;
        }
        if (!Apply) {
          for (int32_t k = 0; k < count; ++k) {
            const size_t kk = static_cast<size_t>(k);
            if (abs(c.normal_impulse[kk]) > k_max_impulse || abs(c.tangent_impulse[kk]) > k_max_impulse) {
              refuse(rec_at, "stored impulse of point " + std::to_string(k) + " is outside ±" +
                                 to_string(k_max_impulse) + " N·s");
              return;
            }
          }
        }
        if (Apply) w_->contacts[i] = c;
        continue;
      }
      if (!Apply && (sc_.shape_alive[static_cast<size_t>(a)] == 0 || sc_.shape_alive[static_cast<size_t>(b)] == 0 ||
                     sc_.body_simulated[static_cast<size_t>(sc_.shape_body[static_cast<size_t>(a)])] == 0 ||
                     sc_.body_simulated[static_cast<size_t>(sc_.shape_body[static_cast<size_t>(b)])] == 0)) {
        refuse(at, "is compact, but its shapes are not both alive on simulated bodies");
        return;
      }
      Contact* c = nullptr;
      if (Apply) {
        c = &w_->contacts[i];
        *c = Contact{};
        c->shape_a = a;
        c->shape_b = b;
        c->generation_a = w_->shape_pool.generations[static_cast<size_t>(a)];
        c->generation_b = w_->shape_pool.generations[static_cast<size_t>(b)];
        c->body_a = w_->shapes[static_cast<size_t>(a)].body_index;
        c->body_b = w_->shapes[static_cast<size_t>(b)].body_index;
        c->flags = count > 0 ? k_contact_touching : 0u;
        c->manifold.point_count = count;
      }
      for (int32_t k = 0; k < count; ++k) {
        const size_t kk = static_cast<size_t>(k);
        const uint16_t id = r_.u16("points[].id");
        const Q32 jn = q32(k == 0 ? "points[0].normal_impulse" : "points[1].normal_impulse", k_max_impulse, "N·s");
        const Q32 jt = q32(k == 0 ? "points[0].tangent_impulse" : "points[1].tangent_impulse", k_max_impulse, "N·s");
        if (Apply) {
          c->manifold.points[kk].id = id;
          c->normal_impulse[kk] = jn;
          c->tangent_impulse[kk] = jt;
        }
      }
      if (!r_.ok()) return;
    }
  }

  void read_pairs(std::vector<PairRecord>* out, const char* kind) {
    r_.set_context(kind);
    const uint32_t n = r_.read_count("count", 16);
    if (!r_.ok()) return;
    if (Apply) out->resize(n);
    const int32_t shape_cap = static_cast<int32_t>(sc_.shape_alive.size());
    PairRecord prev{};
    for (uint32_t i = 0; i < n; ++i) {
      const size_t at = r_.offset();
      PairRecord p;
      p.shape_a = r_.i32("shape_a");
      p.shape_b = r_.i32("shape_b");
      p.generation_a = r_.u32("generation_a");
      p.generation_b = r_.u32("generation_b");
      if (!r_.ok()) return;
      if (!Apply && (p.shape_a < 0 || p.shape_a >= shape_cap || p.shape_b < 0 || p.shape_b >= shape_cap ||
                     (i > 0 && shape_pair_key(p.shape_a, p.shape_b) <= shape_pair_key(prev.shape_a, prev.shape_b)))) {
        r_.set_context(kind, i);
        refuse(at, "names a shape outside the pool or is not sorted");
        return;
      }
      prev = p;
      if (Apply) (*out)[i] = p;
    }
  }

  void pairs() {
    r_.set_context("touching");
    const bool derived = r_.boolean("derived");
    if (!r_.ok()) return;
    if (derived) {
      if (Apply) {
        std::vector<PairRecord>& t = w_->events.touching;
        t.clear();
        for (const Contact& c : w_->contacts) {
          if ((c.flags & k_contact_touching) != 0) {
            t.push_back(PairRecord{c.shape_a, c.shape_b, c.generation_a, c.generation_b});
          }
        }
      }
    } else {
      read_pairs(Apply ? &w_->events.touching : nullptr, "touching");
    }
    if (r_.ok()) read_pairs(Apply ? &w_->events.sensor_overlaps : nullptr, "sensor_overlap");
  }

  void joints() {
    std::vector<uint8_t>& alive = sc_.joint_alive;
    IdPool* jp = Apply ? &w_->joint_pool : nullptr;
    pool(jp, "joint_slot", k_max_bodies, &alive, nullptr);
    if (!r_.ok()) return;
    const size_t cap = alive.size();
    const int32_t body_cap = static_cast<int32_t>(sc_.body_alive.size());
    if (Apply) w_->joints.joints.resize(cap);
    for (size_t i = 0; i < cap; ++i) {
      if (alive[i] == 0) {
        if (Apply) w_->joints.joints[i] = Joint{};
        continue;
      }
      r_.set_context("joint", static_cast<int64_t>(i));
      const size_t at = r_.offset();
      Joint j{};
      ReadVisitor v{&r_};
      visit_joint(v, j);
      if (!r_.ok()) return;
      if (!Apply) {
        const auto live = [&](int32_t b) {
          return b >= 0 && b < body_cap && sc_.body_alive[static_cast<size_t>(b)] != 0;
        };
        if (!live(j.body_a) || !live(j.body_b) || j.body_a == j.body_b) {
          refuse(at, "joins bodies (" + std::to_string(j.body_a) + ", " + std::to_string(j.body_b) +
                         "), which are not two live bodies");
          return;
        }
      } else {
        w_->joints.joints[i] = j;
      }
    }
    r_.set_context("pending joint events");
    const uint32_t n = r_.read_count("count", 53);
    if (!r_.ok()) return;
    if (Apply) w_->joints.pending.resize(n);
    for (uint32_t i = 0; i < n; ++i) {
      r_.set_context("pending joint event", i);
      JointEvent e{};
      ReadVisitor v{&r_};
      visit_joint_event(v, e);
      if (!r_.ok()) return;
      if (Apply) {
        e.joint.world = w_->id;
        e.body_a.world = w_->id;
        e.body_b.world = w_->id;
        w_->joints.pending[i] = e;
      }
    }
  }

  /// What every restore does after replacing the records (as commit_image).
  void finish() {
    World* w = w_;
    w->contact_scratch.clear();
    w->joints.events.clear();
    rebuild_joint_filter(w);
    EventState& e = w->events;
    e.touching_next.clear();
    e.sensor_next.clear();
    e.hit_candidates.clear();
    events_clear_reported(&e);
    broad_phase_reset(w);
    reserve_contact_headroom(w);
    events_reserve_headroom(w);
  }

  const RollbackBuffer& buf_;
  ByteReader r_;
  World* w_;
  const char* fn_;
  Scratch& sc_;
};

}  // namespace

Status rollback_save(WorldId world, RollbackBuffer* buffer) {
  World* w = nullptr;
  Status s = resolve_world(world, "rollback_save", true, &w);
  if (!s.ok()) return s;
  if (buffer == nullptr) return make_status(StatusCode::invalid_argument, "rollback_save: buffer is null");
  write_image(*w, buffer);
  return s;
}

Status rollback_restore(WorldId world, const RollbackBuffer& buffer) {
  World* w = nullptr;
  Status s = resolve_world(world, "rollback_restore", true, &w);
  if (!s.ok()) return s;
  s = Decoder<false>(buffer, nullptr, "rollback_restore").run();
  if (!s.ok()) return s;
  s = Decoder<true>(buffer, w, "rollback_restore").run();
  TANDEM_ASSERT(s.ok());
  return s;
}

uint64_t rollback_hash(const RollbackBuffer& buffer) {
  if (buffer.image.size() < k_hashed_from) return 0;
  return XXH3_64bits(buffer.image.data() + k_hashed_from, buffer.image.size() - k_hashed_from);
}

}  // namespace tandem

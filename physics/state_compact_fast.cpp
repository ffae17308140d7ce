// state_compact_fast.cpp — restore's fast paths over the compact rollback
// image's bulk records (bodies, shapes, contacts): a check that only answers
// "all good", and the applying loops that write the world from checked
// records (state_compact.h declares them; state_compact_restore.cpp runs
// them and owns the layout's checks and messages).
//
// DESIGN. The detailed checker (state_compact_restore.cpp) names the first
// bad byte, which costs a branch and a bookkeeping store per field. Here each
// record's fields are tested branch-free (a range test is one unsigned
// compare), the verdicts are or-ed together, and the cursor is a local, so
// the per-field work is a load and a compare. A check accepts only what the
// detailed checker accepts (the same tests, in any order); when it refuses,
// the detailed checker runs over the same section from the same offset and
// builds the message, so every refusal reads as before. The applying loops
// are the ones that used to run in the decoder's second pass, with a local
// cursor (no store of the offset per field). Restore still recomputes every
// derived value (shape bounds, centres of mass) and trusts nothing cached.
#include "fixed/str_cat.h"
#include "physics/fast_math.h"
#include "physics/state_compact.h"

namespace tandem::compact_detail {

namespace {

inline int64_t ld_raw(const uint8_t* p) { return static_cast<int64_t>(load_le64(p)); }
inline Q32 ld_q32(const uint8_t* p) { return Q32::from_raw(ld_raw(p)); }
inline int32_t ld_i32(const uint8_t* p) { return static_cast<int32_t>(load_le32(p)); }

/// !(−lim ≤ raw ≤ lim) for 0 ≤ lim < 2^62: one unsigned compare (raw + lim
/// modulo 2^64 lands in [0, 2·lim] exactly when raw is in range).
inline bool outside(int64_t raw, Q32 lim) {
  return static_cast<uint64_t>(raw) + static_cast<uint64_t>(lim.raw) > 2 * static_cast<uint64_t>(lim.raw);
}
/// !(0 ≤ raw ≤ hi) for hi ≥ 0.
inline bool outside_from_zero(int64_t raw, Q32 hi) { return static_cast<uint64_t>(raw) > static_cast<uint64_t>(hi.raw); }

constexpr Q32 k_unit_lim = Q32::from_raw(Q32::one().raw + k_unit_tolerance);

}  // namespace

bool fast_check_bodies(const uint8_t* data, size_t size, size_t* io_pos, const uint8_t* alive, size_t cap,
                       uint8_t* simulated) {
  size_t pos = *io_pos;
  bool bad = false;
  for (size_t i = 0; i < cap; ++i) {
    if (alive[i] == 0) continue;
    if (size - pos < 2) return false;
    const uint8_t flags = data[pos];
    const uint8_t present = data[pos + 1];
    const size_t n = body_record_bytes(present);
    if (n > size - pos) return false;
    const uint8_t* p = data + pos + 2;
    const uint8_t type = flags & k_body_type_mask;
    const bool moving = type != static_cast<uint8_t>(BodyType::static_body);
    bool b = type > static_cast<uint8_t>(BodyType::dynamic_body);
    b |= ((flags | present) & 0x80) != 0;
    b |= outside(ld_raw(p), k_max_coordinate);
    b |= outside(ld_raw(p + 8), k_max_coordinate);
    const int64_t c = ld_raw(p + 16);
    const int64_t s = ld_raw(p + 24);
    bool rot_out = outside(c, k_unit_lim);
    rot_out |= outside(s, k_unit_lim);
    b |= rot_out;
    {
      // The detailed checker's unit test (c·c + s·s, each product rounded,
      // within 2^-16 of 1), on components within ±(1 + 2^-16), zeroed
      // otherwise (already refused): nothing saturates, so fast_math.h gives
      // the checked operators' bits, and the difference from 1 is exact.
      const Q32 qc = Q32::from_raw(rot_out ? 0 : c);
      const Q32 qs = Q32::from_raw(rot_out ? 0 : s);
      const Q32 len2 = fast::add(fast::mul(qc, qc), fast::mul(qs, qs));
      b |= outside(len2.raw - Q32::one().raw, Q32::from_raw(k_unit_tolerance));
    }
    p += 32;
    if (present & k_has_velocity) {
      const Q32 vmax = moving ? k_max_speed : Q32::zero();
      const Q32 wmax = moving ? k_max_spin : Q32::zero();
      b |= outside(ld_raw(p), vmax);
      b |= outside(ld_raw(p + 8), vmax);
      b |= outside(ld_raw(p + 16), wmax);
      p += 24;
    }
    if (present & k_has_force) {
      b |= outside(ld_raw(p), k_max_force);
      b |= outside(ld_raw(p + 8), k_max_force);
      b |= outside(ld_raw(p + 16), k_max_torque);
      p += 24;
    }
    if (present & k_has_sleep_time) {
      b |= outside_from_zero(ld_raw(p), k_time_to_sleep);
      p += 8;
    }
    if (present & k_has_sleep_island) {
      const int32_t island = ld_i32(p);
      if (island < 0 || static_cast<size_t>(island) >= cap || alive[static_cast<size_t>(island)] == 0) return false;
      p += 4;
    }
    if (present & k_has_user_data) p += 8;
    if (present & k_has_damping) {
      b |= outside_from_zero(ld_raw(p), k_max_damping);
      b |= outside_from_zero(ld_raw(p + 8), k_max_damping);
      p += 16;
    }
    if (present & k_has_gravity_scale) b |= outside(ld_raw(p), k_max_gravity_scale);
    const bool awake = (flags & k_body_awake) != 0;
    const bool enabled = (flags & k_body_enabled) != 0;
    simulated[i] = moving && awake && enabled ? 1 : 0;
    bad |= b;
    pos += n;
  }
  if (bad) return false;
  *io_pos = pos;
  return true;
}

bool fast_check_shapes(const uint8_t* data, size_t size, size_t* io_pos, const uint8_t* alive, size_t cap,
                       const uint8_t* body_alive, const uint8_t* body_simulated, size_t body_cap,
                       const ShapeGeometry* geometries, int32_t* shape_body, uint8_t* shape_simulated) {
  size_t pos = *io_pos;
  for (size_t i = 0; i < cap; ++i) {
    if (alive[i] == 0) continue;
    if (size - pos < 5) return false;
    const int32_t body = ld_i32(data + pos);
    const uint8_t bits = data[pos + 4];
    const uint8_t type = bits & k_shape_type_mask;
    if (body < 0 || static_cast<size_t>(body) >= body_cap || body_alive[static_cast<size_t>(body)] == 0) return false;
    const ShapeGeometry& g = geometries[i];
    if (type > static_cast<uint8_t>(ShapeType::chain_segment) || static_cast<uint8_t>(g.type) != type ||
        (g.type == ShapeType::polygon && (g.polygon.count < 3 || g.polygon.count > k_max_polygon_vertices))) {
      return false;
    }
    const size_t n = shape_record_bytes(bits);
    if (n > size - pos) return false;
    shape_body[i] = body;
    shape_simulated[i] = body_simulated[static_cast<size_t>(body)];
    if (bits & k_shape_has_materials) {
      const uint8_t* p = data + pos + 5;
      if (outside_from_zero(ld_raw(p), k_max_friction) || outside_from_zero(ld_raw(p + 8), Q32::one()) ||
          outside_from_zero(ld_raw(p + 16), k_max_density)) {
        return false;
      }
    }
    pos += n;
  }
  *io_pos = pos;
  return true;
}

bool fast_check_contacts(const uint8_t* data, size_t size, size_t* io_pos, const uint8_t* shape_simulated,
                         size_t shape_cap, size_t body_cap) {
  size_t pos = *io_pos;
  if (size - pos < 4) return false;
  const uint32_t n = load_le32(data + pos);
  pos += 4;
  if (n > (size - pos) / 9) return false;
  const uint32_t scap = static_cast<uint32_t>(shape_cap);
  const int32_t bcap = static_cast<int32_t>(body_cap);
  uint64_t prev_key = 0;
  bool bad = false;
  for (uint32_t i = 0; i < n; ++i) {
    if (size - pos < 9) return false;
    const int32_t a = ld_i32(data + pos);
    const int32_t b = ld_i32(data + pos + 4);
    const uint8_t head = data[pos + 8];
    const int32_t count = head & k_contact_count_mask;
    // 0 ≤ a < b < shape_cap as one unsigned chain (a < 0 wraps above b).
    if (static_cast<uint32_t>(a) >= static_cast<uint32_t>(b) || static_cast<uint32_t>(b) >= scap ||
        (head & ~(k_contact_count_mask | k_contact_full)) != 0 || count > 2) {
      return false;
    }
    // Sorted: the first key is ≥ 1 (b ≥ 1) > prev_key = 0, as the detailed
    // checker's i > 0 lets it be.
    const uint64_t key = shape_pair_key(a, b);
    if (key <= prev_key) return false;
    prev_key = key;
    pos += 9;
    if ((head & k_contact_full) != 0) {
      Contact c{};
      FastFieldReader r{data, size, pos};
      state_fields::visit_contact(r, c);
      if (r.bad) return false;
      if (c.shape_a != a || c.shape_b != b || c.manifold.point_count != count || c.body_a < 0 || c.body_a >= bcap ||
          c.body_b < 0 || c.body_b >= bcap) {
        return false;
      }
      for (int32_t k = 0; k < count; ++k) {
        const size_t kk = static_cast<size_t>(k);
        bad |= outside(c.normal_impulse[kk].raw, k_max_impulse);
        bad |= outside(c.tangent_impulse[kk].raw, k_max_impulse);
      }
      pos = r.pos;
      continue;
    }
    if ((shape_simulated[static_cast<size_t>(a)] & shape_simulated[static_cast<size_t>(b)]) == 0) return false;
    const size_t bytes = static_cast<size_t>(count) * k_compact_point_bytes;
    if (bytes > size - pos) return false;
    const uint8_t* p = data + pos;
    for (int32_t k = 0; k < count; ++k, p += k_compact_point_bytes) {
      bad |= outside(ld_raw(p + 2), k_max_impulse);
      bad |= outside(ld_raw(p + 10), k_max_impulse);
    }
    pos += bytes;
  }
  if (bad) return false;
  *io_pos = pos;
  return true;
}

size_t apply_bodies(World* w, const uint8_t* data, size_t pos, const uint8_t* alive, size_t cap,
                    const RollbackBodyMass* masses) {
  w->bodies.resize(cap);
  w->body_sims.resize(cap);
  Body* bodies = w->bodies.data();
  BodySim* sims = w->body_sims.data();
  const uint8_t* p = data + pos;
  for (size_t i = 0; i < cap; ++i) {
    if (alive[i] == 0) {
      bodies[i] = Body{};
      sims[i] = BodySim{};
      continue;
    }
    const uint8_t flags = p[0];
    const uint8_t present = p[1];
    const uint8_t type = flags & k_body_type_mask;
    Transform xf;
    xf.p.x = ld_q32(p + 2);
    xf.p.y = ld_q32(p + 10);
    xf.q.c = ld_q32(p + 18);
    xf.q.s = ld_q32(p + 26);
    p += 34;
    Vec2 v{};
    Q32 omega;
    if (present & k_has_velocity) {
      v.x = ld_q32(p);
      v.y = ld_q32(p + 8);
      omega = ld_q32(p + 16);
      p += 24;
    }
    Vec2 force{};
    Q32 torque;
    if (present & k_has_force) {
      force.x = ld_q32(p);
      force.y = ld_q32(p + 8);
      torque = ld_q32(p + 16);
      p += 24;
    }
    Q32 sleep_time;
    if (present & k_has_sleep_time) {
      sleep_time = ld_q32(p);
      p += 8;
    }
    int32_t island = k_null_index;
    if (present & k_has_sleep_island) {
      island = ld_i32(p);
      p += 4;
    }
    uint64_t user = 0;
    if (present & k_has_user_data) {
      user = load_le64(p);
      p += 8;
    }
    Q32 lin_damp, ang_damp;
    if (present & k_has_damping) {
      lin_damp = ld_q32(p);
      ang_damp = ld_q32(p + 8);
      p += 16;
    }
    Q32 gravity_scale = Q32::one();
    if (present & k_has_gravity_scale) {
      gravity_scale = ld_q32(p);
      p += 8;
    }
    const RollbackBodyMass& m = masses[i];
    Body& b = bodies[i];
    b.type = static_cast<BodyType>(type);
    b.head_shape = k_null_index;
    b.shape_count = 0;
    b.mass = m.mass;
    b.rotational_inertia = m.rotational_inertia;
    b.sleep_time = sleep_time;
    b.sleep_island = island;
    b.user_data = user;
    b.enable_sleep = (flags & k_body_enable_sleep) != 0;
    b.awake = (flags & k_body_awake) != 0;
    b.enabled = (flags & k_body_enabled) != 0;
    b.fixed_rotation = (flags & k_body_fixed_rotation) != 0;
    b.bullet = (flags & k_body_bullet) != 0;
    b.min_extent = m.min_extent;
    b.max_extent = m.max_extent;
    BodySim& s = sims[i];
    s.transform = xf;
    s.local_center = m.local_center;
    s.center = fast::transform_point(xf, m.local_center);  // vec2.h's transform_point, same bits (fast_math.h)
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
  return static_cast<size_t>(p - data);
}

size_t apply_shapes(World* w, const uint8_t* data, size_t pos, const uint8_t* alive, size_t cap,
                    const ShapeGeometry* geometries, int32_t* tail, size_t body_cap) {
  w->shapes.resize(cap);
  w->shape_geometries.resize(cap);
  std::fill(tail, tail + body_cap, k_null_index);
  Shape* shapes = w->shapes.data();
  ShapeGeometry* world_geometries = w->shape_geometries.data();
  Body* bodies = w->bodies.data();
  const BodySim* sims = w->body_sims.data();
  const ShapeDef& d = default_shape();
  const uint8_t* p = data + pos;
  for (size_t i = 0; i < cap; ++i) {
    if (alive[i] == 0) {
      shapes[i] = Shape{};
      world_geometries[i] = ShapeGeometry{};
      continue;
    }
    const int32_t body = ld_i32(p);
    const uint8_t bits = p[4];
    p += 5;
    Q32 friction = d.friction, restitution = d.restitution, density = d.density;
    if (bits & k_shape_has_materials) {
      friction = ld_q32(p);
      restitution = ld_q32(p + 8);
      density = ld_q32(p + 16);
      p += 24;
    }
    Filter filter{};
    if (bits & k_shape_has_filter) {
      filter.category_bits = load_le64(p);
      filter.mask_bits = load_le64(p + 8);
      filter.group_index = ld_i32(p + 16);
      p += 20;
    }
    uint64_t user = 0;
    if (bits & k_shape_has_user_data) {
      user = load_le64(p);
      p += 8;
    }
    Shape& s = shapes[i];
    s.body_index = body;
    s.type = static_cast<ShapeType>(bits & k_shape_type_mask);
    s.friction = friction;
    s.restitution = restitution;
    s.density = density;
    s.filter = filter;
    s.user_data = user;
    s.is_sensor = (bits & k_shape_sensor) != 0;
    s.enable_hit_events = (bits & k_shape_hit_events) != 0;
    copy_geometry(geometries[i], &world_geometries[i]);
    // Shape lists run in ascending shape index.
    Body& b = bodies[static_cast<size_t>(body)];
    int32_t& t = tail[static_cast<size_t>(body)];
    s.prev_shape = t;
    s.next_shape = k_null_index;
    if (t == k_null_index) {
      b.head_shape = static_cast<int32_t>(i);
    } else {
      shapes[static_cast<size_t>(t)].next_shape = static_cast<int32_t>(i);
    }
    t = static_cast<int32_t>(i);
    ++b.shape_count;
    s.aabb = compute_shape_aabb(world_geometries[i], sims[static_cast<size_t>(body)].transform);
  }
  return static_cast<size_t>(p - data);
}

// apply_contacts writes a compact contact field by field: a new field must be
// written there too. The sizes are those of 64-bit targets (i686 aligns 64-bit
// members to 4 bytes, so its structs are smaller); the 64-bit builds guard.
static_assert(sizeof(void*) != 8 || (sizeof(Contact) == 232 && sizeof(ManifoldPoint) == 64),
              "apply_contacts writes every field of Contact: add the new field there");

size_t apply_contacts(World* w, const uint8_t* data, size_t size, size_t pos) {
  const uint32_t n = load_le32(data + pos);
  pos += 4;
  w->contacts.resize(n);
  Contact* contacts = w->contacts.data();
  const uint32_t* generations = w->shape_pool.generations.data();
  const Shape* shapes = w->shapes.data();
  for (uint32_t i = 0; i < n; ++i) {
    const int32_t a = ld_i32(data + pos);
    const int32_t b = ld_i32(data + pos + 4);
    const uint8_t head = data[pos + 8];
    const int32_t count = head & k_contact_count_mask;
    pos += 9;
    Contact& c = contacts[i];
    if ((head & k_contact_full) != 0) {
      Contact full{};
      FastFieldReader r{data, size, pos};  // checked before: accepted
      state_fields::visit_contact(r, full);
      c = full;
      pos = r.pos;
      continue;
    }
    // The manifold geometry and mixed materials are zero: the next step
    // recomputes them (rollback.h). Every field is written (the values of
    // `c = Contact{}` and the header's), field by field: a whole-record
    // clear compiles to a 29-word rep stos.
    c.shape_a = a;
    c.shape_b = b;
    c.generation_a = generations[static_cast<size_t>(a)];
    c.generation_b = generations[static_cast<size_t>(b)];
    c.body_a = shapes[static_cast<size_t>(a)].body_index;
    c.body_b = shapes[static_cast<size_t>(b)].body_index;
    c.flags = count > 0 ? k_contact_touching : 0u;
    c.friction = Q32::zero();
    c.restitution = Q32::zero();
    c.manifold.normal = Vec2{};
    c.manifold.points[0] = ManifoldPoint{};
    c.manifold.points[1] = ManifoldPoint{};
    c.manifold.point_count = count;
    c.normal_impulse = {};
    c.tangent_impulse = {};
    const uint8_t* p = data + pos;
    for (int32_t k = 0; k < count; ++k, p += k_compact_point_bytes) {
      const size_t kk = static_cast<size_t>(k);
      c.manifold.points[kk].id = load_le16(p);
      c.normal_impulse[kk] = ld_q32(p + 2);
      c.tangent_impulse[kk] = ld_q32(p + 10);
    }
    pos += static_cast<size_t>(count) * k_compact_point_bytes;
  }
  return pos;
}

}  // namespace tandem::compact_detail

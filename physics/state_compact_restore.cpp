// state_compact_restore.cpp — checking and applying the records of a compact
// rollback image (replay/rollback.h; the layout is in state_compact.cpp;
// replay checks the header and calls check_compact_records, then
// apply_compact_records, through physics/state_access.h).
//
// DESIGN. One decoder runs twice over the image. The first pass (Apply =
// false) checks everything — bytes left, enums, indices, cross references,
// value ranges — and touches no world; the second (Apply = true) writes the
// world and cannot fail, so a refused image changes nothing and an accepted
// one needs no scratch copy of the world. Bounds are checked once per record
// (its length follows from its flag bytes), then its fields are read with
// plain little-endian loads; the rare sections with many fields (world
// settings, full contacts, joints, joint events) run the field lists of
// state_fields.h with a checking FieldReader (state_compact.h).
// The bulk sections (bodies, shapes, contacts) are first checked by the fast
// paths of state_compact_fast.cpp, which only answer "all good"; when they
// refuse, the detailed checks here run over the section from the same offset
// and name the culprit, so every refusal reads the same whichever path found
// it (tests/replay/test_rollback_fast_checks.cpp compares the two). The
// second pass writes those sections with the applying loops of that file.
// Messages: "rollback_restore: offset N: body 12 position.x 3e6 m is outside
// [-2000000, 2000000] m".
#include "physics/state_compact.h"

#include <atomic>

#include "fixed/str_cat.h"

namespace tandem::state_access {

using namespace compact_detail;

namespace {

constexpr size_t k_pair_bytes = 16;

/// What the first pass learns and the checks of later records need
/// (per-thread, reused, so a warm restore does not allocate).
struct Scratch {
  std::vector<uint8_t> body_alive;
  std::vector<uint8_t> body_simulated;
  std::vector<uint8_t> shape_alive;
  std::vector<int32_t> shape_body;
  std::vector<uint8_t> shape_simulated;  // alive on a simulated body
  std::vector<uint8_t> joint_alive;
  std::vector<int32_t> tail;  // second pass: each body's last listed shape
};

Scratch& scratch() {
  thread_local Scratch s;
  return s;
}

/// set_compact_fast_checks (tests turn the fast checks off to compare).
std::atomic<bool> g_fast_checks{true};
bool fast_checks() { return g_fast_checks.load(std::memory_order_relaxed); }

template <bool Apply>
class Decoder {
 public:
  Decoder(const uint8_t* data, size_t size, size_t from, CompactStructureView st, World* w)
      : masses_(*st.masses), geometries_(*st.geometries), data_(data), size_(size), from_(from), w_(w),
        sc_(scratch()) {}

  /// Decodes (checks, or applies) the records; the error when refused.
  const std::string& run() {
    pos_ = from_;
    if (!Apply) {
      if (!need(1, "broad-phase kind")) return error_;
      if (data_[from_] > static_cast<uint8_t>(BroadPhaseKind::tree)) {
        fail(from_, "expected a broad-phase kind 0..3, got " + std::to_string(data_[from_]));
        return error_;
      }
    }
    pos_ = from_ + 1;
    world();
    if (ok()) pool(Apply ? &w_->body_pool : nullptr, "body_slot", k_max_bodies, &sc_.body_alive);
    if (ok()) bodies();
    if (ok()) pool(Apply ? &w_->shape_pool : nullptr, "shape_slot", k_max_shapes, &sc_.shape_alive);
    if (ok()) shapes();
    if (ok()) contacts();
    if (ok()) pairs();
    if (ok()) joints();
    if (ok() && pos_ != size_) {
      fail(pos_, "expected the end of the image, " + std::to_string(size_ - pos_) + " bytes left over");
    }
    if (ok() && Apply) rebuild_after_restore(w_);
    return error_;
  }
  const std::string& run_error() const { return error_; }

 private:
  // --- reading -------------------------------------------------------------
  bool ok() const { return error_.empty(); }
  void context(const char* kind, int64_t index = -1) {
    kind_ = kind;
    index_ = index;
  }
  /// Refuses at byte `at`: "offset N: <record> <what>".
  [[gnu::cold, gnu::noinline]] void fail(size_t at, const std::string& what) {
    if (!ok()) return;
    error_ = "offset ";
    error_ += std::to_string(at);
    error_ += ": ";
    if (kind_ != nullptr) {
      error_ += kind_;
      if (index_ >= 0) {
        error_ += ' ';
        error_ += std::to_string(index_);
      }
      error_ += ' ';
    }
    error_ += what;
  }
  /// True when n more bytes are there (else refuses, naming `what`).
  bool need(size_t n, const char* what) {
    if (n <= size_ - pos_) [[likely]] {
      return true;
    }
    refuse_short(n, what);
    return false;
  }
  [[gnu::cold, gnu::noinline]] void refuse_short(size_t n, const char* what) {
    fail(pos_, str_cat("expected ", std::to_string(n), " bytes of ", what, ", ", std::to_string(size_ - pos_), " left"));
  }
  // Unchecked little-endian loads (after need()).
  uint8_t u8() { return data_[pos_++]; }
  uint16_t u16() {
    const uint16_t v = load_le16(data_ + pos_);
    pos_ += 2;
    return v;
  }
  uint32_t u32() {
    const uint32_t v = load_le32(data_ + pos_);
    pos_ += 4;
    return v;
  }
  uint64_t u64() {
    const uint64_t v = load_le64(data_ + pos_);
    pos_ += 8;
    return v;
  }
  int32_t i32() { return static_cast<int32_t>(u32()); }
  Q32 q32() { return Q32::from_raw(static_cast<int64_t>(u64())); }
  /// A Q32 within ±lim (checked in the first pass).
  Q32 q32(const char* field, Q32 lim, const char* unit) {
    const size_t at = pos_;
    const Q32 v = q32();
    if (!Apply && !(-lim <= v && v <= lim)) refuse_range(at, field, v, -lim, lim, unit);
    return v;
  }
  [[gnu::cold, gnu::noinline]] void refuse_range(size_t at, const char* field, Q32 v, Q32 lo, Q32 hi,
                                                 const char* unit) {
    std::string m(field);
    m += ' ';
    m += to_string(v);
    m += *unit ? " " : "";
    m += unit;
    m += " is outside [";
    m += to_string(lo);
    m += ", ";
    m += to_string(hi);
    m += "]";
    m += *unit ? " " : "";
    m += unit;
    fail(at, m);
  }
  /// Reads a record kept whole with the checking FieldReader at the
  /// current offset (offsets in its messages absolute).
  template <typename F>
  void visited(F&& f) {
    FieldReader r{data_, size_, pos_, kind_, index_, {}};
    f(r);
    if (!r.ok()) {
      if (ok()) error_ = std::move(r.error);
      return;
    }
    pos_ = r.pos;
  }

  // --- sections ------------------------------------------------------------
  void world() {
    context("world");
    WorldDef def{};
    uint64_t steps = 0;
    int32_t solver_bodies = 0;
    visited([&](auto& v) {
      visit_world_def(v, def);
      v.u64("step_count", steps);
      v.i32("last_solver_body_count", solver_bodies);
    });
    if (!ok() || !Apply) return;
    const int32_t cookie = w_->def.internal_cookie;
    w_->def = def;
    w_->def.internal_cookie = cookie;
    w_->def.broad_phase = static_cast<BroadPhaseKind>(data_[from_]);
    w_->step_count = steps;
    w_->last_solver_body_count = solver_bodies;
  }

  void pool(IdPool* pool, const char* kind, int32_t max_capacity, std::vector<uint8_t>* alive) {
    context(kind);
    if (!need(4, "capacity")) return;
    const size_t at = pos_;
    const uint32_t cap = u32();
    if (!Apply && (cap > static_cast<uint32_t>(max_capacity) || cap > (size_ - pos_) / 5)) {
      fail(at, "capacity " + std::to_string(cap) + " is above " + std::to_string(max_capacity) +
                   " or the bytes left (" + std::to_string(size_ - pos_) + ", 5 per slot)");
      return;
    }
    if constexpr (!Apply) {
      alive->assign(cap, 0);
      uint8_t* live_out = alive->data();
      const uint8_t* p = data_ + pos_;
      for (uint32_t i = 0; i < cap; ++i, p += 5) {
        const uint32_t g = load_le32(p);
        const uint8_t live = p[4];
        if (g == 0 || live > 1) [[unlikely]] {
          context(kind, i);
          const size_t slot_at = static_cast<size_t>(p - data_);
          fail(slot_at, "generation " + std::to_string(g) + " / alive " + std::to_string(live) +
                            ": expected a generation ≥ 1 and alive 0 or 1");
          return;
        }
        live_out[i] = live;
      }
    } else {
      pool->generations.resize(cap);
      pool->alive.resize(cap);
      pool->free_heap.clear();
      uint32_t* generations = pool->generations.data();
      uint8_t* live_out = pool->alive.data();
      const uint8_t* p = data_ + pos_;
      int32_t alive_count = 0;
      for (uint32_t i = 0; i < cap; ++i, p += 5) {
        const uint8_t live = p[4];
        generations[i] = load_le32(p);
        live_out[i] = live;
        if (live != 0) {
          ++alive_count;
        } else {
          pool->free_heap.push_back(static_cast<int32_t>(i));  // ascending: a valid min-heap
        }
      }
      pool->alive_count = alive_count;
    }
    pos_ += static_cast<size_t>(cap) * 5;
  }


  void bodies();
  void check_bodies();
  void shapes();
  void check_shapes();
  void contacts();
  void check_contacts();
  void read_pairs(std::vector<PairRecord>* out, const char* kind);
  void pairs();
  void joints();

  const std::vector<RollbackBodyMass>& masses_;
  const std::vector<ShapeGeometry>& geometries_;
  const uint8_t* data_;
  size_t size_;
  size_t from_;
  size_t pos_ = 0;
  World* w_;
  Scratch& sc_;
  std::string error_;
  const char* kind_ = nullptr;
  int64_t index_ = -1;
};

template <bool Apply>
void Decoder<Apply>::bodies() {
  const size_t cap = sc_.body_alive.size();
  if constexpr (Apply) {
    pos_ = apply_bodies(w_, data_, pos_, sc_.body_alive.data(), cap, masses_.data());
  } else {
    if (masses_.size() < cap) {
      fail(pos_, "the buffer's body masses hold " + std::to_string(masses_.size()) + " entries, the image needs " +
                     std::to_string(cap));
      return;
    }
    sc_.body_simulated.assign(cap, 0);
    if (!fast_checks() ||
        !fast_check_bodies(data_, size_, &pos_, sc_.body_alive.data(), cap, sc_.body_simulated.data())) {
      check_bodies();  // names the culprit (or accepts after all)
    }
  }
}

/// The detailed check of the bodies (after fast_check_bodies refused).
template <bool Apply>
void Decoder<Apply>::check_bodies() {
  const size_t cap = sc_.body_alive.size();
  const Q32 unit_lim = Q32::from_raw(Q32::one().raw + k_unit_tolerance);
  for (size_t i = 0; i < cap; ++i) {
    if (sc_.body_alive[i] == 0) continue;
    context("body", static_cast<int64_t>(i));
    const size_t at = pos_;
    if (!need(2, "body flags")) return;
    const uint8_t flags = u8();
    const uint8_t present = u8();
    const uint8_t type = flags & k_body_type_mask;
    if (type > static_cast<uint8_t>(BodyType::dynamic_body) || (flags & 0x80) != 0 || (present & 0x80) != 0) {
      fail(at, "flags " + std::to_string(flags) + " / presence " + std::to_string(present) +
                   ": expected a body type 0..2 and defined bits only");
      return;
    }
    if (!need(body_record_bytes(present) - 2, "the body record")) return;
    Transform xf;
    xf.p.x = q32("position.x", k_max_coordinate, "m");
    xf.p.y = q32("position.y", k_max_coordinate, "m");
    const size_t rot_at = pos_;
    xf.q.c = q32("rotation.c", unit_lim, "");
    xf.q.s = q32("rotation.s", unit_lim, "");
    if (ok()) {
      const Q32 n = xf.q.c * xf.q.c + xf.q.s * xf.q.s;  // components ≤ 1 + 2^-16: no saturation
      if ((n - Q32::one()).raw > k_unit_tolerance || (Q32::one() - n).raw > k_unit_tolerance) {
        fail(rot_at, "rotation (" + to_string(xf.q.c) + ", " + to_string(xf.q.s) +
                         ") is not a unit vector (squared length " + to_string(n) + ")");
      }
    }
    const bool moving = type != static_cast<uint8_t>(BodyType::static_body);
    if (present & k_has_velocity) {
      const Q32 vmax = moving ? k_max_speed : Q32::zero();
      q32("linear_velocity.x", vmax, "m/s");
      q32("linear_velocity.y", vmax, "m/s");
      q32("angular_velocity", moving ? k_max_spin : Q32::zero(), "rad/s");
    }
    if (present & k_has_force) {
      q32("force.x", k_max_force, "N");
      q32("force.y", k_max_force, "N");
      q32("torque", k_max_torque, "N·m");
    }
    if (present & k_has_sleep_time) {
      const size_t st_at = pos_;
      const Q32 sleep_time = q32();
      if (sleep_time < Q32::zero() || sleep_time > k_time_to_sleep) {
        refuse_range(st_at, "sleep_time", sleep_time, Q32::zero(), k_time_to_sleep, "s");
      }
    }
    if (present & k_has_sleep_island) {
      const size_t is_at = pos_;
      const int32_t island = i32();
      if (island < 0 || static_cast<size_t>(island) >= cap || sc_.body_alive[static_cast<size_t>(island)] == 0) {
        fail(is_at, "sleep_island " + std::to_string(island) + " is not a live body");
      }
    }
    if (present & k_has_user_data) pos_ += 8;
    if (present & k_has_damping) {
      const size_t d_at = pos_;
      const Q32 lin_damp = q32();
      const Q32 ang_damp = q32();
      if (lin_damp < Q32::zero() || lin_damp > k_max_damping) {
        refuse_range(d_at, "linear_damping", lin_damp, Q32::zero(), k_max_damping, "1/s");
      }
      if (ang_damp < Q32::zero() || ang_damp > k_max_damping) {
        refuse_range(d_at + 8, "angular_damping", ang_damp, Q32::zero(), k_max_damping, "1/s");
      }
    }
    if (present & k_has_gravity_scale) q32("gravity_scale", k_max_gravity_scale, "");
    if (!ok()) return;
    const bool awake = (flags & k_body_awake) != 0;
    const bool enabled = (flags & k_body_enabled) != 0;
    sc_.body_simulated[i] = moving && awake && enabled ? 1 : 0;
  }
}

template <bool Apply>
void Decoder<Apply>::shapes() {
  const size_t cap = sc_.shape_alive.size();
  const size_t body_cap = sc_.body_alive.size();
  if constexpr (Apply) {
    sc_.tail.resize(body_cap);
    pos_ = apply_shapes(w_, data_, pos_, sc_.shape_alive.data(), cap, geometries_.data(), sc_.tail.data(), body_cap);
  } else {
    if (geometries_.size() < cap) {
      fail(pos_, "the buffer's geometries hold " + std::to_string(geometries_.size()) +
                     " entries, the image needs " + std::to_string(cap));
      return;
    }
    sc_.shape_body.assign(cap, k_null_index);
    sc_.shape_simulated.assign(cap, 0);
    if (!fast_checks() ||
        !fast_check_shapes(data_, size_, &pos_, sc_.shape_alive.data(), cap, sc_.body_alive.data(),
                           sc_.body_simulated.data(), body_cap, geometries_.data(), sc_.shape_body.data(),
                           sc_.shape_simulated.data())) {
      check_shapes();  // names the culprit (or accepts after all)
    }
  }
}

/// The detailed check of the shapes (after fast_check_shapes refused).
template <bool Apply>
void Decoder<Apply>::check_shapes() {
  const size_t cap = sc_.shape_alive.size();
  const size_t body_cap = sc_.body_alive.size();
  for (size_t i = 0; i < cap; ++i) {
    if (sc_.shape_alive[i] == 0) continue;
    context("shape", static_cast<int64_t>(i));
    const size_t at = pos_;
    if (!need(5, "the shape record")) return;
    const int32_t body = i32();
    const uint8_t bits = u8();
    const uint8_t type = bits & k_shape_type_mask;
    if (body < 0 || static_cast<size_t>(body) >= body_cap || sc_.body_alive[static_cast<size_t>(body)] == 0) {
      fail(at, "body " + std::to_string(body) + " is not a live body");
      return;
    }
    const ShapeGeometry& g = geometries_[i];
    if (type > static_cast<uint8_t>(ShapeType::chain_segment) || static_cast<uint8_t>(g.type) != type ||
        (g.type == ShapeType::polygon && (g.polygon.count < 3 || g.polygon.count > k_max_polygon_vertices))) {
      fail(at + 4, "type " + std::to_string(type) + " does not match the buffer's geometry (type " +
                       std::to_string(static_cast<int32_t>(g.type)) + ")");
      return;
    }
    if (!need(shape_record_bytes(bits) - 5, "the shape record")) return;
    sc_.shape_body[i] = body;
    sc_.shape_simulated[i] = sc_.body_simulated[static_cast<size_t>(body)];
    if (bits & k_shape_has_materials) {
      const size_t m_at = pos_;
      const Q32 friction = q32();
      const Q32 restitution = q32();
      const Q32 density = q32();
      if (friction < Q32::zero() || friction > k_max_friction) {
        refuse_range(m_at, "friction", friction, Q32::zero(), k_max_friction, "");
      } else if (restitution < Q32::zero() || restitution > Q32::one()) {
        refuse_range(m_at + 8, "restitution", restitution, Q32::zero(), Q32::one(), "");
      } else if (density < Q32::zero() || density > k_max_density) {
        refuse_range(m_at + 16, "density", density, Q32::zero(), k_max_density, "kg/m²");
      }
    }
    if (bits & k_shape_has_filter) pos_ += 20;
    if (bits & k_shape_has_user_data) pos_ += 8;
    if (!ok()) return;
  }
}
template <bool Apply>
void Decoder<Apply>::contacts() {
  if constexpr (Apply) {
    pos_ = apply_contacts(w_, data_, size_, pos_);
  } else {
    if (!fast_checks() || !fast_check_contacts(data_, size_, &pos_, sc_.shape_simulated.data(),
                                               sc_.shape_alive.size(), sc_.body_alive.size())) {
      check_contacts();  // names the culprit (or accepts after all)
    }
  }
}

/// The detailed check of the contacts (after fast_check_contacts refused).
template <bool Apply>
void Decoder<Apply>::check_contacts() {
  context("contacts");
  if (!need(4, "count")) return;
  const uint32_t n = u32();
  if (n > (size_ - pos_) / 9) {
    fail(pos_ - 4, "count " + std::to_string(n) + " needs more than the " + std::to_string(size_ - pos_) +
                       " bytes left (9 per contact at least)");
    return;
  }
  const int32_t shape_cap = static_cast<int32_t>(sc_.shape_alive.size());
  const int32_t body_cap = static_cast<int32_t>(sc_.body_alive.size());
  uint64_t prev_key = 0;
  for (uint32_t i = 0; i < n; ++i) {
    context("contact", i);
    const size_t at = pos_;
    if (!need(9, "the contact header")) return;
    const int32_t a = i32();
    const int32_t b = i32();
    const uint8_t head = u8();
    const int32_t count = head & k_contact_count_mask;
    if (a < 0 || b >= shape_cap || a >= b || (head & ~(k_contact_count_mask | k_contact_full)) != 0 || count > 2) {
      fail(at, "shapes (" + std::to_string(a) + ", " + std::to_string(b) + ") / header " + std::to_string(head) +
                   ": expected two shapes of the pool in ascending order and 0..2 points");
      return;
    }
    const uint64_t key = shape_pair_key(a, b);
    if (i > 0 && key <= prev_key) {
      fail(at, "is not sorted by shape pair");
      return;
    }
    prev_key = key;
    if ((head & k_contact_full) != 0) {
      Contact c{};
      const size_t rec_at = pos_;
      visited([&](auto& v) { visit_contact(v, c); });
      if (!ok()) return;
      if (c.shape_a != a || c.shape_b != b || c.manifold.point_count != count || c.body_a < 0 ||
          c.body_a >= body_cap || c.body_b < 0 || c.body_b >= body_cap) {
        fail(rec_at, "full record disagrees with its header or names bodies outside the pool");
        return;
      }
      for (int32_t k = 0; k < count; ++k) {
        const size_t kk = static_cast<size_t>(k);
        if (abs(c.normal_impulse[kk]) > k_max_impulse || abs(c.tangent_impulse[kk]) > k_max_impulse) {
          fail(rec_at, "stored impulse of point " + std::to_string(k) + " is outside ±" + to_string(k_max_impulse) +
                           " N·s");
          return;
        }
      }
      continue;
    }
    if (sc_.shape_alive[static_cast<size_t>(a)] == 0 || sc_.shape_alive[static_cast<size_t>(b)] == 0 ||
        sc_.body_simulated[static_cast<size_t>(sc_.shape_body[static_cast<size_t>(a)])] == 0 ||
        sc_.body_simulated[static_cast<size_t>(sc_.shape_body[static_cast<size_t>(b)])] == 0) {
      fail(at, "is compact, but its shapes are not both alive on simulated bodies");
      return;
    }
    if (!need(static_cast<size_t>(count) * 18, "the contact points")) return;
    for (int32_t k = 0; k < count; ++k) {
      pos_ += 2;  // feature id
      q32(k == 0 ? "points[0].normal_impulse" : "points[1].normal_impulse", k_max_impulse, "N·s");
      q32(k == 0 ? "points[0].tangent_impulse" : "points[1].tangent_impulse", k_max_impulse, "N·s");
    }
    if (!ok()) return;
  }
}
template <bool Apply>
void Decoder<Apply>::read_pairs(std::vector<PairRecord>* out, const char* kind) {
  context(kind);
  if (!need(4, "count")) return;
  const uint32_t n = u32();
  if (!Apply && n > (size_ - pos_) / k_pair_bytes) {
    fail(pos_ - 4, "count " + std::to_string(n) + " needs more than the " + std::to_string(size_ - pos_) +
                       " bytes left");
    return;
  }
  if (Apply) out->resize(n);
  const int32_t shape_cap = static_cast<int32_t>(sc_.shape_alive.size());
  PairRecord prev{};
  for (uint32_t i = 0; i < n; ++i) {
    const size_t at = pos_;
    PairRecord p;
    p.shape_a = i32();
    p.shape_b = i32();
    p.generation_a = u32();
    p.generation_b = u32();
    if (!Apply && (p.shape_a < 0 || p.shape_a >= shape_cap || p.shape_b < 0 || p.shape_b >= shape_cap ||
                   (i > 0 && shape_pair_key(p.shape_a, p.shape_b) <= shape_pair_key(prev.shape_a, prev.shape_b)))) {
      context(kind, i);
      fail(at, "names a shape outside the pool or is not sorted");
      return;
    }
    prev = p;
    if (Apply) (*out)[i] = p;
  }
}

template <bool Apply>
void Decoder<Apply>::pairs() {
  context("touching");
  if (!need(1, "derived flag")) return;
  const size_t at = pos_;
  const uint8_t derived = u8();
  if (!Apply && derived > 1) {
    fail(at, "derived flag " + std::to_string(derived) + ": expected 0 or 1");
    return;
  }
  if (derived != 0) {
    if (Apply) {
      std::vector<PairRecord>& t = w_->events.touching;
      t.clear();
      for (const Contact& c : w_->contacts) {
        if ((c.flags & k_contact_touching) != 0) t.push_back(PairRecord{c.shape_a, c.shape_b, c.generation_a, c.generation_b});
      }
    }
  } else {
    read_pairs(Apply ? &w_->events.touching : nullptr, "touching");
  }
  if (ok()) read_pairs(Apply ? &w_->events.sensor_overlaps : nullptr, "sensor_overlap");
}

template <bool Apply>
void Decoder<Apply>::joints() {
  pool(Apply ? &w_->joint_pool : nullptr, "joint_slot", k_max_bodies, &sc_.joint_alive);
  if (!ok()) return;
  const std::vector<uint8_t>& alive = Apply ? w_->joint_pool.alive : sc_.joint_alive;
  const size_t cap = alive.size();
  const int32_t body_cap = static_cast<int32_t>(sc_.body_alive.size());
  if (Apply) w_->joints.joints.resize(cap);
  for (size_t i = 0; i < cap; ++i) {
    if (alive[i] == 0) {
      if (Apply) w_->joints.joints[i] = Joint{};
      continue;
    }
    context("joint", static_cast<int64_t>(i));
    const size_t at = pos_;
    Joint j{};
    visited([&](auto& v) { visit_joint(v, j); });
    if (!ok()) return;
    if (!Apply) {
      const auto live = [&](int32_t b) { return b >= 0 && b < body_cap && sc_.body_alive[static_cast<size_t>(b)] != 0; };
      if (!live(j.body_a) || !live(j.body_b) || j.body_a == j.body_b) {
        fail(at, "joins bodies (" + std::to_string(j.body_a) + ", " + std::to_string(j.body_b) +
                     "), which are not two live bodies");
        return;
      }
      FieldRangeFailure bad;
      if (first_joint_field_out_of_range(j, &bad)) {
        // The field's offset inside the record, found by walking the visitor.
        Joint copy = j;
        FieldOffset offset{bad.field};
        visit_joint(offset, copy);
        refuse_range(at + offset.at, bad.field, bad.value, bad.lo, bad.hi, bad.unit);
        return;
      }
      if (j.lower > j.upper) {
        fail(at, "lower " + to_string(j.lower) + " is above upper " + to_string(j.upper));
        return;
      }
    } else {
      w_->joints.joints[i] = j;
    }
  }
  context("pending joint events");
  if (!need(4, "count")) return;
  const uint32_t n = u32();
  if (!Apply && n > (size_ - pos_) / 53) {
    fail(pos_ - 4, "count " + std::to_string(n) + " needs more than the bytes left");
    return;
  }
  if (Apply) w_->joints.pending.resize(n);
  for (uint32_t i = 0; i < n; ++i) {
    context("pending joint event", i);
    JointEvent e{};
    visited([&](auto& v) { visit_joint_event(v, e); });
    if (!ok()) return;
    if (Apply) {
      e.joint.world = w_->id;
      e.body_a.world = w_->id;
      e.body_b.world = w_->id;
      w_->joints.pending[i] = e;
    }
  }
}

}  // namespace

void set_compact_fast_checks(bool on) { g_fast_checks.store(on, std::memory_order_relaxed); }

bool check_compact_records(const uint8_t* image, size_t size, size_t from, CompactStructureView structure,
                           std::string* error) {
  Decoder<false> check(image, size, from, structure, nullptr);
  if (check.run().empty()) return true;
  *error = check.run_error();
  return false;
}

void apply_compact_records(WorldState& world, const uint8_t* image, size_t size, size_t from,
                           CompactStructureView structure) {
  Decoder<true> apply(image, size, from, structure, &as_world(world));
  [[maybe_unused]] const bool ok = apply.run().empty();
  TANDEM_ASSERT(ok);
}

}  // namespace tandem::state_access

// state_access.cpp — the canonical walk of a world's state and of decoded
// images, the census, and commit (state_access.h describes the interface;
// state_check.cpp checks images). The record order written down here is the
// canonical state order of replay/state.h's format.
#include "physics/state_access.h"

#include <vector>

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

using state_fields::FieldsOf;

void StateImageDeleter::operator()(StateImage* image) const { delete image; }

WorldState* find_world_state(WorldId id, bool unlocked_only) {
  World* w = find_world(id);
  if (w == nullptr || (unlocked_only && w->locked)) return nullptr;
  return as_state(w);
}

Status resolve_world_state(WorldId id, const char* function, bool mutating, WorldState** out) {
  World* w = nullptr;
  Status s = resolve_world(id, function, mutating, &w);
  if (s.ok()) *out = as_state(w);
  return s;
}

WorldState* find_body_state(BodyId id, int32_t* out_index) {
  World* w = nullptr;
  if (!find_body(id, &w, out_index) || w->locked) return nullptr;
  return as_state(w);
}

StateCensus census(const WorldState& state) {
  const World& w = as_world(state);
  StateCensus c;
  c.body_slots = w.body_pool.generations.size();
  c.bodies = static_cast<size_t>(w.body_pool.alive_count);
  c.shape_slots = w.shape_pool.generations.size();
  for (size_t i = 0; i < w.shapes.size() && i < w.shape_pool.alive.size(); ++i) {
    if (w.shape_pool.alive[i] == 0) continue;
    const Shape& s = w.shapes[i];
    const size_t t = static_cast<size_t>(s.type);
    if (t < 5) ++c.shapes_by_type[t];
    if (s.type == ShapeType::polygon) {
      c.polygon_vertices += static_cast<size_t>(std::clamp(w.shape_geometries[i].polygon.count, 0, 8));
    }
  }
  c.contacts = w.contacts.size();
  for (const Contact& ct : w.contacts) c.contact_points += static_cast<size_t>(std::clamp(ct.manifold.point_count, 0, 2));
  c.touching = w.events.touching.size();
  c.sensor_overlaps = w.events.sensor_overlaps.size();
  c.joint_slots = w.joint_pool.generations.size();
  c.joints = static_cast<size_t>(w.joint_pool.alive_count);
  c.pending_joint_events = w.joints.pending.size();
  return c;
}

namespace {

/// Pool slots (generation, alive) after the capacity.
template <typename F>
void visit_pool(F& f, IdPool& pool, StateList list, const char* kind, int32_t max_capacity) {
  uint32_t capacity = static_cast<uint32_t>(pool.generations.size());
  f.count(list, kind, "capacity", capacity, static_cast<uint32_t>(max_capacity));
  if (!f.ok()) return;
  if constexpr (F::k_reading) {
    pool.generations.assign(capacity, 0);
    pool.alive.assign(capacity, 0);
  }
  for (uint32_t i = 0; i < capacity; ++i) {
    bool alive = pool.alive[i] != 0;
    f.slot(kind, i, pool.generations[i], alive);
    if constexpr (F::k_reading) {
      if (!f.ok()) return;
      pool.alive[i] = alive ? 1 : 0;
    }
  }
  if constexpr (F::k_reading) {
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

/// A sorted pair list after its count.
template <typename F>
void visit_pairs(F& f, std::vector<PairRecord>& pairs, StateList list, const char* kind) {
  uint32_t n = static_cast<uint32_t>(pairs.size());
  f.count(list, kind, "count", n, UINT32_MAX);
  if (!f.ok()) return;
  if constexpr (F::k_reading) pairs.resize(n);
  for (uint32_t i = 0; i < n; ++i) {
    f.record(kind, pairs[i].shape_a, pairs[i].shape_b, 0);
    if constexpr (F::k_reading) f.begin_read(kind, i);
    state_fields::visit_pair(f, pairs[i]);
  }
}

/// The world record: settings, step count, solver body count.
template <typename F>
void visit_header(F& f, World& w) {
  state_fields::visit_world_def(f, w.def);
  f.u64("step_count", w.step_count);
  f.i32("last_solver_body_count", w.last_solver_body_count);
}

/// The live records of one pool's table, each after record() (and
/// begin_read() when reading).
template <typename F, typename Visit>
void visit_live(F& f, const IdPool& pool, const char* kind, Visit visit) {
  for (size_t i = 0; i < pool.generations.size(); ++i) {
    if (pool.alive[i] == 0) continue;
    f.record(kind, static_cast<int64_t>(i), -1, pool.generations[i]);
    if constexpr (F::k_reading) f.begin_read(kind, static_cast<int64_t>(i));
    visit(i);
    if (!f.ok()) return;
  }
}

/// The whole state (state.h's format, after the header).
template <typename F>
void visit_all(F& f, World& w, StateSections sections) {
  f.tag("WRLD");
  f.record("world", 0, -1, 0);
  visit_header(f, w);
  if (!f.ok()) return;

  f.tag("BPOL");
  visit_pool(f, w.body_pool, StateList::body_slots, "body_slot", k_max_bodies);
  if (!f.ok()) return;
  if constexpr (F::k_reading) {
    w.bodies.assign(w.body_pool.generations.size(), Body{});
    w.body_sims.assign(w.body_pool.generations.size(), BodySim{});
  }
  f.tag("BODY");
  visit_live(f, w.body_pool, "body", [&](size_t i) { state_fields::visit_body(f, w.bodies[i], w.body_sims[i]); });
  if (!f.ok()) return;

  f.tag("SPOL");
  visit_pool(f, w.shape_pool, StateList::shape_slots, "shape_slot", k_max_shapes);
  if (!f.ok()) return;
  if constexpr (F::k_reading) {
    w.shapes.assign(w.shape_pool.generations.size(), Shape{});
    w.shape_geometries.assign(w.shape_pool.generations.size(), ShapeGeometry{});
  }
  f.tag("SHAP");
  visit_live(f, w.shape_pool, "shape",
             [&](size_t i) { state_fields::visit_shape(f, w.shapes[i], w.shape_geometries[i]); });
  if (!f.ok()) return;

  f.tag("CONT");
  uint32_t contact_count = static_cast<uint32_t>(w.contacts.size());
  f.count(StateList::contacts, "contacts", "count", contact_count, UINT32_MAX);
  if (!f.ok()) return;
  if constexpr (F::k_reading) w.contacts.assign(contact_count, Contact{});
  for (uint32_t i = 0; i < contact_count; ++i) {
    Contact& c = w.contacts[i];
    f.record("contact", c.shape_a, c.shape_b, 0);
    if constexpr (F::k_reading) f.begin_read("contact", i);
    state_fields::visit_contact(f, c);
    if (!f.ok()) return;
  }

  f.tag("TUCH");
  visit_pairs(f, w.events.touching, StateList::touching, "touching");
  if (!f.ok()) return;
  f.tag("SENS");
  visit_pairs(f, w.events.sensor_overlaps, StateList::sensor_overlaps, "sensor_overlap");
  if (!sections.joints || !f.ok()) return;

  f.tag("JPOL");
  visit_pool(f, w.joint_pool, StateList::joint_slots, "joint_slot", k_max_bodies);
  if (!f.ok()) return;
  std::vector<Joint>& joints = w.joints.joints;
  if constexpr (F::k_reading) joints.assign(w.joint_pool.generations.size(), Joint{});
  f.tag("JOIN");
  visit_live(f, w.joint_pool, "joint", [&](size_t i) { state_fields::visit_joint(f, joints[i]); });
  if (!sections.joint_events || !f.ok()) return;

  f.tag("JEVP");
  std::vector<JointEvent>& pending = w.joints.pending;
  uint32_t pending_count = static_cast<uint32_t>(pending.size());
  f.count(StateList::pending_joint_events, "pending joint events", "count", pending_count, UINT32_MAX);
  if (!f.ok()) return;
  if constexpr (F::k_reading) pending.assign(pending_count, JointEvent{});
  for (uint32_t i = 0; i < pending_count; ++i) {
    f.record("joint_event", i, -1, 0);
    if constexpr (F::k_reading) f.begin_read("joint_event", i);
    state_fields::visit_joint_event(f, pending[i]);
    if (!f.ok()) return;
  }
}

/// Writes the canonical bytes itself (FieldVisitor::output_buffer): the
/// same bytes as replay's WriteVisitor, without a virtual call per field.
struct RawWriter {
  static constexpr bool k_reading = false;
  OutputBuffer& out;
  void put64(uint64_t x, size_t n) {
    if (out.size <= out.capacity && n <= out.capacity - out.size) {
      uint8_t* p = out.data + out.size;
      for (size_t i = 0; i < n; ++i) p[i] = static_cast<uint8_t>(x >> (8 * i));
    }
    out.size += n;
  }
  void q32(const char*, Q32& x) { put64(static_cast<uint64_t>(x.raw), 8); }
  void q32_in(const char*, Q32& x, Q32, Q32, const char*) { q32(nullptr, x); }
  void vec2(const char*, const char*, Vec2& x) {
    q32(nullptr, x.x);
    q32(nullptr, x.y);
  }
  void vec2_in(const char*, const char*, Vec2& x, Q32, Q32, const char*) { vec2(nullptr, nullptr, x); }
  void i32(const char*, int32_t& x) { put64(static_cast<uint32_t>(x), 4); }
  void u32(const char*, uint32_t& x) { put64(x, 4); }
  void u16(const char*, uint16_t& x) { put64(x, 2); }
  void u64(const char*, uint64_t& x) { put64(x, 8); }
  void boolean(const char*, bool& x) { put64(x ? 1u : 0u, 1); }
  template <typename E>
  void enum8(const char*, E& e, int32_t) {
    put64(static_cast<uint8_t>(static_cast<int32_t>(e)), 1);
  }
  void ranged_i32(const char*, int32_t& x, int32_t, int32_t) { i32(nullptr, x); }
  bool ok() const { return true; }
  void record(const char*, int64_t, int64_t, uint32_t) {}
  void begin_read(const char*, int64_t) {}
  void tag(const char* t) {
    for (size_t i = 0; i < 4; ++i) put64(static_cast<uint8_t>(t[i]), 1);
  }
  void count(StateList, const char*, const char*, uint32_t& n, uint32_t) { u32(nullptr, n); }
  void slot(const char*, uint32_t, uint32_t& generation, bool& alive) {
    u32(nullptr, generation);
    boolean(nullptr, alive);
  }
};

/// Runs `visit` with the visitor's adapter (reading or not).
template <typename Visit>
void with_fields(FieldVisitor& v, Visit visit) {
  if (v.reading()) {
    FieldsOf<true> f{v};
    visit(f);
  } else {
    FieldsOf<false> f{v};
    visit(f);
  }
}

/// Runs `visit` with the broad-phase kind visited as naive when asked.
template <typename Visit>
void with_broad_phase(World& w, bool as_naive, Visit visit) {
  const BroadPhaseKind kind = w.def.broad_phase;
  if (as_naive) w.def.broad_phase = BroadPhaseKind::naive;
  visit();
  w.def.broad_phase = kind;
}

}  // namespace

void visit_world(WorldState& state, FieldVisitor& v, StateSections sections, bool broad_phase_as_naive) {
  World& w = as_world(state);
  with_broad_phase(w, broad_phase_as_naive, [&] {
    if (OutputBuffer* out = v.output_buffer()) {
      RawWriter f{*out};
      visit_all(f, w, sections);
    } else {
      FieldsOf<false> f{v};
      visit_all(f, w, sections);
    }
  });
}

void visit_world_header(WorldState& state, FieldVisitor& v, bool broad_phase_as_naive) {
  World& w = as_world(state);
  with_broad_phase(w, broad_phase_as_naive, [&] { with_fields(v, [&](auto& f) { visit_header(f, w); }); });
}

void visit_body_with_shapes(WorldState& state, int32_t body, FieldVisitor& v) {
  World& w = as_world(state);
  FieldsOf<false> f{v};
  const size_t b = static_cast<size_t>(body);
  state_fields::visit_body(f, w.bodies[b], w.body_sims[b]);
  for (int32_t s = w.bodies[b].head_shape; s != k_null_index; s = w.shapes[static_cast<size_t>(s)].next_shape) {
    state_fields::visit_shape(f, w.shapes[static_cast<size_t>(s)], w.shape_geometries[static_cast<size_t>(s)]);
  }
}

bool body_alive(const WorldState& state, int32_t body) { return id_pool_is_alive(as_world(state).body_pool, body); }

void visit_default_record(DefaultRecord record, int32_t variant, FieldVisitor& v) {
  FieldsOf<false> f{v};
  switch (record) {
    case DefaultRecord::world: {
      WorldDef d{};
      uint64_t steps = 0;
      int32_t solver_bodies = 0;
      state_fields::visit_world_def(f, d);
      v.u64("step_count", steps);
      v.i32("last_solver_body_count", solver_bodies);
      break;
    }
    case DefaultRecord::body: {
      Body b{};
      BodySim s{};
      state_fields::visit_body(f, b, s);
      break;
    }
    case DefaultRecord::shape: {
      Shape s{};
      ShapeGeometry g{};
      s.type = static_cast<ShapeType>(variant);
      g.polygon.count = 0;
      state_fields::visit_shape(f, s, g);
      break;
    }
    case DefaultRecord::contact: {
      Contact c{};
      c.manifold.point_count = variant;
      state_fields::visit_contact(f, c);
      break;
    }
    case DefaultRecord::joint: {
      Joint j{};
      state_fields::visit_joint(f, j);
      break;
    }
    case DefaultRecord::joint_event: {
      JointEvent e{};
      state_fields::visit_joint_event(f, e);
      break;
    }
  }
}

StateImagePtr new_image() { return StateImagePtr(new StateImage); }

StateImage& scratch_image() {
  thread_local StateImage image;
  return image;
}

void visit_image(StateImage& image, FieldVisitor& v, StateSections sections) {
  World& w = image.world;
  if (v.reading()) {
    w.joints.pending.clear();
    if (!sections.joints) {
      w.joint_pool = IdPool{};
      w.joints.joints.clear();
    }
  }
  with_fields(v, [&](auto& f) { visit_all(f, w, sections); });
}

bool visit_image_record(StateImage& image, RecordKind kind, int64_t index, FieldVisitor& v) {
  World& w = image.world;
  FieldsOf<false> f{v};
  const size_t i = static_cast<size_t>(index);
  const auto live = [&](const IdPool& pool) { return index >= 0 && i < pool.alive.size() && pool.alive[i] != 0; };
  switch (kind) {
    case RecordKind::world: state_fields::visit_world_def(f, w.def); return true;
    case RecordKind::body:
      if (!live(w.body_pool)) return false;
      state_fields::visit_body(f, w.bodies[i], w.body_sims[i]);
      return true;
    case RecordKind::shape:
      if (!live(w.shape_pool)) return false;
      state_fields::visit_shape(f, w.shapes[i], w.shape_geometries[i]);
      return true;
    case RecordKind::contact:
      if (index < 0 || i >= w.contacts.size()) return false;
      state_fields::visit_contact(f, w.contacts[i]);
      return true;
    case RecordKind::joint:
      if (!live(w.joint_pool)) return false;
      state_fields::visit_joint(f, w.joints.joints[i]);
      return true;
  }
  return false;
}

void commit_image(WorldState& state, StateImage& image) {
  World* w = &as_world(state);
  World& img = image.world;
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
  std::swap(w->joint_pool, img.joint_pool);
  std::swap(w->joints.joints, img.joints.joints);
  std::swap(w->joints.pending, img.joints.pending);
  std::swap(w->events.touching, img.events.touching);
  std::swap(w->events.sensor_overlaps, img.events.sensor_overlaps);
  rebuild_after_restore(w);
}

void rebuild_after_restore(World* w) {
  w->contact_scratch.clear();
  w->awake_contacts.clear();  // derived: the next update_contacts rebuilds it
  w->awake_contacts_all = false;
  w->awake_contacts_wake_count = ~uint64_t{0};
  w->contact_set_unchanged = false;
  w->joints.events.clear();
  for (JointEvent& e : w->joints.pending) {  // stale handles of this world
    e.joint.world = w->id;
    e.body_a.world = w->id;
    e.body_b.world = w->id;
  }
  rebuild_joint_filter(w);
  EventState& e = w->events;
  e.touching_next.clear();
  e.sensor_next.clear();
  e.hit_candidates.clear();
  events_clear_reported(&e);
  e.touching_in_sync = false;  // the next step diffs the restored touching set in full
  broad_phase_reset(w);
  // Buffers sized for the restored scene, so its next step does not allocate.
  reserve_contact_headroom(w);
  events_reserve_headroom(w);
}

}  // namespace tandem::state_access

// state_encode.cpp — canonical state encoding: sizes, snapshots, hashes
// (state.h describes the format, state_internal.h the design).
#include "replay/state_internal.h"

#define XXH_INLINE_ALL
#include <xxhash.h>

namespace tandem {
namespace state_detail {

// ---------------------------------------------------------------------------
// Sizes
// ---------------------------------------------------------------------------

template <typename F>
size_t measure(F&& f) {
  ByteWriter counter(nullptr, 0);
  WriteVisitor v{&counter};
  f(v);
  return counter.size();
}

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
    s.joint_event = measure([](WriteVisitor& v) {
      JointEvent e{};
      visit_joint_event(v, e);
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
  const uint32_t version = image_version(w);
  if (version >= k_state_format_version_joint_events) {
    n += 4 + 4 + w.joints.pending.size() * rs.joint_event;
  }
  if (version >= k_state_format_version_joints) {
    n += 4 + 4 + w.joint_pool.generations.size() * k_slot_bytes;
    n += 4 + static_cast<size_t>(w.joint_pool.alive_count) * rs.joint;
  }
  return n;
}

void write_header(ByteWriter* out, uint32_t version) {
  out->bytes(k_state_magic, 4);
  out->u32(version);
  out->u32(k_state_kind_full);
}

size_t encode_into(World* w, uint8_t* buffer, size_t capacity) {
  ByteWriter out(buffer, capacity);
  const uint32_t version = image_version(*w);
  write_header(&out, version);
  WriteVisitor v{&out};
  visit_world(v, *w, nullptr, version);
  return out.size();
}

Status resolve_for_state(WorldId id, const char* function, bool mutating, World** out) {
  return resolve_world(id, function, mutating, out);
}

std::vector<uint8_t>& scratch_bytes() {
  thread_local std::vector<uint8_t> bytes;
  return bytes;
}

}  // namespace state_detail

using namespace state_detail;

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

}  // namespace tandem

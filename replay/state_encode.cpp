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

size_t measure_default(DefaultRecord record, int32_t variant) {
  return measure([&](WriteVisitor& v) { visit_default_record(record, variant, v); });
}

const RecordSizes& record_sizes() {
  static const RecordSizes sizes = [] {
    RecordSizes s;
    s.world = measure_default(DefaultRecord::world, 0);
    s.body = measure_default(DefaultRecord::body, 0);
    for (int32_t t = 0; t < 5; ++t) s.shape[t] = measure_default(DefaultRecord::shape, t);
    s.contact = measure_default(DefaultRecord::contact, 0);
    s.contact_point = measure_default(DefaultRecord::contact, 1) - s.contact;
    s.joint = measure_default(DefaultRecord::joint, 0);
    s.joint_event = measure_default(DefaultRecord::joint_event, 0);
    return s;
  }();
  return sizes;
}

size_t min_record_bytes(StateList list) {
  switch (list) {
    case StateList::body_slots:
    case StateList::shape_slots:
    case StateList::joint_slots: return k_slot_bytes;
    case StateList::contacts: return record_sizes().contact;
    case StateList::touching:
    case StateList::sensor_overlaps: return k_pair_bytes;
    case StateList::pending_joint_events: return k_min_joint_event_bytes;
  }
  return 1;
}

size_t encoded_size(const StateCensus& c) {
  const RecordSizes& rs = record_sizes();
  size_t n = k_header_bytes + 4 + rs.world;
  n += 4 + 4 + c.body_slots * k_slot_bytes;
  n += 4 + c.bodies * rs.body;
  n += 4 + 4 + c.shape_slots * k_slot_bytes;
  n += 4;
  for (size_t t = 0; t < 5; ++t) n += c.shapes_by_type[t] * rs.shape[t];
  n += c.polygon_vertices * rs.polygon_vertex;
  n += 4 + 4 + c.contacts * rs.contact + c.contact_points * rs.contact_point;
  n += 4 + 4 + c.touching * k_pair_bytes;
  n += 4 + 4 + c.sensor_overlaps * k_pair_bytes;
  const uint32_t version = image_version(c);
  if (version >= k_state_format_version_joint_events) n += 4 + 4 + c.pending_joint_events * rs.joint_event;
  if (version >= k_state_format_version_joints) {
    n += 4 + 4 + c.joint_slots * k_slot_bytes;
    n += 4 + c.joints * rs.joint;
  }
  return n;
}

void write_header(ByteWriter* out, uint32_t version) {
  out->bytes(k_state_magic, 4);
  out->u32(version);
  out->u32(k_state_kind_full);
}

size_t encode_into(WorldState& world, const StateCensus& census, uint8_t* buffer, size_t capacity,
                   bool broad_phase_as_naive, bool per_field) {
  ByteWriter out(buffer, capacity);
  const uint32_t version = image_version(census);
  write_header(&out, version);
  WriteVisitor v{&out};
  OutputBuffer raw{buffer, capacity, out.size()};
  if (!per_field) v.raw = &raw;
  visit_world(world, v, sections_of(version), broad_phase_as_naive);
  return per_field ? out.size() : raw.size;
}

std::vector<uint8_t>& scratch_bytes() {
  thread_local std::vector<uint8_t> bytes;
  return bytes;
}

void DescribeVisitor::record(const char* kind, int64_t index, int64_t index2, uint32_t generation) {
  DecodedRecord rec;
  rec.kind = kind;
  rec.index = index;
  rec.index2 = index2;
  rec.generation = generation;
  out->records.push_back(std::move(rec));
}

}  // namespace state_detail

using namespace state_detail;

// ---------------------------------------------------------------------------
// Public API
// ---------------------------------------------------------------------------

size_t world_snapshot_size(WorldId world) {
  WorldState* w = find_world_state(world, false);
  return w == nullptr ? 0 : encoded_size(census(*w));
}

Status world_snapshot(WorldId world, uint8_t* buffer, size_t capacity, size_t* written) {
  WorldState* w = nullptr;
  Status s = resolve_world_state(world, "world_snapshot", true, &w);
  if (!s.ok()) return s;
  const StateCensus c = census(*w);
  const size_t needed = encoded_size(c);
  if (written != nullptr) *written = needed;
  if (capacity < needed || (buffer == nullptr && needed != 0)) {
    return Status{StatusCode::capacity_exceeded, "world_snapshot: the buffer holds " + std::to_string(capacity) +
                                                          " bytes; the snapshot of " + describe(world) + " needs " +
                                                          std::to_string(needed)};
  }
  const size_t n = encode_into(*w, c, buffer, capacity, false);
  TANDEM_ASSERT(n == needed);
  (void)n;
  return s;
}

Status world_snapshot_append(WorldId world, std::vector<uint8_t>* out) {
  WorldState* w = nullptr;
  Status s = resolve_world_state(world, "world_snapshot_append", true, &w);
  if (!s.ok()) return s;
  const StateCensus c = census(*w);
  const size_t needed = encoded_size(c);
  const size_t old = out->size();
  out->resize(old + needed);
  const size_t n = encode_into(*w, c, out->data() + old, needed, false);
  TANDEM_ASSERT(n == needed);
  (void)n;
  return s;
}

Status encode_world_state(WorldId world, std::vector<uint8_t>* out) {
  WorldState* w = nullptr;
  Status s = resolve_world_state(world, "encode_world_state", true, &w);
  if (!s.ok()) return s;
  out->clear();
  return world_snapshot_append(world, out);
}

uint64_t world_state_hash(WorldId world) {
  WorldState* w = find_world_state(world, true);
  if (w == nullptr) return 0;
  std::vector<uint8_t>& buf = scratch_bytes();
  const StateCensus c = census(*w);
  const size_t needed = encoded_size(c);
  if (buf.size() < needed) buf.resize(needed);
  // The broad-phase kind is kept in snapshots (a restore brings it back) but
  // by contract changes no result, so the hash sees every world as naive:
  // the same simulation hashes the same whichever broad phase ran it.
  const size_t n = encode_into(*w, c, buf.data(), buf.size(), true);
  TANDEM_ASSERT(n == needed);
  return XXH3_64bits(buf.data(), n);
}

namespace {
uint64_t hash_body(WorldState& w, int32_t index) {
  std::vector<uint8_t>& buf = scratch_bytes();
  buf.clear();
  ByteWriter out(&buf);
  WriteVisitor v{&out};
  visit_body_with_shapes(w, index, v);
  return XXH3_64bits(buf.data(), buf.size());
}
}  // namespace

uint64_t body_state_hash(BodyId body) {
  int32_t index = 0;
  WorldState* w = find_body_state(body, &index);
  return w == nullptr ? 0 : hash_body(*w, index);
}

Status world_body_hashes(WorldId world, std::vector<uint64_t>* out) {
  WorldState* w = nullptr;
  Status s = resolve_world_state(world, "world_body_hashes", true, &w);
  if (!s.ok()) return s;
  const int32_t cap = static_cast<int32_t>(census(*w).body_slots);
  out->assign(static_cast<size_t>(cap), 0);
  for (int32_t i = 0; i < cap; ++i) {
    if (body_alive(*w, i)) (*out)[static_cast<size_t>(i)] = hash_body(*w, i);
  }
  return s;
}

}  // namespace tandem

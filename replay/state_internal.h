// state_internal.h — what the canonical-state files share (internal, not
// installed): the field visitors that turn physics' field lists into bytes
// and back, record sizes, and the shared declarations.
//
// Files (state.h describes the format):
//   state_internal.h   visitors, record sizes, shared declarations
//   state_encode.cpp   sizes, encoding, snapshot and hash API
//   state_restore.cpp  decoding, restore, decode/locate API
//   state_diff.cpp     deltas against a base image, field-level diffs
//
// DESIGN. physics owns the state: which records and fields a world holds and
// in which order (physics/state_fields.h), the checks of a decoded image and
// the rebuild after a restore (physics/state_access.h, the only physics
// header here besides the public ones). replay owns the bytes. It implements
// physics' FieldVisitor four times:
//   WriteVisitor     fields → bytes (ByteWriter; a null buffer only counts)
//   ReadVisitor      bytes → fields (ByteReader; names go into messages)
//   DescribeVisitor  fields → DecodedRecord named fields (diffs)
//   OffsetVisitor    a field's byte offset inside its record (messages)
// so encode, decode, size and diff cannot disagree about the order. The
// exact encoded size is computed arithmetically from a census of the world
// and per-record sizes that are measured once by running the WriteVisitor in
// counting mode over default records.
//
// Restore decodes into a StateImage (physics' scratch world, reused so warm
// rollbacks do not allocate), has physics check it, then commits it.
#pragma once

#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "physics/state_access.h"
#include "replay/bytes.h"
#include "replay/state.h"

namespace tandem::state_detail {

using namespace state_access;

inline constexpr uint32_t k_state_kind_full = 0;
inline constexpr size_t k_header_bytes = 12;  // magic, version, kind
inline constexpr size_t k_world_record_offset = k_header_bytes + 4;  // after the "WRLD" tag
inline constexpr size_t k_slot_bytes = 5;   // generation u32 + alive u8
inline constexpr size_t k_pair_bytes = 16;
/// The least bytes of a pending joint event record, for read_count.
inline constexpr size_t k_min_joint_event_bytes = 53;

/// Byte offsets of the records of a decoded image (reader only), by their
/// position in their section, for messages.
struct ImageOffsets {
  std::vector<size_t> body;     // by body index
  std::vector<size_t> shape;    // by shape index
  std::vector<size_t> contact;  // by contact order
  std::vector<size_t> joint;    // by joint index
};

/// The smallest encoded record of a list, for read_count.
size_t min_record_bytes(StateList list);

// ---------------------------------------------------------------------------
// Visitors
// ---------------------------------------------------------------------------

/// Fields → bytes.
struct WriteVisitor final : FieldVisitor {
  ByteWriter* w;
  /// When set, physics writes a whole world's bytes here itself (the same
  /// bytes, without a call per field; encode_into).
  OutputBuffer* raw = nullptr;
  explicit WriteVisitor(ByteWriter* writer) : w(writer) {}
  OutputBuffer* output_buffer() override { return raw; }
  bool reading() const override { return false; }
  void record(const char*, int64_t, int64_t, uint32_t) override {}
  void tag(const char* t) override { w->bytes(reinterpret_cast<const uint8_t*>(t), 4); }
  void q32(const char*, Q32& v) override { w->q32(v); }
  void vec2(const char*, const char*, Vec2& v) override { w->vec2(v); }
  void i32(const char*, int32_t& v) override { w->i32(v); }
  void u32(const char*, uint32_t& v) override { w->u32(v); }
  void u16(const char*, uint16_t& v) override { w->u16(v); }
  void u64(const char*, uint64_t& v) override { w->u64(v); }
  void boolean(const char*, bool& v) override { w->boolean(v); }
  void enum8(const char*, int32_t& v, int32_t) override { w->u8(static_cast<uint8_t>(v)); }
  void ranged_i32(const char*, int32_t& v, int32_t, int32_t) override { w->i32(v); }
  void count(StateList, const char*, const char*, uint32_t& n, uint32_t) override { w->u32(n); }
  void slot(const char*, uint32_t, uint32_t& generation, bool& alive) override {
    w->u32(generation);
    w->boolean(alive);
  }
  bool ok() const override { return true; }
};

/// Bytes → fields, with checks; records the offsets of the records read.
struct ReadVisitor final : FieldVisitor {
  ByteReader* r;
  ImageOffsets* offsets;  ///< may be null
  ReadVisitor(ByteReader* reader, ImageOffsets* out_offsets) : r(reader), offsets(out_offsets) {}
  bool reading() const override { return true; }
  void record(const char* kind, int64_t index, int64_t, uint32_t) override { r->set_context(kind, index); }
  void begin_read(const char* kind, int64_t position) override;
  void tag(const char* t) override;
  void q32(const char* name, Q32& v) override;
  void vec2(const char* nx, const char* ny, Vec2& v) override {
    q32(nx, v.x);
    q32(ny, v.y);
  }
  void i32(const char* name, int32_t& v) override { v = r->i32(name); }
  void u32(const char* name, uint32_t& v) override { v = r->u32(name); }
  void u16(const char* name, uint16_t& v) override { v = r->u16(name); }
  void u64(const char* name, uint64_t& v) override { v = r->u64(name); }
  void boolean(const char* name, bool& v) override { v = r->boolean(name); }
  void enum8(const char* name, int32_t& v, int32_t max) override;
  void ranged_i32(const char* name, int32_t& v, int32_t lo, int32_t hi) override;
  void count(StateList list, const char* context, const char* name, uint32_t& n, uint32_t max) override {
    r->set_context(context);
    n = r->read_count(name, min_record_bytes(list), max);
  }
  void slot(const char* kind, uint32_t index, uint32_t& generation, bool& alive) override;
  bool ok() const override { return r->ok(); }
};

/// Fields → named DecodedRecord fields (over an already decoded image).
struct DescribeVisitor final : FieldVisitor {
  DecodedState* out;
  explicit DescribeVisitor(DecodedState* decoded) : out(decoded) {}
  bool reading() const override { return false; }
  void record(const char* kind, int64_t index, int64_t index2, uint32_t generation) override;
  void field(const char* name, int64_t v, bool q) { out->records.back().fields.push_back({name, v, q}); }
  void tag(const char*) override {}
  void q32(const char* name, Q32& v) override { field(name, v.raw, true); }
  void vec2(const char* nx, const char* ny, Vec2& v) override {
    field(nx, v.x.raw, true);
    field(ny, v.y.raw, true);
  }
  void i32(const char* name, int32_t& v) override { field(name, v, false); }
  void u32(const char* name, uint32_t& v) override { field(name, v, false); }
  void u16(const char* name, uint16_t& v) override { field(name, v, false); }
  void u64(const char* name, uint64_t& v) override { field(name, static_cast<int64_t>(v), false); }
  void boolean(const char* name, bool& v) override { field(name, v ? 1 : 0, false); }
  void enum8(const char* name, int32_t& v, int32_t) override { field(name, v, false); }
  void ranged_i32(const char* name, int32_t& v, int32_t, int32_t) override { field(name, v, false); }
  void count(StateList, const char*, const char*, uint32_t&, uint32_t) override {}
  void slot(const char* kind, uint32_t index, uint32_t& generation, bool& alive) override {
    record(kind, index, -1, generation);
    field("generation", generation, false);
    field("alive", alive ? 1 : 0, false);
  }
  bool ok() const override { return true; }
};

/// Finds the byte offset of a named field inside one record by walking the
/// record's field list in counting mode.
struct OffsetVisitor final : FieldVisitor {
  ByteWriter* w;
  const char* target;
  size_t found = SIZE_MAX;
  OffsetVisitor(ByteWriter* counter, const char* field) : w(counter), target(field) {}
  void mark(const char* name) {
    if (found == SIZE_MAX && std::strcmp(name, target) == 0) found = w->size();
  }
  bool reading() const override { return false; }
  void record(const char*, int64_t, int64_t, uint32_t) override {}
  void tag(const char*) override { w->bytes(reinterpret_cast<const uint8_t*>("TAGS"), 4); }
  void q32(const char* n, Q32& v) override {
    mark(n);
    w->q32(v);
  }
  void vec2(const char* nx, const char* ny, Vec2& v) override {
    mark(nx);
    w->q32(v.x);
    mark(ny);
    w->q32(v.y);
  }
  void i32(const char* n, int32_t& v) override {
    mark(n);
    w->i32(v);
  }
  void u32(const char* n, uint32_t& v) override {
    mark(n);
    w->u32(v);
  }
  void u16(const char* n, uint16_t& v) override {
    mark(n);
    w->u16(v);
  }
  void u64(const char* n, uint64_t& v) override {
    mark(n);
    w->u64(v);
  }
  void boolean(const char* n, bool& v) override {
    mark(n);
    w->boolean(v);
  }
  void enum8(const char* n, int32_t& v, int32_t) override {
    mark(n);
    w->u8(static_cast<uint8_t>(v));
  }
  void ranged_i32(const char* n, int32_t& v, int32_t, int32_t) override {
    mark(n);
    w->i32(v);
  }
  void count(StateList, const char*, const char* n, uint32_t& v, uint32_t) override {
    mark(n);
    w->u32(v);
  }
  void slot(const char*, uint32_t, uint32_t& generation, bool& alive) override {
    u32("generation", generation);
    boolean("alive", alive);
  }
  bool ok() const override { return true; }
};

/// The byte offset of `field` inside the record that `visit` walks with an
/// OffsetVisitor (0 when the record has no such field).
template <typename F>
size_t field_offset_in(const char* field, F&& visit) {
  ByteWriter counter(nullptr, 0);
  OffsetVisitor v{&counter, field};
  visit(v);
  return v.found == SIZE_MAX ? 0 : v.found;
}

// ---------------------------------------------------------------------------
// Shared between the files (defined where noted)
// ---------------------------------------------------------------------------

struct RecordSizes {
  size_t world = 0;           // def + step count + solver count (no tag)
  size_t body = 0;
  size_t shape[5] = {};       // by ShapeType; polygon: with 0 vertices
  size_t polygon_vertex = 32; // vertex + normal
  size_t contact = 0;         // with no points
  size_t contact_point = 0;
  size_t joint = 0;
  size_t joint_event = 0;
};

/// The format version an image of a world with this census is written in:
/// 1 for worlds that never had a joint (the format before joints, byte for
/// byte), 3 while joint events wait for the next step (joints destroyed with
/// a body since the last step), 2 otherwise (so the images and hashes of
/// every tick after a step are those of version 2).
inline uint32_t image_version(const StateCensus& c) {
  if (c.joint_slots == 0 && c.pending_joint_events == 0) return k_state_format_version;
  return c.pending_joint_events == 0 ? k_state_format_version_joints : k_state_format_version_joint_events;
}
/// The sections an image of `version` holds after the version-1 ones.
inline StateSections sections_of(uint32_t version) {
  return StateSections{version >= k_state_format_version_joints, version >= k_state_format_version_joint_events};
}

// state_encode.cpp
const RecordSizes& record_sizes();
size_t encoded_size(const StateCensus& census);
/// Encodes into buffer[0, capacity); returns the size (> capacity: nothing
/// past the capacity was written). per_field: through WriteVisitor's own
/// methods instead of physics' direct writer (the same bytes; tests compare).
size_t encode_into(WorldState& world, const StateCensus& census, uint8_t* buffer, size_t capacity,
                   bool broad_phase_as_naive, bool per_field = false);
std::vector<uint8_t>& scratch_bytes();

// state_restore.cpp
/// Decodes a full image into *img and has physics check it. Returns an
/// error Status (invalid_argument, "<function>: offset N: expected ...").
Status decode_image(const uint8_t* data, size_t size, const char* function, StateImage* img, ImageOffsets* offsets,
                    uint32_t* out_version);

}  // namespace tandem::state_detail

// state_restore.cpp — structural decoding of a state image, restore, decode and locate
// (state.h describes the format, state_internal.h the design).
#include "replay/state_internal.h"

namespace tandem {
namespace state_detail {

// ---------------------------------------------------------------------------
// ReadVisitor
// ---------------------------------------------------------------------------

void ReadVisitor::begin_read(const char* kind, int64_t position) {
  r->set_context(kind, position);
  if (offsets == nullptr) return;
  std::vector<size_t>* table = nullptr;
  if (std::strcmp(kind, "body") == 0) {
    table = &offsets->body;
  } else if (std::strcmp(kind, "shape") == 0) {
    table = &offsets->shape;
  } else if (std::strcmp(kind, "contact") == 0) {
    table = &offsets->contact;
  } else if (std::strcmp(kind, "joint") == 0) {
    table = &offsets->joint;
  } else {
    return;
  }
  const size_t i = static_cast<size_t>(position);
  if (table->size() <= i) table->resize(i + 1);
  (*table)[i] = r->offset();
}

void ReadVisitor::tag(const char* t) {
  const size_t at = r->offset();
  const std::span<const uint8_t> b = r->bytes(4, (std::string("section tag ") + t).c_str());
  if (b.size() == 4 && std::memcmp(b.data(), t, 4) != 0) {
    r->fail_at(at, std::string("expected section tag \"") + t + "\"");
  }
}

void ReadVisitor::q32(const char* name, Q32& v) {
  const size_t at = r->offset();
  v = r->q32(name);
  if (v.raw == INT64_MIN) r->fail_at(at, "expected " + r->describe_what(name) + " (Q32.32), got raw INT64_MIN");
}

void ReadVisitor::enum8(const char* name, int32_t& v, int32_t max) {
  const size_t at = r->offset();
  const uint8_t raw = r->u8(name);
  if (!r->ok()) return;
  if (raw > max) {
    r->fail_at(at, "expected " + r->describe_what(name) + " 0.." + std::to_string(max) + ", got " + std::to_string(raw));
    return;
  }
  v = raw;
}

void ReadVisitor::ranged_i32(const char* name, int32_t& v, int32_t lo, int32_t hi) {
  const size_t at = r->offset();
  const int32_t x = r->i32(name);
  if (!r->ok()) return;
  if (x < lo || x > hi) {
    r->fail_at(at, "expected " + r->describe_what(name) + " in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                       "], got " + std::to_string(x));
    return;
  }
  v = x;
}

void ReadVisitor::slot(const char* kind, uint32_t index, uint32_t& generation, bool& alive) {
  record(kind, index, -1, 0);
  generation = r->u32("generation");
  alive = r->boolean("alive");
  if (r->ok() && generation == 0) {
    r->fail_at(r->offset() - k_slot_bytes, r->describe_what("generation") + ": expected ≥ 1, got 0");
  }
}

// ---------------------------------------------------------------------------
// Decoding
// ---------------------------------------------------------------------------

namespace {

/// The byte offset of a record of a decoded image.
size_t record_offset(const ImageOffsets& offsets, RecordKind kind, int64_t index) {
  const size_t i = static_cast<size_t>(index);
  const auto at = [&](const std::vector<size_t>& table) { return i < table.size() ? table[i] : 0; };
  switch (kind) {
    case RecordKind::world: return k_world_record_offset;
    case RecordKind::body: return at(offsets.body);
    case RecordKind::shape: return at(offsets.shape);
    case RecordKind::contact: return at(offsets.contact);
    case RecordKind::joint: return at(offsets.joint);
  }
  return 0;
}

/// Where physics refused an image, as a byte offset ("offset N: ...").
std::string refusal_text(StateImage& img, const ImageOffsets& offsets, const StateRefusal& refusal) {
  if (refusal.where == StateRefusal::Where::none) return refusal.message;
  size_t at = record_offset(offsets, refusal.kind, refusal.index);
  if (refusal.where == StateRefusal::Where::field) {
    at += field_offset_in(refusal.field,
                          [&](OffsetVisitor& v) { (void)visit_image_record(img, refusal.kind, refusal.index, v); });
  }
  return "offset " + std::to_string(at) + ": " + refusal.message;
}

}  // namespace

Status decode_image(const uint8_t* data, size_t size, const char* function, StateImage* img, ImageOffsets* offsets,
                    uint32_t* out_version) {
  ByteReader r(data, size);
  const auto bad = [&](const std::string& msg) {
    return Status{StatusCode::invalid_argument, std::string(function) + ": " + msg};
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
  if (version != k_state_format_version && version != k_state_format_version_joints &&
      version != k_state_format_version_joint_events) {
    return bad("offset 4: expected format version " + std::to_string(k_state_format_version) + ", " +
               std::to_string(k_state_format_version_joints) + " or " +
               std::to_string(k_state_format_version_joint_events) + ", got " + std::to_string(version));
  }
  if (out_version != nullptr) *out_version = version;
  const uint32_t kind = r.u32("image kind");
  if (!r.ok()) return bad(r.error());
  if (kind != k_state_kind_full) {
    return bad("offset 8: expected image kind 0 (full state), got " + std::to_string(kind));
  }

  ReadVisitor v{&r, offsets};
  visit_image(*img, v, sections_of(version));
  if (!r.ok()) return bad(r.error());
  if (!r.at_end()) {
    return bad("offset " + std::to_string(r.offset()) + ": expected the end of the image, " +
               std::to_string(r.remaining()) + " bytes left over");
  }
  StateRefusal refusal;
  if (!check_image(*img, &refusal)) return bad(refusal_text(*img, *offsets, refusal));
  return Status{};
}

ImageOffsets& scratch_offsets() {
  thread_local ImageOffsets offsets;
  return offsets;
}

}  // namespace state_detail

using namespace state_detail;

// ---------------------------------------------------------------------------
// Public API: restore, decode, locate
// ---------------------------------------------------------------------------

Status world_restore(WorldId world, const uint8_t* data, size_t size) {
  WorldState* w = nullptr;
  Status s = resolve_world_state(world, "world_restore", true, &w);
  if (!s.ok()) return s;
  StateImage& img = scratch_image();
  s = decode_image(data, size, "world_restore", &img, &scratch_offsets(), nullptr);
  if (!s.ok()) return s;
  commit_image(*w, img);
  return s;
}

Result<WorldId> create_world_from_snapshot(const uint8_t* data, size_t size) {
  Result<WorldId> result = create_world(default_world_def());
  if (!result.ok()) return result;
  Status s = world_restore(result.value, data, size);
  if (!s.ok()) {
    (void)destroy_world(result.value);  // just created: cannot fail
    result.value = WorldId{};
    result.status = Status{s.code, "create_world_from_snapshot: " + s.message};
  }
  return result;
}

Status decode_world_state(const uint8_t* data, size_t size, DecodedState* out) {
  StateImagePtr img = new_image();
  ImageOffsets offsets;
  uint32_t version = 0;
  Status s = decode_image(data, size, "decode_world_state", img.get(), &offsets, &version);
  if (!s.ok()) return s;
  out->version = version;
  out->records.clear();
  DescribeVisitor v{out};
  visit_image(*img, v, sections_of(version));
  return s;
}

Status locate_state_field(const uint8_t* data, size_t size, const std::string& kind, int64_t index,
                          const std::string& field, size_t* out_offset) {
  StateImagePtr img = new_image();
  ImageOffsets offsets;
  Status s = decode_image(data, size, "locate_state_field", img.get(), &offsets, nullptr);
  if (!s.ok()) return s;
  const auto missing = [&](const std::string& what) {
    return Status{StatusCode::invalid_argument, "locate_state_field: " + what};
  };
  RecordKind record = RecordKind::world;
  if (kind == "world") {
    index = 0;
  } else if (kind == "body") {
    record = RecordKind::body;
  } else if (kind == "shape") {
    record = RecordKind::shape;
  } else if (kind == "contact") {
    record = RecordKind::contact;
  } else {
    return missing("unknown record kind \"" + kind + "\" (world, body, shape or contact)");
  }
  ByteWriter counter(nullptr, 0);
  OffsetVisitor v{&counter, field.c_str()};
  if (!visit_image_record(*img, record, index, v)) {
    return missing(kind + " " + std::to_string(index) +
                   (record == RecordKind::contact ? " is not in the image" : " is not alive in the image"));
  }
  if (v.found == SIZE_MAX) return missing(kind + " has no field \"" + field + "\"");
  *out_offset = record_offset(offsets, record, index) + v.found;
  return s;
}

}  // namespace tandem

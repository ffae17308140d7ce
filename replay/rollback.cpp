// rollback.cpp — the compact rollback snapshot (rollback.h describes what it
// holds and why that is enough).
//
// DESIGN. replay owns the image's frame: the header (magic "TNDR", u32
// version), the buffer and its reuse, and the hash. The records after the
// header are physics' (physics/state_compact.cpp lays them out and lists,
// record by record, which fields are packed, carried beside the image or
// recomputed): replay asks for them through physics/state_access.h
// (write_compact_records, check_compact_records, apply_compact_records), as
// the portable format asks for its field lists. The first record byte is the
// broad-phase kind, which rollback_hash skips.
//
// Restore checks the whole image first (header here, records in physics)
// and changes the world only once it is accepted, so a refused image changes
// nothing.
#include "replay/rollback.h"

#include <cstring>
#include <string>

#define XXH_INLINE_ALL
#include <xxhash.h>

#include "fixed/str_cat.h"
#include "physics/state_access.h"

namespace tandem {

namespace {

/// The header: magic and version; the records start with the broad-phase kind.
constexpr size_t k_header_bytes = 8;
/// rollback_hash hashes from here: everything but the header and the kind.
constexpr size_t k_hashed_from = k_header_bytes + 1;

void store_u32(uint8_t* p, uint32_t v) {
  for (size_t i = 0; i < 4; ++i) p[i] = static_cast<uint8_t>(v >> (8 * i));
}

uint32_t load_u32(const uint8_t* p) {
  uint32_t v = 0;
  for (size_t i = 0; i < 4; ++i) v |= static_cast<uint32_t>(p[i]) << (8 * i);
  return v;
}

Status refuse(size_t at, const std::string& what) {
  return Status{StatusCode::invalid_argument, str_cat("rollback_restore: offset ", std::to_string(at), ": ", what)};
}

}  // namespace

Status rollback_save(WorldId world, RollbackBuffer* buffer) {
  state_access::WorldState* w = nullptr;
  Status s = state_access::resolve_world_state(world, "rollback_save", true, &w);
  if (!s.ok()) return s;
  if (buffer == nullptr) return Status{StatusCode::invalid_argument, "rollback_save: buffer is null"};
  // The records are written into the thread's scratch, sized for their upper
  // bound (several times the image: every contact counted as a full record),
  // and then copied into the image: growing the image itself to the bound
  // zero-filled the bytes beyond the last image on every save, which cost
  // more than writing the records.
  thread_local std::vector<uint8_t> scratch;
  const size_t bound = k_header_bytes + state_access::compact_records_bound(*w);
  if (scratch.size() < bound) scratch.resize(bound);
  std::memcpy(scratch.data(), k_rollback_magic, 4);
  store_u32(scratch.data() + 4, k_rollback_format_version);
  const size_t n = state_access::write_compact_records(*w, scratch.data() + k_header_bytes,
                                                       {&buffer->geometries, &buffer->masses});
  buffer->image.assign(scratch.data(), scratch.data() + k_header_bytes + n);
  return s;
}

Status rollback_restore(WorldId world, const RollbackBuffer& buffer) {
  state_access::WorldState* w = nullptr;
  Status s = state_access::resolve_world_state(world, "rollback_restore", true, &w);
  if (!s.ok()) return s;
  const uint8_t* data = buffer.image.data();
  const size_t size = buffer.image.size();
  if (size < k_hashed_from) {
    return refuse(0, str_cat("expected ", std::to_string(k_hashed_from),
                         " bytes of header (magic, version, broad-phase kind), ", std::to_string(size), " left"));
  }
  if (std::memcmp(data, k_rollback_magic, 4) != 0) return refuse(0, "expected magic \"TNDR\" (a compact rollback image)");
  const uint32_t version = load_u32(data + 4);
  if (version != k_rollback_format_version) {
    return refuse(4, str_cat("expected rollback format version ", std::to_string(k_rollback_format_version), ", got ",
                         std::to_string(version)));
  }
  const state_access::CompactStructureView structure{&buffer.geometries, &buffer.masses};
  std::string error;
  if (!state_access::check_compact_records(data, size, k_header_bytes, structure, &error)) {
    return Status{StatusCode::invalid_argument, str_cat("rollback_restore: ", error)};
  }
  state_access::apply_compact_records(*w, data, size, k_header_bytes, structure);
  return s;
}

uint64_t rollback_hash(const RollbackBuffer& buffer) {
  if (buffer.image.size() < k_hashed_from) return 0;
  return XXH3_64bits(buffer.image.data() + k_hashed_from, buffer.image.size() - k_hashed_from);
}

}  // namespace tandem

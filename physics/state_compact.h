// state_compact.h — what state_compact.cpp (save) and
// state_compact_restore.cpp (check and apply) share (internal to physics):
// the compact rollback image's bit assignments, explicit little-endian loads
// and stores, the geometry copy, and the two template visitors that write and
// read the records kept whole (world settings, full contacts, joints, joint
// events) through the field lists of state_fields.h. state_compact.cpp
// describes the layout; replay/rollback.h what the image holds and why.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <string>

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

namespace tandem::compact_detail {

using state_access::StateList;
using state_fields::FieldRangeFailure;
using state_fields::first_joint_field_out_of_range;
using state_fields::visit_contact;
using state_fields::visit_joint;
using state_fields::visit_joint_event;
using state_fields::visit_world_def;

// Explicit little-endian loads and stores of one value: a copy of the value's
// bytes, swapped on a big-endian host, so each compiles to one move on
// x86-64 and aarch64 (the byte-shift form of bytes.h does not always fold
// inside the long save and restore loops). The bytes are the same on every
// host.
inline void store_le64(uint8_t* p, uint64_t v) {
  if constexpr (std::endian::native == std::endian::big) v = __builtin_bswap64(v);
  std::memcpy(p, &v, 8);
}
inline void store_le32(uint8_t* p, uint32_t v) {
  if constexpr (std::endian::native == std::endian::big) v = __builtin_bswap32(v);
  std::memcpy(p, &v, 4);
}
inline void store_le16(uint8_t* p, uint16_t v) {
  if constexpr (std::endian::native == std::endian::big) v = __builtin_bswap16(v);
  std::memcpy(p, &v, 2);
}
inline uint64_t load_le64(const uint8_t* p) {
  uint64_t v;
  std::memcpy(&v, p, 8);
  if constexpr (std::endian::native == std::endian::big) v = __builtin_bswap64(v);
  return v;
}
inline uint32_t load_le32(const uint8_t* p) {
  uint32_t v;
  std::memcpy(&v, p, 4);
  if constexpr (std::endian::native == std::endian::big) v = __builtin_bswap32(v);
  return v;
}
inline uint16_t load_le16(const uint8_t* p) {
  uint16_t v;
  std::memcpy(&v, p, 2);
  if constexpr (std::endian::native == std::endian::big) v = __builtin_bswap16(v);
  return v;
}


// Body flag bits.
inline constexpr uint8_t k_body_type_mask = 3;
inline constexpr uint8_t k_body_enable_sleep = 1u << 2;
inline constexpr uint8_t k_body_awake = 1u << 3;
inline constexpr uint8_t k_body_enabled = 1u << 4;
inline constexpr uint8_t k_body_fixed_rotation = 1u << 5;
inline constexpr uint8_t k_body_bullet = 1u << 6;
// Body presence bits.
inline constexpr uint8_t k_has_velocity = 1u << 0;
inline constexpr uint8_t k_has_force = 1u << 1;
inline constexpr uint8_t k_has_sleep_time = 1u << 2;
inline constexpr uint8_t k_has_sleep_island = 1u << 3;
inline constexpr uint8_t k_has_user_data = 1u << 4;
inline constexpr uint8_t k_has_damping = 1u << 5;
inline constexpr uint8_t k_has_gravity_scale = 1u << 6;
// Shape bits (type in the low 3).
inline constexpr uint8_t k_shape_type_mask = 7;
inline constexpr uint8_t k_shape_sensor = 1u << 3;
inline constexpr uint8_t k_shape_hit_events = 1u << 4;
inline constexpr uint8_t k_shape_has_materials = 1u << 5;
inline constexpr uint8_t k_shape_has_filter = 1u << 6;
inline constexpr uint8_t k_shape_has_user_data = 1u << 7;
// Contact header bits.
inline constexpr uint8_t k_contact_count_mask = 3;
inline constexpr uint8_t k_contact_full = 1u << 2;

inline constexpr size_t k_max_body_bytes = 2 + 32 + 24 + 24 + 8 + 4 + 8 + 16 + 8;
inline constexpr size_t k_max_shape_bytes = 4 + 1 + 24 + 20 + 8;
inline constexpr size_t k_compact_point_bytes = 2 + 8 + 8;

inline const ShapeDef& default_shape() {
  static const ShapeDef def = default_shape_def();
  return def;
}

inline bool default_materials(const Shape& s) {
  const ShapeDef& d = default_shape();
  return s.friction == d.friction && s.restitution == d.restitution && s.density == d.density;
}

inline bool default_filter(const Filter& f) {
  const Filter d{};
  return f.category_bits == d.category_bits && f.mask_bits == d.mask_bits && f.group_index == d.group_index;
}

/// Copies the active variant only (the others are not state).
inline void copy_geometry(const ShapeGeometry& from, ShapeGeometry* to) {
  if (to->type != from.type) *to = ShapeGeometry{};  // stale variants as a fresh record has them
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

// Ranges restored (the portable restore's, physics/state_check.cpp).
inline constexpr Q32 k_max_coordinate = k_max_world_coordinate * 2;
inline constexpr Q32 k_max_speed = k_max_linear_speed * 4;
inline constexpr Q32 k_max_spin = k_max_angular_speed * 64;  // small bodies spin fast; the rim speed is what matters
inline constexpr Q32 k_max_impulse = Q32::from_raw(int64_t{400000000} << 32);
inline constexpr int64_t k_unit_tolerance = int64_t{1} << 16;

/// The bytes of a body record by presence bits (bit 7 ignored), and of a
/// shape record by its bits: one table load per record.
inline constexpr auto k_body_record_bytes = [] {
  std::array<uint8_t, 256> t{};
  for (size_t present = 0; present < t.size(); ++present) {
    size_t n = 2 + 32;
    if (present & k_has_velocity) n += 24;
    if (present & k_has_force) n += 24;
    if (present & k_has_sleep_time) n += 8;
    if (present & k_has_sleep_island) n += 4;
    if (present & k_has_user_data) n += 8;
    if (present & k_has_damping) n += 16;
    if (present & k_has_gravity_scale) n += 8;
    t[present] = static_cast<uint8_t>(n);
  }
  return t;
}();
inline constexpr auto k_shape_record_bytes = [] {
  std::array<uint8_t, 256> t{};
  for (size_t bits = 0; bits < t.size(); ++bits) {
    size_t n = 5;
    if (bits & k_shape_has_materials) n += 24;
    if (bits & k_shape_has_filter) n += 20;
    if (bits & k_shape_has_user_data) n += 8;
    t[bits] = static_cast<uint8_t>(n);
  }
  return t;
}();
inline size_t body_record_bytes(uint8_t present) { return k_body_record_bytes[present]; }
inline size_t shape_record_bytes(uint8_t bits) { return k_shape_record_bytes[bits]; }

// ---------------------------------------------------------------------------
// Restore's fast paths (state_compact_fast.cpp). The checks answer only
// "all good": each accepts exactly what the detailed checker of
// state_compact_restore.cpp accepts, or less (then that checker runs from the
// same offset and names the culprit, or accepts after all); they fill the
// same per-record tables. The applying functions write the world from
// checked records. `pos` is the offset of the section; the functions return
// or advance it past the section.
// ---------------------------------------------------------------------------

/// Bodies: fills simulated[0, cap) (cap = the body pool's capacity).
bool fast_check_bodies(const uint8_t* data, size_t size, size_t* pos, const uint8_t* alive, size_t cap,
                       uint8_t* simulated);
/// Shapes: fills shape_body and shape_simulated (1: alive on a simulated
/// body; zeroed beforehand) for the live shapes; geometries holds ≥ cap
/// entries.
bool fast_check_shapes(const uint8_t* data, size_t size, size_t* pos, const uint8_t* alive, size_t cap,
                       const uint8_t* body_alive, const uint8_t* body_simulated, size_t body_cap,
                       const ShapeGeometry* geometries, int32_t* shape_body, uint8_t* shape_simulated);
/// Contacts (count and records).
bool fast_check_contacts(const uint8_t* data, size_t size, size_t* pos, const uint8_t* shape_simulated,
                         size_t shape_cap, size_t body_cap);
size_t apply_bodies(World* w, const uint8_t* data, size_t pos, const uint8_t* alive, size_t cap,
                    const RollbackBodyMass* masses);
/// tail: body_cap entries of scratch (each body's last listed shape).
size_t apply_shapes(World* w, const uint8_t* data, size_t pos, const uint8_t* alive, size_t cap,
                    const ShapeGeometry* geometries, int32_t* tail, size_t body_cap);
size_t apply_contacts(World* w, const uint8_t* data, size_t size, size_t pos);

// ---------------------------------------------------------------------------
// The records kept whole (world settings, full contacts, joints, joint
// events) run the field lists of state_fields.h with these visitors: the
// bytes are those of the portable format's fields (replay/state.h), in the
// same order; a bounded field's range is checked after the record is read
// (first_joint_field_out_of_range).
// ---------------------------------------------------------------------------

/// Fields → little-endian bytes at p (the caller sized the buffer).
struct FieldWriter {
  static constexpr bool k_reading = false;
  uint8_t* p;
  void q32(const char*, Q32& x) {
    store_le64(p, static_cast<uint64_t>(x.raw));
    p += 8;
  }
  void q32_in(const char*, Q32& x, Q32, Q32, const char*) { q32(nullptr, x); }
  void vec2(const char*, const char*, Vec2& x) {
    q32(nullptr, x.x);
    q32(nullptr, x.y);
  }
  void vec2_in(const char*, const char*, Vec2& x, Q32, Q32, const char*) { vec2(nullptr, nullptr, x); }
  void u32(const char*, uint32_t& x) {
    store_le32(p, x);
    p += 4;
  }
  void i32(const char*, int32_t& x) {
    uint32_t u = static_cast<uint32_t>(x);
    u32(nullptr, u);
  }
  void u16(const char*, uint16_t& x) {
    store_le16(p, x);
    p += 2;
  }
  void u64(const char*, uint64_t& x) {
    store_le64(p, x);
    p += 8;
  }
  void boolean(const char*, bool& x) { *p++ = x ? 1 : 0; }
  template <typename E>
  void enum8(const char*, E& e, int32_t) {
    *p++ = static_cast<uint8_t>(static_cast<int32_t>(e));
  }
  void ranged_i32(const char*, int32_t& x, int32_t, int32_t) { i32(nullptr, x); }
  bool ok() const { return true; }
};

/// The bytes `visit` writes with a FieldWriter (records of at most 1 KiB).
template <typename Visit>
size_t record_bytes(Visit visit) {
  uint8_t scratch[1024];
  FieldWriter f{scratch};
  visit(f);
  return static_cast<size_t>(f.p - scratch);
}

/// The byte offset of the field named `target` inside a record (the walk
/// counts the bytes before it; the record's size when no field has the name).
struct FieldOffset {
  static constexpr bool k_reading = false;
  const char* target;
  size_t at = 0;
  bool found = false;
  void add(const char* n, size_t bytes) {
    if (found) return;
    if (n != nullptr && std::strcmp(n, target) == 0) {
      found = true;
      return;
    }
    at += bytes;
  }
  void q32(const char* n, Q32&) { add(n, 8); }
  void q32_in(const char* n, Q32&, Q32, Q32, const char*) { add(n, 8); }
  void vec2(const char* nx, const char* ny, Vec2&) {
    add(nx, 8);
    add(ny, 8);
  }
  void vec2_in(const char* nx, const char* ny, Vec2& x, Q32, Q32, const char*) { vec2(nx, ny, x); }
  void i32(const char* n, int32_t&) { add(n, 4); }
  void u32(const char* n, uint32_t&) { add(n, 4); }
  void u16(const char* n, uint16_t&) { add(n, 2); }
  void u64(const char* n, uint64_t&) { add(n, 8); }
  void boolean(const char* n, bool&) { add(n, 1); }
  template <typename E>
  void enum8(const char* n, E&, int32_t) {
    add(n, 1);
  }
  void ranged_i32(const char* n, int32_t&, int32_t, int32_t) { add(n, 4); }
  bool ok() const { return true; }
};

/// Bytes → fields, checked: bytes left, booleans 0 or 1, enums and ranged
/// integers in range, no Q32 of raw INT64_MIN. The first failure stops the
/// walk; `error` then reads "offset N: <kind> <index> expected ...".
struct FieldReader {
  static constexpr bool k_reading = true;
  const uint8_t* data;
  size_t size;
  size_t pos;
  const char* kind;
  int64_t index;
  std::string error;

  bool ok() const { return error.empty(); }
  [[gnu::cold, gnu::noinline]] void fail(size_t at, const char* name, const std::string& what) {
    if (!ok()) return;
    error = "offset " + std::to_string(at) + ": ";
    if (kind != nullptr) {
      error += kind;
      if (index >= 0) error += ' ' + std::to_string(index);
      error += ' ';
    }
    error += "expected ";
    error += name != nullptr ? name : "";
    error += what;
  }
  /// The next n bytes, or null (refused) when fewer are left.
  const uint8_t* take(size_t n, const char* name) {
    if (!ok()) return nullptr;
    if (n > size - pos) {
      fail(pos, name, " (" + std::to_string(n) + " bytes), " + std::to_string(size - pos) + " left");
      return nullptr;
    }
    const uint8_t* p = data + pos;
    pos += n;
    return p;
  }
  void q32(const char* n, Q32& x) {
    const uint8_t* p = take(8, n);
    if (p == nullptr) return;
    const int64_t raw = static_cast<int64_t>(load_le64(p));
    if (raw == INT64_MIN) {
      fail(pos - 8, n, " (Q32.32), got raw INT64_MIN");
      return;
    }
    x = Q32::from_raw(raw);
  }
  void q32_in(const char* n, Q32& x, Q32, Q32, const char*) { q32(n, x); }
  void vec2(const char* nx, const char* ny, Vec2& x) {
    q32(nx, x.x);
    q32(ny, x.y);
  }
  void vec2_in(const char* nx, const char* ny, Vec2& x, Q32, Q32, const char*) { vec2(nx, ny, x); }
  void u32(const char* n, uint32_t& x) {
    if (const uint8_t* p = take(4, n)) x = load_le32(p);
  }
  void i32(const char* n, int32_t& x) {
    if (const uint8_t* p = take(4, n)) x = static_cast<int32_t>(load_le32(p));
  }
  void u16(const char* n, uint16_t& x) {
    if (const uint8_t* p = take(2, n)) x = load_le16(p);
  }
  void u64(const char* n, uint64_t& x) {
    if (const uint8_t* p = take(8, n)) x = load_le64(p);
  }
  void boolean(const char* n, bool& x) {
    const uint8_t* p = take(1, n);
    if (p == nullptr) return;
    if (*p > 1) {
      fail(pos - 1, n, " 0 or 1, got " + std::to_string(*p));
      return;
    }
    x = *p == 1;
  }
  template <typename E>
  void enum8(const char* n, E& e, int32_t max) {
    const uint8_t* p = take(1, n);
    if (p == nullptr) return;
    if (*p > max) {
      fail(pos - 1, n, " 0.." + std::to_string(max) + ", got " + std::to_string(*p));
      return;
    }
    e = static_cast<E>(*p);
  }
  void ranged_i32(const char* n, int32_t& x, int32_t lo, int32_t hi) {
    int32_t v = 0;
    i32(n, v);
    if (!ok()) return;
    if (v < lo || v > hi) {
      fail(pos - 4, n, " in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + std::to_string(v));
      return;
    }
    x = v;
  }
};

/// FieldReader's checks without messages: `bad` after the first failure
/// (the fast paths then hand over to the detailed checker). Names are
/// ignored. Reads the same values as FieldReader from a record it accepts.
struct FastFieldReader {
  static constexpr bool k_reading = true;
  const uint8_t* data;
  size_t size;
  size_t pos;
  bool bad = false;

  bool ok() const { return !bad; }
  const uint8_t* take(size_t n) {
    if (bad || n > size - pos) {
      bad = true;
      return nullptr;
    }
    const uint8_t* p = data + pos;
    pos += n;
    return p;
  }
  void q32(const char*, Q32& x) {
    const uint8_t* p = take(8);
    if (p == nullptr) return;
    const int64_t raw = static_cast<int64_t>(load_le64(p));
    bad = raw == INT64_MIN;
    x = Q32::from_raw(raw);
  }
  void q32_in(const char* n, Q32& x, Q32, Q32, const char*) { q32(n, x); }
  void vec2(const char*, const char*, Vec2& x) {
    q32(nullptr, x.x);
    q32(nullptr, x.y);
  }
  void vec2_in(const char*, const char*, Vec2& x, Q32, Q32, const char*) { vec2(nullptr, nullptr, x); }
  void u32(const char*, uint32_t& x) {
    if (const uint8_t* p = take(4)) x = load_le32(p);
  }
  void i32(const char*, int32_t& x) {
    if (const uint8_t* p = take(4)) x = static_cast<int32_t>(load_le32(p));
  }
  void u16(const char*, uint16_t& x) {
    if (const uint8_t* p = take(2)) x = load_le16(p);
  }
  void u64(const char*, uint64_t& x) {
    if (const uint8_t* p = take(8)) x = load_le64(p);
  }
  void boolean(const char*, bool& x) {
    const uint8_t* p = take(1);
    if (p == nullptr) return;
    bad = *p > 1;
    x = *p == 1;
  }
  template <typename E>
  void enum8(const char*, E& e, int32_t max) {
    const uint8_t* p = take(1);
    if (p == nullptr) return;
    if (*p > max) {
      bad = true;
      return;
    }
    e = static_cast<E>(*p);
  }
  void ranged_i32(const char*, int32_t& x, int32_t lo, int32_t hi) {
    int32_t v = 0;
    i32(nullptr, v);
    if (bad) return;
    if (v < lo || v > hi) {
      bad = true;
      return;
    }
    x = v;
  }
};

}  // namespace tandem::compact_detail

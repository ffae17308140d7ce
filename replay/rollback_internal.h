// rollback_internal.h — what rollback.cpp (save, hash) and
// rollback_restore.cpp (check and restore) share (internal): the image's
// bit assignments and the geometry copy. rollback.cpp describes the layout.
#pragma once

#include <algorithm>
#include <bit>
#include <cstring>

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
#include "replay/rollback.h"
#include "replay/state_internal.h"

namespace tandem::rollback_detail {

using state_fields::FieldRangeFailure;
using state_fields::FieldsOf;
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

inline constexpr size_t k_kind_offset = 8;
inline constexpr size_t k_hashed_from = 9;

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

}  // namespace tandem::rollback_detail

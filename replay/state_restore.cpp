// state_restore.cpp — structural decoding of a state image, restore, decode and locate
// (state.h describes the format, state_internal.h the design).
#include "replay/state_internal.h"

namespace tandem {
namespace state_detail {

Status decode_image(const uint8_t* data, size_t size, const char* function, WorldImage* img, uint32_t* out_version) {
  ByteReader r(data, size);
  const auto bad = [&](const std::string& msg) {
    return make_status(StatusCode::invalid_argument, std::string(function) + ": " + msg);
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

  ReadVisitor v{&r};
  const bool with_joints = version >= k_state_format_version_joints;
  img->joints.pending.clear();
  if (!with_joints) {
    img->joint_pool = IdPool{};
    img->joints.joints.clear();
    img->joint_offsets.clear();
  }
  visit_world(v, *img, &r, version);
  if (!r.ok()) return bad(r.error());
  if (!r.at_end()) {
    return bad("offset " + std::to_string(r.offset()) + ": expected the end of the image, " +
               std::to_string(r.remaining()) + " bytes left over");
  }

  // Cross references.
  const auto at = [&](size_t offset, const std::string& msg) {
    return bad("offset " + std::to_string(offset) + ": " + msg);
  };
  const int32_t body_cap = static_cast<int32_t>(img->bodies.size());
  const int32_t shape_cap = static_cast<int32_t>(img->shapes.size());
  if (img->body_pool.alive_count > k_max_bodies || img->shape_pool.alive_count > k_max_shapes) {
    return bad("too many live bodies or shapes");
  }
  if (img->last_solver_body_count < 0 || img->last_solver_body_count > body_cap) {
    return bad("last_solver_body_count " + std::to_string(img->last_solver_body_count) + " outside [0, " +
               std::to_string(body_cap) + "]");
  }
  if (!(img->def.bounds.lower.x < img->def.bounds.upper.x && img->def.bounds.lower.y < img->def.bounds.upper.y)) {
    return bad("world bounds must have lower < upper");
  }
  int64_t listed_shapes = 0;
  for (int32_t b = 0; b < body_cap; ++b) {
    if (img->body_pool.alive[static_cast<size_t>(b)] == 0) continue;
    const Body& body = img->bodies[static_cast<size_t>(b)];
    const size_t off = img->body_offsets[static_cast<size_t>(b)];
    const std::string who = "body " + std::to_string(b);
    if (body.sleep_island != k_null_index && (body.sleep_island < 0 || body.sleep_island >= body_cap ||
                                              img->body_pool.alive[static_cast<size_t>(body.sleep_island)] == 0)) {
      return at(off, who + " sleep_island " + std::to_string(body.sleep_island) + " is not a live body");
    }
    int32_t count = 0;
    int32_t prev = k_null_index;
    for (int32_t s = body.head_shape; s != k_null_index;) {
      if (s < 0 || s >= shape_cap || img->shape_pool.alive[static_cast<size_t>(s)] == 0) {
        return at(off, who + " shape list names shape " + std::to_string(s) + ", which is not a live shape");
      }
      const Shape& shape = img->shapes[static_cast<size_t>(s)];
      if (shape.body_index != b || shape.prev_shape != prev || s <= prev) {
        return at(img->shape_offsets[static_cast<size_t>(s)],
                  "shape " + std::to_string(s) + " is inconsistent with " + who +
                      "'s shape list (body, prev_shape or order)");
      }
      if (++count > body.shape_count) break;
      prev = s;
      s = shape.next_shape;
    }
    if (count != body.shape_count) {
      return at(off, who + " shape_count " + std::to_string(body.shape_count) + " but its list holds " +
                         (count > body.shape_count ? "more" : std::to_string(count)));
    }
    listed_shapes += count;
  }
  if (listed_shapes != img->shape_pool.alive_count) {
    return bad("bodies list " + std::to_string(listed_shapes) + " shapes but " +
               std::to_string(img->shape_pool.alive_count) + " shapes are alive");
  }
  // Geometry the narrow phase divides by or takes roots of.
  for (int32_t i = 0; i < shape_cap; ++i) {
    if (img->shape_pool.alive[static_cast<size_t>(i)] == 0) continue;
    const ShapeGeometry& g = img->shape_geometries[static_cast<size_t>(i)];
    bool valid = true;
    switch (g.type) {
      case ShapeType::circle: valid = g.circle.radius > Q32::zero(); break;
      case ShapeType::capsule: valid = g.capsule.radius > Q32::zero() && g.capsule.center1 != g.capsule.center2; break;
      case ShapeType::segment: valid = g.segment.point1 != g.segment.point2; break;
      case ShapeType::polygon: valid = g.polygon.radius >= Q32::zero(); break;
      case ShapeType::chain_segment:
        valid = g.chain_segment.segment.point1 != g.chain_segment.segment.point2;
        break;
      case ShapeType::count: valid = false; break;
    }
    if (!valid) {
      return at(img->shape_offsets[static_cast<size_t>(i)],
                "shape " + std::to_string(i) + " has degenerate geometry (zero or negative radius, or coincident points)");
    }
  }
  uint64_t prev_key = 0;
  for (size_t i = 0; i < img->contacts.size(); ++i) {
    const Contact& c = img->contacts[i];
    const size_t off = img->contact_offsets[i];
    if (c.shape_a < 0 || c.shape_b >= shape_cap || c.shape_a >= c.shape_b || c.body_a < 0 || c.body_a >= body_cap ||
        c.body_b < 0 || c.body_b >= body_cap) {
      return at(off, "contact " + std::to_string(i) + " names shapes (" + std::to_string(c.shape_a) + ", " +
                         std::to_string(c.shape_b) + ") / bodies (" + std::to_string(c.body_a) + ", " +
                         std::to_string(c.body_b) + ") outside the pools or out of order");
    }
    const uint64_t key = contact_key(c);
    if (i > 0 && key <= prev_key) return at(off, "contact " + std::to_string(i) + " is not sorted by shape pair");
    prev_key = key;
  }
  const auto check_pairs = [&](const std::vector<PairRecord>& pairs, const char* what) -> Status {
    for (size_t i = 0; i < pairs.size(); ++i) {
      const PairRecord& p = pairs[i];
      if (p.shape_a < 0 || p.shape_a >= shape_cap || p.shape_b < 0 || p.shape_b >= shape_cap) {
        return bad(std::string(what) + " " + std::to_string(i) + " names a shape outside the pool");
      }
      if (i > 0 && shape_pair_key(p.shape_a, p.shape_b) <=
                       shape_pair_key(pairs[i - 1].shape_a, pairs[i - 1].shape_b)) {
        return bad(std::string(what) + " " + std::to_string(i) + " is not sorted");
      }
    }
    return Status{};
  };
  Status s = check_pairs(img->events.touching, "touching pair");
  if (!s.ok()) return s;
  s = check_pairs(img->events.sensor_overlaps, "sensor overlap");
  if (!s.ok()) return s;
  for (size_t i = 0; i < img->joints.joints.size(); ++i) {
    if (img->joint_pool.alive[i] == 0) continue;
    const Joint& j = img->joints.joints[i];
    const auto live = [&](int32_t b) {
      return b >= 0 && b < body_cap && img->body_pool.alive[static_cast<size_t>(b)] != 0;
    };
    if (!live(j.body_a) || !live(j.body_b) || j.body_a == j.body_b) {
      return at(img->joint_offsets[i], "joint " + std::to_string(i) + " joins bodies (" + std::to_string(j.body_a) +
                                           ", " + std::to_string(j.body_b) + "), which are not two live bodies");
    }
  }
  return validate_image_values(img, function);
}

/// Replaces the world's state with a validated image. Vectors are swapped,
/// so the scratch image keeps the world's old buffers for the next decode
/// (no allocation in a warm rollback loop).
void commit_image(World* w, WorldImage& img) {
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
  w->contact_scratch.clear();
  std::swap(w->joint_pool, img.joint_pool);
  std::swap(w->joints.joints, img.joints.joints);
  w->joints.events.clear();
  std::swap(w->joints.pending, img.joints.pending);
  for (JointEvent& e : w->joints.pending) {  // stale handles of this world
    e.joint.world = w->id;
    e.body_a.world = w->id;
    e.body_b.world = w->id;
  }
  rebuild_joint_filter(w);
  EventState& e = w->events;
  std::swap(e.touching, img.events.touching);
  std::swap(e.sensor_overlaps, img.events.sensor_overlaps);
  e.touching_next.clear();
  e.sensor_next.clear();
  e.hit_candidates.clear();
  events_clear_reported(&e);
  broad_phase_reset(w);
  // Buffers sized for the restored scene, so its next step does not allocate.
  reserve_contact_headroom(w);
  events_reserve_headroom(w);
}

WorldImage& scratch_image() {
  thread_local WorldImage image;
  return image;
}

}  // namespace state_detail

using namespace state_detail;

// ---------------------------------------------------------------------------
// Public API: restore, decode, locate
// ---------------------------------------------------------------------------

Status world_restore(WorldId world, const uint8_t* data, size_t size) {
  World* w = nullptr;
  Status s = resolve_for_state(world, "world_restore", true, &w);
  if (!s.ok()) return s;
  WorldImage& img = scratch_image();
  s = decode_image(data, size, "world_restore", &img, nullptr);
  if (!s.ok()) return s;
  commit_image(w, img);
  return s;
}

Result<WorldId> create_world_from_snapshot(const uint8_t* data, size_t size) {
  Result<WorldId> result = create_world(default_world_def());
  if (!result.ok()) return result;
  Status s = world_restore(result.value, data, size);
  if (!s.ok()) {
    (void)destroy_world(result.value);  // just created: cannot fail
    result.value = WorldId{};
    result.status = make_status(s.code, "create_world_from_snapshot: " + s.message);
  }
  return result;
}

Status decode_world_state(const uint8_t* data, size_t size, DecodedState* out) {
  WorldImage img;
  uint32_t version = 0;
  Status s = decode_image(data, size, "decode_world_state", &img, &version);
  if (!s.ok()) return s;
  out->version = version;
  out->records.clear();
  DescribeVisitor v{out};
  visit_world(v, img, nullptr, version);
  return s;
}

Status locate_state_field(const uint8_t* data, size_t size, const std::string& kind, int64_t index,
                          const std::string& field, size_t* out_offset) {
  WorldImage img;
  Status s = decode_image(data, size, "locate_state_field", &img, nullptr);
  if (!s.ok()) return s;
  const auto missing = [&](const std::string& what) {
    return make_status(StatusCode::invalid_argument, "locate_state_field: " + what);
  };
  const char* f = field.c_str();
  size_t base = 0;
  size_t found = SIZE_MAX;
  const auto find = [&](auto&& visit) {
    ByteWriter counter(nullptr, 0);
    OffsetVisitor v{&counter, f};
    visit(v);
    found = v.found;
  };
  if (kind == "world") {
    base = 16;
    find([&](OffsetVisitor& v) { visit_world_def(v, img.def); });
  } else if (kind == "body" || kind == "shape") {
    const bool body = kind == "body";
    const size_t cap = body ? img.bodies.size() : img.shapes.size();
    if (index < 0 || static_cast<size_t>(index) >= cap ||
        (body ? img.body_pool : img.shape_pool).alive[static_cast<size_t>(index)] == 0) {
      return missing(kind + " " + std::to_string(index) + " is not alive in the image");
    }
    const size_t i = static_cast<size_t>(index);
    if (body) {
      base = img.body_offsets[i];
      find([&](OffsetVisitor& v) { visit_body(v, img.bodies[i], img.body_sims[i]); });
    } else {
      base = img.shape_offsets[i];
      find([&](OffsetVisitor& v) { visit_shape(v, img.shapes[i], img.shape_geometries[i]); });
    }
  } else if (kind == "contact") {
    if (index < 0 || static_cast<size_t>(index) >= img.contacts.size()) {
      return missing("contact " + std::to_string(index) + " is not in the image");
    }
    base = img.contact_offsets[static_cast<size_t>(index)];
    find([&](OffsetVisitor& v) { visit_contact(v, img.contacts[static_cast<size_t>(index)]); });
  } else {
    return missing("unknown record kind \"" + kind + "\" (world, body, shape or contact)");
  }
  if (found == SIZE_MAX) return missing(kind + " has no field \"" + field + "\"");
  *out_offset = base + found;
  return s;
}

}  // namespace tandem

// broad_phase.cpp — the shared part of every broad phase (pre-pass, the one
// candidate test, the final ordering, stats, the public settings) and the
// naive implementation. See broad_phase.h for the contract.
//
// Pre-pass: proxies are gathered in ascending shape index (live, non-sensor
// shapes on enabled bodies), each with its AABB sanitised (clamped into
// ±k_broad_phase_coordinate_limit and put in order per axis; the identity for
// every box a world computes) and fattened by k_speculative_distance (exact
// additions), into a list and into by-shape arrays that the structures read.
// Sanitising here, once, is what makes every structure safe against a corrupt
// box: the sweep's end points always open before they close, the grid's and
// tree's arithmetic stays far from overflow, and fattening never saturates.
//
// Naive: for i < j over the proxy list, a pair is emitted when the fat boxes
// overlap and the filters agree; the nested loop visits (i, j) in ascending
// key order, so no sort is needed.
//
// Ordering of the other kinds' output: a counting sort of the emitted keys by
// lower index (two linear passes), then an insertion sort of each lower
// index's partners (a handful each). Keys are unique, so the result is the
// one sorted list whatever order the structure visited pairs in.
//
// Timing: update_nanoseconds comes from std::chrono::steady_clock and is only
// stored for world_broad_phase_stats; nothing reads it back.
#include "physics/broad_phase.h"

#include <chrono>

#include "physics/contact.h"
#include "physics/shape.h"
#include "physics/world.h"

namespace tandem {

bool filters_should_collide(const Filter& a, const Filter& b) {
  if (a.group_index == b.group_index && a.group_index != 0) return a.group_index > 0;
  return (a.category_bits & b.mask_bits) != 0 && (b.category_bits & a.mask_bits) != 0;
}

bool shapes_should_collide(const World& world, int32_t shape_a, int32_t shape_b) {
  const Shape& a = world.shapes[static_cast<size_t>(shape_a)];
  const Shape& b = world.shapes[static_cast<size_t>(shape_b)];
  if (a.body_index == b.body_index || a.is_sensor || b.is_sensor) return false;
  const Body& ba = world.bodies[static_cast<size_t>(a.body_index)];
  const Body& bb = world.bodies[static_cast<size_t>(b.body_index)];
  if (!ba.enabled || !bb.enabled) return false;
  if (ba.type != BodyType::dynamic_body && bb.type != BodyType::dynamic_body) return false;
  if (!filters_should_collide(a.filter, b.filter)) return false;
  if (joint_blocks_collision(world, a.body_index, b.body_index)) return false;  // collide_connected (joint.h)
  const BroadPhase& bp = world.broad_phase;
  if (bp.custom_filter == nullptr) return true;
  const int32_t lower = shape_a < shape_b ? shape_a : shape_b;
  const int32_t higher = shape_a < shape_b ? shape_b : shape_a;
  return bp.custom_filter(make_shape_id(world, lower), make_shape_id(world, higher), bp.custom_context);
}

namespace {

/// The filters after the box test: shapes_should_collide, then the custom
/// filter with (lower, higher). Both shapes are proxies (not sensors, bodies
/// enabled) and one is dynamic, so shapes_should_collide reduces to
/// "different bodies and the filters agree", read from the pre-pass's dense
/// copy (the same values, so the same answer).
bool pair_passes_filters(World* world, int32_t lower, int32_t higher) {
  const BroadPhase& bp = world->broad_phase;
  const ProxyFilter& fa = bp.shape_filter[static_cast<size_t>(lower)];
  const ProxyFilter& fb = bp.shape_filter[static_cast<size_t>(higher)];
  if (fa.body == fb.body) return false;
  if (fa.group_index == fb.group_index && fa.group_index != 0) {
    if (fa.group_index < 0) return false;
  } else if ((fa.category_bits & fb.mask_bits) == 0 || (fb.category_bits & fa.mask_bits) == 0) {
    return false;
  }
  if (joint_blocks_collision(*world, fa.body, fb.body)) return false;  // collide_connected (joint.h)
  if (bp.custom_filter == nullptr) return true;
  return bp.custom_filter(make_shape_id(*world, lower), make_shape_id(*world, higher), bp.custom_context);
}

}  // namespace

/// Shapes per block of the parallel per-shape part of broad_phase_gather_proxies.
constexpr int32_t k_proxy_block = 256;

/// Lists the proxies and the sensors and fills the by-shape arrays. The
/// per-shape part (kind, sanitised fat box, filter copy: each shape writes
/// only its own slots) runs in fixed blocks of k_proxy_block shapes on any
/// thread (task.h); the lists are then built serially in ascending shape
/// index from the kinds, so they are the same for every worker count.
void broad_phase_gather_proxies(World* world, bool in_step) {
  BroadPhase& bp = world->broad_phase;
  const int32_t capacity = id_pool_capacity(world->shape_pool);
  const size_t cap = static_cast<size_t>(capacity);
  bp.proxies.clear();
  bp.fat_bounds.clear();
  bp.proxy_dynamic.clear();
  bp.sensors.clear();
  if (bp.shape_fat.size() < cap) bp.shape_fat.resize(cap);
  if (bp.shape_kind.size() < cap) bp.shape_kind.resize(cap);
  if (bp.shape_filter.size() < cap) bp.shape_filter.resize(cap);
  // Slots beyond the pool (a restore may leave fewer) take no part.
  for (size_t s = cap; s < bp.shape_kind.size(); ++s) bp.shape_kind[s] = k_proxy_none;
  const World* w = world;
  uint8_t* kinds = bp.shape_kind.data();
  AABB* fats = bp.shape_fat.data();
  ProxyFilter* filters = bp.shape_filter.data();
  const auto per_shape = [=](int32_t begin, int32_t end) {
    for (int32_t s = begin; s < end; ++s) {
      const size_t si = static_cast<size_t>(s);
      kinds[si] = k_proxy_none;
      if (!id_pool_is_alive(w->shape_pool, s)) continue;
      const Shape& shape = w->shapes[si];
      const Body& body = w->bodies[static_cast<size_t>(shape.body_index)];
      if (shape.is_sensor || !body.enabled) continue;
      const bool dynamic = body.type == BodyType::dynamic_body;
      kinds[si] = dynamic ? k_proxy_dynamic : k_proxy_static;
      fats[si] = aabb_fatten(broad_phase_sanitize_box(shape.aabb), k_speculative_distance);
      filters[si] =
          ProxyFilter{shape.body_index, shape.filter.group_index, shape.filter.category_bits, shape.filter.mask_bits};
    }
  };
  if (in_step) {
    parallel_for(&world->tasks, "broad_phase_proxies", capacity, k_proxy_block, per_shape);
  } else {
    per_shape(0, capacity);
  }
  for (int32_t s = 0; s < capacity; ++s) {
    const size_t si = static_cast<size_t>(s);
    const uint8_t kind = kinds[si];
    if (kind == k_proxy_none) {
      // Sensors of enabled bodies are not proxies; queries scan their list.
      if (id_pool_is_alive(world->shape_pool, s)) {
        const Shape& shape = world->shapes[si];
        if (shape.is_sensor && world->bodies[static_cast<size_t>(shape.body_index)].enabled) bp.sensors.push_back(s);
      }
      continue;
    }
    bp.proxies.push_back(s);
    bp.fat_bounds.push_back(fats[si]);
    bp.proxy_dynamic.push_back(kind == k_proxy_dynamic ? 1 : 0);
  }
}

namespace {

void naive_update(World* world) {
  BroadPhase& bp = world->broad_phase;
  const size_t n = bp.proxies.size();
  int64_t candidates = 0;
  for (size_t i = 0; i < n; ++i) {
    const AABB box = bp.fat_bounds[i];
    const int32_t a = bp.proxies[i];
    const bool a_dynamic = bp.proxy_dynamic[i] != 0;
    for (size_t j = i + 1; j < n; ++j) {
      if (!a_dynamic && bp.proxy_dynamic[j] == 0) continue;  // static/kinematic against static/kinematic
      ++candidates;
      if (!aabb_overlaps(box, bp.fat_bounds[j])) continue;
      const int32_t b = bp.proxies[j];
      if (!pair_passes_filters(world, a, b)) continue;
      bp.pairs.push_back(ShapePair{a, b});
    }
  }
  bp.candidate_count = candidates;
}

/// Orders bp.unsorted into bp.pairs (see the file comment).
void sort_emitted(World* world) {
  BroadPhase& bp = world->broad_phase;
  const size_t m = bp.unsorted.size();
  bp.pairs.resize(m);
  if (m == 0) return;
  const size_t cap = static_cast<size_t>(id_pool_capacity(world->shape_pool));
  bp.counts.assign(cap + 1, 0);
  for (const uint64_t key : bp.unsorted) ++bp.counts[static_cast<size_t>(key >> 32) + 1];
  for (size_t i = 1; i <= cap; ++i) bp.counts[i] += bp.counts[i - 1];
  // counts[lower] is now the first slot of that lower index's run.
  for (const uint64_t key : bp.unsorted) {
    const size_t lower = static_cast<size_t>(key >> 32);
    const size_t slot = static_cast<size_t>(bp.counts[lower]++);
    bp.pairs[slot] = ShapePair{static_cast<int32_t>(lower), static_cast<int32_t>(key & 0xFFFFFFFFu)};
  }
  // Each run [start, end): insertion sort by the higher index.
  size_t start = 0;
  while (start < m) {
    const int32_t lower = bp.pairs[start].shape_a;
    size_t end = start + 1;
    while (end < m && bp.pairs[end].shape_a == lower) ++end;
    for (size_t i = start + 1; i < end; ++i) {
      const ShapePair p = bp.pairs[i];
      size_t j = i;
      while (j > start && bp.pairs[j - 1].shape_b > p.shape_b) {
        bp.pairs[j] = bp.pairs[j - 1];
        --j;
      }
      bp.pairs[j] = p;
    }
    start = end;
  }
}

/// Vector growth rule shared with contact.cpp's headroom: grow when the use
/// passes 3/4 of the capacity, to twice the use plus 64.
template <typename T>
void reserve_for(std::vector<T>* v, size_t use) {
  if (4 * use + 4 <= 3 * v->capacity()) return;
  v->reserve(2 * use + 64);
}

}  // namespace

AABB broad_phase_sanitize_box(AABB box) {
  const auto clamp = [](Q32 v) {
    return Q32::from_raw(v.raw < -k_broad_phase_coordinate_limit
                             ? -k_broad_phase_coordinate_limit
                             : (v.raw > k_broad_phase_coordinate_limit ? k_broad_phase_coordinate_limit : v.raw));
  };
  const Q32 x0 = clamp(box.lower.x), x1 = clamp(box.upper.x);
  const Q32 y0 = clamp(box.lower.y), y1 = clamp(box.upper.y);
  return AABB{{x0 < x1 ? x0 : x1, y0 < y1 ? y0 : y1}, {x0 < x1 ? x1 : x0, y0 < y1 ? y1 : y0}};
}

uint64_t broad_phase_typical_limit(const int32_t* histogram, int32_t count) {
  const int32_t wanted = count - count / 16;
  int32_t bucket = 0;
  for (int32_t seen = 0; bucket < 65; ++bucket) {
    seen += histogram[bucket];
    if (seen >= wanted) break;
  }
  // Every extent in classes ≤ bucket is < 2^bucket; allow 4× that.
  return bucket + 2 >= 64 ? UINT64_MAX : (uint64_t{1} << (bucket + 2));
}

void broad_phase_emit_candidate(World* world, int32_t a, int32_t b) {
  BroadPhase& bp = world->broad_phase;
  const size_t ai = static_cast<size_t>(a);
  const size_t bi = static_cast<size_t>(b);
  if (bp.shape_kind[ai] != k_proxy_dynamic && bp.shape_kind[bi] != k_proxy_dynamic) return;
  ++bp.candidate_count;
  if (!aabb_overlaps(bp.shape_fat[ai], bp.shape_fat[bi])) return;
  broad_phase_emit_overlapping(world, a, b);
}

void broad_phase_emit_overlapping(World* world, int32_t a, int32_t b) {
  BroadPhase& bp = world->broad_phase;
  const int32_t lower = a < b ? a : b;
  const int32_t higher = a < b ? b : a;
  if (!pair_passes_filters(world, lower, higher)) return;
  bp.unsorted.push_back(shape_pair_key(lower, higher));
}

void broad_phase_update_pairs(World* world) {
  const auto start = std::chrono::steady_clock::now();
  BroadPhase& bp = world->broad_phase;
  bp.pairs.clear();
  bp.unsorted.clear();
  bp.stats = BroadPhaseStats{};
  bp.candidate_count = 0;
  broad_phase_gather_proxies(world, true);
  switch (world->def.broad_phase) {
    case BroadPhaseKind::sweep_and_prune:
      sap_update(world);
      sort_emitted(world);
      break;
    case BroadPhaseKind::grid:
      grid_update(world);
      sort_emitted(world);
      break;
    case BroadPhaseKind::tree:
      tree_update(world);
      sort_emitted(world);
      break;
    case BroadPhaseKind::naive:
    default:
      naive_update(world);
      break;
  }
  bp.stats.proxies = static_cast<int32_t>(bp.proxies.size());
  bp.stats.pairs = static_cast<int32_t>(bp.pairs.size());
  bp.stats.candidate_pairs =
      bp.candidate_count > INT32_MAX ? INT32_MAX : static_cast<int32_t>(bp.candidate_count);
  const auto elapsed = std::chrono::steady_clock::now() - start;
  const int64_t ns = std::chrono::duration_cast<std::chrono::nanoseconds>(elapsed).count();
  bp.stats.update_nanoseconds = ns > 0 ? static_cast<uint64_t>(ns) : 0;
  // The rest of the step moves bodies: queries after it re-synchronise.
  bp.query_synced = false;
}

void broad_phase_reset(World* world) {
  BroadPhase& bp = world->broad_phase;
  bp.pairs.clear();
  bp.proxies.clear();
  bp.fat_bounds.clear();
  bp.proxy_dynamic.clear();
  bp.unsorted.clear();
  bp.sensors.clear();
  bp.query_synced = false;
  sap_reset(&bp.sap);
  tree_reset(&bp.tree);
}

void broad_phase_reserve_headroom(World* world) {
  BroadPhase& bp = world->broad_phase;
  const size_t shapes = static_cast<size_t>(id_pool_capacity(world->shape_pool));
  const size_t pairs = bp.pairs.size();
  reserve_for(&bp.pairs, pairs);
  reserve_for(&bp.unsorted, pairs);
  reserve_for(&bp.proxies, shapes);
  reserve_for(&bp.fat_bounds, shapes);
  reserve_for(&bp.proxy_dynamic, shapes);
  reserve_for(&bp.shape_fat, shapes);
  reserve_for(&bp.shape_kind, shapes);
  reserve_for(&bp.shape_filter, shapes);
  reserve_for(&bp.counts, shapes + 1);
  reserve_for(&bp.sap.endpoints, 2 * shapes);
  reserve_for(&bp.sap.merged, 2 * shapes);
  reserve_for(&bp.sap.added, 2 * shapes);
  reserve_for(&bp.sap.present, shapes);
  reserve_for(&bp.sap.active_dynamic, shapes);
  reserve_for(&bp.sap.active_other, shapes);
  reserve_for(&bp.sap.active_slot, shapes);
  reserve_for(&bp.grid.proxy_cell, shapes);
  reserve_for(&bp.grid.proxy_bucket, shapes);
  reserve_for(&bp.grid.entries, shapes);
  reserve_for(&bp.grid.outliers, shapes);
  reserve_for(&bp.grid.bucket_start, 4 * shapes + 17);
  reserve_for(&bp.tree.nodes, 2 * shapes);
  reserve_for(&bp.tree.leaf_of_shape, shapes);
  reserve_for(&bp.tree.stack, 256);
  reserve_for(&bp.sensors, shapes);
  reserve_for(&bp.sap.wide, bp.sap.wide.size());
}

// ---------------------------------------------------------------------------
// Public settings and stats
// ---------------------------------------------------------------------------

Status world_set_broad_phase(WorldId id, BroadPhaseKind kind) {
  World* world = nullptr;
  Status s = resolve_world(id, "world_set_broad_phase", true, &world);
  if (!s.ok()) return s;
  const int32_t k = static_cast<int32_t>(kind);
  if (k < static_cast<int32_t>(BroadPhaseKind::naive) || k > static_cast<int32_t>(BroadPhaseKind::tree)) {
    return make_status(StatusCode::invalid_argument,
                       "world_set_broad_phase: unknown broad-phase kind " + std::to_string(k) + " (0…3)");
  }
  if (world->def.broad_phase != kind) {
    world->def.broad_phase = kind;
    broad_phase_reset(world);
  }
  return s;
}

BroadPhaseKind world_broad_phase(WorldId id) {
  const World* world = find_world(id);
  return world == nullptr ? BroadPhaseKind::naive : world->def.broad_phase;
}

BroadPhaseStats world_broad_phase_stats(WorldId id) {
  const World* world = find_world(id);
  if (world == nullptr) return BroadPhaseStats{};
  BroadPhaseStats stats = world->broad_phase.stats;
  // The contact list holds one contact per emitted pair (contact.cpp), so the
  // touching ones are counted here rather than in the contact stage.
  int32_t touching = 0;
  for (const Contact& c : world->contacts) {
    if ((c.flags & k_contact_touching) != 0) ++touching;
  }
  stats.touching_pairs = touching;
  stats.awake_contacts = awake_contact_count(*world);
  stats.contacts_read_after_update = world->contacts_read_after_update;
  return stats;
}

Status world_set_custom_filter(WorldId id, CustomFilterFn filter, void* context) {
  World* world = nullptr;
  Status s = resolve_world(id, "world_set_custom_filter", true, &world);
  if (!s.ok()) return s;
  world->broad_phase.custom_filter = filter;
  world->broad_phase.custom_context = filter == nullptr ? nullptr : context;
  return s;
}

}  // namespace tandem

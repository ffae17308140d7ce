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
// Carry-over: whether two proxies form a pair is a function of their kinds,
// fat boxes and filter copies (and of the joints' no-collide set and the
// custom filter). The pre-pass flags every shape whose kind, stored AABB or
// filter differs from what the last update used (shape_changed; sticky until
// an update consumes it, since a query's sync gathers too). When the last
// update's pairs are valid, no custom filter is set (a user callback is only
// promised to be deterministic, not unchanged between steps), the no-collide
// set is the same and at most a quarter of the proxies changed, the update
// keeps the last pairs whose shapes both did not change and searches only the
// changed proxies against every proxy, through the current kind's structure
// (the tree re-synced for the changed shapes alone, sweep-and-prune's query,
// the grid with a list of stale entries, naive's scan). A pair found from
// both sides is emitted from its lower changed shape only. The new pairs are
// sorted and merged with the kept ones, which gives exactly the full
// search's list: a kept pair's inputs are those that made it a pair, a pair
// dropped last time between unchanged proxies is still dropped, and every
// pair with a changed proxy is searched. So a sleeping pile costs the
// per-shape compare and the merge, not a search; results never depend on
// which path ran. Nothing here is state: a restore, a kind change or a new
// custom filter clears pairs_valid and the next update is a full search.
//
// Timing: update_nanoseconds comes from std::chrono::steady_clock and is only
// stored for world_broad_phase_stats; nothing reads it back.
#include "physics/broad_phase.h"

#include <algorithm>
#include <chrono>
#include <cstring>

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

// The per-shape change test of broad_phase_gather_proxies, on raw words.
// Written out rather than AABB's and a defaulted ProxyFilter operator==:
// with those, g++ 12 -O3 spent ~10 more instructions per shape (circles-16k
// broad phase 12.87 -> 13.03 M per step, callgrind).
bool same_raw_box(const AABB& a, const AABB& b) {
  return a.lower.x.raw == b.lower.x.raw && a.lower.y.raw == b.lower.y.raw && a.upper.x.raw == b.upper.x.raw &&
         a.upper.y.raw == b.upper.y.raw;
}

bool same_filter(const ProxyFilter& a, const ProxyFilter& b) {
  return a.body == b.body && a.group_index == b.group_index && a.category_bits == b.category_bits &&
         a.mask_bits == b.mask_bits;
}

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

/// Fills the by-shape arrays, flags the changed shapes and counts the
/// proxies. The per-shape part (kind, sanitised fat box, filter copy, changed
/// flag: each shape writes only its own slots; counts per block) runs in
/// fixed blocks of k_proxy_block shapes on any thread (task.h); the block
/// counts are summed in block order and the changed list is read from the
/// flags in ascending shape index, so all is the same for every worker count.
void broad_phase_gather_proxies(World* world, bool in_step) {
  BroadPhase& bp = world->broad_phase;
  const int32_t capacity = id_pool_capacity(world->shape_pool);
  const size_t cap = static_cast<size_t>(capacity);
  bp.changed.clear();
  bp.changed_count = 0;
  bp.proxy_count = 0;
  if (bp.shape_fat.size() < cap) bp.shape_fat.resize(cap);
  if (bp.shape_kind.size() < cap) bp.shape_kind.resize(cap);
  if (bp.shape_filter.size() < cap) bp.shape_filter.resize(cap);
  if (bp.shape_changed.size() < cap) bp.shape_changed.resize(cap, 0);
  if (bp.shape_box.size() < cap) bp.shape_box.resize(cap);
  // Slots beyond the pool (a restore may leave fewer) take no part; pairs
  // that named them cannot be carried over.
  for (size_t s = cap; s < bp.shape_kind.size(); ++s) {
    if (bp.shape_kind[s] != k_proxy_none) bp.pairs_valid = false;
    bp.shape_kind[s] = k_proxy_none;
  }
  uint8_t* kinds = bp.shape_kind.data();
  AABB* fats = bp.shape_fat.data();
  ProxyFilter* filters = bp.shape_filter.data();
  uint8_t* changed = bp.shape_changed.data();
  AABB* boxes = bp.shape_box.data();
  // Proxies per block.
  const int32_t blocks = in_step ? block_count_of(capacity, k_proxy_block) : (capacity > 0 ? 1 : 0);
  int32_t local_count = 0;
  int32_t* counts =
      in_step ? arena_allocate_array<int32_t>(&world->arena, blocks, "proxy_block_counts") : &local_count;
  // Base pointers read once: the loop's byte stores could alias them.
  const uint8_t* alive = world->shape_pool.alive.data();
  const Shape* shapes = world->shapes.data();
  const Body* bodies = world->bodies.data();
  const auto per_shape = [=](int32_t begin, int32_t end) {
    int32_t proxies = 0;
    for (int32_t s = begin; s < end; ++s) {
      const size_t si = static_cast<size_t>(s);
      const uint8_t old_kind = kinds[si];
      uint8_t kind = k_proxy_none;
      bool differs = old_kind != k_proxy_none;  // a proxy that stops taking part changed
      if (alive[si] != 0) {
        const Shape& shape = shapes[si];
        const Body& body = bodies[static_cast<size_t>(shape.body_index)];
        if (!shape.is_sensor && body.enabled) {
          kind = body.type == BodyType::dynamic_body ? k_proxy_dynamic : k_proxy_static;
          const ProxyFilter filter{shape.body_index, shape.filter.group_index, shape.filter.category_bits,
                                   shape.filter.mask_bits};
          ++proxies;
          // The fat box is a function of the stored AABB: recomputed only
          // when that changed.
          differs = kind != old_kind || !same_raw_box(shape.aabb, boxes[si]) || !same_filter(filter, filters[si]);
          if (differs) {
            boxes[si] = shape.aabb;
            fats[si] = aabb_fatten(broad_phase_sanitize_box(shape.aabb), k_speculative_distance);
            filters[si] = filter;
          }
        }
      }
      kinds[si] = kind;
      // Sticky until an update consumes it (a query's sync gathers too).
      if (differs) changed[si] = 1;
    }
    counts[begin / k_proxy_block] = proxies;
  };
  if (in_step) {
    parallel_for(&world->tasks, "broad_phase_proxies", capacity, k_proxy_block, per_shape);
  } else if (capacity > 0) {
    per_shape(0, capacity);  // one block: counts[0]
  }
  int32_t proxy_count = 0;
  for (int32_t k = 0; k < blocks; ++k) proxy_count += counts[k];
  if (in_step) arena_free(&world->arena, counts);
  bp.proxy_count = proxy_count;
  // Count the flags eight at a time (each byte 0 or 1: the byte sum of a
  // word is its top byte times 0x0101…01) and list them, ascending, while
  // the list stays short enough to carry over (the limit in can_carry_over
  // is lower).
  const size_t room = cap / 4 + 64;
  size_t changed_count = 0;
  const auto note = [&](size_t s) {
    ++changed_count;
    if (bp.changed.size() < room) bp.changed.push_back(static_cast<int32_t>(s));
  };
  size_t s = 0;
  for (; s + 8 <= cap; s += 8) {
    uint64_t word;
    std::memcpy(&word, changed + s, 8);
    if (word == 0) continue;
    if (bp.changed.size() >= room) {
      changed_count += static_cast<size_t>((word * 0x0101010101010101ull) >> 56);
      continue;
    }
    for (size_t j = 0; j < 8; ++j) {
      if (changed[s + j] != 0) note(s + j);
    }
  }
  for (; s < cap; ++s) {
    if (changed[s] != 0) note(s);
  }
  bp.changed_count = static_cast<int32_t>(changed_count);
  if (!in_step) broad_phase_list_proxies(world);
}

void broad_phase_list_proxies(World* world) {
  BroadPhase& bp = world->broad_phase;
  const int32_t capacity = id_pool_capacity(world->shape_pool);
  const uint8_t* kinds = bp.shape_kind.data();
  bp.proxies.clear();
  bp.fat_bounds.clear();
  bp.proxy_dynamic.clear();
  bp.sensors.clear();
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
    bp.fat_bounds.push_back(bp.shape_fat[si]);
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

void broad_phase_offer_changed(World* world, int32_t p, int32_t q) {
  BroadPhase& bp = world->broad_phase;
  const size_t pi = static_cast<size_t>(p);
  const size_t qi = static_cast<size_t>(q);
  if (q == p) return;
  const uint8_t kq = bp.shape_kind[qi];
  if (kq == k_proxy_none) return;
  if (bp.shape_kind[pi] != k_proxy_dynamic && kq != k_proxy_dynamic) return;
  if (bp.shape_changed[qi] != 0 && q < p) return;  // found from q's side
  ++bp.candidate_count;
  if (!aabb_overlaps(bp.shape_fat[pi], bp.shape_fat[qi])) return;
  broad_phase_emit_overlapping(world, p, q);
}

namespace {

void full_update(World* world);

/// Visitor of the carry-over searches that go through a structure's query.
struct ChangedSearch {
  World* world = nullptr;
  int32_t shape = 0;  ///< the changed proxy being searched
};

Q32 offer_changed_visit(void* context, int32_t q) {
  const ChangedSearch* search = static_cast<const ChangedSearch*>(context);
  broad_phase_offer_changed(search->world, search->shape, q);
  return Q32::one();
}

/// Whether this update may carry pairs over (see "Carry-over" in the file
/// comment): the last update's pairs are valid, no custom filter (a user
/// callback is only promised to be deterministic, not unchanged between
/// steps), the joints' no-collide set is the same (`same_joint_keys`), and
/// few proxies changed.
bool can_carry_over(const BroadPhase& bp, bool same_joint_keys) {
  if (!bp.pairs_valid || bp.custom_filter != nullptr || !same_joint_keys) return false;
  if (static_cast<size_t>(bp.changed_count) != bp.changed.size()) return false;  // more than bp.changed holds
  return 4 * static_cast<int64_t>(bp.changed_count) <= int64_t{bp.proxy_count} + 128;
}

/// The carry-over update: the changed proxies are searched against every
/// proxy through the current kind's structure, their pairs sorted, and merged
/// with the last update's pairs between two unchanged proxies.
void carry_over_update(World* world) {
  BroadPhase& bp = world->broad_phase;
  ChangedSearch search{world, 0};
  BroadPhaseQuery q;
  q.visit = offer_changed_visit;
  q.context = &search;
  int32_t searched = 0;
  const auto each_changed = [&](auto&& f) {
    for (const int32_t p : bp.changed) {
      if (bp.shape_kind[static_cast<size_t>(p)] == k_proxy_none) continue;
      ++searched;
      search.shape = p;
      q.box = bp.shape_fat[static_cast<size_t>(p)];
      f(p);
    }
  };
  switch (world->def.broad_phase) {
    case BroadPhaseKind::sweep_and_prune:
      if (!bp.changed.empty()) {
        broad_phase_list_proxies(world);
        sap_sync(world);
        sap_prepare_query(&bp);
      }
      each_changed([&](int32_t) { sap_query(world, &q); });
      break;
    case BroadPhaseKind::grid:
      grid_search_changed(world);
      each_changed([&](int32_t) {});
      break;
    case BroadPhaseKind::tree:
      tree_sync_changed(world);
      each_changed([&](int32_t) { tree_query(world, &q); });
      break;
    case BroadPhaseKind::naive:
    default:
      if (!bp.changed.empty()) broad_phase_list_proxies(world);
      each_changed([&](int32_t p) {
        for (const int32_t other : bp.proxies) broad_phase_offer_changed(world, p, other);
      });
      break;
  }
  bp.stats.proxies_searched = searched;
  // The new pairs in key order (keys are unique, so the order is too).
  std::sort(bp.unsorted.begin(), bp.unsorted.end());
  const size_t fresh_count = bp.unsorted.size();
  if (bp.changed.empty()) {  // nothing changed: the same pairs
    std::swap(bp.pairs, bp.previous);
    bp.stats.pairs_carried = static_cast<int32_t>(bp.pairs.size());
    return;
  }
  // Merge: previous pairs without a changed shape (in key order) and the new
  // ones (in key order; disjoint, since each new pair has a changed shape).
  const uint8_t* changed = bp.shape_changed.data();
  const uint64_t* fresh = bp.unsorted.data();
  bp.pairs.resize(bp.previous.size() + fresh_count);
  ShapePair* out = bp.pairs.data();
  size_t k = 0;
  const auto take_fresh = [&](uint64_t key) {
    *out++ = ShapePair{static_cast<int32_t>(key >> 32), static_cast<int32_t>(key & 0xFFFFFFFFu)};
  };
  for (const ShapePair& pr : bp.previous) {
    if ((changed[static_cast<size_t>(pr.shape_a)] | changed[static_cast<size_t>(pr.shape_b)]) != 0) continue;
    if (k < fresh_count) {
      const uint64_t key = shape_pair_key(pr.shape_a, pr.shape_b);
      while (k < fresh_count && fresh[k] < key) take_fresh(fresh[k++]);
    }
    *out++ = pr;
  }
  const size_t carried = static_cast<size_t>(out - bp.pairs.data()) - k;
  while (k < fresh_count) take_fresh(fresh[k++]);
  bp.pairs.resize(static_cast<size_t>(out - bp.pairs.data()));
  bp.stats.pairs_carried = static_cast<int32_t>(carried);
}

}  // namespace

void broad_phase_update_pairs(World* world) {
  const auto start = std::chrono::steady_clock::now();
  BroadPhase& bp = world->broad_phase;
  std::swap(bp.pairs, bp.previous);
  bp.pairs.clear();
  bp.unsorted.clear();
  bp.stats = BroadPhaseStats{};
  bp.candidate_count = 0;
  broad_phase_gather_proxies(world, true);
  // Compared once per update (a copy of the list only when it changed).
  const bool same_joint_keys = bp.joint_keys == world->joints.no_collide_keys;
  if (can_carry_over(bp, same_joint_keys)) {
    carry_over_update(world);
  } else {
    broad_phase_list_proxies(world);
    full_update(world);
    bp.stats.proxies_searched = bp.proxy_count;
  }
  // The changes are consumed: clear the sticky flags.
  if (static_cast<size_t>(bp.changed_count) == bp.changed.size()) {
    for (const int32_t s : bp.changed) bp.shape_changed[static_cast<size_t>(s)] = 0;
  } else {
    std::fill(bp.shape_changed.begin(), bp.shape_changed.end(), uint8_t{0});
  }
  if (!same_joint_keys) bp.joint_keys = world->joints.no_collide_keys;
  bp.pairs_valid = true;
  bp.stats.proxies = bp.proxy_count;
  bp.stats.pairs = static_cast<int32_t>(bp.pairs.size());
  bp.stats.candidate_pairs =
      bp.candidate_count > INT32_MAX ? INT32_MAX : static_cast<int32_t>(bp.candidate_count);
  const auto elapsed = std::chrono::steady_clock::now() - start;
  const int64_t ns = std::chrono::duration_cast<std::chrono::nanoseconds>(elapsed).count();
  bp.stats.update_nanoseconds = ns > 0 ? static_cast<uint64_t>(ns) : 0;
  // The rest of the step moves bodies: queries after it re-synchronise.
  bp.query_synced = false;
}

namespace {

/// Every proxy searched by the current kind (the reference path).
void full_update(World* world) {
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
}

}  // namespace

void broad_phase_reset(World* world) {
  BroadPhase& bp = world->broad_phase;
  bp.pairs.clear();
  bp.proxies.clear();
  bp.fat_bounds.clear();
  bp.proxy_dynamic.clear();
  bp.unsorted.clear();
  bp.sensors.clear();
  bp.query_synced = false;
  bp.pairs_valid = false;
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
  reserve_for(&bp.shape_box, shapes);
  reserve_for(&bp.shape_changed, shapes);
  reserve_for(&bp.changed, shapes / 4 + 64);
  reserve_for(&bp.previous, pairs);
  reserve_for(&bp.grid.outlier_shapes, shapes);
  reserve_for(&bp.grid.dirty, shapes);
  reserve_for(&bp.grid.is_dirty, shapes);
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
  world->broad_phase.pairs_valid = false;  // pairs were filtered by the old one
  world->broad_phase.custom_context = filter == nullptr ? nullptr : context;
  return s;
}

}  // namespace tandem

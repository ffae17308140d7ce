// broad_phase_sap.cpp — sweep and prune on x with persistent end points.
//
// The end points (min and max x of every proxy's fattened box) stay sorted
// between updates. Each update:
//   1. refreshes every end point's value from its shape's current box and
//      drops those of shapes that no longer take part (one compacting pass);
//   2. insertion-sorts the array — nearly sorted when most things move a
//      little or sleep, so this is close to linear; if the shifts pass a
//      budget (a scene that was shuffled) it finishes with std::sort instead;
//   3. sorts the end points of new proxies on their own and merges them in;
//   4. sweeps: a min end point opens an interval that is tested against every
//      open one (the exact test prunes on y), a max end point closes it.
// Keys are (value, tag) with tag = (is_max << 31) | shape index: unique, and
// at equal x the opening end points come first, so boxes that only touch are
// still found (closed intervals, as the contract's overlap test).
//
// Open intervals are kept in two lists, dynamic and not, so a static or
// kinematic proxy is only tested against dynamic ones. Each pair is found
// once: when the later-opening interval opens while the other is open.
//
// Rejected: incremental pair maintenance on swaps (Bullet's SAP): the contact
// stage wants the whole list each step anyway, and the exact test already
// filters the sweep's candidates.
#include <algorithm>

#include "physics/broad_phase.h"
#include "physics/world.h"

namespace tandem {

namespace {

constexpr uint32_t k_max_flag = 0x80000000u;

bool endpoint_less(const SapEndpoint& a, const SapEndpoint& b) {
  return a.value < b.value || (a.value == b.value && a.tag < b.tag);
}

/// Insertion sort that gives up (returns false) after `budget` shifts.
bool insertion_sort(std::vector<SapEndpoint>* v, int64_t budget) {
  SapEndpoint* e = v->data();
  const size_t n = v->size();
  int64_t shifts = 0;
  for (size_t i = 1; i < n; ++i) {
    const SapEndpoint x = e[i];
    size_t j = i;
    while (j > 0 && endpoint_less(x, e[j - 1])) {
      e[j] = e[j - 1];
      --j;
      ++shifts;
    }
    e[j] = x;
    if (shifts > budget) return false;
  }
  return true;
}

void remove_active(std::vector<int32_t>* list, std::vector<int32_t>* slot, int32_t shape) {
  const size_t pos = static_cast<size_t>((*slot)[static_cast<size_t>(shape)]);
  const int32_t last = list->back();
  (*list)[pos] = last;
  (*slot)[static_cast<size_t>(last)] = static_cast<int32_t>(pos);
  list->pop_back();
}

}  // namespace

void sap_reset(SweepAndPrune* sap) {
  sap->endpoints.clear();
  sap->present.clear();
  sap->added.clear();
  sap->merged.clear();
}

void sap_sync(World* world) {
  BroadPhase& bp = world->broad_phase;
  SweepAndPrune& sap = bp.sap;
  const size_t cap = static_cast<size_t>(id_pool_capacity(world->shape_pool));
  if (sap.present.size() < cap) sap.present.resize(cap, 0);
  if (sap.active_slot.size() < cap) sap.active_slot.resize(cap, 0);

  // 1. Refresh values; drop shapes that left.
  size_t kept = 0;
  for (size_t r = 0; r < sap.endpoints.size(); ++r) {
    SapEndpoint e = sap.endpoints[r];
    const size_t s = static_cast<size_t>(e.tag & ~k_max_flag);
    if (s >= cap || bp.shape_kind[s] == k_proxy_none) {
      if (s < sap.present.size()) sap.present[s] = 0;
      continue;
    }
    const AABB& box = bp.shape_fat[s];
    e.value = (e.tag & k_max_flag) != 0 ? box.upper.x.raw : box.lower.x.raw;
    sap.endpoints[kept++] = e;
  }
  sap.endpoints.resize(kept);

  // 2. Re-sort the survivors.
  const int64_t budget = 16 * static_cast<int64_t>(kept) + 1024;
  if (!insertion_sort(&sap.endpoints, budget)) {
    std::sort(sap.endpoints.begin(), sap.endpoints.end(), endpoint_less);
  }

  // 3. New proxies.
  sap.added.clear();
  for (const int32_t s : bp.proxies) {
    const size_t si = static_cast<size_t>(s);
    if (sap.present[si] != 0) continue;
    sap.present[si] = 1;
    const AABB& box = bp.shape_fat[si];
    sap.added.push_back(SapEndpoint{box.lower.x.raw, static_cast<uint32_t>(s)});
    sap.added.push_back(SapEndpoint{box.upper.x.raw, static_cast<uint32_t>(s) | k_max_flag});
  }
  if (!sap.added.empty()) {
    std::sort(sap.added.begin(), sap.added.end(), endpoint_less);
    sap.merged.resize(sap.endpoints.size() + sap.added.size());
    std::merge(sap.endpoints.begin(), sap.endpoints.end(), sap.added.begin(), sap.added.end(), sap.merged.begin(),
               endpoint_less);
    std::swap(sap.endpoints, sap.merged);
  }
}

void sap_update(World* world) {
  sap_sync(world);
  BroadPhase& bp = world->broad_phase;
  SweepAndPrune& sap = bp.sap;

  // 4. Sweep.
  sap.active_dynamic.clear();
  sap.active_other.clear();
  int64_t candidates = 0;
  for (const SapEndpoint& e : sap.endpoints) {
    const int32_t s = static_cast<int32_t>(e.tag & ~k_max_flag);
    const size_t si = static_cast<size_t>(s);
    const bool dynamic = bp.shape_kind[si] == k_proxy_dynamic;
    std::vector<int32_t>& own = dynamic ? sap.active_dynamic : sap.active_other;
    if ((e.tag & k_max_flag) != 0) {
      remove_active(&own, &sap.active_slot, s);
      continue;
    }
    const AABB box = bp.shape_fat[si];
    for (const int32_t t : sap.active_dynamic) {
      ++candidates;
      if (aabb_overlaps(box, bp.shape_fat[static_cast<size_t>(t)])) broad_phase_emit_overlapping(world, s, t);
    }
    if (dynamic) {
      for (const int32_t t : sap.active_other) {
        ++candidates;
        if (aabb_overlaps(box, bp.shape_fat[static_cast<size_t>(t)])) broad_phase_emit_overlapping(world, s, t);
      }
    }
    sap.active_slot[si] = static_cast<int32_t>(own.size());
    own.push_back(s);
  }
  bp.candidate_count += candidates;
}

}  // namespace tandem

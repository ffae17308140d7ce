// broad_phase_query.cpp — candidates for world queries from the current
// broad phase (see "Queries" in broad_phase.h; query.cpp runs the exact tests
// and orders the results).
//
// Sync: a query first re-runs the current kind's synchronisation when the
// structure is stale (broad_phase_mark_stale, or any update, since the step
// moves bodies after its update). For sweep-and-prune it also splits the
// proxies into narrow and wide on x (below); the other kinds need nothing
// beyond what their update keeps.
//
// Sweep-and-prune has sorted end points on x but no interval index, so a box
// query finds the proxies with lower x in [x0 − W, x1] by a binary search,
// where W is the widest "narrow" proxy, and scans the few wide ones (wider
// than 4× the 15/16-quantile power-of-two width class, the grid's outlier
// rule: walls and grounds) separately.
//
// Sweep-and-prune and the grid walk in the ray's direction (x, resp. rows in
// y) and the tree takes the nearer child first, re-reading the ray's current
// bounds as they go, so a closest hit found early ends the walk.
//
// The segment test is exact: the segment's bounding box against the box, then
// the separating axis along the segment's normal, |n·(2c − 2p)| ≤ |n_x|·2h_x +
// |n_y|·2h_y on doubled raw values in 128-bit integers (fixed/wide.h; the
// doubled box terms stay below 2^62 for any sanitised or fattened box and the
// ray's terms below 2^56, so sums of products stay below 2^120), so no box the
// segment touches is ever skipped. A ray's far end moves in to origin +
// translation · f (rounded to nearest) when a closest-hit visitor lowers f;
// the candidates' fattened boxes reach k_speculative_distance (0.02 m, about
// 2^26 raw) beyond the shapes' bounds, far more than that rounding or a ray
// cast's own (a hit point lies on the shape and on the ray to within a few raw
// units), so a shape hit at or before f always stays a candidate.
#include <algorithm>
#include <bit>

#include "fixed/wide.h"
#include "physics/broad_phase.h"
#include "physics/world.h"

namespace tandem {

namespace {

uint64_t x_width(const AABB& b) {
  return static_cast<uint64_t>(b.upper.x.raw) - static_cast<uint64_t>(b.lower.x.raw);
}

}  // namespace

/// Splits the proxies for sap_query (file comment).
void sap_prepare_query(BroadPhase* bp) {
  SweepAndPrune& sap = bp->sap;
  sap.wide.clear();
  sap.query_width = 0;
  const size_t n = bp->proxies.size();
  if (n == 0) return;
  int32_t histogram[65] = {};
  for (size_t i = 0; i < n; ++i) ++histogram[std::bit_width(x_width(bp->fat_bounds[i]))];
  const uint64_t limit = broad_phase_typical_limit(histogram, static_cast<int32_t>(n));
  uint64_t widest = 0;
  for (size_t i = 0; i < n; ++i) {
    const uint64_t w = x_width(bp->fat_bounds[i]);
    if (w > limit) {
      sap.wide.push_back(bp->proxies[i]);
    } else if (w > widest) {
      widest = w;
    }
  }
  sap.query_width = static_cast<int64_t>(widest);  // ≤ 2^62: sanitised, fattened boxes
}

namespace {

void naive_query(World* world, BroadPhaseQuery* q) {
  BroadPhase& bp = world->broad_phase;
  const size_t n = bp.proxies.size();
  for (size_t i = 0; i < n; ++i) {
    if (q->accepts(bp.fat_bounds[i])) q->offer(bp.proxies[i]);
  }
}

void run_query(World* world, BroadPhaseQuery* q, bool include_sensors) {
  broad_phase_sync_for_query(world);
  switch (world->def.broad_phase) {
    case BroadPhaseKind::sweep_and_prune: sap_query(world, q); break;
    case BroadPhaseKind::grid: grid_query(world, q); break;
    case BroadPhaseKind::tree: tree_query(world, q); break;
    case BroadPhaseKind::naive:
    default: naive_query(world, q); break;
  }
  if (!include_sensors) return;
  // Fattened like the proxies, so the same margin covers a ray's rounding.
  for (const int32_t s : world->broad_phase.sensors) {
    if (q->accepts(aabb_fatten(world->shapes[static_cast<size_t>(s)].aabb, k_speculative_distance))) q->offer(s);
  }
}

}  // namespace

bool segment_overlaps_box(Vec2 p, Vec2 q, const AABB& b) {
  const AABB seg{min(p, q), max(p, q)};
  if (!aabb_overlaps(seg, b)) return false;
  // Ranges (file comment): |p|, |q| < 2^55; box coordinates within ±2^60
  // plus margins, so every difference and sum below fits int64.
  const int64_t dx = q.x.raw - p.x.raw;
  const int64_t dy = q.y.raw - p.y.raw;
  const int64_t cx = b.lower.x.raw + b.upper.x.raw - 2 * p.x.raw;
  const int64_t cy = b.lower.y.raw + b.upper.y.raw - 2 * p.y.raw;
  const int64_t hx = b.upper.x.raw - b.lower.x.raw;
  const int64_t hy = b.upper.y.raw - b.lower.y.raw;
  const wide::U128 side = wide::abs_u(wide::sub(wide::mul_s64(dx, cy), wide::mul_s64(dy, cx)));
  const wide::U128 reach = wide::add(wide::mul_s64(dy < 0 ? -dy : dy, hx), wide::mul_s64(dx < 0 ? -dx : dx, hy));
  return !wide::less_u(reach, side);
}

void BroadPhaseQuery::offer(int32_t shape) {
  const Q32 f = visit(context, shape);
  if (!is_ray || !(f < max_fraction)) return;
  max_fraction = f < Q32::zero() ? Q32::zero() : f;
  end = origin + translation * max_fraction;
  box = AABB{min(origin, end), max(origin, end)};
}

void broad_phase_mark_stale(World* world) { world->broad_phase.query_synced = false; }

void broad_phase_sync_for_query(World* world) {
  BroadPhase& bp = world->broad_phase;
  if (bp.query_synced) return;
  broad_phase_gather_proxies(world, false);
  switch (world->def.broad_phase) {
    case BroadPhaseKind::sweep_and_prune:
      sap_sync(world);
      sap_prepare_query(&bp);
      break;
    case BroadPhaseKind::grid: grid_sync(world); break;
    case BroadPhaseKind::tree: tree_sync(world); break;
    case BroadPhaseKind::naive:
    default: break;
  }
  bp.query_synced = true;
}

void broad_phase_query_box(World* world, AABB box, bool include_sensors, BroadPhaseVisit visit, void* context) {
  BroadPhaseQuery q;
  q.box = box;
  q.visit = visit;
  q.context = context;
  run_query(world, &q, include_sensors);
}

void broad_phase_query_ray(World* world, Vec2 origin, Vec2 translation, bool include_sensors, BroadPhaseVisit visit,
                           void* context) {
  BroadPhaseQuery q;
  q.is_ray = true;
  q.origin = origin;
  q.translation = translation;
  q.max_fraction = Q32::one();
  q.end = origin + translation;
  q.box = AABB{min(origin, q.end), max(origin, q.end)};
  q.visit = visit;
  q.context = context;
  run_query(world, &q, include_sensors);
}

void sap_query(World* world, BroadPhaseQuery* q) {
  const BroadPhase& bp = world->broad_phase;
  const SweepAndPrune& sap = bp.sap;
  const int64_t reach = sap.query_width;
  const uint64_t limit = static_cast<uint64_t>(reach);
  const auto try_endpoint = [&](const SapEndpoint& e) {
    if ((e.tag & 0x80000000u) != 0) return;  // a max end point
    const int32_t s = static_cast<int32_t>(e.tag);
    const AABB& fat = bp.shape_fat[static_cast<size_t>(s)];
    if (x_width(fat) > limit) return;  // wide: below
    if (q->accepts(fat)) q->offer(s);
  };
  // Narrow proxies have lower x in [x0 − W, x1] of the query's current box
  // (x0 − W ≥ −2^62: the box lies within ±2^56, W ≤ 2^62 − 2^56). Walked in
  // the ray's x direction, so a closest hit that pulls the far end in also
  // ends the walk.
  const std::vector<SapEndpoint>& ep = sap.endpoints;
  const auto by_value = [](const SapEndpoint& e, int64_t v) { return e.value < v; };
  if (q->is_ray && q->translation.x < Q32::zero()) {
    auto it = std::lower_bound(ep.begin(), ep.end(), q->box.upper.x.raw + 1, by_value);
    while (it != ep.begin()) {
      --it;
      if (it->value < q->box.lower.x.raw - reach) break;
      try_endpoint(*it);
    }
  } else {
    auto it = std::lower_bound(ep.begin(), ep.end(), q->box.lower.x.raw - reach, by_value);
    for (; it != ep.end() && it->value <= q->box.upper.x.raw; ++it) try_endpoint(*it);
  }
  for (const int32_t s : sap.wide) {
    if (q->accepts(bp.shape_fat[static_cast<size_t>(s)])) q->offer(s);
  }
}

}  // namespace tandem

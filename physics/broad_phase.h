// broad_phase.h — candidate shape pairs for the contact stage (internal).
//
// Contract every broad phase implements (naive, sweep-and-prune, grid and
// tree, selected by WorldDef::broad_phase / world_set_broad_phase):
//   * Input: the world's live shapes with their world AABBs (Shape::aabb,
//     updated at the end of each step and on teleport), passed through
//     broad_phase_sanitize_box (the identity for any box a world computes;
//     any box at all, inverted or at the limits of Q32, is safe).
//   * Output: every pair of shapes whose AABBs, each fattened by
//     k_speculative_distance, overlap (closed intervals) and that may
//     collide (shapes_should_collide, then the custom filter), as (lower
//     shape index, higher shape index), sorted ascending by that key, without
//     duplicates. The output depends only on the shapes' data, never on
//     addresses or the order in which an implementation visits them, so every
//     broad phase gives the same list for the same world — the contact
//     stage's order (contact.cpp) starts here.
//   * No heap allocation once warmed up: the pair buffer and any scratch are
//     kept in the BroadPhase record and only grow.
//
// How the four keep the contract (broad_phase.cpp has the shared part):
//   * A shared pre-pass lists the proxies (live, non-sensor shapes on enabled
//     bodies) in ascending shape index with their fattened boxes and whether
//     their body is dynamic. Whatever a structure visits, a candidate pair
//     goes through one function, emit_candidate(): skip two non-dynamic
//     shapes, the exact fattened-box test, the filters. So a structure may
//     over-approximate (a tree's enlarged boxes, a grid's cells) but the test
//     that decides is the naive one's, bit for bit.
//   * Each structure finds every overlapping pair exactly once; the emitted
//     keys are then put in order by a counting sort on the lower index and an
//     insertion sort of each lower index's few partners (a global sort of all
//     pairs was ~10× slower in the prototype). Keys are unique, so the order
//     is the unique sorted order.
//   * naive (broad_phase.cpp): all pairs in key order, no sort.
//   * sweep_and_prune (broad_phase_sap.cpp): persistent end points on x.
//   * grid (broad_phase_grid.cpp): Max Grid, rebuilt every step.
//   * tree (broad_phase_tree.cpp): persistent dynamic AABB tree.
//   Persistent state is keyed by shape index and re-synchronised from the
//   shapes at every update (a pass over the shape slots comparing boxes), so
//   no other file has to tell the broad phase about creates, destroys or
//   teleports, and broad_phase_reset() (snapshot restore, kind change) only
//   has to forget it.
//   * Carry-over (broad_phase.cpp): when few proxies changed since the last
//     update, only they are searched and the other pairs are kept; the list
//     is the full search's, bit for bit.
#pragma once

#include <cstdint>
#include <vector>

#include "fixed/vec2.h"
#include "physics/defs.h"
#include "physics/tandem.h"

namespace tandem {

struct World;
struct Shape;
struct Body;

/// A candidate pair: shape indices with shape_a < shape_b.
struct ShapePair {
  int32_t shape_a = 0;
  int32_t shape_b = 0;
};

/// The sort key of a pair: (lower index << 32) | higher index.
constexpr uint64_t shape_pair_key(int32_t lower, int32_t higher) {
  return (static_cast<uint64_t>(static_cast<uint32_t>(lower)) << 32) | static_cast<uint32_t>(higher);
}

/// Per shape index: whether the shape took part in the last update.
inline constexpr uint8_t k_proxy_none = 0;     ///< dead, sensor or on a disabled body
inline constexpr uint8_t k_proxy_static = 1;   ///< on a static or kinematic body
inline constexpr uint8_t k_proxy_dynamic = 2;  ///< on a dynamic body

/// A sweep-and-prune end point: the x of a box side and a tag, (is_max << 31)
/// | shape index. Sorted by (value, tag): at equal x the minimum end points
/// come first (closed intervals touch), and the tag makes the key unique.
struct SapEndpoint {
  int64_t value = 0;
  uint32_t tag = 0;
};

/// Persistent sweep-and-prune state (broad_phase_sap.cpp).
struct SweepAndPrune {
  std::vector<SapEndpoint> endpoints;  ///< sorted by (value, tag)
  std::vector<SapEndpoint> added;      ///< scratch: end points of new proxies
  std::vector<SapEndpoint> merged;     ///< scratch: merge target
  std::vector<uint8_t> present;        ///< by shape index: 1 when its end points are in `endpoints`
  std::vector<int32_t> active_dynamic; ///< sweep scratch: open intervals of dynamic shapes
  std::vector<int32_t> active_other;   ///< sweep scratch: open intervals of the others
  std::vector<int32_t> active_slot;    ///< by shape index: position in its active list
  // Queries (broad_phase_query.cpp), set by the last sync: proxies wider on x
  // than query_width are listed in `wide` (ascending shape index) and found by
  // a scan; the others by a binary search of `endpoints` from x − query_width.
  std::vector<int32_t> wide;
  int64_t query_width = 0;             ///< raw Q32, ≥ 0
};

/// One grid entry (broad_phase_grid.cpp), stored in bucket order so a cell's
/// proxies are read from consecutive memory.
struct GridEntry {
  AABB box;             ///< fattened bounds
  uint64_t cell = 0;    ///< (uint32 cx << 32) | uint32 cy
  int32_t shape = 0;    ///< shape index
  uint8_t dynamic = 0;  ///< 1 when on a dynamic body
};

/// Max Grid scratch, rebuilt each update (broad_phase_grid.cpp).
struct Grid {
  std::vector<uint64_t> proxy_cell;     ///< per proxy: cell key, or 0x8000000080000000 for an outlier
  std::vector<uint32_t> proxy_bucket;   ///< per proxy: hash bucket
  std::vector<uint32_t> bucket_start;   ///< table size + 1 offsets into entries
  std::vector<GridEntry> entries;       ///< grid proxies in bucket order
  std::vector<int32_t> outliers;        ///< proxy positions of outliers, ascending
  std::vector<int32_t> outlier_shapes;  ///< the same outliers as shape indices (positions shift between gathers)
  // Carry-over updates (broad_phase.cpp, "Carry-over"): shapes whose box,
  // kind or filter changed since this grid was built. Their entries (and
  // outlier slots) are stale; the search reads them from `dirty` instead.
  std::vector<int32_t> dirty;           ///< shape indices, in the order they became dirty
  std::vector<uint8_t> is_dirty;        ///< by shape index: 1 when listed in `dirty`
  int64_t cell_size = 0;                ///< raw Q32 (last update; for tests); 0 while no grid was built
  uint32_t bucket_bits = 0;             ///< table size = 1 << bucket_bits
  // The occupied cell range and layout, kept for queries.
  int64_t min_cx = 0, min_cy = 0, max_cx = -1, max_cy = -1;
  uint64_t width = 1;                   ///< cells per row in the dense layout
  bool dense = true;
};

/// A dynamic-tree node (broad_phase_tree.cpp). A leaf has child1 = −1.
struct TreeNode {
  AABB box;              ///< leaf: the shape's fattened box grown by the tree margin; inner: union of children
  int32_t parent = -1;   ///< parent node, −1 at the root; next free node while on the free list
  int32_t child1 = -1;
  int32_t child2 = -1;
  int32_t height = 0;    ///< leaf 0; −1 while free
  int32_t shape = -1;    ///< leaf: shape index
};

/// Persistent dynamic AABB tree (broad_phase_tree.cpp).
struct DynamicTree {
  std::vector<TreeNode> nodes;        ///< node pool
  int32_t root = -1;
  int32_t free_list = -1;             ///< LIFO list through TreeNode::parent
  std::vector<int32_t> leaf_of_shape; ///< by shape index: leaf node or −1
  std::vector<int32_t> stack;         ///< traversal scratch (node pairs)
};

/// What the pair filter needs of a proxy, copied by the pre-pass into one
/// dense array so the filter does not chase Shape and Body records.
struct ProxyFilter {
  int32_t body = -1;
  int32_t group_index = 0;
  uint64_t category_bits = 0;
  uint64_t mask_bits = 0;
};

/// Broad-phase state kept between steps (buffers that only grow).
struct BroadPhase {
  std::vector<ShapePair> pairs;   ///< the last update's output, sorted by shape_pair_key
  std::vector<int32_t> proxies;   ///< scratch: shapes that take part, ascending index
  std::vector<AABB> fat_bounds;   ///< scratch: their fattened bounds, parallel to proxies
  std::vector<uint8_t> proxy_dynamic;  ///< scratch: 1 when on a dynamic body, parallel to proxies
  std::vector<AABB> shape_fat;    ///< by shape index: fattened bounds (valid where shape_kind ≠ none)
  std::vector<uint8_t> shape_kind;     ///< by shape index: k_proxy_*
  std::vector<ProxyFilter> shape_filter;  ///< by shape index: body and filter (valid for proxies)
  std::vector<uint64_t> unsorted; ///< scratch: emitted keys in the structure's visiting order
  // Carry-over (broad_phase.cpp): what the last update's pairs were computed
  // from, so pairs between two unchanged proxies can be kept. Never state: a
  // restore, a kind change or a custom filter change clears pairs_valid.
  std::vector<AABB> shape_box;          ///< by shape index: Shape::aabb the fat box was computed from
  int32_t proxy_count = 0;             ///< proxies at the last gather (the lists may not be built in a step)
  std::vector<uint8_t> shape_changed;  ///< by shape index: kind, fat box or filter differs from the last update
  std::vector<int32_t> changed;        ///< scratch: shapes with shape_changed set, ascending (while ≤ the limit)
  int32_t changed_count = 0;           ///< shapes with shape_changed set at the last gather
  std::vector<ShapePair> previous;     ///< scratch: the last update's pairs during an update
  std::vector<uint64_t> joint_keys;    ///< World::joints.no_collide_keys at the last update
  bool pairs_valid = false;            ///< `pairs` and the by-shape arrays describe the last update
  std::vector<int32_t> counts;    ///< scratch: counting sort by lower index
  SweepAndPrune sap;
  Grid grid;
  DynamicTree tree;
  BroadPhaseStats stats;          ///< the last update's figures
  int64_t candidate_count = 0;    ///< the update's exact tests so far (clamped into stats)
  CustomFilterFn custom_filter = nullptr;
  void* custom_context = nullptr;
  // Queries (broad_phase_query.cpp).
  std::vector<int32_t> sensors;   ///< live sensor shapes on enabled bodies at the last sync, ascending index
  bool query_synced = false;      ///< the structure and by-shape arrays hold the shapes' current bounds
  bool query_brute_force = false; ///< tests: queries visit every shape (the reference path)
};

/// True when two shapes may form a contact by their filters alone (Box2D's
/// rule): a shared non-zero group index decides (positive: always, negative:
/// never); otherwise (A.category & B.mask) != 0 and (B.category & A.mask) != 0.
bool filters_should_collide(const Filter& a, const Filter& b);

/// True when two live shapes may form a contact: different bodies, neither a
/// sensor, both bodies enabled, at least one body dynamic, the filters agree,
/// and the world's custom filter (if any) accepts (lower, higher).
bool shapes_should_collide(const World& world, int32_t shape_a, int32_t shape_b);

/// Recomputes world->broad_phase.pairs (see the contract above) with the
/// world's broad-phase kind, and its stats (touching_pairs excepted).
void broad_phase_update_pairs(World* world);

/// Drops all persistent broad-phase state (sorted end points, grid, tree),
/// keeping buffer capacity, so the next update rebuilds from the shapes. A
/// snapshot restore and a change of broad-phase kind call it. Never fails.
void broad_phase_reset(World* world);

/// Grows the broad phase's buffers (outside the step) so that the next steps
/// of a scene whose counts drift a little do not allocate.
void broad_phase_reserve_headroom(World* world);

/// Raw Q32 bound (2^60, about 2.7e8 m) that broad_phase_sanitize_box clamps
/// box coordinates into; every box of a valid world lies far inside it
/// (limits.h: ±k_max_world_coordinate plus k_max_shape_size).
inline constexpr int64_t k_broad_phase_coordinate_limit = int64_t{1} << 60;

/// The box every broad phase works on for a shape's stored AABB: each
/// coordinate clamped into ±k_broad_phase_coordinate_limit, then lower and
/// upper swapped on an axis where lower > upper. For a box the world computed
/// (ordered, in range) it returns the box unchanged, so results do not move;
/// for a corrupt one (an inverted or huge box, say from a crafted snapshot
/// that bypassed restore's checks) every broad phase still sees the same
/// ordered, in-range box, so none reads out of bounds, overflows or hangs, and
/// all four still report the same pairs.
AABB broad_phase_sanitize_box(AABB box);

// ---------------------------------------------------------------------------
// Queries (broad_phase_query.cpp)
// ---------------------------------------------------------------------------
//
// Between steps the world queries (query.cpp) ask the current structure for
// candidates instead of visiting every shape. The structure is brought up to
// date first (broad_phase_sync_for_query): the step's update synchronised it
// with the poses at the START of the step, and teleports, creations,
// destructions and enable/disable since then change bounds too, so every
// such change (and every update) marks it stale and the next query re-runs
// the update's synchronisation part — gather the proxies, then sweep-and-
// prune's end-point refresh and merge, the grid's build or the tree's
// re-inserts — without looking for pairs. What that sync does is what the next
// step's update would do with the same bounds, so a query costs the step
// nothing extra; the pair list (and so every simulated bit) does not depend on
// it either way (the contract above).
//
// A candidate is a shape whose fattened box (structure boxes are larger
// still) meets the query box or the ray segment; every shape the exact tests
// would accept is a candidate, each is offered exactly once, in an order that
// is a function of the structure (callers sort or take a unique minimum, so
// results never depend on it). Sensors are not proxies: with include_sensors
// the live sensors on enabled bodies are offered too (a scan of that list).

/// Called once per candidate shape index. Returns the largest ray fraction
/// still of interest (a closest-hit query returns its best fraction so far, so
/// farther boxes are skipped; an all-hits query returns 1); box queries ignore
/// the value.
using BroadPhaseVisit = Q32 (*)(void* context, int32_t shape);

/// Marks the query structure stale: bounds, the live set or a body's enabled
/// flag changed outside the broad phase's knowledge (teleport, create, destroy,
/// enable, disable). Cheap; the next query re-synchronises.
void broad_phase_mark_stale(World* world);

/// Brings the current kind's structure up to date with the shapes (a no-op when
/// nothing changed since the last sync). Outside a step only.
void broad_phase_sync_for_query(World* world);

/// Offers every shape whose fattened box overlaps `box` (closed), then, with
/// include_sensors, every sensor whose bounds overlap it. Syncs first.
void broad_phase_query_box(World* world, AABB box, bool include_sensors, BroadPhaseVisit visit, void* context);

/// Offers every shape whose fattened box meets the segment origin → origin +
/// translation · f, where f starts at 1 and is lowered to each visit's return
/// value; then the sensors likewise (include_sensors). Syncs first.
void broad_phase_query_ray(World* world, Vec2 origin, Vec2 translation, bool include_sensors, BroadPhaseVisit visit,
                           void* context);

/// Whether the closed segment p → q meets the closed box b; exact (128-bit
/// separating-axis test), so it never rejects a box the segment touches.
bool segment_overlaps_box(Vec2 p, Vec2 q, const AABB& b);

/// One query as the structures see it: a box, or a ray whose far end moves in
/// as the visitor lowers its fraction (then `box` bounds the current segment).
struct BroadPhaseQuery {
  AABB box;                  ///< query box, or bounds of origin → end
  bool is_ray = false;
  Vec2 origin;               ///< ray start, m
  Vec2 translation;          ///< full ray, m
  Vec2 end;                  ///< origin + translation · max_fraction (rounded to nearest), m
  Q32 max_fraction;          ///< in [0, 1]
  BroadPhaseVisit visit = nullptr;
  void* context = nullptr;

  /// Whether a structure box `b` may hold a candidate: it meets the box, and
  /// for a ray the current segment.
  bool accepts(const AABB& b) const {
    return aabb_overlaps(box, b) && (!is_ray || segment_overlaps_box(origin, end, b));
  }
  /// Offers a candidate shape; a ray takes the visitor's fraction when lower.
  void offer(int32_t shape);
};

// The structures' queries: each offers every proxy whose fattened box
// q->accepts(), exactly once (broad_phase_query.cpp has naive's).
void sap_query(World* world, BroadPhaseQuery* q);
void grid_query(World* world, BroadPhaseQuery* q);
void tree_query(World* world, BroadPhaseQuery* q);

// Shared by the implementations (broad_phase.cpp).

/// The outlier rule of the grid (and of sweep-and-prune's queries): given a
/// histogram of extents by power-of-two class (histogram[std::bit_width(e)],
/// 65 entries) over `count` proxies, 4× the class bound that holds 15/16 of
/// them; extents above it are outsized.
uint64_t broad_phase_typical_limit(const int32_t* histogram, int32_t count);

/// The candidate (a, b), a ≠ b, in either order: unless both are non-dynamic,
/// counts it, applies the exact fattened-box test and the filters, and
/// appends its key to bp.unsorted. The caller guarantees each unordered pair
/// is offered at most once per update.
void broad_phase_emit_candidate(World* world, int32_t a, int32_t b);

/// The tail of broad_phase_emit_candidate for a caller that has already
/// skipped non-dynamic pairs, counted the candidate and found the fattened
/// boxes (bp.shape_fat) overlapping: the filters, then the key.
void broad_phase_emit_overlapping(World* world, int32_t a, int32_t b);

// The structures (one file each). Each fills bp.unsorted from the proxies
// listed by the pre-pass (bp.proxies, bp.shape_fat, bp.shape_kind).
// *_sync brings the structure up to date with the pre-pass (queries use it
// alone); *_update is sync followed by the pair search.
void sap_sync(World* world);
void sap_update(World* world);
void sap_reset(SweepAndPrune* sap);
void grid_sync(World* world);
void grid_update(World* world);
void tree_sync(World* world);
void tree_update(World* world);
void tree_reset(DynamicTree* tree);
/// Fills the by-shape arrays, flags and lists the changed shapes and counts
/// the proxies; the first part of every update and sync. `in_step`: inside
/// world_step, where the per-shape part may run on the world's workers and
/// the proxy lists are left to broad_phase_list_proxies (an update that
/// carries pairs over may not need them); false (queries between steps)
/// runs it on the calling thread, never calls a user task callback, and
/// lists the proxies too.
void broad_phase_gather_proxies(World* world, bool in_step);
/// Lists the proxies (bp.proxies, fat_bounds, proxy_dynamic; ascending shape
/// index) and the sensors from the by-shape arrays of the last gather.
void broad_phase_list_proxies(World* world);
/// Carry-over search of one changed proxy (broad_phase.cpp): for every proxy
/// q the structure offers whose fattened box overlaps p's, emits (p, q)
/// unless q is p, both are non-dynamic, or q also changed and q < p (that
/// pair is emitted from q's side). Counts candidates and the search.
void broad_phase_offer_changed(World* world, int32_t p, int32_t q);
/// The carry-over searches of the structures: every changed proxy (bp.changed)
/// against every proxy, through broad_phase_offer_changed.
void grid_search_changed(World* world);
/// Sweep-and-prune's split of the proxies for sap_query (broad_phase_query.cpp).
void sap_prepare_query(BroadPhase* bp);
/// tree_sync restricted to the changed shapes (bp.changed, ascending): the
/// same tree as tree_sync, since an unchanged shape's leaf needs no work.
void tree_sync_changed(World* world);
/// Checks the tree's structure (parents, heights, boxes containing children);
/// for tests. Returns the number of leaves, or −1 when broken.
int32_t tree_validate(const DynamicTree& tree);

}  // namespace tandem

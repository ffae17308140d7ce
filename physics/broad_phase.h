// broad_phase.h — candidate shape pairs for the contact stage (internal).
//
// Contract every broad phase implements (naive now; sweep-and-prune, grid and
// tree later, selected by WorldDef::broad_phase):
//   * Input: the world's live shapes with their world AABBs (Shape::aabb,
//     updated at the end of each step and on teleport).
//   * Output: every pair of shapes whose AABBs, each fattened by
//     k_speculative_distance, overlap (closed intervals) and that may
//     collide (shapes_should_collide), as (lower shape index, higher shape
//     index), sorted ascending by that key, without duplicates. The output
//     depends only on the shapes' data, never on addresses or the order in
//     which an implementation visits them, so every broad phase gives the
//     same list for the same world — the contact stage's order (contact.cpp)
//     starts here.
//   * No heap allocation once warmed up: the pair buffer and any scratch are
//     kept in the BroadPhase record and only grow.
//
// The naive implementation tests all pairs (O(n²)), in ascending shape index
// for the lower shape and then the higher one, which is already the output
// order. Rejected for now: anything smarter — that is the broad-phase issue.
#pragma once

#include <cstdint>
#include <vector>

#include "fixed/vec2.h"
#include "physics/defs.h"

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

/// Broad-phase state kept between steps (buffers that only grow).
struct BroadPhase {
  std::vector<ShapePair> pairs;   ///< the last update's output, sorted by shape_pair_key
  std::vector<int32_t> proxies;   ///< scratch: shapes that take part, ascending index
  std::vector<AABB> fat_bounds;   ///< scratch: their fattened bounds, parallel to proxies
};

/// True when two shapes may form a contact by their filters alone (Box2D's
/// rule): a shared non-zero group index decides (positive: always, negative:
/// never); otherwise (A.category & B.mask) != 0 and (B.category & A.mask) != 0.
bool filters_should_collide(const Filter& a, const Filter& b);

/// True when two live shapes may form a contact: different bodies, neither a
/// sensor, both bodies enabled, at least one body dynamic, and the filters
/// agree.
bool shapes_should_collide(const World& world, int32_t shape_a, int32_t shape_b);

/// Recomputes world->broad_phase.pairs (see the contract above).
void broad_phase_update_pairs(World* world);

}  // namespace tandem

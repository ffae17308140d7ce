// id_pool.h — slot allocation with generation counters, for bodies, shapes,
// joints (and, with a fixed capacity, worlds).
//
// Reuse order: allocation returns the LOWEST free index, and a fresh index
// (the current capacity) only when no slot is free. So the index handed out
// depends only on which slots are free, never on the order in which they were
// freed. Two consequences: the same sequence of creates and destroys gives the
// same indices on every machine; and a snapshot needs to store only each
// slot's generation and alive flag — the free set, and therefore every future
// allocation, follows from them.
//
// Rejected: Box2D's LIFO free array (O(1), but the next index depends on the
// destroy order, which a snapshot would then have to store). Lowest-first
// costs O(log n) per allocate and free through a binary min-heap of the free
// indices; the heap's internal layout may differ between standard libraries,
// but its minimum is unique (indices are distinct), so the allocation order
// does not.
//
// Generations: a slot starts at generation 1; free() increments it (from
// 2^32 − 1 it wraps to 1, skipping 0). A handle {index, generation} is valid
// while the slot is alive with that generation.
//
// The pool allocates (vector growth) only in allocate() and free(), which the
// world calls between steps, never inside one.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "physics/ids.h"

namespace tandem {

/// Slots with generation counters. Plain data; use the id_pool_* functions.
struct IdPool {
  std::vector<uint32_t> generations;  ///< per slot; ≥ 1; the live object's generation while alive
  std::vector<uint8_t> alive;         ///< per slot; 1 while allocated
  std::vector<int32_t> free_heap;     ///< min-heap of free slot indices
  int32_t alive_count = 0;            ///< slots currently allocated
};

/// Allocates the lowest free slot, or a new one at the end; returns its index
/// (≥ 0). The slot's generation is unchanged by allocation (1 for a new slot).
int32_t id_pool_allocate(IdPool* pool);

/// Frees an allocated slot and increments its generation (skipping 0).
/// Freeing a slot that is not alive is an invariant failure (TANDEM_ASSERT).
void id_pool_free(IdPool* pool, int32_t index);

/// The number of slots ever allocated (highest index + 1).
inline int32_t id_pool_capacity(const IdPool& pool) { return static_cast<int32_t>(pool.generations.size()); }

/// True when the slot exists and is allocated.
inline bool id_pool_is_alive(const IdPool& pool, int32_t index) {
  return index >= 0 && index < id_pool_capacity(pool) && pool.alive[static_cast<size_t>(index)] != 0;
}

/// The slot's current generation (0 for a slot that was never allocated).
inline uint32_t id_pool_generation(const IdPool& pool, int32_t index) {
  if (index < 0 || index >= id_pool_capacity(pool)) return 0;
  return pool.generations[static_cast<size_t>(index)];
}

/// True when the slot is alive with exactly this generation.
inline bool id_pool_is_valid(const IdPool& pool, int32_t index, uint32_t generation) {
  return id_pool_is_alive(pool, index) && pool.generations[static_cast<size_t>(index)] == generation;
}

/// Reserves room for `capacity` slots so later allocations up to that many do
/// not grow the arrays.
void id_pool_reserve(IdPool* pool, int32_t capacity);

/// The generation after `generation`: +1, wrapping from 2^32 − 1 to 1.
constexpr uint32_t next_generation(uint32_t generation) { return generation == UINT32_MAX ? 1u : generation + 1u; }

}  // namespace tandem

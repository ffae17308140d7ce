// arena.h — the per-step stack allocator.
//
// step() takes all its scratch memory (solver bodies, later contact
// constraints, colour batches, island work lists) from one contiguous block,
// allocating and freeing in nested (LIFO) order, and the block is empty again
// when step() returns. When a step needs more than the block holds, the
// excess comes from the heap for that step only, the high-water mark is
// recorded, and arena_grow() — called by step() after the arena is empty —
// replaces the block by one 1.5× the high-water mark. After the first steps of
// a scene the block is big enough and step() makes no heap allocation
// (tests/physics/test_world.cpp counts them).
//
// Alignment: every allocation starts on a 16-byte boundary (sizes are rounded
// up), enough for every Q32.32 and 128-bit type used here.
//
// Rejected: a growable vector per stage (reallocates mid-step, one heap block
// per array); a free-list allocator (order of reuse would need care for
// determinism; nested lifetimes make a stack sufficient).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <type_traits>

#include "physics/ids.h"

namespace tandem {

/// Alignment of every arena allocation, bytes.
inline constexpr int64_t k_arena_alignment = 16;
/// Most live allocations at once (a fixed table, so the arena itself never
/// allocates bookkeeping).
inline constexpr int32_t k_max_arena_entries = 64;

/// One live allocation.
struct ArenaEntry {
  std::byte* data = nullptr;
  int64_t size = 0;        ///< bytes, rounded up to k_arena_alignment
  bool used_heap = false;  ///< true when the block was full and this came from the heap
  const char* name = "";   ///< what it holds, for debugging
};

/// A stack allocator. Plain data; use the arena_* functions.
struct Arena {
  std::unique_ptr<std::byte[]> block;                  ///< the stack, `capacity` bytes
  int64_t capacity = 0;                                ///< bytes in block
  int64_t index = 0;                                   ///< bytes of block in use
  int64_t allocation = 0;                              ///< bytes in use, block and heap together
  int64_t max_allocation = 0;                          ///< high-water mark of `allocation` since the last grow
  std::array<ArenaEntry, k_max_arena_entries> entries{};
  int32_t entry_count = 0;
};

/// An arena whose block holds `capacity` bytes (≥ 0).
void arena_init(Arena* arena, int64_t capacity);

/// `size` bytes (≥ 0), 16-byte aligned, from the top of the stack (or the
/// heap when the block is full). Never returns null.
void* arena_allocate(Arena* arena, int64_t size, const char* name);

/// Frees the most recent live allocation; `memory` must be it (checked by
/// TANDEM_ASSERT).
void arena_free(Arena* arena, void* memory);

/// Call only when the arena is empty: if a step needed more than the block,
/// replaces the block by one of 1.5× the high-water mark. Resets the mark.
void arena_grow(Arena* arena);

/// `count` default-initialised objects of a trivially destructible type T.
template <typename T>
T* arena_allocate_array(Arena* arena, int32_t count, const char* name) {
  static_assert(std::is_trivially_destructible_v<T>, "arena memory is released without destructors");
  static_assert(alignof(T) <= k_arena_alignment);
  const int32_t n = count > 0 ? count : 0;
  T* p = static_cast<T*>(arena_allocate(arena, static_cast<int64_t>(sizeof(T)) * n, name));
  for (int32_t i = 0; i < n; ++i) ::new (static_cast<void*>(p + i)) T;
  return p;
}

/// `count` objects of T left unwritten (std::make_unique_for_overwrite's
/// sense): for a hot array whose every field the caller writes before any
/// read, where arena_allocate_array's default member initialisers would be a
/// second full pass over it. T must be an aggregate (an implicit-lifetime
/// type: its objects exist in the storage without a constructor call) of
/// trivially copyable fields, so nothing but the caller's stores gives it
/// values; reading a field before writing it is a bug (MSan would report it).
template <typename T>
T* arena_allocate_array_for_overwrite(Arena* arena, int32_t count, const char* name) {
  static_assert(std::is_aggregate_v<T> && std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>,
                "only plain records may be handed out unwritten");
  static_assert(alignof(T) <= k_arena_alignment);
  const int32_t n = count > 0 ? count : 0;
  return static_cast<T*>(arena_allocate(arena, static_cast<int64_t>(sizeof(T)) * n, name));
}

}  // namespace tandem

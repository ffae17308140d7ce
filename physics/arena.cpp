// arena.cpp — the per-step stack allocator (see arena.h).
#include "physics/arena.h"

namespace tandem {

namespace {

int64_t round_up(int64_t size) { return (size + (k_arena_alignment - 1)) / k_arena_alignment * k_arena_alignment; }

}  // namespace

void arena_init(Arena* arena, int64_t capacity) {
  TANDEM_ASSERT(arena->entry_count == 0);
  const int64_t c = capacity > 0 ? round_up(capacity) : 0;
  arena->block = c > 0 ? std::make_unique<std::byte[]>(static_cast<size_t>(c)) : nullptr;
  arena->capacity = c;
  arena->index = 0;
  arena->allocation = 0;
  arena->max_allocation = 0;
}

void* arena_allocate(Arena* arena, int64_t size, const char* name) {
  TANDEM_ASSERT(size >= 0);
  TANDEM_ASSERT(arena->entry_count < k_max_arena_entries);
  // A zero-byte request still gets a distinct, valid entry (one alignment unit).
  const int64_t bytes = round_up(size > 0 ? size : 1);
  ArenaEntry& entry = arena->entries[static_cast<size_t>(arena->entry_count)];
  entry.size = bytes;
  entry.name = name;
  if (arena->index + bytes > arena->capacity) {
    // The block is full: this step borrows from the heap; arena_grow() makes
    // the block big enough for next time.
    entry.data = static_cast<std::byte*>(::operator new(static_cast<size_t>(bytes), std::align_val_t{k_arena_alignment}));
    entry.used_heap = true;
  } else {
    entry.data = arena->block.get() + arena->index;
    entry.used_heap = false;
    arena->index += bytes;
  }
  arena->allocation += bytes;
  if (arena->allocation > arena->max_allocation) arena->max_allocation = arena->allocation;
  ++arena->entry_count;
  return entry.data;
}

void arena_free(Arena* arena, void* memory) {
  TANDEM_ASSERT(arena->entry_count > 0);
  ArenaEntry& entry = arena->entries[static_cast<size_t>(arena->entry_count - 1)];
  TANDEM_ASSERT(memory == entry.data);  // frees must mirror allocations (LIFO)
  if (entry.used_heap) {
    ::operator delete(entry.data, std::align_val_t{k_arena_alignment});
  } else {
    arena->index -= entry.size;
  }
  arena->allocation -= entry.size;
  entry = ArenaEntry{};
  --arena->entry_count;
}

void arena_grow(Arena* arena) {
  TANDEM_ASSERT(arena->entry_count == 0 && arena->index == 0 && arena->allocation == 0);
  if (arena->max_allocation > arena->capacity) {
    arena_init(arena, arena->max_allocation + arena->max_allocation / 2);
  }
  arena->max_allocation = 0;
}

}  // namespace tandem

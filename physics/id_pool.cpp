// id_pool.cpp — lowest-free-index slot allocation (see id_pool.h), and the
// invariant-failure reporter behind TANDEM_ASSERT.
#include "physics/id_pool.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <functional>

namespace tandem {

void assert_failed(const char* condition, const char* file, int line) {
  std::fprintf(stderr, "tandem: invariant failed: %s at %s:%d\n", condition, file, line);
  std::abort();
}

int32_t id_pool_allocate(IdPool* pool) {
  if (!pool->free_heap.empty()) {
    // The heap's front is its unique minimum: the lowest free index.
    std::pop_heap(pool->free_heap.begin(), pool->free_heap.end(), std::greater<int32_t>{});
    const int32_t index = pool->free_heap.back();
    pool->free_heap.pop_back();
    TANDEM_ASSERT(pool->alive[static_cast<size_t>(index)] == 0);
    pool->alive[static_cast<size_t>(index)] = 1;
    ++pool->alive_count;
    return index;
  }
  const int32_t index = id_pool_capacity(*pool);
  pool->generations.push_back(1u);
  pool->alive.push_back(1);
  ++pool->alive_count;
  return index;
}

void id_pool_free(IdPool* pool, int32_t index) {
  TANDEM_ASSERT(id_pool_is_alive(*pool, index));
  const size_t i = static_cast<size_t>(index);
  pool->alive[i] = 0;
  pool->generations[i] = next_generation(pool->generations[i]);
  pool->free_heap.push_back(index);
  std::push_heap(pool->free_heap.begin(), pool->free_heap.end(), std::greater<int32_t>{});
  --pool->alive_count;
}

void id_pool_reserve(IdPool* pool, int32_t capacity) {
  if (capacity <= 0) return;
  const size_t n = static_cast<size_t>(capacity);
  pool->generations.reserve(n);
  pool->alive.reserve(n);
  pool->free_heap.reserve(n);
}

}  // namespace tandem

// counting_allocator.h — replaces the global operator new/delete with ones
// that count allocations while g_count_allocations is set, for the tests that
// assert a hot path allocates nothing. The replacements are definitions:
// include this header in exactly one source file of a test binary.
//
// Under ThreadSanitizer (the clang-tsan preset) the runtime defines operator
// new/delete itself and a second definition does not link: there the
// replacements are left out, nothing is counted, and each counting test
// returns early through TANDEM_REQUIRE_ALLOCATION_COUNTING() (every other
// build runs them).
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>

#if defined(__SANITIZE_THREAD__)
#define TANDEM_TEST_TSAN 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define TANDEM_TEST_TSAN 1
#endif
#endif
#ifndef TANDEM_TEST_TSAN
#define TANDEM_TEST_TSAN 0
#endif

/// Returns from the calling test case (with a Catch2 warning) where
/// allocations are not counted (ThreadSanitizer builds).
#define TANDEM_REQUIRE_ALLOCATION_COUNTING()                                       \
  do {                                                                             \
    if (TANDEM_TEST_TSAN) {                                                        \
      WARN("allocations are not counted under ThreadSanitizer: test not run");   \
      return;                                                                      \
    }                                                                              \
  } while (false)

namespace {
std::atomic<bool> g_count_allocations{false};
std::atomic<int64_t> g_allocation_count{0};

#if !TANDEM_TEST_TSAN
void* counted_malloc(std::size_t size) {
  if (g_count_allocations.load(std::memory_order_relaxed)) g_allocation_count.fetch_add(1);
  return std::malloc(size == 0 ? 1 : size);
}

void* counted_aligned(std::size_t size, std::align_val_t alignment) {
  if (g_count_allocations.load(std::memory_order_relaxed)) g_allocation_count.fetch_add(1);
  const std::size_t a = static_cast<std::size_t>(alignment);
  const std::size_t n = size == 0 ? a : (size + a - 1) / a * a;
  return std::aligned_alloc(a, n);
}
#endif
}  // namespace

#if !TANDEM_TEST_TSAN
void* operator new(std::size_t size) {
  void* p = counted_malloc(size);
  if (p == nullptr) throw std::bad_alloc();
  return p;
}
void* operator new[](std::size_t size) {
  void* p = counted_malloc(size);
  if (p == nullptr) throw std::bad_alloc();
  return p;
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept { return counted_malloc(size); }
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept { return counted_malloc(size); }
void* operator new(std::size_t size, std::align_val_t alignment) {
  void* p = counted_aligned(size, alignment);
  if (p == nullptr) throw std::bad_alloc();
  return p;
}
void* operator new[](std::size_t size, std::align_val_t alignment) {
  void* p = counted_aligned(size, alignment);
  if (p == nullptr) throw std::bad_alloc();
  return p;
}
void* operator new(std::size_t size, std::align_val_t alignment, const std::nothrow_t&) noexcept {
  return counted_aligned(size, alignment);
}
void* operator new[](std::size_t size, std::align_val_t alignment, const std::nothrow_t&) noexcept {
  return counted_aligned(size, alignment);
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }
#endif  // !TANDEM_TEST_TSAN

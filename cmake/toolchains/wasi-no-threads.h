// wasi-no-threads.h — force-included by wasm32-wasi.cmake. WASI (clang 14,
// libc++ built without threads) has one thread and no <mutex> types, but
// physics/world.cpp guards its world registry with std::mutex and
// std::lock_guard. On a single-threaded target a lock that does nothing is
// exact, so this supplies the two names, only when libc++ says it has no
// threads. Likewise replay/state.cpp's thread_local scratch buffers need
// __cxa_thread_atexit (registering their destructors), which wasi-libc
// lacks: a weak do-nothing one is supplied (the buffers are then never
// freed at exit, which a test run does not notice). Test-toolchain only;
// nothing here reaches other builds.
#pragma once
#ifdef __cplusplus
#include <mutex>
#if defined(_LIBCPP_HAS_NO_THREADS)
namespace std {
class mutex {
 public:
  constexpr mutex() noexcept = default;
  mutex(const mutex&) = delete;
  mutex& operator=(const mutex&) = delete;
  void lock() {}
  bool try_lock() { return true; }
  void unlock() {}
};
template <class Mutex>
class lock_guard {
 public:
  explicit lock_guard(Mutex& m) : m_(m) { m_.lock(); }
  ~lock_guard() { m_.unlock(); }
  lock_guard(const lock_guard&) = delete;
  lock_guard& operator=(const lock_guard&) = delete;

 private:
  Mutex& m_;
};
}  // namespace std
extern "C" __attribute__((weak)) int __cxa_thread_atexit(void (*)(void*), void*, void*) { return 0; }
#endif
#endif

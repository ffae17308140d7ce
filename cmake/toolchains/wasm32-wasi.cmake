# WebAssembly: Debian's clang 14 with --target=wasm32-wasi and the wasi-libc,
# libc++ and compiler-rt packages (sysroot /usr), run under node's WASI
# through wasi-run.mjs. WASI has no exceptions in clang 14 and no signals:
# -fno-exceptions with Catch2's CATCH_CONFIG_DISABLE_EXCEPTIONS (a failed
# REQUIRE ends the run) and CATCH_CONFIG_NO_POSIX_SIGNALS. The golden files
# are read through node's preopened "/" (the host's file system). WASI has
# one thread and libc++ 14 for it no std::mutex: wasi-no-threads.h (force-
# included) supplies do-nothing std::mutex and std::lock_guard.
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR wasm32)
set(CMAKE_C_COMPILER clang)
set(CMAKE_CXX_COMPILER clang++)
set(CMAKE_C_COMPILER_TARGET wasm32-wasi)
set(CMAKE_CXX_COMPILER_TARGET wasm32-wasi)
set(CMAKE_SYSROOT /usr)
# GNU ar cannot index wasm objects.
set(CMAKE_AR llvm-ar-14)
set(CMAKE_RANLIB llvm-ranlib-14)
string(APPEND CMAKE_CXX_FLAGS_INIT " -fno-exceptions -DCATCH_CONFIG_DISABLE_EXCEPTIONS -DCATCH_CONFIG_NO_POSIX_SIGNALS"
  " -include ${CMAKE_CURRENT_LIST_DIR}/wasi-no-threads.h")
# --experimental-wasi-unstable-preview1: Debian 12's node 18 needs it for node:wasi; node 20 accepts it.
set(CMAKE_CROSSCOMPILING_EMULATOR node --experimental-wasi-unstable-preview1 --no-warnings ${CMAKE_CURRENT_LIST_DIR}/wasi-run.mjs)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
include(${CMAKE_CURRENT_LIST_DIR}/host-headers.cmake)

# aarch64-linux-gnu: Debian's g++-aarch64-linux-gnu, run under qemu-user (qemu-aarch64).
# CMAKE_CROSSCOMPILING_EMULATOR lets catch_discover_tests and ctest run the
# cross-built tests; -L points qemu at the target's loader and libraries.
# Debian's multiarch cross compilers also search /usr/include, so the
# header-only Catch2 and xxHash need no extra include directory.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64 -L /usr/aarch64-linux-gnu)
set(CMAKE_FIND_ROOT_PATH /usr/aarch64-linux-gnu)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

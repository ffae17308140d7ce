# arm-linux-gnueabihf: Debian's g++-arm-linux-gnueabihf, run under qemu-user (qemu-arm).
# CMAKE_CROSSCOMPILING_EMULATOR lets catch_discover_tests and ctest run the
# cross-built tests; -L points qemu at the target's loader and libraries.
# Debian's multiarch cross compilers also search /usr/include, so the
# header-only Catch2 and xxHash need no extra include directory.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR arm)
set(CMAKE_C_COMPILER arm-linux-gnueabihf-gcc)
set(CMAKE_CXX_COMPILER arm-linux-gnueabihf-g++)
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-arm -L /usr/arm-linux-gnueabihf)
set(CMAKE_FIND_ROOT_PATH /usr/arm-linux-gnueabihf)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

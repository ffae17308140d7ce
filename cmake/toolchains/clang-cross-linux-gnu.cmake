# Linux cross builds with clang 14 (--target=<triple>), using the headers, libraries and
# linker of Debian's g++-<triple>; tests run under qemu-<processor>.
# Pick the target with -DTANDEM_CROSS_TRIPLE=<triple>, e.g. aarch64-linux-gnu or s390x-linux-gnu
# (tools/matrix.sh's clang rows).
if(NOT TANDEM_CROSS_TRIPLE)
  message(FATAL_ERROR "clang-cross-linux-gnu.cmake: set -DTANDEM_CROSS_TRIPLE=<triple> (e.g. aarch64-linux-gnu)")
endif()
# try_compile projects re-read this file: hand them the triple too.
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES TANDEM_CROSS_TRIPLE)
string(REGEX MATCH "^[^-]+" tandem_cross_processor "${TANDEM_CROSS_TRIPLE}")
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR ${tandem_cross_processor})
set(CMAKE_C_COMPILER clang)
set(CMAKE_CXX_COMPILER clang++)
set(CMAKE_C_COMPILER_TARGET ${TANDEM_CROSS_TRIPLE})
set(CMAKE_CXX_COMPILER_TARGET ${TANDEM_CROSS_TRIPLE})
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-${tandem_cross_processor} -L /usr/${TANDEM_CROSS_TRIPLE})
set(CMAKE_FIND_ROOT_PATH /usr/${TANDEM_CROSS_TRIPLE})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# WebAssembly for the browser: Debian's emscripten package (3.1.6, with its
# prebuilt system libraries in /usr/share/emscripten/cache, so no cold cache
# build). Builds the engine, the scene loader and the web page's glue
# (tools/web) into tandem_web.js + tandem_web.wasm; no pthreads.
#
# Header-only host libraries reach the cross compiler only through a folder
# of links (host-headers.cmake: Catch2, xxHash; here also nlohmann-json for
# the scene loader), never through /usr/include as a whole.
#
# Debian's emcc runs its JS optimizer under node and needs Debian's acorn
# module from /usr/share/nodejs: Debian's own nodejs searches there, other
# node builds (nodesource) do not, so links run with NODE_PATH set.
include(/usr/share/emscripten/cmake/Modules/Platform/Emscripten.cmake)
include(${CMAKE_CURRENT_LIST_DIR}/host-headers.cmake)
foreach(_h nlohmann)
  if(EXISTS "/usr/include/${_h}" AND NOT EXISTS "${_tandem_host_headers}/${_h}")
    file(CREATE_LINK "/usr/include/${_h}" "${_tandem_host_headers}/${_h}" SYMBOLIC)
  endif()
endforeach()
set(CMAKE_CXX_LINKER_LAUNCHER env NODE_PATH=/usr/share/nodejs)
# Without pthreads libc++ keeps std::mutex (as no-ops); the WASI shim is
# harmless here (it acts only when libc++ says it has no threads).
string(APPEND CMAKE_CXX_FLAGS_INIT " -include ${CMAKE_CURRENT_LIST_DIR}/wasi-no-threads.h")
# The scene loader reports bad input by throwing internally and catching at
# its entry points (tools/scene/scene.cpp), so exceptions must be caught:
# WebAssembly's native exception handling (zero cost until a throw; Chromium
# and node ≥ 17 run it; Debian's cache has the matching libc++-except).
string(APPEND CMAKE_CXX_FLAGS_INIT " -fwasm-exceptions")
string(APPEND CMAKE_EXE_LINKER_FLAGS_INIT " -fwasm-exceptions")

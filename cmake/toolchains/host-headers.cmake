# Included by the toolchains whose compiler does not search /usr/include
# (mingw-w64, wasm32-wasi): a folder of links to the host's architecture-
# independent header-only libraries the tests need (Catch2 2, xxHash), so no
# other host header can reach the cross compiler.
set(_tandem_host_headers "${CMAKE_BINARY_DIR}/host-headers")
file(MAKE_DIRECTORY "${_tandem_host_headers}")
foreach(_h catch2 xxhash.h)
  if(EXISTS "/usr/include/${_h}" AND NOT EXISTS "${_tandem_host_headers}/${_h}")
    file(CREATE_LINK "/usr/include/${_h}" "${_tandem_host_headers}/${_h}" SYMBOLIC)
  endif()
endforeach()
string(APPEND CMAKE_CXX_FLAGS_INIT " -isystem ${_tandem_host_headers}")

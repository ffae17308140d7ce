# consumer_test.cmake — ctest's "install/consumer" test (cmake -P).
#
# 1. installs the build in TANDEM_BINARY_DIR to WORK_DIR/prefix;
# 2. configures, builds and runs tests/consumer there with find_package(Tandem);
# 3. compiles tests/consumer/main.cpp again with `pkg-config --cflags --libs
#    tandem` (PKG_CONFIG_PATH pointing into the prefix) and runs it;
# 4. with C_API on: runs the C consumer (c_consumer.c, linked to the installed
#    libtandem.so through Tandem::c) and compiles it again with `pkg-config
#    tandem-c` (the C compiler matching CXX: gcc for g++, clang for clang++)
#    and runs it with LD_LIBRARY_PATH at the prefix's lib directory.
# Any failing step fails the test with the step's output.
foreach(var TANDEM_BINARY_DIR TANDEM_CONSUMER_DIR WORK_DIR CXX GENERATOR LIBDIR PKG_CONFIG)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "consumer_test.cmake: ${var} is not set")
  endif()
endforeach()
if(NOT BUILD_TYPE)
  set(BUILD_TYPE Release)
endif()

# step(NAME COMMAND...): runs a command, echoes its output, stops on failure.
function(step name)
  message(STATUS "consumer test: ${name}")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "consumer test: ${name} failed (${rc}):\n${out}")
  endif()
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})

step("install to ${prefix}" ${CMAKE_COMMAND} --install ${TANDEM_BINARY_DIR} --prefix ${prefix})
foreach(f ${LIBDIR}/cmake/Tandem/TandemConfig.cmake ${LIBDIR}/pkgconfig/tandem.pc include/tandem/fixed/fixed.h)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "consumer test: ${f} was not installed")
  endif()
endforeach()

# --- the include tree holds only the public API ------------------------------------
# Internal headers (the engine's own furniture) must not be installed, and every
# installed header may include only installed headers.
foreach(internal physics/world.h physics/arena.h physics/body.h physics/shape.h physics/contact.h
        physics/contact_solver.h physics/broad_phase.h physics/event_state.h physics/joint_state.h physics/island.h
        physics/id_pool.h)
  if(EXISTS ${prefix}/include/tandem/${internal})
    message(FATAL_ERROR "consumer test: the internal header ${internal} was installed")
  endif()
endforeach()
file(GLOB_RECURSE installed_headers RELATIVE ${prefix}/include/tandem ${prefix}/include/tandem/*.h)
foreach(h IN LISTS installed_headers)
  file(STRINGS ${prefix}/include/tandem/${h} includes REGEX "^#include \"[a-z_0-9]+/[a-z_0-9]+\\.h\"")
  foreach(line IN LISTS includes)
    string(REGEX REPLACE "^#include \"([^\"]+)\".*" "\\1" inc "${line}")
    if(NOT EXISTS ${prefix}/include/tandem/${inc})
      message(FATAL_ERROR "consumer test: installed ${h} includes ${inc}, which is not installed (internal?)")
    endif()
  endforeach()
endforeach()
list(LENGTH installed_headers n_headers)
message(STATUS "consumer test: ${n_headers} installed headers, none internal")

# --- find_package(Tandem) --------------------------------------------------------
step("configure tests/consumer" ${CMAKE_COMMAND} -S ${TANDEM_CONSUMER_DIR} -B ${WORK_DIR}/build -G ${GENERATOR}
  -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_BUILD_TYPE=${BUILD_TYPE} -DCMAKE_PREFIX_PATH=${prefix}
  -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
step("build tests/consumer" ${CMAKE_COMMAND} --build ${WORK_DIR}/build)
step("run the CMake consumer" ${WORK_DIR}/build/tandem_consumer)
message(STATUS "${step_output}")

# --- pkg-config ----------------------------------------------------------------
set(ENV{PKG_CONFIG_PATH} ${prefix}/${LIBDIR}/pkgconfig)
step("pkg-config --cflags tandem" ${PKG_CONFIG} --cflags tandem)
string(STRIP "${step_output}" cflags)
step("pkg-config --libs tandem" ${PKG_CONFIG} --libs tandem)
string(STRIP "${step_output}" libs)
separate_arguments(cflags UNIX_COMMAND "${cflags}")
separate_arguments(libs UNIX_COMMAND "${libs}")
step("compile with pkg-config flags" ${CXX} ${cflags} ${TANDEM_CONSUMER_DIR}/main.cpp -o ${WORK_DIR}/pc_consumer ${libs})
step("run the pkg-config consumer" ${WORK_DIR}/pc_consumer)
message(STATUS "${step_output}")

# --- the C API: libtandem.so both ways --------------------------------------------
if(C_API)
  foreach(f ${LIBDIR}/libtandem.so ${LIBDIR}/pkgconfig/tandem-c.pc include/tandem/tandem_c.h)
    if(NOT EXISTS ${prefix}/${f})
      message(FATAL_ERROR "consumer test: ${f} was not installed")
    endif()
  endforeach()
  step("run the CMake C consumer (Tandem::c)" ${WORK_DIR}/build/tandem_c_consumer)
  message(STATUS "${step_output}")
  string(REGEX REPLACE "clang\\+\\+$" "clang" cc "${CXX}")
  string(REGEX REPLACE "g\\+\\+$" "gcc" cc "${cc}")
  step("pkg-config --cflags tandem-c" ${PKG_CONFIG} --cflags tandem-c)
  string(STRIP "${step_output}" c_cflags)
  step("pkg-config --libs tandem-c" ${PKG_CONFIG} --libs tandem-c)
  string(STRIP "${step_output}" c_libs)
  separate_arguments(c_cflags UNIX_COMMAND "${c_cflags}")
  separate_arguments(c_libs UNIX_COMMAND "${c_libs}")
  step("compile the C consumer with pkg-config tandem-c" ${cc} -std=c11 -Wall -Wextra -pedantic -Werror ${c_cflags}
    ${TANDEM_CONSUMER_DIR}/c_consumer.c -o ${WORK_DIR}/pc_c_consumer ${c_libs})
  set(ENV{LD_LIBRARY_PATH} ${prefix}/${LIBDIR})
  step("run the pkg-config C consumer" ${WORK_DIR}/pc_c_consumer)
  message(STATUS "${step_output}")
endif()

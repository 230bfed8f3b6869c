# The ctest case relief_installed_package_builds_a_consumer (tests/CMakeLists.txt): installs
# the build tree RELIEF_BUILD_DIR into a prefix under WORK_DIR, configures and builds the
# project CONSUMER_SOURCE_DIR against it with warnings as errors, and runs it.
#
#   cmake -DRELIEF_BUILD_DIR=... -DCONSUMER_SOURCE_DIR=... -DWORK_DIR=... -DGENERATOR=...
#         -DCXX_COMPILER=... -DBUILD_TYPE=... -P run_consumer_test.cmake
foreach(variable RELIEF_BUILD_DIR CONSUMER_SOURCE_DIR WORK_DIR GENERATOR CXX_COMPILER)
  if(NOT DEFINED ${variable})
    message(FATAL_ERROR "run_consumer_test.cmake: -D${variable}=... is missing")
  endif()
endforeach()

set(prefix "${WORK_DIR}/prefix")
set(build "${WORK_DIR}/build")
file(REMOVE_RECURSE "${WORK_DIR}")

function(run_step what)
  message(STATUS "${what}")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${what} failed (${status}): ${ARGN}")
  endif()
endfunction()

run_step("installing ${RELIEF_BUILD_DIR} into ${prefix}"
         "${CMAKE_COMMAND}" --install "${RELIEF_BUILD_DIR}" --prefix "${prefix}")
foreach(file include/relief/relief.h bin/relief)
  if(NOT EXISTS "${prefix}/${file}")
    message(FATAL_ERROR "the install tree has no ${file}")
  endif()
endforeach()
# The one installed header includes only the standard library.
file(STRINGS "${prefix}/include/relief/relief.h" includes REGEX "^#include")
foreach(line IN LISTS includes)
  if(NOT line MATCHES "^#include <[a-z_]+>$")
    message(FATAL_ERROR "relief/relief.h includes more than the standard library: ${line}")
  endif()
endforeach()

# Only the install tree may be found: no package registry, no other prefix.
run_step("configuring the consumer"
         "${CMAKE_COMMAND}" -S "${CONSUMER_SOURCE_DIR}" -B "${build}" -G "${GENERATOR}"
         "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}" "-DCMAKE_BUILD_TYPE=${BUILD_TYPE}"
         "-DCMAKE_PREFIX_PATH=${prefix}" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF
         "-DCMAKE_CXX_FLAGS=-Wall -Wextra -Wpedantic -Wshadow -Wconversion -Werror")
file(STRINGS "${build}/CMakeCache.txt" relief_dir REGEX "^relief_DIR:")
if(NOT relief_dir STREQUAL "relief_DIR:PATH=${prefix}/lib/cmake/relief" AND
   NOT relief_dir MATCHES "^relief_DIR:PATH=${prefix}/lib/[^/]+/cmake/relief$")
  message(FATAL_ERROR "find_package(relief) found another package: ${relief_dir}")
endif()
run_step("building the consumer" "${CMAKE_COMMAND}" --build "${build}")
run_step("running the consumer" "${build}/relief_consumer")
file(REMOVE_RECURSE "${WORK_DIR}")

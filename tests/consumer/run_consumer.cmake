# Driver of the CTest test consumer_find_package (cmake -P script).
#
# Installs a pradis build tree into a scratch prefix, configures and builds the
# consumer project (this directory) against that prefix with find_package(pradis),
# and runs the consumer. Every step must succeed; any failure ends the script
# with FATAL_ERROR (non-zero exit status), which fails the test.
#
# Variables (-D...):
#   PRADIS_BUILD_DIR   the pradis build tree to install
#   PREFIX             scratch install prefix (deleted and recreated)
#   CONSUMER_SOURCE    this directory
#   CONSUMER_BUILD     scratch build directory of the consumer (deleted and recreated)
#   GENERATOR          CMake generator; optional GENERATOR_PLATFORM, GENERATOR_TOOLSET
#   CXX_COMPILER       the C++ compiler of the pradis build
#   EIGEN3_DIR         where Eigen3Config.cmake was found (optional)
#   CONFIG             build configuration (may be empty)

cmake_minimum_required(VERSION 3.20)

foreach(var PRADIS_BUILD_DIR PREFIX CONSUMER_SOURCE CONSUMER_BUILD GENERATOR CXX_COMPILER)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "run_consumer.cmake: ${var} is not set")
  endif()
endforeach()

function(run_step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  message("---- ${what}\n${out}")
  if(NOT rc STREQUAL "0")
    message(FATAL_ERROR "consumer_find_package: step '${what}' failed (${rc})")
  endif()
endfunction()

file(REMOVE_RECURSE "${PREFIX}" "${CONSUMER_BUILD}")

set(config_args)
if(NOT "${CONFIG}" STREQUAL "")
  set(config_args --config "${CONFIG}")
endif()

# 1. Install the build tree (headers, pradisTargets.cmake, pradisConfig*.cmake).
run_step("install pradis into ${PREFIX}"
  "${CMAKE_COMMAND}" --install "${PRADIS_BUILD_DIR}" --prefix "${PREFIX}" ${config_args})

# 2. Configure the consumer against the prefix only (no package registries).
set(gen_args -G "${GENERATOR}")
if(NOT "${GENERATOR_PLATFORM}" STREQUAL "")
  list(APPEND gen_args -A "${GENERATOR_PLATFORM}")
endif()
if(NOT "${GENERATOR_TOOLSET}" STREQUAL "")
  list(APPEND gen_args -T "${GENERATOR_TOOLSET}")
endif()
set(cache_args
  "-DCMAKE_PREFIX_PATH=${PREFIX}"
  "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}"
  -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF
  -DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF)
if(NOT "${EIGEN3_DIR}" STREQUAL "")
  list(APPEND cache_args "-DEigen3_DIR=${EIGEN3_DIR}")
endif()
if(NOT "${CONFIG}" STREQUAL "")
  list(APPEND cache_args "-DCMAKE_BUILD_TYPE=${CONFIG}")
endif()
run_step("configure the consumer"
  "${CMAKE_COMMAND}" -S "${CONSUMER_SOURCE}" -B "${CONSUMER_BUILD}" ${gen_args} ${cache_args})

# The package must come from the scratch prefix, not from the source or build tree.
file(STRINGS "${CONSUMER_BUILD}/CMakeCache.txt" pradis_dir_line REGEX "^pradis_DIR:")
string(REGEX REPLACE "^pradis_DIR:[A-Z]+=" "" pradis_dir "${pradis_dir_line}")
file(REAL_PATH "${PREFIX}" real_prefix)
file(REAL_PATH "${pradis_dir}" real_pradis_dir)
string(FIND "${real_pradis_dir}/" "${real_prefix}/" at)
if(NOT at EQUAL 0)
  message(FATAL_ERROR "consumer_find_package: pradis was found in '${pradis_dir}', not under '${PREFIX}'")
endif()

# 3. Build.
run_step("build the consumer" "${CMAKE_COMMAND}" --build "${CONSUMER_BUILD}" ${config_args})

# 4. Run.
set(exe_file "${CONSUMER_BUILD}/consumer_executable_${CONFIG}.txt")
if(NOT EXISTS "${exe_file}")
  file(GLOB exe_files "${CONSUMER_BUILD}/consumer_executable_*.txt")
  list(GET exe_files 0 exe_file)
endif()
file(READ "${exe_file}" exe)
run_step("run ${exe}" "${exe}")
message("consumer_find_package: OK")

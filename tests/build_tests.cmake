# Build tests of pradis, included from tests/CMakeLists.txt:
#
#   compile_fail.<name>     every tests/compile_fail/*.cpp is compiled with
#                           -fsyntax-only. A file must NOT compile, and the
#                           compiler output must contain the message on its first
#                           line ("// pradis-expect: <message>"). Files named
#                           ok_*.cpp are positive controls and MUST compile.
#   docs.listings           every ```cpp listing of README.md and docs/*.md must
#                           compile (tests/docs/check_listings.cmake).
#   consumer_find_package   installs this build tree into a scratch prefix and
#                           builds and runs tests/consumer against it with
#                           find_package(pradis).
#
# Run them with: ctest -L build   (or ctest -R 'compile_fail|consumer')
# The asan-ubsan test preset leaves them out (label "build"): they compile code
# with the plain compiler, exactly as in the dev run, so a second run under the
# sanitizer preset would check nothing new (and cost about 5 minutes of CI).

set(_pradis_bt_dir "${CMAKE_CURRENT_LIST_DIR}")

# ---- compile-fail tests --------------------------------------------------------
if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
  # The C++20 flag exactly as CMake would pass it for this compiler.
  set(_pradis_std_flag "${CMAKE_CXX20_STANDARD_COMPILE_OPTION}")
  if(_pradis_std_flag STREQUAL "")
    set(_pradis_std_flag "-std=c++20")
  endif()

  # Include directories: our headers, then Eigen's (taken from the Eigen3::Eigen target).
  set(_pradis_includes "${PROJECT_SOURCE_DIR}/include")
  get_target_property(_pradis_eigen_dirs Eigen3::Eigen INTERFACE_INCLUDE_DIRECTORIES)
  if(NOT _pradis_eigen_dirs)
    message(FATAL_ERROR "build_tests.cmake: Eigen3::Eigen has no INTERFACE_INCLUDE_DIRECTORIES")
  endif()
  foreach(_dir IN LISTS _pradis_eigen_dirs)
    if(_dir MATCHES "^\\$<BUILD_INTERFACE:(.*)>$")
      set(_dir "${CMAKE_MATCH_1}")  # Eigen added as a subproject
    elseif(_dir MATCHES "^\\$<")
      continue()                    # $<INSTALL_INTERFACE:...> and other expressions
    endif()
    list(APPEND _pradis_includes "${_dir}")
  endforeach()
  string(REPLACE ";" "|" _pradis_includes "${_pradis_includes}")  # one -D value for the driver

  file(GLOB _pradis_cf_sources CONFIGURE_DEPENDS "${_pradis_bt_dir}/compile_fail/*.cpp")
  foreach(_src IN LISTS _pradis_cf_sources)
    get_filename_component(_name "${_src}" NAME_WE)
    if(_name MATCHES "^ok_")
      set(_mode pass)
    else()
      set(_mode fail)
    endif()
    add_test(NAME compile_fail.${_name}
             COMMAND "${CMAKE_COMMAND}"
                     "-DCOMPILER=${CMAKE_CXX_COMPILER}"
                     "-DSTD_FLAG=${_pradis_std_flag}"
                     "-DINCLUDES=${_pradis_includes}"
                     "-DSOURCE=${_src}"
                     "-DMODE=${_mode}"
                     -P "${_pradis_bt_dir}/compile_fail/compile_check.cmake")
    set_tests_properties(compile_fail.${_name} PROPERTIES
                         LABELS "build;compile_fail"
                         FAIL_REGULAR_EXPRESSION "pradis-compile-check: FAILED"
                         TIMEOUT 300)
    if(_mode STREQUAL "fail")
      # The expected message, as a regular expression. PASS_REGULAR_EXPRESSION makes
      # CTest ignore the exit status, so a file that compiles is caught by the driver
      # (it prints the FAIL_REGULAR_EXPRESSION marker, which takes precedence).
      file(READ "${_src}" _head LIMIT 1000)
      if(NOT _head MATCHES "^// pradis-expect: ([^\r\n]+)")
        message(FATAL_ERROR "build_tests.cmake: ${_src} must start with '// pradis-expect: <message>'")
      endif()
      string(REGEX REPLACE "([][.*+?()|^$\\])" "\\\\\\1" _expected "${CMAKE_MATCH_1}")
      string(REPLACE ";" "." _expected "${_expected}")  # ';' would split the property into a list
      set_tests_properties(compile_fail.${_name} PROPERTIES PASS_REGULAR_EXPRESSION "${_expected}")
    endif()
  endforeach()

  # The C++ listings of README.md and docs/*.md (tests/docs/check_listings.cmake).
  add_test(NAME docs.listings
           COMMAND "${CMAKE_COMMAND}"
                   "-DSOURCE_DIR=${PROJECT_SOURCE_DIR}"
                   "-DOUTPUT=${CMAKE_CURRENT_BINARY_DIR}/doc_listings.cpp"
                   "-DCOMPILER=${CMAKE_CXX_COMPILER}"
                   "-DSTD_FLAG=${_pradis_std_flag}"
                   "-DINCLUDES=${_pradis_includes}"
                   -P "${_pradis_bt_dir}/docs/check_listings.cmake")
  set_tests_properties(docs.listings PROPERTIES
                       LABELS "build;docs"
                       FAIL_REGULAR_EXPRESSION "pradis-compile-check: FAILED"
                       TIMEOUT 300)
else()
  message(STATUS "pradis: compile_fail tests need a GCC or Clang style compiler; skipped for ${CMAKE_CXX_COMPILER_ID}")
endif()

# ---- consumer project ------------------------------------------------------------
add_test(NAME consumer_find_package
         COMMAND "${CMAKE_COMMAND}"
                 "-DPRADIS_BUILD_DIR=${PROJECT_BINARY_DIR}"
                 "-DPREFIX=${CMAKE_CURRENT_BINARY_DIR}/consumer_prefix"
                 "-DCONSUMER_SOURCE=${_pradis_bt_dir}/consumer"
                 "-DCONSUMER_BUILD=${CMAKE_CURRENT_BINARY_DIR}/consumer_build"
                 "-DGENERATOR=${CMAKE_GENERATOR}"
                 "-DGENERATOR_PLATFORM=${CMAKE_GENERATOR_PLATFORM}"
                 "-DGENERATOR_TOOLSET=${CMAKE_GENERATOR_TOOLSET}"
                 "-DCXX_COMPILER=${CMAKE_CXX_COMPILER}"
                 "-DEIGEN3_DIR=${Eigen3_DIR}"
                 "-DCONFIG=$<CONFIG>"
                 -P "${_pradis_bt_dir}/consumer/run_consumer.cmake")
set_tests_properties(consumer_find_package PROPERTIES
                     LABELS "build;consumer"
                     TIMEOUT 900)

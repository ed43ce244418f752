# Driver of the compile_fail.* CTest tests (cmake -P script).
#
# Compiles one source file with -fsyntax-only and prints the compiler's output.
#
#   MODE=fail  the file must NOT compile and the output must contain the text of
#              the file's first line after "// pradis-expect: ".
#   MODE=pass  the file must compile (positive control: proves the harness does
#              not simply pass everything).
#
# Any problem prints a line starting with "pradis-compile-check: FAILED" (the
# tests' FAIL_REGULAR_EXPRESSION) and ends with a non-zero exit status. The
# expected text itself is never printed here, so only the compiler can produce
# the match the tests' PASS_REGULAR_EXPRESSION looks for.
#
# Variables (-D...): COMPILER, STD_FLAG, INCLUDES ("|"-separated), SOURCE, MODE.

cmake_minimum_required(VERSION 3.20)

# Prints the marker line unwrapped (message(FATAL_ERROR) re-wraps its text), then stops.
function(fail text)
  message("pradis-compile-check: FAILED: ${text}")
  message(FATAL_ERROR "compile check of ${SOURCE} failed")
endfunction()

foreach(var COMPILER STD_FLAG SOURCE MODE)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    fail("${var} is not set")
  endif()
endforeach()

set(include_flags)
string(REPLACE "|" ";" include_dirs "${INCLUDES}")
foreach(dir IN LISTS include_dirs)
  list(APPEND include_flags "-I${dir}")
endforeach()

execute_process(
  COMMAND "${COMPILER}" ${STD_FLAG} -fsyntax-only ${include_flags} "${SOURCE}"
  RESULT_VARIABLE rc
  OUTPUT_VARIABLE out
  ERROR_VARIABLE out)
message("${out}")

if(MODE STREQUAL "pass")
  if(NOT rc STREQUAL "0")
    fail("${SOURCE} must compile but did not (${rc})")
  endif()
  message("pradis-compile-check: compiled as required")
elseif(MODE STREQUAL "fail")
  if(rc STREQUAL "0")
    fail("${SOURCE} compiled, but it must not")
  endif()
  if(NOT rc MATCHES "^[0-9]+$")
    fail("the compiler did not run (${rc})")
  endif()
  # file(READ), not file(STRINGS): the latter escapes the ';' some messages contain.
  file(READ "${SOURCE}" head LIMIT 1000)
  if(NOT head MATCHES "^// pradis-expect: ([^\r\n]+)")
    fail("the first line of ${SOURCE} is not '// pradis-expect: <message>'")
  endif()
  set(expected "${CMAKE_MATCH_1}")
  string(FIND "${out}" "${expected}" at)
  if(at EQUAL -1)
    fail("the compiler rejected ${SOURCE}, but not with the expected message (see its first line)")
  endif()
else()
  fail("MODE must be 'fail' or 'pass', not '${MODE}'")
endif()

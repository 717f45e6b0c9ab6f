# CTest runs each Catch test case by its name (catch_discover_tests, which escapes only ',', '['
# and ']'). A name that does not reach Catch's test-spec parser as written matches nothing, and the
# test passes without running (--warn NoTests, tests/CMakeLists.txt, now fails it instead):
#   ';'   CTest splits the name into two arguments;
#   '\'   Catch takes it as an escape and drops it ("as \n" looks for "as n");
#   '"'   Catch starts or ends a quoted name;
#   a leading '~', '-', '*' or "exclude:", a trailing '*': an exclusion, an option, a wildcard;
#   leading or trailing blanks: Catch trims the spec.
# Catch matches names ignoring case: two names equal but for case would each run both.
# This check lists every test case (hidden ones too) and fails on any such name.
# Usage: cmake -DTESTS=<test executable> -P check_test_names.cmake
# (Catch2 2.x answers a listing with the number of names as its exit status: not checked.)
cmake_minimum_required(VERSION 3.25)
execute_process(COMMAND "${TESTS}" --list-test-names-only OUTPUT_VARIABLE shown)
execute_process(COMMAND "${TESTS}" --list-test-names-only "[.]" OUTPUT_VARIABLE hidden)
string(LENGTH "${shown}" length)
if(length LESS 1000)
  message(FATAL_ERROR "${TESTS} listed almost no test cases:\n${shown}")
endif()
# Out of a CMake list's way: ';' separates, '\' escapes, '[' ']' hold ';' together.
string(REPLACE "\\" "<BACKSLASH>" all "${shown}${hidden}")
string(REPLACE ";" "<SEMICOLON>" all "${all}")
string(REPLACE "[" "<LEFT>" all "${all}")
string(REPLACE "]" "<RIGHT>" all "${all}")
string(REPLACE "\n" ";" lines "${all}")
set(bad "")
set(seen "")
foreach(line IN LISTS lines)
  if(line STREQUAL "")
    continue()
  endif()
  set(why "")
  if(line MATCHES "<SEMICOLON>")
    string(APPEND why " ';'")
  endif()
  if(line MATCHES "<BACKSLASH>")
    string(APPEND why " '\\'")
  endif()
  if(line MATCHES "\"" AND NOT line MATCHES "^\"#[^\"]*\"$")  # Catch lists "#name" quoted, and reads it back
    string(APPEND why " '\"'")
  endif()
  if(line MATCHES "^([~*-]|exclude:)" OR line MATCHES "[*]$")
    string(APPEND why " a leading ~ - * or exclude:, or a trailing *")
  endif()
  if(line MATCHES "^[ \t]" OR line MATCHES "[ \t]$")
    string(APPEND why " a leading or trailing blank")
  endif()
  string(TOLOWER "${line}" lower)
  if(lower IN_LIST seen)
    string(APPEND why " another name equal but for case")
  endif()
  list(APPEND seen "${lower}")
  if(why)
    string(REPLACE "<BACKSLASH>" "\\" line "${line}")
    string(REPLACE "<SEMICOLON>" ";" line "${line}")
    string(REPLACE "<LEFT>" "[" line "${line}")
    string(REPLACE "<RIGHT>" "]" line "${line}")
    string(APPEND bad "  ${line}   (${why} )\n")
  endif()
endforeach()
list(LENGTH seen count)
if(bad)
  message(FATAL_ERROR "test case names CTest would not run as written (rename them; ',' is safe):\n${bad}")
endif()
message(STATUS "${count} test case names, each reaches Catch as written")

# CTest runs each Catch test case by its name (catch_discover_tests), and a ';' in a name splits
# it into two names that match nothing: the test then passes without running. This check lists
# every test case (hidden ones too) and fails on any name with a ';'.
# Usage: cmake -DTESTS=<test executable> -P check_test_names.cmake
# (Catch2 2.x answers a listing with the number of names as its exit status: not checked.)
execute_process(COMMAND "${TESTS}" --list-test-names-only OUTPUT_VARIABLE shown)
execute_process(COMMAND "${TESTS}" --list-test-names-only "[.]" OUTPUT_VARIABLE hidden)
string(LENGTH "${shown}" length)
if(length LESS 1000)
  message(FATAL_ERROR "${TESTS} listed almost no test cases:\n${shown}")
endif()
string(REPLACE ";" "<SEMICOLON>" all "${shown}${hidden}")
string(REPLACE "\n" ";" lines "${all}")
set(bad "")
foreach(line IN LISTS lines)
  if(line MATCHES "<SEMICOLON>")
    string(REPLACE "<SEMICOLON>" ";" line "${line}")
    string(APPEND bad "  ${line}\n")
  endif()
endforeach()
if(bad)
  message(FATAL_ERROR "test case names with a ';' (CTest splits them and runs nothing; use ',' instead):\n${bad}")
endif()

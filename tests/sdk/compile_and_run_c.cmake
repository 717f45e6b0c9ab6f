# cmake -DCOMPILER=cc -DSOURCE=x.c -DINCLUDE=dir -DOUTPUT=exe -P compile_and_run_c.cmake
# Compiles one C file as strict C11 (warnings are errors) and runs it: the test fails on any
# warning, any error or a non-zero exit of the program.
if(NOT COMPILER)
  message(FATAL_ERROR "no C compiler found for this test (${COMPILER}): scripts/install-deps.sh installs gcc and clang")
endif()
execute_process(COMMAND ${COMPILER} -std=c11 -Wall -Wextra -pedantic -Werror -I${INCLUDE} ${SOURCE} -o ${OUTPUT}
  RESULT_VARIABLE compiled)
if(NOT compiled EQUAL 0)
  message(FATAL_ERROR "${COMPILER} could not compile ${SOURCE} as C11 without warnings")
endif()
execute_process(COMMAND ${OUTPUT} RESULT_VARIABLE ran)
if(NOT ran EQUAL 0)
  message(FATAL_ERROR "${OUTPUT} failed its check number ${ran}")
endif()

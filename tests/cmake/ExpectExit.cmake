# ctest helper (cmake -P): runs TOOL with ARGS ('|'-separated) and checks both its exit code
# (EXIT) and its output (REGEX); PASS_REGULAR_EXPRESSION alone cannot check an exit code.
string(REPLACE "|" ";" args "${ARGS}")
execute_process(COMMAND ${TOOL} ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT "${rc}" STREQUAL "${EXIT}")
  message(FATAL_ERROR "exit code '${rc}', expected ${EXIT}; output:\n${out}${err}")
endif()
if(NOT "${out}${err}" MATCHES "${REGEX}")
  message(FATAL_ERROR "the output does not match '${REGEX}':\n${out}${err}")
endif()
message("exit code ${rc} and output as expected:\n${out}${err}")

# Run at build time by fe_discover_tests (FeDiscoverTests.cmake): lists TEST_EXECUTABLE's cases
# and writes CTEST_FILE, the add_test calls CTest includes.
execute_process(COMMAND "${TEST_EXECUTABLE}" --gtest_list_tests
                OUTPUT_VARIABLE listing RESULT_VARIABLE rc TIMEOUT 60)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${TEST_EXECUTABLE} --gtest_list_tests failed (${rc}):\n${listing}")
endif()
string(REPLACE ";" "\\;" listing "${listing}")
string(REPLACE "\n" ";" lines "${listing}")

set(out "")
set(groups "")
set(suite "")
# A run whose every case skipped prints this line (tests/EverythingSkipped.cpp, linked into each
# binary): then the CTest test is skipped, not passed. Not gtest's "[  PASSED  ] 0 tests", which
# a failed one-case run prints too (and CTest's skip expression outranks the exit code).
set(skip "fe test: every case was skipped")
macro(emit name filter cost)
  string(APPEND out "add_test([==[${name}]==] [==[${TEST_EXECUTABLE}]==] [==[--gtest_filter=${filter}]==])\n"
         "set_tests_properties([==[${name}]==] PROPERTIES WORKING_DIRECTORY [==[${WORKING_DIR}]==] "
         "SKIP_REGULAR_EXPRESSION [==[${skip}]==] LABELS [==[${LABELS}]==] COST ${cost} "
         "ENVIRONMENT [==[${ENVIRONMENT}]==])\n")
endmacro()
foreach(line IN LISTS lines)
  if(line MATCHES "^([^ #][^ ]*)\\.")  # a suite: "Backends/Shadows."
    set(suite "${CMAKE_MATCH_1}")
  elseif(line MATCHES "^  ([^ #]+)")  # a case: "  Forward/vulkan  # GetParam() = ..."
    set(case "${CMAKE_MATCH_1}")
    if(suite MATCHES "^Backends/" AND case MATCHES "/([^/]+)$")
      set(key "${suite}/${CMAKE_MATCH_1}")
      if(NOT DEFINED count_${key})
        list(APPEND groups "${key}")
        set(count_${key} 0)
        set(filter_${key} "${suite}.*/${CMAKE_MATCH_1}")
      endif()
      math(EXPR count_${key} "${count_${key}} + 1")
    else()
      emit("${suite}.${case}" "${suite}.${case}" 1)
    endif()
  endif()
endforeach()
foreach(key IN LISTS groups)
  emit("${key}" "${filter_${key}}" "${count_${key}}")
endforeach()
file(WRITE "${CTEST_FILE}" "${out}")

# fe_discover_tests(TARGET [LABELS ...]): registers a GoogleTest binary's cases with CTest, as
# gtest_discover_tests does (listed after each build), but with the cases of one backend-
# parameterised suite (Backends/Suite.Case/backend) run as one CTest test, "Backends/Suite/backend".
# Each CTest test is a process, and a process that loads a driver stack (the Vulkan loader,
# lavapipe and LLVM, the validation layer; EGL or OSMesa and llvmpipe) spends 0.2 to 0.4 s before
# its case begins: run one by one, the 486 backend cases spent more there than in most of
# their bodies. Every case still runs, with its own device; a failure names the case in the
# output (--output-on-failure), and `fe_unit_tests --gtest_filter=...` runs one alone.
# Other cases stay one CTest test each (the sanitized run selects some by name).
include(${CMAKE_CURRENT_LIST_DIR}/FeTestEnvironment.cmake)
set(FE_DISCOVER_TESTS_SCRIPT "${CMAKE_CURRENT_LIST_DIR}/FeDiscoverTestsScript.cmake")

function(fe_discover_tests target)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "" "LABELS")
  set(ctest_file "${CMAKE_CURRENT_BINARY_DIR}/${target}_tests.cmake")
  add_custom_command(
    TARGET ${target} POST_BUILD
    COMMAND "${CMAKE_COMMAND}" -D "TEST_EXECUTABLE=$<TARGET_FILE:${target}>"
            -D "CTEST_FILE=${ctest_file}" -D "WORKING_DIR=${CMAKE_CURRENT_BINARY_DIR}"
            -D "LABELS=${arg_LABELS}" -D "ENVIRONMENT=${FE_TEST_ENVIRONMENT}" -P "${FE_DISCOVER_TESTS_SCRIPT}"
    BYPRODUCTS "${ctest_file}"
    VERBATIM)
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES "${ctest_file}")
endfunction()

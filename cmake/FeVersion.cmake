# Run at build time (cmake -P): writes OUT with the engine version and `git describe` of SRC,
# only when they changed, so reports name the commit that was built and nothing else rebuilds.
execute_process(COMMAND git describe --always --dirty --tags
                WORKING_DIRECTORY ${SRC} OUTPUT_VARIABLE describe RESULT_VARIABLE rc
                OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
if(NOT rc EQUAL 0 OR describe STREQUAL "")
  set(describe "unknown")  # not a git checkout, or git missing
endif()
set(content "#define FE_VERSION \"${VERSION}\"\n#define FE_GIT_DESCRIBE \"${describe}\"\n")
set(old "")
if(EXISTS ${OUT})
  file(READ ${OUT} old)
endif()
if(NOT old STREQUAL content)
  file(WRITE ${OUT} "${content}")
endif()

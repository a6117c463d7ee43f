# Sanitizer builds: -DFE_SANITIZE=address,undefined (any list -fsanitize takes), used by
# tools/run-sanitized-tests.sh and CI. Every target is instrumented; undefined behaviour stops
# the program (no recovery), so a test that triggers it fails.
#
# Leak checking needs the driver modules loaded at exit: the Vulkan loader and our GL platform
# dlclose Mesa's drivers and the validation layer when a device goes, and LeakSanitizer then
# cannot tell which module a leaked block came from, so suppressions by module name (see
# tools/sanitizers/lsan.supp) cannot match. Linking KeepModulesLoaded.c into every program
# keeps every dlopened module mapped until the process ends; nothing else changes.
set(FE_SANITIZE "" CACHE STRING "Sanitizers to build with, e.g. address,undefined (empty: none)")
if(FE_SANITIZE)
  add_compile_options(-fsanitize=${FE_SANITIZE} -fno-omit-frame-pointer -fno-sanitize-recover=all)
  add_link_options(-fsanitize=${FE_SANITIZE})
endif()
# The fuzzers (-DFE_FUZZ=ON) are sanitized too and need the same for their exit leak check.
if(FE_SANITIZE OR FE_FUZZ)
  # Line tables are all a sanitizer report needs (function, file and line per frame); full debug
  # info made these CI builds about 40 % slower to compile (a test file: 29.7 s with -g, 21.3 s
  # with -g1). The last -g level given wins, and compile options follow the configuration's flags.
  add_compile_options(-g1)
  # Exported, so the interposed dlclose also serves libraries that are dlopened (Mesa's EGL).
  add_link_options(-Wl,--export-dynamic-symbol=dlclose)
  # Compiled here and put on every program's link line (not into the installed libraries):
  # KeepModulesLoaded.c as above, SanitizerDefaults.c the runtime options every program needs.
  foreach(_src KeepModulesLoaded SanitizerDefaults)
    set(_obj ${CMAKE_BINARY_DIR}/${_src}.o)
    execute_process(COMMAND ${CMAKE_C_COMPILER} -O2 -fPIC -c ${CMAKE_CURRENT_LIST_DIR}/../tools/sanitizers/${_src}.c -o ${_obj}
                    RESULT_VARIABLE _failed)
    if(_failed)
      message(FATAL_ERROR "fe: cannot compile tools/sanitizers/${_src}.c")
    endif()
    string(APPEND CMAKE_C_STANDARD_LIBRARIES " ${_obj}")
    string(APPEND CMAKE_CXX_STANDARD_LIBRARIES " ${_obj}")
  endforeach()
  message(STATUS "fe: driver modules stay loaded for leak checking")
endif()

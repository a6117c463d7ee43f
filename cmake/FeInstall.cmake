# `cmake --install`: headers, static libraries, the compiled shaders (embedded in the renderer
# library), the fe tool and its report script, a CMake package (find_package(fe) giving
# fe::gdi and fe::renderer, versioned) and a pkg-config file (fe.pc).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# The targets a consumer names (and fe::ui, the UI renderer, which brings Dear ImGui): the abstract device with every backend, and the renderer.
add_library(fe_package_gdi INTERFACE)
target_link_libraries(fe_package_gdi INTERFACE fe_gdi fe_gdi_json fe_gdi_capture fe_backends)
set_target_properties(fe_package_gdi PROPERTIES EXPORT_NAME gdi)
add_library(fe_package_renderer INTERFACE)
target_link_libraries(fe_package_renderer INTERFACE fe_package_gdi fe_render)
set_target_properties(fe_package_renderer PROPERTIES EXPORT_NAME renderer)
add_library(fe::gdi ALIAS fe_package_gdi)
add_library(fe::renderer ALIAS fe_package_renderer)
add_library(fe::ui ALIAS fe_ui)

# The libraries behind them, exported under short names (fe::core, fe::render, ...) because a
# static library's dependencies must be installed with it.
set(FE_EXPORTED fe_gdi:core fe_gdi_json:gdi_json fe_gdi_capture:gdi_capture fe_platform:platform fe_backend_vulkan:backend_vulkan
    fe_backend_gl:backend_gl fe_backends:backends fe_assets:assets fe_frame:frame fe_graph:graph fe_render:render
    fe_shaders_scene:shaders_scene fe_ui:ui)
set(FE_EXPORTED_TARGETS fe_package_gdi fe_package_renderer)
foreach(pair ${FE_EXPORTED})
  string(REPLACE ":" ";" pair ${pair})
  list(GET pair 0 target)
  list(GET pair 1 name)
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name})
  list(APPEND FE_EXPORTED_TARGETS ${target})
endforeach()

install(TARGETS ${FE_EXPORTED_TARGETS} EXPORT feTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        OBJECTS DESTINATION ${CMAKE_INSTALL_LIBDIR}/fe-objects
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/gdi/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/renderer/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/fe/renderer
        FILES_MATCHING PATTERN "*.h")
install(TARGETS fe fe_hlsl RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(FILES ${PROJECT_SOURCE_DIR}/tools/bench/report.py DESTINATION ${CMAKE_INSTALL_DATADIR}/fe/bench)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/bench/sweeps DESTINATION ${CMAKE_INSTALL_DATADIR}/fe/bench)

set(FE_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/fe)
install(EXPORT feTargets NAMESPACE fe:: DESTINATION ${FE_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/feConfig.cmake.in ${CMAKE_CURRENT_BINARY_DIR}/feConfig.cmake
                              INSTALL_DESTINATION ${FE_CMAKE_DIR} PATH_VARS CMAKE_INSTALL_DATADIR CMAKE_INSTALL_BINDIR)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/feConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/feConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/feConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/FeShaders.cmake ${PROJECT_SOURCE_DIR}/cmake/fe-glslang.sh
              ${PROJECT_SOURCE_DIR}/cmake/fe-spirv-embed.sh
        DESTINATION ${FE_CMAKE_DIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/shaders/include/ DESTINATION ${CMAKE_INSTALL_DATADIR}/fe/shaders/include)

# pkg-config: the same libraries in link order; the shader objects are inside libfe_render.a.
configure_file(${PROJECT_SOURCE_DIR}/cmake/fe.pc.in ${CMAKE_CURRENT_BINARY_DIR}/fe.pc @ONLY)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/fe.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

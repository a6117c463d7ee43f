# fe_add_shaders(<target> BASE_DIR <dir> SOURCES <files...>)
#
# Compiles each GLSL 450 source twice at BUILD time with glslangValidator: once for Vulkan
# (-V, FE_VULKAN defined) and once for OpenGL (-G, FE_OPENGL defined, loaded via ARB_gl_spirv).
# Build time because a broken shader then fails the build with glslang's "file:line" message,
# and the binaries ship inside the executable (no shader files to find at run time).
# The result is a static library whose registry answers fe::shaders::find("<path under BASE_DIR>").
find_program(GLSLANG_VALIDATOR glslangValidator REQUIRED)
# glslangValidator through a wrapper that adds, to an error on a one-API built-in
# (gl_VertexIndex, gl_VertexID, ...), the portable macro to write instead.
set(FE_GLSLANG_WRAPPER ${CMAKE_CURRENT_LIST_DIR}/fe-glslang.sh)
# Graphics stages through spirv-opt (Debian's spirv-tools, which the engine needs anyway), both
# encodings: fe-spirv-embed.sh says why. Without spirv-opt they are embedded as glslang wrote them.
find_program(FE_SPIRV_OPT spirv-opt)
set(FE_SPIRV_EMBED ${CMAKE_CURRENT_LIST_DIR}/fe-spirv-embed.sh)
# The engine's GLSL includes (fe_common.glsl, ...): the source tree's, or the installed
# package's (feConfig.cmake sets it before including this file).
if(NOT FE_SHADER_INCLUDE_DIR)
  set(FE_SHADER_INCLUDE_DIR ${CMAKE_CURRENT_LIST_DIR}/../shaders/include)
endif()

# HLSL: a file named NAME.STAGE.hlsl (STAGE: vert, tesc, tese, geom, frag, comp) whose entry
# point is `main` or the one a line "// fe-entry: NAME" names, compiled by fe-hlsl (the engine's
# run-time HLSL compiler as a tool: HLSL -> SPIR-V -> GLSL 450 -> both encodings). The binaries'
# entry point is "main".
function(fe_add_hlsl_command abs index vk_h gl_h define name)
  if(NOT abs MATCHES "\\.(vert|tesc|tese|geom|frag|comp)\\.hlsl$")
    message(FATAL_ERROR "fe_add_shaders: ${abs}: an HLSL file is named NAME.STAGE.hlsl (STAGE: vert, tesc, tese, geom, frag or comp)")
  endif()
  set(stage ${CMAKE_MATCH_1})
  file(STRINGS ${abs} entry_lines REGEX "^// fe-entry: [A-Za-z_0-9]+")
  set(entry main)
  foreach(line ${entry_lines})
    string(REGEX REPLACE "^// fe-entry: ([A-Za-z_0-9]+).*$" "\\1" entry "${line}")
  endforeach()
  if(TARGET fe_hlsl)
    set(tool $<TARGET_FILE:fe_hlsl>)
    set(tool_dep fe_hlsl)
  elseif(FE_HLSL_COMPILER)
    set(tool ${FE_HLSL_COMPILER})
    set(tool_dep ${FE_HLSL_COMPILER})
  else()
    message(FATAL_ERROR "fe_add_shaders: ${abs}: no fe-hlsl (FE_HLSL_COMPILER) to compile HLSL")
  endif()
  # ASan's leak check off: glslang keeps process-wide tables to the end.
  add_custom_command(
    OUTPUT ${vk_h} ${gl_h}
    COMMAND ${CMAKE_COMMAND} -E env ASAN_OPTIONS=detect_leaks=0 ${tool} ${stage} ${entry} ${abs}
            ${vk_h} fe_spv_vk_${index} ${gl_h} fe_spv_gl_${index} ${define} -I${FE_SHADER_INCLUDE_DIR}
    DEPENDS ${abs} ${tool_dep}
    COMMENT "fe-hlsl ${name}"
    VERBATIM)
endfunction()

function(fe_add_shaders target)
  cmake_parse_arguments(ARG "" "BASE_DIR" "SOURCES" ${ARGN})
  set(out_dir ${CMAKE_CURRENT_BINARY_DIR}/${target}_spv)
  file(MAKE_DIRECTORY ${out_dir})
  set(headers "")
  set(entries "")
  set(includes "")
  set(index 0)
  file(GLOB common_includes ${FE_SHADER_INCLUDE_DIR}/*.glsl)
  foreach(src ${ARG_SOURCES})
    get_filename_component(abs ${src} ABSOLUTE)
    file(RELATIVE_PATH rel ${ARG_BASE_DIR} ${abs})
    # Variants: a line "// fe-variant: NAME (why)" compiles the source once more with NAME defined,
    # registered as "<path>:NAME" (a path a pipeline picks when it is made, not a run-time
    # branch); "NAME+OTHER" defines both, registered as "<path>:NAME+OTHER". Read at configure
    # time, so editing a shader re-runs the configuration.
    set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${abs})
    file(STRINGS ${abs} variant_lines REGEX "^// fe-variant: [A-Za-z_0-9+]+")
    set(variants "-")
    foreach(line ${variant_lines})
      string(REGEX REPLACE "^// fe-variant: ([A-Za-z_0-9+]+).*$" "\\1" v "${line}")
      list(APPEND variants ${v})
    endforeach()
    foreach(variant ${variants})
      if(variant STREQUAL "-")
        set(name ${rel})
        set(define "")
      else()
        set(name "${rel}:${variant}")
        string(REPLACE "+" "=1;-D" define "-D${variant}=1")
      endif()
      set(vk_h ${out_dir}/s${index}_vk.h)
      set(gl_h ${out_dir}/s${index}_gl.h)
      if(abs MATCHES "\\.hlsl$")
        fe_add_hlsl_command(${abs} ${index} ${vk_h} ${gl_h} "${define}" ${name})
      else()
      if(FE_SPIRV_OPT AND NOT abs MATCHES "\\.comp$")  # compute: fe-spirv-embed.sh says why not
        set(vk_spv ${out_dir}/s${index}_vk.spv)
        set(gl_spv ${out_dir}/s${index}_gl.spv)
        set(commands
            COMMAND sh ${FE_GLSLANG_WRAPPER} ${GLSLANG_VALIDATOR} -V --target-env vulkan1.2 -DFE_VULKAN=1 ${define}
                    -I${FE_SHADER_INCLUDE_DIR} --quiet -o ${vk_spv} ${abs}
            COMMAND sh ${FE_SPIRV_EMBED} ${FE_SPIRV_OPT} vulkan1.2 ${vk_spv} ${vk_h} fe_spv_vk_${index}
            COMMAND sh ${FE_GLSLANG_WRAPPER} ${GLSLANG_VALIDATOR} -G -DFE_OPENGL=1 ${define}
                    -I${FE_SHADER_INCLUDE_DIR} --quiet -o ${gl_spv} ${abs}
            COMMAND sh ${FE_SPIRV_EMBED} ${FE_SPIRV_OPT} opengl4.5 ${gl_spv} ${gl_h} fe_spv_gl_${index})
      else()
        set(commands
            COMMAND sh ${FE_GLSLANG_WRAPPER} ${GLSLANG_VALIDATOR} -V --target-env vulkan1.2 -DFE_VULKAN=1 ${define}
                    -I${FE_SHADER_INCLUDE_DIR} --quiet --vn fe_spv_vk_${index} -o ${vk_h} ${abs}
            COMMAND sh ${FE_GLSLANG_WRAPPER} ${GLSLANG_VALIDATOR} -G -DFE_OPENGL=1 ${define}
                    -I${FE_SHADER_INCLUDE_DIR} --quiet --vn fe_spv_gl_${index} -o ${gl_h} ${abs})
      endif()
      add_custom_command(
        OUTPUT ${vk_h} ${gl_h}
        ${commands}
        DEPENDS ${abs} ${common_includes} ${FE_SPIRV_EMBED}
        COMMENT "glslang ${name}"
        VERBATIM)
      endif()
      list(APPEND headers ${vk_h} ${gl_h})
      string(APPEND includes "#include \"s${index}_vk.h\"\n#include \"s${index}_gl.h\"\n")
      string(APPEND entries "    {\"${name}\", {fe_spv_vk_${index}, sizeof(fe_spv_vk_${index}) / 4}, {fe_spv_gl_${index}, sizeof(fe_spv_gl_${index}) / 4}},\n")
      math(EXPR index "${index} + 1")
    endforeach()
  endforeach()
  set(registry ${out_dir}/registry.cpp)
  file(GENERATE OUTPUT ${registry} CONTENT "// Generated by fe_add_shaders: do not edit.
#include <cstdint>
#include <cstring>
#include \"fe/gdi/ShaderRegistry.h\"
${includes}
namespace {
struct Entry { const char* name; std::span<const uint32_t> vk, gl; };
const Entry kEntries[] = {
${entries}};
struct Registrar {
    Registrar() { for (const Entry& e : kEntries) fe::shaders::registerBinary({e.name, e.vk, e.gl}); }
} registrar;
}  // namespace
extern \"C\" void fe_shaders_link_${target}() {}
")
  add_library(${target} OBJECT ${registry} ${headers})
  target_include_directories(${target} PRIVATE ${out_dir})
  if(TARGET fe_gdi)
    target_link_libraries(${target} PUBLIC fe_gdi)     # inside the engine's build
  else()
    target_link_libraries(${target} PUBLIC fe::core)   # a project using the installed package
  endif()
endfunction()

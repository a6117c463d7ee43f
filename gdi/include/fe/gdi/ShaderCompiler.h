// GLSL and HLSL compiled at run time (glslang as a library), for editors, material tools and hot reload:
// the same two encodings the build step (fe_add_shaders) makes, so a shader given as source
// behaves on every backend as one compiled at build time.
//   ShaderHandle fs = device->createShader({.stage = ShaderStage::Fragment,
//                                           .source = {.text = glsl, .name = "tint.frag"}});
//   ShaderBinary b = compileShader({.stage = ShaderStage::Vertex, .text = glsl});  // or by hand
// - GLSL 450 with FE_VULKAN or FE_OPENGL defined as the build step does, `#include
//   "fe_common.glsl"` (FE_VERTEX_ID, FE_CONSTANTS) built in, and other includes through the
//   source's `include` callback (none: an include is an error naming it).
// - An error is a gdi::Error with glslang's messages as "NAME:LINE: message" (the build step's
//   form), plus the portable name when the source used a built-in only one API has.
// - Compiled once per text, stage, defines and includes' text: an unchanged source is not
//   compiled twice in a process (the binaries stay valid for the process, so their spans can
//   go into ShaderDesc::binary and captures).
#pragma once
#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "fe/gdi/Device.h"

namespace fe::gdi {

struct ShaderSourceCompile {
    ShaderStage stage = ShaderStage::None;
    std::string_view text;
    // HLSL: compiled from `entryPoint` to SPIR-V, then written as GLSL 450 (SPIRV-Cross; a
    // texture and the sampler it is sampled with become one sampler at the texture's register),
    // which is compiled as any GLSL: the binaries' entry point is "main".
    ShaderLanguage language = ShaderLanguage::GLSL;
    std::string entryPoint = "main";
    std::string name = "shader";       // in messages: "NAME:LINE: ..."
    std::vector<std::string> defines;  // "NAME" or "NAME=VALUE", as -D
    // `#include "NAME"`: the text of NAME (included from `includer`), or nullopt if there is none.
    // Called on the compiling thread, for HLSL too (whose translation runs in a child process,
    // so that a glslang crash costs only the child: the child asks, this process answers), so
    // what it records and the locks it takes are the caller's; an exception it throws reaches
    // the caller.
    std::function<std::optional<std::string>(const std::string& name, const std::string& includer)>
        include;
};

// Both encodings of the source (ShaderBinary::vulkan and ::opengl); throws Error as above.
ShaderBinary compileShader(const ShaderSourceCompile& source);
// HLSL as the GLSL 450 the HLSL path compiles (what the build step's fe_add_shaders makes of a
// .hlsl file too), for reading and tests; throws Error as above.
std::string hlslToGlsl(const ShaderSourceCompile& source);

// createShader's first step on every backend: a desc given as source (ShaderDesc::source) with
// its binary compiled; any other desc unchanged.
ShaderDesc withCompiledSource(const ShaderDesc& desc);

// How many compiles the process has run (the cache's misses), for tests of the cache.
uint64_t shaderCompileCount();
// Tests of the HLSL translation's stall detection: the next `count` translation children sleep
// for good before translating, as a child blocked on a lock it inherited at the fork would (each
// is noticed after `stallLimit` asleep, killed and forked again; three tries, then an Error).
// The limit is 2 s in use; a test may shorten it while it stalls children (count 0 restores it).
void stallHlslChildrenForTesting(int count,
                                 std::chrono::milliseconds stallLimit = std::chrono::seconds(2));

}  // namespace fe::gdi

// Conformance case for GLSL compiled at run time (ShaderDesc::source, gdi::compileShader): the
// same image and the same errors on every backend.
#include <atomic>

#include "CaseSupport.h"
#include "fe/gdi/ShaderCompiler.h"

namespace fe::conformance {

using namespace gdi;

namespace {

constexpr const char* kVertex = R"(#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_common.glsl"
// A triangle over the whole target.
void main() {
    vec2 p = vec2((FE_VERTEX_ID << 1) & 2, FE_VERTEX_ID & 2);
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";

constexpr const char* kFragment = R"(#version 450
#extension GL_GOOGLE_include_directive : require
#include "palette.glsl"
layout(location = 0) out vec4 outColor;
void main() { outColor = paletteColour() * SCALE; }
)";

// A vertex and a fragment shader from source, an include from the callback and a define, drawn
// over the target; the cache compiles an unchanged source once and an edited include again;
// mistakes are Errors naming the file and line.
std::vector<CaseImage> runtimeGlslCompile(Device& d) {
    DeviceObjects o(d);
    std::string palette = "vec4 paletteColour() { return vec4(0.0, 1.0, 0.5, 1.0); }\n";
    auto include = [&](const std::string& name, const std::string&) -> std::optional<std::string> {
        if (name == "palette.glsl") return palette;
        return std::nullopt;
    };
    auto fragment = [&] {
        return o.add(d.createShader({.stage = ShaderStage::Fragment,
                                     .source = {.text = kFragment,
                                                .name = "runtime.frag",
                                                .defines = {"SCALE=vec4(1.0, 1.0, 0.5, 1.0)"},
                                                .include = include}}));
    };
    const ShaderHandle vs = o.add(d.createShader(
        {.stage = ShaderStage::Vertex, .source = {.text = kVertex, .name = "runtime.vert"}}));
    const ShaderHandle fs = fragment();
    const PipelineHandle p = o.add(d.createGraphicsPipeline(
        {.vertexShader = vs, .fragmentShader = fs, .colorFormats = {Format::RGBA8}}));
    const TextureHandle target = caseTarget(o);
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = target, .clear = {0, 0, 0, 1}}}});
    cmd->setPipeline(p);
    cmd->draw(3);
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));

    // The cache: the same source, defines and include text again are not compiled again; an
    // edited include is.
    const uint64_t before = shaderCompileCount();
    fragment();
    FE_CONFORMANCE_CHECK(shaderCompileCount() == before,
                         "an unchanged source is not compiled a second time");
    // An edit this process has not compiled yet (the cache outlives a case: the suite runs every
    // backend in one process).
    static std::atomic<int> edits{0};
    palette =
        "// edit " + std::to_string(++edits) + "\nvec4 paletteColour() { return vec4(1.0); }\n";
    fragment();
    FE_CONFORMANCE_CHECK(shaderCompileCount() == before + 1, "an edited include is compiled");

    expectError(
        [&] {
            d.createShader({.stage = ShaderStage::Fragment,
                            .source = {.text = "#version 450\nlayout(location = 0) out vec4 c;\n"
                                               "void main() { c = nope; }\n",
                                       .name = "broken.frag"}});
        },
        "shader 'broken.frag' does not compile for Vulkan:\nbroken.frag:3: 'nope' : undeclared "
        "identifier");
    expectError(
        [&] {
            d.createShader({.stage = ShaderStage::Vertex,
                            .source = {.text = "#version 450\nvoid main() { gl_Position = "
                                               "vec4(gl_VertexIndex); }\n",
                                       .name = "vulkan_only.vert"}});
        },
        "gl_VertexIndex is Vulkan's name and gl_VertexID GL's: write FE_VERTEX_ID");
    expectError(
        [&] {
            d.createShader({.stage = ShaderStage::Fragment,
                            .source = {.text = "#version 450\n#extension "
                                               "GL_GOOGLE_include_directive : require\n#include "
                                               "\"missing.glsl\"\nvoid main() {}\n",
                                       .name = "includes.frag"}});
        },
        "includes.frag:3: '#include' : Could not process include directive for header name: "
        "missing.glsl");
    expectError(
        [&] {
            d.createShader(
                {.stage = ShaderStage::Vertex,
                 .binary = compileShader({.stage = ShaderStage::Vertex, .text = kVertex}),
                 .source = {.text = kVertex, .name = "both.vert"}});
        },
        "createShader 'both.vert': give a binary or a source, not both");
    return {drawn8("palette times SCALE", d.readTexture(target),
                   solid(Format::RGBA8, {0, 1, 0.25f, 1}))};
}

}  // namespace

std::vector<Case> shaderSourceCases() { return {{"runtime_glsl_compile", runtimeGlslCompile}}; }

}  // namespace fe::conformance

// Conformance case for GLSL compiled at run time (ShaderDesc::source, gdi::compileShader): the
// same image and the same errors on every backend.
#include <atomic>

#include "CaseSupport.h"
#include "fe/gdi/ShaderCompiler.h"
#include "fe/gdi/ShaderRegistry.h"

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

// The HLSL cases' draw: a vertex and a pixel shader over a 64x64 target, the pixel shader's
// block at slot 0 (a float4x4 from glm's column-major memory, then a float4) and a 2x2 texture
// at slot 1, sampled nearest.
struct HlslParams {
    float transform[16];
    float tint[4];
};
const uint8_t kQuadrants[16] = {255, 255, 255, 255, 255, 128, 0,   255,
                                0,   255, 255, 255, 128, 64,  255, 255};

Image drawHlsl(Device& d, ShaderHandle vs, ShaderHandle fs) {
    DeviceObjects o(d);
    // Columns (0,0,1,0), (1,0,0,0), (0,1,0,0), (0,0,0,1): rows (0,1,0,0), (0,0,1,0), (1,0,0,0),
    // (0,0,0,1), so mul(M, tint) = (tint.y, tint.z, tint.x, tint.w) = (0.5, 0.25, 1, 1); read
    // transposed it would be (0.25, 1, 0.5, 1).
    const HlslParams params{{0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 1}, {1, 0.5f, 0.25f, 1}};
    const BufferHandle ubo = o.add(
        d.createBuffer({.size = sizeof params, .usage = BufferUsage::Uniform}, bytesOf(params)));
    const TextureHandle quadrants = o.add(d.createTexture(
        {.width = 2, .height = 2, .usage = TextureUsage::Sampled | TextureUsage::CopyDst}));
    d.writeTexture(quadrants, {}, bytesOf(kQuadrants));
    const SamplerHandle nearest = o.add(d.createSampler({.minFilter = Filter::Nearest,
                                                         .magFilter = Filter::Nearest,
                                                         .addressU = AddressMode::ClampToEdge,
                                                         .addressV = AddressMode::ClampToEdge}));
    const PipelineHandle p = o.add(d.createGraphicsPipeline(
        {.vertexShader = vs, .fragmentShader = fs, .colorFormats = {Format::RGBA8}}));
    const TextureHandle target = caseTarget(o);
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = target, .clear = {0, 0, 0, 1}}}});
    cmd->setPipeline(p);
    cmd->setUniformBuffer(0, ubo);
    cmd->setTexture(1, quadrants, nearest);
    cmd->draw(3);
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
    return d.readTexture(target);
}

Image hlslExpected() {
    return expectImage(Format::RGBA8, [](uint32_t x, uint32_t y) -> Texel {
        const uint8_t* t = &kQuadrants[4 * ((y / 32) * 2 + x / 32)];
        return {t[0] / 255.0f * 0.5f, t[1] / 255.0f * 0.25f, t[2] / 255.0f, 1};
    });
}

// HLSL compiled by the build step (fe_add_shaders runs fe-hlsl on NAME.STAGE.hlsl files).
std::vector<CaseImage> hlslShaders(Device& d) {
    DeviceObjects o(d);
    const ShaderHandle vs =
        o.add(d.createShader({.stage = ShaderStage::Vertex,
                              .binary = shaders::find("conformance/hlsl_fullscreen.vert.hlsl")}));
    const ShaderHandle fs =
        o.add(d.createShader({.stage = ShaderStage::Fragment,
                              .binary = shaders::find("conformance/hlsl_tint.frag.hlsl")}));
    return {drawn8("hlsl_registers_and_matrix", drawHlsl(d, vs, fs), hlslExpected())};
}

constexpr const char* kHlslVertex = R"(// fe's clip space is Vulkan's: y down.
#include "fullscreen.hlsli"
struct VSOut { float4 position : SV_Position; float2 uv : TEXCOORD0; };
VSOut VSMain(uint id : SV_VertexID) {
    VSOut o;
    o.uv = corner(id);
    o.position = float4(o.uv * 2.0 - 1.0, 0.0, 1.0);
    return o;
}
)";

constexpr const char* kHlslPixel =
    R"(cbuffer Params : register(b0) { float4x4 transform; float4 tint; };
Texture2D<float4> quadrants : register(t1);
SamplerState nearest : register(s1);
float4 PSMain(float4 position : SV_Position, float2 uv : TEXCOORD0) : SV_Target0 {
    return quadrants.Sample(nearest, uv) * mul(transform, tint) * SCALE;
}
)";

// HLSL given as source: an include from the callback, a define, entry points by name; the same
// image as the build step's; mistakes are Errors naming file and line.
std::vector<CaseImage> runtimeHlslCompile(Device& d) {
    DeviceObjects o(d);
    auto include = [](const std::string& name, const std::string&) -> std::optional<std::string> {
        if (name == "fullscreen.hlsli")
            return "float2 corner(uint id) { return float2((id << 1) & 2, id & 2); }\n";
        return std::nullopt;
    };
    const ShaderHandle vs = o.add(d.createShader({.stage = ShaderStage::Vertex,
                                                  .entryPoint = "VSMain",
                                                  .source = {.text = kHlslVertex,
                                                             .language = ShaderLanguage::HLSL,
                                                             .name = "runtime.vert.hlsl",
                                                             .include = include}}));
    const ShaderHandle fs = o.add(d.createShader({.stage = ShaderStage::Fragment,
                                                  .entryPoint = "PSMain",
                                                  .source = {.text = kHlslPixel,
                                                             .language = ShaderLanguage::HLSL,
                                                             .name = "runtime.frag.hlsl",
                                                             .defines = {"SCALE=1.0"}}}));
    auto hlsl = [&](const char* text, const char* name, const char* entry) {
        d.createShader({.stage = ShaderStage::Fragment,
                        .entryPoint = entry,
                        .source = {.text = text, .language = ShaderLanguage::HLSL, .name = name}});
    };
    expectError(
        [&] { hlsl("float4 main() : SV_Target0 {\n  return nope;\n}\n", "bad.hlsl", "main"); },
        "shader 'bad.hlsl' does not compile as HLSL:\nbad.hlsl:2: 'nope' : unknown "
        "variable");
    expectError([&] { hlsl("float4 main() : SV_Target0 { return 1; }\n", "entry.hlsl", "PSMain"); },
                "shader 'entry.hlsl' does not");
    expectError(
        [&] {
            hlsl(
                "Texture2D t : register(t0);\nSamplerState a : register(s0);\nSamplerState b : "
                "register(s1);\nfloat4 main(float2 uv : TEXCOORD0) : SV_Target0 {\n  return "
                "t.Sample(a, uv) + t.Sample(b, uv);\n}\n",
                "two.hlsl", "main");
        },
        "shader 'two.hlsl': texture 't' is sampled with two samplers (Load counting as one); the "
        "device binds one sampler per texture slot (setTexture)");
    // Sources on which glslang 11.13's HLSL front end dereferences null (found by
    // ShaderSourceFuzzer): refused with an Error naming the shader, and the process goes on (the
    // translation runs in a child process; the first is also refused before glslang sees it).
    expectError(
        [&] {
            hlsl("float4 main(float : TEXCOORD0) : SV_Target0 { return 1; }\n", "unnamed.hlsl",
                 "main");
        },
        "shader 'unnamed.hlsl': parameter 1 of entry point 'main' has no name");
    expectError([&] { hlsl("Texture2D t x4 m; float4 t\x04#versiinto", "crash.hlsl", "main"); },
                "shader 'crash.hlsl'");
    return {drawn8("hlsl_from_source", drawHlsl(d, vs, fs), hlslExpected())};
}

}  // namespace

std::vector<Case> shaderSourceCases() {
    return {{"runtime_glsl_compile", runtimeGlslCompile},
            {"hlsl_shaders", hlslShaders},
            {"runtime_hlsl_compile", runtimeHlslCompile}};
}

}  // namespace fe::conformance

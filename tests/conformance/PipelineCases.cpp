// Conformance cases for pipelines checked against their shaders: binding slots taken
// from SPIR-V reflection, and every mismatch between a pipeline and its shaders or its pass
// refused with the same gdi::Error on every backend, before any native call (the runner fails
// a case on any validation or GL debug message, and fe conformance --no-validation runs them
// without the layer).
#include <cstring>

#include "CaseSupport.h"

namespace fe::conformance {

using namespace gdi;

namespace {

// Graphics and compute pipelines with no binding list: the slots come from the shaders (a
// uniform block read by both stages at 0, a sampled texture at 1; a storage buffer at 0 and a
// storage image at 1), and draws and dispatches that bind them work. A hand-written list equal
// to the shaders' draws the same.
std::vector<CaseImage> pipelineLayoutFromShader(Device& d) {
    DeviceObjects o(d);
    const ShaderHandle vs =
        registryShader(o, ShaderStage::Vertex, "conformance/fullscreen_ubo.vert");
    const ShaderHandle fs =
        registryShader(o, ShaderStage::Fragment, "conformance/textured_uv.frag");
    const ShaderHandle cs = registryShader(o, ShaderStage::Compute, "conformance/fill.comp");
    const PipelineHandle derived = o.add(d.createGraphicsPipeline({.vertexShader = vs,
                                                                   .fragmentShader = fs,
                                                                   .colorFormats = {Format::RGBA8},
                                                                   .debugName = "derived"}));
    const PipelineHandle declared = o.add(d.createGraphicsPipeline(
        {.vertexShader = vs,
         .fragmentShader = fs,
         .colorFormats = {Format::RGBA8},
         .bindings = {{0, BindingType::UniformBuffer, ShaderStage::AllGraphics},
                      {1, BindingType::SampledTexture, ShaderStage::Fragment}},
         .debugName = "declared"}));
    const PipelineHandle fill =
        o.add(d.createComputePipeline({.computeShader = cs, .debugName = "derived compute"}));

    const TextureHandle image = o.add(d.createTexture(
        {.format = Format::RGBA32F,
         .width = 64,
         .height = 64,
         .usage = TextureUsage::Storage | TextureUsage::Sampled | TextureUsage::CopySrc}));
    const BufferHandle values =
        o.add(d.createBuffer({.size = 64 * 64 * 4, .usage = BufferUsage::Storage}));
    const float params[8] = {1, 1, 0, 0, 0, 0, 0, 0};  // uv = pixel / 64, level 0, depth 0
    const BufferHandle ubo = o.add(
        d.createBuffer({.size = sizeof params, .usage = BufferUsage::Uniform}, bytesOf(params)));
    const SamplerHandle nearest = o.add(d.createSampler({.minFilter = Filter::Nearest,
                                                         .magFilter = Filter::Nearest,
                                                         .addressU = AddressMode::ClampToEdge,
                                                         .addressV = AddressMode::ClampToEdge}));
    std::array<TextureHandle, 2> targets;
    for (auto& t : targets)
        t = o.add(d.createTexture({.width = 64,
                                   .height = 64,
                                   .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc}));
    auto cmd = d.createCommandList();
    cmd->setPipeline(fill);
    cmd->setStorageBuffer(0, values);
    cmd->setStorageTexture(1, image);
    cmd->dispatch(8, 8);
    for (size_t i = 0; i < targets.size(); ++i) {
        cmd->beginRenderPass({.colors = {{.texture = targets[i]}}});
        cmd->setPipeline(i == 0 ? derived : declared);
        cmd->setUniformBuffer(0, ubo);
        cmd->setTexture(1, image, nearest);
        cmd->draw(3);
        cmd->endRenderPass();
    }
    d.wait(d.submit(*cmd));
    // fill.comp's gradient (x / 64, y / 64, 0.5, 1) as an 8-bit image.
    const Image expected = expectImage(Format::RGBA8, [](uint32_t x, uint32_t y) -> Texel {
        return {float(x) / 64.0f, float(y) / 64.0f, 0.5f, 1};
    });
    const std::vector<uint8_t> bytes = d.readBuffer(values, 0, 64 * 64 * 4);
    for (uint32_t i = 0; i < 64 * 64; ++i) {
        uint32_t v;
        std::memcpy(&v, &bytes[4 * i], 4);
        FE_CONFORMANCE_CHECK(v == 3 * i + 1,
                             "the derived compute pipeline's storage buffer holds 3i + 1");
    }
    const char* reason = "x / 64 and y / 64 converted to 8 bits: one rounding step";
    return {within("derived", d.readTexture(targets[0]), expected, 1.0 / 255.0, reason),
            within("declared", d.readTexture(targets[1]), expected, 1.0 / 255.0, reason)};
}

// Each mistake between a pipeline and its shaders or its pass is a gdi::Error naming what is
// wrong, raised before any native call: no validation message, no crash, on every backend.
std::vector<CaseImage> bindingMismatchErrors(Device& d) {
    DeviceObjects o(d);
    const ShaderHandle vs =
        registryShader(o, ShaderStage::Vertex, "conformance/fullscreen_ubo.vert");
    const ShaderHandle fs = registryShader(o, ShaderStage::Fragment, "conformance/ubo_color.frag");
    const ShaderHandle uintVs =
        registryShader(o, ShaderStage::Vertex, "conformance/vertex_uint.vert");
    const ShaderHandle valueFs = registryShader(o, ShaderStage::Fragment, "conformance/value.frag");
    auto message = [&](const std::function<void()>& fn) -> std::string {
        try {
            fn();
        } catch (const Error& e) {
            return e.what();
        }
        return "(no error)";
    };
    auto expect = [&](const std::function<void()>& fn, const std::string& text) {
        const std::string got = message(fn);
        FE_CONFORMANCE_CHECK(got.find(text) != std::string::npos,
                             ("expected \"" + text + "\", got \"" + got + "\"").c_str());
    };
    auto create = [&](GraphicsPipelineDesc desc) {
        return [&d, desc] { d.destroy(d.createGraphicsPipeline(desc)); };
    };
    const GraphicsPipelineDesc ubo{.vertexShader = vs,
                                   .fragmentShader = fs,
                                   .colorFormats = {Format::RGBA8},
                                   .debugName = "ubo"};
    GraphicsPipelineDesc omitted = ubo;
    omitted.bindings = {{3, BindingType::UniformBuffer, ShaderStage::AllGraphics}};
    expect(create(omitted),
           "binding slot 0 (uniform buffer) is used by the vertex and fragment shader but missing");
    GraphicsPipelineDesc mistyped = ubo;
    mistyped.bindings = {{0, BindingType::SampledTexture, ShaderStage::AllGraphics}};
    expect(create(mistyped), "binding slot 0 is declared a sampled texture");
    GraphicsPipelineDesc noAttribute{.vertexShader = uintVs,
                                     .fragmentShader = valueFs,
                                     .colorFormats = {Format::RGBA8},
                                     .debugName = "attrs"};
    expect(create(noAttribute),
           "vertex shader input 'inPosition' (location 0) has no attribute in the vertex layout");
    GraphicsPipelineDesc wrongOutput = ubo;
    wrongOutput.colorFormats = {Format::R32U};
    expect(create(wrongOutput), "colour target 0 is R32U (uint)");

    const PipelineHandle p = o.add(d.createGraphicsPipeline(ubo));
    const BufferHandle buffer =
        o.add(d.createBuffer({.size = 4096, .usage = BufferUsage::Uniform | BufferUsage::Storage}));
    const TextureHandle rgba16 = o.add(d.createTexture(
        {.format = Format::RGBA16F, .width = 8, .height = 8, .usage = TextureUsage::RenderTarget}));
    const TextureHandle rgba8 =
        o.add(d.createTexture({.width = 8, .height = 8, .usage = TextureUsage::RenderTarget}));
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = rgba16}}});
    expect([&] { cmd->setPipeline(p); },
           "renders to colour [RGBA8], depth none but the render pass has colour [RGBA16F]");
    cmd->endRenderPass();
    cmd->beginRenderPass({.colors = {{.texture = rgba8}}});
    cmd->setPipeline(p);
    expect([&] { cmd->draw(3); }, "missing binding for slot(s) 0");
    const uint32_t align = d.info().limits.uniformBufferOffsetAlignment;
    if (align > 1)
        expect([&] { cmd->setUniformBuffer(0, buffer, align / 2, 16); },
               "uniformBufferOffsetAlignment");
    cmd->setStorageBuffer(0, buffer);  // accepted here: the kind is checked at the draw
    expect([&] { cmd->draw(3); }, "slot 0 expects");
    cmd->setUniformBuffer(0, buffer, 0, 32);
    cmd->draw(3);  // now valid
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
    return {};
}

}  // namespace

std::vector<Case> pipelineCases() {
    return {
        {"pipeline_layout_from_shader", pipelineLayoutFromShader},
        {"binding_mismatch_errors", bindingMismatchErrors},
    };
}

}  // namespace fe::conformance

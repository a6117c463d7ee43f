#include "Conformance.h"

#include <array>
#include <cmath>
#include <cstring>

#include "fe/gdi/DeviceObjects.h"
#include "fe/gdi/ShaderRegistry.h"

namespace fe::conformance {

using namespace gdi;

namespace {

constexpr uint32_t kSize = 64;

Image solid(Format f, std::array<float, 4> c, uint32_t w = kSize, uint32_t h = kSize) {
    return Image::fromTexels(w, h, f, std::vector<std::array<float, 4>>(size_t(w) * h, c));
}

// Cases own what they create through a DeviceObjects (CaseSupport.h says why).
TextureHandle target(DeviceObjects& objects, Format f) {
    return objects.add(objects.device().createTexture(
        {.format = f,
         .width = kSize,
         .height = kSize,
         .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc | TextureUsage::Sampled}));
}

struct Params {
    float color[4];
    float depth[4];
};

// Clear to a known value and read back: covers clears and readback of every colour format.
std::vector<CaseImage> clearEveryFormat(Device& d) {
    std::vector<CaseImage> out;
    const std::array<float, 4> c{0.25f, 0.5f, 0.75f, 1.0f};
    for (Format f :
         {Format::RGBA8, Format::RGBA8_SRGB, Format::RGBA16F, Format::RG16F, Format::R16F,
          Format::RGBA32F, Format::RG32F, Format::R32F, Format::R11G11B10F}) {
        DeviceObjects iteration(d);
        TextureHandle t = target(iteration, f);
        auto cmd = d.createCommandList();
        cmd->beginRenderPass({.colors = {{.texture = t, .clear = {c[0], c[1], c[2], c[3]}}}});
        cmd->endRenderPass();
        d.wait(d.submit(*cmd));
        // sRGB targets store the encoded value of the linear clear colour.
        std::array<float, 4> stored = c;
        if (f == Format::RGBA8_SRGB)
            for (int k = 0; k < 3; ++k)
                stored[k] = c[k] <= 0.0031308f ? 12.92f * c[k]
                                               : 1.055f * std::pow(c[k], 1.0f / 2.4f) - 0.055f;
        CaseImage ci{std::string(formatInfo(f).name), d.readTexture(t), solid(f, stored)};
        if (formatInfo(f).isFloat) {
            ci.absTolerance = 1e-3;
            ci.maxFractionOver = 0;
            ci.toleranceReason =
                "float clear of values exact in 16/11-bit floats: 1e-3 absolute, no pixel over";
        }
        out.push_back(std::move(ci));
    }
    return out;
}

std::vector<CaseImage> triangle(Device& d) {
    DeviceObjects objects(d);
    TextureHandle t = target(objects, Format::RGBA8);
    auto vs = objects.add(d.createShader(
        {.stage = ShaderStage::Vertex, .binary = shaders::find("conformance/triangle.vert")}));
    auto fs = objects.add(d.createShader(
        {.stage = ShaderStage::Fragment, .binary = shaders::find("conformance/color.frag")}));
    auto p = objects.add(d.createGraphicsPipeline(
        {.vertexShader = vs, .fragmentShader = fs, .colorFormats = {Format::RGBA8}}));
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = t, .clear = {0, 0, 0, 1}}}});
    cmd->setPipeline(p);
    cmd->draw(3);
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
    Image img = d.readTexture(t);
    // Analytic coverage: inside the triangle (-0.8,0.8),(0.8,0.8),(0,-0.8) away from its edges,
    // colour = barycentric mix; outside: the clear colour. Edge pixels take the rendered value.
    std::vector<std::array<float, 4>> texels(kSize * kSize);
    for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x) {
            double px = (x + 0.5) / kSize * 2 - 1, py = (y + 0.5) / kSize * 2 - 1;
            double ax = -0.8, ay = 0.8, bx = 0.8, by = 0.8, cx = 0.0, cy = -0.8;
            double den = (by - cy) * (ax - cx) + (cx - bx) * (ay - cy);
            double l0 = ((by - cy) * (px - cx) + (cx - bx) * (py - cy)) / den;
            double l1 = ((cy - ay) * (px - cx) + (ax - cx) * (py - cy)) / den;
            double l2 = 1 - l0 - l1;
            double m = std::min({l0, l1, l2});
            if (std::abs(m) < 0.03)
                texels[y * kSize + x] = img.texel(x, y);
            else if (m > 0)
                texels[y * kSize + x] = {float(l0), float(l1), float(l2), 1.0f};
            else
                texels[y * kSize + x] = {0, 0, 0, 1};
        }
    CaseImage ci{"triangle", img, Image::fromTexels(kSize, kSize, Format::RGBA8, texels)};
    return {ci};
}

// Uniform buffer colour, additive accumulation into RGBA16F beyond 1.0, and the depth test.
std::vector<CaseImage> uniformBlendDepth(Device& d) {
    DeviceObjects objects(d);
    auto vs =
        objects.add(d.createShader({.stage = ShaderStage::Vertex,
                                    .binary = shaders::find("conformance/fullscreen_ubo.vert")}));
    auto fs = objects.add(d.createShader(
        {.stage = ShaderStage::Fragment, .binary = shaders::find("conformance/ubo_color.frag")}));
    const std::vector<BindingSlot> slots = {
        {0, BindingType::UniformBuffer, ShaderStage::AllGraphics}};
    std::vector<CaseImage> out;

    // Additive: three draws of 0.75 into RGBA16F = 2.25 (exact in half floats).
    TextureHandle acc = target(objects, Format::RGBA16F);
    auto add = objects.add(d.createGraphicsPipeline({.vertexShader = vs,
                                                     .fragmentShader = fs,
                                                     .blend = {{.enable = true,
                                                                .srcColor = BlendFactor::One,
                                                                .dstColor = BlendFactor::One,
                                                                .srcAlpha = BlendFactor::One,
                                                                .dstAlpha = BlendFactor::One}},
                                                     .colorFormats = {Format::RGBA16F},
                                                     .bindings = slots}));
    Params params{{0.75f, 0.5f, 0.25f, 1.0f}, {0.5f, 0, 0, 0}};
    BufferHandle ubo = objects.add(d.createBuffer(
        {.size = sizeof(Params), .usage = BufferUsage::Uniform}, gdi::bytesOf(params)));
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = acc}}});
    cmd->setPipeline(add);
    cmd->setUniformBuffer(0, ubo);
    for (int i = 0; i < 3; ++i) cmd->draw(3);
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
    CaseImage ci{"additive_rgba16f", d.readTexture(acc),
                 solid(Format::RGBA16F, {2.25f, 1.5f, 0.75f, 3.0f})};
    ci.absTolerance = 1e-3;
    ci.maxFractionOver = 0;
    ci.toleranceReason = "sums of values exact in half floats: 1e-3 absolute, no pixel over";
    out.push_back(ci);

    // Depth: near red (0.25) drawn first, far green (0.75) second must be hidden with Less.
    for (Format df : {Format::D32F, Format::D24S8}) {
        DeviceObjects iteration(d);
        TextureHandle color = target(iteration, Format::RGBA8);
        TextureHandle depth = iteration.add(d.createTexture(
            {.format = df, .width = kSize, .height = kSize, .usage = TextureUsage::RenderTarget}));
        auto dp = iteration.add(
            d.createGraphicsPipeline({.vertexShader = vs,
                                      .fragmentShader = fs,
                                      .depthStencil = {.depthTest = true,
                                                       .depthWrite = true,
                                                       .depthCompare = CompareOp::Less},
                                      .colorFormats = {Format::RGBA8},
                                      .depthFormat = df,
                                      .bindings = slots}));
        Params nearP{{1, 0, 0, 1}, {0.25f, 0, 0, 0}}, farP{{0, 1, 0, 1}, {0.75f, 0, 0, 0}};
        BufferHandle u2 =
            iteration.add(d.createBuffer({.size = 512, .usage = BufferUsage::Uniform}));
        d.writeBuffer(u2, 0, gdi::bytesOf(nearP));
        d.writeBuffer(u2, 256, gdi::bytesOf(farP));
        cmd->beginRenderPass(
            {.colors = {{.texture = color, .clear = {0, 0, 1, 1}}}, .depth = {.texture = depth}});
        cmd->setPipeline(dp);
        cmd->setUniformBuffer(0, u2, 0, sizeof(Params));
        cmd->draw(3);
        cmd->setUniformBuffer(0, u2, 256, sizeof(Params));
        cmd->draw(3);
        cmd->endRenderPass();
        d.wait(d.submit(*cmd));
        out.push_back({std::string("depth_") + std::string(formatInfo(df).name),
                       d.readTexture(color), solid(Format::RGBA8, {1, 0, 0, 1})});
    }
    return out;
}

// Texture upload, nearest sampling, and sRGB decode on sampling.
std::vector<CaseImage> textureSampling(Device& d) {
    DeviceObjects objects(d);
    auto vs =
        objects.add(d.createShader({.stage = ShaderStage::Vertex,
                                    .binary = shaders::find("conformance/fullscreen_ubo.vert")}));
    auto fs = objects.add(d.createShader(
        {.stage = ShaderStage::Fragment, .binary = shaders::find("conformance/textured.frag")}));
    std::vector<CaseImage> out;
    Params params{{0, 0, 0, 0}, {0.5f, 0, 0, 0}};
    BufferHandle ubo = objects.add(d.createBuffer(
        {.size = sizeof(Params), .usage = BufferUsage::Uniform}, gdi::bytesOf(params)));
    SamplerHandle nearest =
        objects.add(d.createSampler({.minFilter = Filter::Nearest, .magFilter = Filter::Nearest}));
    for (Format tf : {Format::RGBA8, Format::RGBA8_SRGB}) {
        DeviceObjects iteration(d);
        // 4x4 checker of 16 distinct values, magnified 16x with nearest filtering.
        std::vector<uint8_t> px(4 * 4 * 4);
        for (int i = 0; i < 16; ++i) {
            px[i * 4 + 0] = uint8_t(i * 16);
            px[i * 4 + 1] = uint8_t(255 - i * 16);
            px[i * 4 + 2] = uint8_t((i % 4) * 64);
            px[i * 4 + 3] = 255;
        }
        TextureHandle tex = iteration.add(d.createTexture({.format = tf, .width = 4, .height = 4}));
        d.writeTexture(tex, {}, gdi::bytesOf(px));
        TextureHandle t = target(iteration, Format::RGBA32F);
        auto p = iteration.add(d.createGraphicsPipeline(
            {.vertexShader = vs,
             .fragmentShader = fs,
             .colorFormats = {Format::RGBA32F},
             .bindings = {{0, BindingType::UniformBuffer, ShaderStage::Vertex},
                          {1, BindingType::SampledTexture, ShaderStage::Fragment}}}));
        auto cmd = d.createCommandList();
        cmd->beginRenderPass({.colors = {{.texture = t}}});
        cmd->setPipeline(p);
        cmd->setUniformBuffer(0, ubo);
        cmd->setTexture(1, tex, nearest);
        cmd->draw(3);
        cmd->endRenderPass();
        d.wait(d.submit(*cmd));
        std::vector<std::array<float, 4>> texels(kSize * kSize);
        auto decode = [&](uint8_t v, bool colour) {
            double c = v / 255.0;
            if (tf == Format::RGBA8_SRGB && colour)
                c = c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
            return float(c);
        };
        for (uint32_t y = 0; y < kSize; ++y)
            for (uint32_t x = 0; x < kSize; ++x) {
                const uint8_t* s = &px[((y / 16) * 4 + x / 16) * 4];
                texels[y * kSize + x] = {decode(s[0], true), decode(s[1], true), decode(s[2], true),
                                         decode(s[3], false)};
            }
        CaseImage ci{std::string("nearest_") + std::string(formatInfo(tf).name), d.readTexture(t),
                     Image::fromTexels(kSize, kSize, Format::RGBA32F, texels)};
        ci.absTolerance = 2e-3;
        ci.maxFractionOver = 0;
        ci.toleranceReason =
            "8-bit texels decoded to float: sRGB decode may be table-based, 2e-3 absolute";
        out.push_back(ci);
    }
    return out;
}

// Timestamp queries measure a non-zero duration around real work.
std::vector<CaseImage> timestamps(Device& d) {
    FE_CONFORMANCE_CHECK(d.info().features.timestamps, "the device reports timestamp support");
    DeviceObjects objects(d);
    TextureHandle t = target(objects, Format::RGBA8);
    TimerHandle timer = objects.add(d.createTimer());
    auto cmd = d.createCommandList();
    cmd->beginTimer(timer);
    for (int i = 0; i < 4; ++i) {
        cmd->beginRenderPass({.colors = {{.texture = t, .clear = {0.5f, 0.5f, 0.5f, 1}}}});
        cmd->endRenderPass();
    }
    cmd->endTimer(timer);
    d.wait(d.submit(*cmd));
    auto ns = d.timerNanoseconds(timer);
    FE_CONFORMANCE_CHECK(ns.has_value(), "the timer has a result after wait");
    FE_CONFORMANCE_CHECK(*ns > 0.0,
                         "the timer measured a non-zero duration around four render passes");
    CaseImage ci{"cleared", d.readTexture(t), solid(Format::RGBA8, {0.5f, 0.5f, 0.5f, 1})};
    return {ci};
}

}  // namespace

std::vector<Case> drawCases();           // DrawCases.cpp
std::vector<Case> textureCases();        // TextureCases.cpp
std::vector<Case> stateCases();          // StateCases.cpp
std::vector<Case> executionCases();      // ExecutionCases.cpp
std::vector<Case> fixedFunctionCases();  // FixedFunctionCases.cpp
std::vector<Case> pipelineCases();       // PipelineCases.cpp
std::vector<Case> samplerStateCases();   // SamplerStateCases.cpp
std::vector<Case> constantsCases();      // ConstantsCases.cpp
std::vector<Case> queryCases();          // QueryCases.cpp
std::vector<Case> regionAndViewCases();  // RegionAndViewCases.cpp
std::vector<Case> uniformBlockCases();   // UniformBlockCases.cpp
std::vector<Case> shaderSourceCases();   // ShaderSourceCases.cpp
std::vector<Case> queueCases();          // QueueCases.cpp
std::vector<Case> stageCases();          // StageCases.cpp

const std::vector<Case>& cases() {
    static const std::vector<Case> all = [] {
        std::vector<Case> v = {
            {"clear_every_format", clearEveryFormat},
            {"triangle", triangle},
            {"uniform_blend_depth", uniformBlendDepth},
            {"texture_sampling", textureSampling},
            {"timestamps", timestamps},
        };
        for (auto* group :
             {drawCases, textureCases, stateCases, executionCases, fixedFunctionCases,
              pipelineCases, samplerStateCases, constantsCases, queryCases, regionAndViewCases,
              uniformBlockCases, shaderSourceCases, queueCases, stageCases})
            for (Case& c : group()) v.push_back(std::move(c));
        return v;
    }();
    return all;
}

void checkFailed(const char* file, int line, const char* condition, const char* what) {
    const char* slash = std::strrchr(file, '/');
    throw Error(std::string(slash ? slash + 1 : file) + ":" + std::to_string(line) +
                ": check failed: " + what + " (" + condition + ")");
}

CaseResult runCase(Device& device, const Case& c) {
    CaseResult r;
    r.caseName = c.name;
    const uint32_t errorsBefore = device.validationErrorCount();
    try {
        r.images = c.run(device);
    } catch (const std::exception& e) {
        r.passed = false;
        r.message = e.what();
        return r;
    }
    for (CaseImage& ci : r.images) {
        if (ci.expected.data.empty()) continue;
        ci.diff = compareImages(ci.image, ci.expected, ci.absTolerance);
        if (!ci.passed()) {
            r.passed = false;
            r.message += ci.name + ": " + std::to_string(ci.diff->pixelsOverTolerance) + " of " +
                         std::to_string(ci.diff->pixels) + " pixels off (max error " +
                         std::to_string(ci.diff->maxAbsError) + "); ";
        }
    }
    if (device.validationErrorCount() != errorsBefore) {
        r.passed = false;
        r.message +=
            std::to_string(device.validationErrorCount() - errorsBefore) + " validation error(s)";
    }
    return r;
}

}  // namespace fe::conformance

#include "CaseSupport.h"

#include "fe/gdi/ShaderRegistry.h"

namespace fe::conformance {

using namespace gdi;

Image solid(Format f, Texel c, uint32_t w, uint32_t h) {
    return Image::fromTexels(w, h, f, std::vector<Texel>(size_t(w) * h, c));
}

Image expectImage(Format f, const std::function<Texel(uint32_t, uint32_t)>& fn, uint32_t w,
                  uint32_t h) {
    std::vector<Texel> t;
    t.reserve(size_t(w) * h);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) t.push_back(fn(x, y));
    return Image::fromTexels(w, h, f, t);
}

CaseImage exact(const std::string& name, Image image, Image expected) {
    CaseImage ci{name, std::move(image), std::move(expected)};
    ci.absTolerance = 1e-6;
    ci.maxFractionOver = 0;
    ci.toleranceReason =
        "data written and read back, or values exact in the format: no difference allowed";
    return ci;
}

CaseImage within(const std::string& name, Image image, Image expected, double absTolerance,
                 std::string reason) {
    CaseImage ci{name, std::move(image), std::move(expected)};
    ci.absTolerance = absTolerance;
    ci.maxFractionOver = 0;
    ci.toleranceReason = std::move(reason);
    return ci;
}

ShaderHandle registryShader(DeviceObjects& o, ShaderStage stage, const char* path) {
    return o.add(o.device().createShader({.stage = stage, .binary = shaders::find(path)}));
}

TextureHandle caseTarget(DeviceObjects& o, Format f) {
    return o.add(
        o.device().createTexture({.format = f,
                                  .width = kCaseSize,
                                  .height = kCaseSize,
                                  .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc}));
}

CaseImage drawn8(const std::string& name, Image image, Image expected, double steps) {
    return within(name, std::move(image), std::move(expected), steps / 255.0,
                  "values drawn into an 8-bit target: float-to-unorm rounding");
}

bool throws(const std::function<void()>& fn) {
    try {
        fn();
    } catch (const Error&) {
        return true;
    }
    return false;
}

FullscreenSampler::FullscreenSampler(Device& d, const char* fragmentShader,
                                     const SamplerDesc& samplerDesc)
    : objects(d), fragment(fragmentShader) {
    vs = objects.add(d.createShader({.stage = ShaderStage::Vertex,
                                     .binary = shaders::find("conformance/fullscreen_ubo.vert")}));
    fs = objects.add(
        d.createShader({.stage = ShaderStage::Fragment, .binary = shaders::find(fragmentShader)}));
    sampler = objects.add(d.createSampler(samplerDesc));
}

Image FullscreenSampler::draw(Device& d, TextureHandle texture, Format target,
                              std::array<float, 4> a, std::array<float, 4> b) {
    DeviceObjects drawing(d);
    PipelineHandle p = drawing.add(d.createGraphicsPipeline(
        {.vertexShader = vs,
         .fragmentShader = fs,
         .colorFormats = {target},
         .bindings = {{0, BindingType::UniformBuffer, ShaderStage::AllGraphics},
                      {1, BindingType::SampledTexture, ShaderStage::Fragment}},
         .debugName = fragment.c_str()}));
    const std::array<float, 8> params = {a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3]};
    BufferHandle ubo = drawing.add(
        d.createBuffer({.size = sizeof params, .usage = BufferUsage::Uniform}, bytesOf(params)));
    TextureHandle t =
        drawing.add(d.createTexture({.format = target,
                                     .width = kCaseSize,
                                     .height = kCaseSize,
                                     .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc}));
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = t, .clear = {0, 0, 0, 0}}}});
    cmd->setPipeline(p);
    cmd->setUniformBuffer(0, ubo);
    cmd->setTexture(1, texture, sampler);
    cmd->draw(3);
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
    Image img = d.readTexture(t);
    FE_CONFORMANCE_CHECK(img.width == kCaseSize && img.height == kCaseSize && img.format == target,
                         "readback has the target's size and format");
    return img;
}

void expectError(const std::function<void()>& fn, const std::string& text) {
    std::string got = "(no error)";
    try {
        fn();
    } catch (const gdi::Error& e) {
        got = e.what();
    }
    FE_CONFORMANCE_CHECK(got.find(text) != std::string::npos,
                         ("expected \"" + text + "\", got \"" + got + "\"").c_str());
}

QuadConstants pixelQuad(uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1, Texel color) {
    QuadConstants q{};
    const auto ndc = [](uint32_t p) { return -1.0f + 2.0f * float(p) / float(kCaseSize); };
    q.rect[0] = ndc(x0), q.rect[1] = ndc(y0), q.rect[2] = ndc(x1), q.rect[3] = ndc(y1);
    std::copy(color.begin(), color.end(), q.color);
    return q;
}

}  // namespace fe::conformance

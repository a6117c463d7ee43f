// Conformance cases for draws, fixed-function state, compute and copies.
#include <array>
#include <cmath>
#include <algorithm>
#include <cstring>

#include "CaseSupport.h"
#include "fe/gdi/Backend.h"
#include "Conformance.h"
#include "fe/gdi/DeviceObjects.h"
#include "fe/gdi/ShaderRegistry.h"

namespace fe::conformance {

using namespace gdi;

namespace {

constexpr uint32_t kSize = 64;
using Texel = std::array<float, 4>;

struct Vertex {
    float x, y;
    float r, g, b, a;
};

// Cases own what they create through a DeviceObjects (CaseSupport.h says why).
TextureHandle colorTarget(DeviceObjects& objects, Format f = Format::RGBA8) {
    return objects.add(objects.device().createTexture(
        {.format = f,
         .width = kSize,
         .height = kSize,
         .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc | TextureUsage::Sampled}));
}

// Coverage of a triangle at pixel centres: >0 inside, <0 outside, ~0 on an edge.
double insideness(const float* v, double px, double py) {
    double ax = v[0], ay = v[1], bx = v[2], by = v[3], cx = v[4], cy = v[5];
    double den = (by - cy) * (ax - cx) + (cx - bx) * (ay - cy);
    double l0 = ((by - cy) * (px - cx) + (cx - bx) * (py - cy)) / den;
    double l1 = ((cy - ay) * (px - cx) + (ax - cx) * (py - cy)) / den;
    return std::min({l0, l1, 1 - l0 - l1});
}

// Expected image: listed triangles in their colour (later ones on top), background elsewhere;
// pixels on an edge take the rendered value (coverage rules are the API's, not ours).
Image expectTriangles(const Image& rendered,
                      const std::vector<std::pair<std::array<float, 6>, Texel>>& tris,
                      Texel background) {
    std::vector<Texel> t(kSize * kSize, background);
    for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x) {
            double px = (x + 0.5) / kSize * 2 - 1, py = (y + 0.5) / kSize * 2 - 1;
            for (const auto& [v, c] : tris) {
                double m = insideness(v.data(), px, py);
                if (std::abs(m) < 0.03)
                    t[y * kSize + x] = rendered.texel(x, y);
                else if (m > 0)
                    t[y * kSize + x] = c;
            }
        }
    return Image::fromTexels(kSize, kSize, rendered.format, t);
}

struct VertexColorPipeline {
    DeviceObjects objects;
    ShaderHandle vs, fs;
    GraphicsPipelineDesc desc;
    explicit VertexColorPipeline(Device& d) : objects(d) {
        vs =
            objects.add(d.createShader({.stage = ShaderStage::Vertex,
                                        .binary = shaders::find("conformance/vertex_color.vert")}));
        fs = objects.add(d.createShader(
            {.stage = ShaderStage::Fragment, .binary = shaders::find("conformance/color.frag")}));
        desc = {
            .vertexShader = vs,
            .fragmentShader = fs,
            .vertexBuffers =
                {{.stride = sizeof(Vertex),
                  .attributes = {{0, VertexFormat::Float2, 0}, {1, VertexFormat::Float4, 8}}},
                 {.stride = 8, .perInstance = true, .attributes = {{2, VertexFormat::Float2, 0}}}},
            .colorFormats = {Format::RGBA8}};
    }
};

std::vector<CaseImage> cullingWinding(Device& d) {
    VertexColorPipeline vc(d);
    DeviceObjects objects(d);
    // Left: counter-clockwise on screen (y down); right: clockwise.
    const std::array<float, 6> ccw = {-0.8f, 0.8f, -0.2f, 0.8f, -0.5f, -0.8f};
    const std::array<float, 6> cw = {0.2f, 0.8f, 0.5f, -0.8f, 0.8f, 0.8f};
    std::vector<Vertex> v;
    for (int i = 0; i < 3; ++i) v.push_back({ccw[i * 2], ccw[i * 2 + 1], 1, 0, 0, 1});
    for (int i = 0; i < 3; ++i) v.push_back({cw[i * 2], cw[i * 2 + 1], 0, 1, 0, 1});
    BufferHandle vb = objects.add(d.createBuffer(
        {.size = v.size() * sizeof(Vertex), .usage = BufferUsage::Vertex}, gdi::bytesOf(v)));
    const float zero[2] = {0, 0};
    BufferHandle ib =
        objects.add(d.createBuffer({.size = 8, .usage = BufferUsage::Vertex}, gdi::bytesOf(zero)));
    std::vector<CaseImage> out;
    struct Variant {
        const char* name;
        CullMode cull;
        FrontFace face;
        bool showCcw, showCw;
    };
    for (Variant var :
         {Variant{"back_ccw", CullMode::Back, FrontFace::CounterClockwise, true, false},
          Variant{"back_cw", CullMode::Back, FrontFace::Clockwise, false, true},
          Variant{"front_ccw", CullMode::Front, FrontFace::CounterClockwise, false, true},
          Variant{"none", CullMode::None, FrontFace::CounterClockwise, true, true}}) {
        DeviceObjects iteration(d);
        GraphicsPipelineDesc pd = vc.desc;
        pd.raster = {.cullMode = var.cull, .frontFace = var.face};
        PipelineHandle p = iteration.add(d.createGraphicsPipeline(pd));
        TextureHandle t = colorTarget(iteration);
        auto cmd = d.createCommandList();
        cmd->beginRenderPass({.colors = {{.texture = t, .clear = {0, 0, 0, 1}}}});
        cmd->setPipeline(p);
        cmd->setVertexBuffer(0, vb);
        cmd->setVertexBuffer(1, ib);
        cmd->draw(6);
        cmd->endRenderPass();
        d.wait(d.submit(*cmd));
        Image img = d.readTexture(t);
        std::vector<std::pair<std::array<float, 6>, Texel>> tris;
        if (var.showCcw) tris.push_back({ccw, {1, 0, 0, 1}});
        if (var.showCw) tris.push_back({cw, {0, 1, 0, 1}});
        out.push_back({var.name, img, expectTriangles(img, tris, {0, 0, 0, 1})});
    }
    return out;
}

std::vector<CaseImage> indexedInstancedBaseVertex(Device& d) {
    VertexColorPipeline vc(d);
    DeviceObjects objects(d);
    PipelineHandle p = objects.add(d.createGraphicsPipeline(vc.desc));
    // Four junk vertices, then a quad: indices address the quad through baseVertex = 4.
    std::vector<Vertex> v(4, Vertex{5, 5, 1, 1, 1, 1});
    for (auto [x, y] : {std::pair{-0.9f, -0.4f}, std::pair{-0.1f, -0.4f}, std::pair{-0.9f, 0.4f},
                        std::pair{-0.1f, 0.4f}})
        v.push_back({x, y, 0.25f, 0.5f, 1.0f, 1});
    BufferHandle vb = objects.add(d.createBuffer(
        {.size = v.size() * sizeof(Vertex), .usage = BufferUsage::Vertex}, gdi::bytesOf(v)));
    const float offsets[4] = {0, 0, 1.0f, 0};  // two instances: left and right half
    BufferHandle inst = objects.add(d.createBuffer(
        {.size = sizeof offsets, .usage = BufferUsage::Vertex}, gdi::bytesOf(offsets)));
    const uint16_t i16[6] = {0, 1, 2, 2, 1, 3};
    const uint32_t i32[6] = {0, 1, 2, 2, 1, 3};
    BufferHandle b16 = objects.add(
        d.createBuffer({.size = sizeof i16, .usage = BufferUsage::Index}, gdi::bytesOf(i16)));
    BufferHandle b32 = objects.add(
        d.createBuffer({.size = sizeof i32, .usage = BufferUsage::Index}, gdi::bytesOf(i32)));
    std::vector<CaseImage> out;
    for (bool wide : {false, true}) {
        DeviceObjects iteration(d);
        TextureHandle t = colorTarget(iteration);
        auto cmd = d.createCommandList();
        cmd->beginRenderPass({.colors = {{.texture = t, .clear = {0, 0, 0, 1}}}});
        cmd->setPipeline(p);
        cmd->setVertexBuffer(0, vb);
        cmd->setVertexBuffer(1, inst);
        cmd->setIndexBuffer(wide ? b32 : b16, wide ? IndexType::U32 : IndexType::U16);
        cmd->drawIndexed(6, 2, 0, 4, 0);
        cmd->endRenderPass();
        d.wait(d.submit(*cmd));
        Image img = d.readTexture(t);
        const Texel c{0.25f, 0.5f, 1.0f, 1};
        std::vector<std::pair<std::array<float, 6>, Texel>> tris;
        for (float o : {0.0f, 1.0f}) {
            tris.push_back({{-0.9f + o, -0.4f, -0.1f + o, -0.4f, -0.9f + o, 0.4f}, c});
            tris.push_back({{-0.9f + o, 0.4f, -0.1f + o, -0.4f, -0.1f + o, 0.4f}, c});
        }
        Image expected = expectTriangles(img, tris, {0, 0, 0, 1});
        // The shared diagonal is an edge of both triangles but inside the quad: fill it too.
        std::vector<Texel> e(kSize * kSize);
        for (uint32_t y = 0; y < kSize; ++y)
            for (uint32_t x = 0; x < kSize; ++x) {
                double px = (x + 0.5) / kSize * 2 - 1, py = (y + 0.5) / kSize * 2 - 1;
                bool inside = false, edge = false;
                for (float o : {0.0f, 1.0f}) {
                    double dx = std::min(px - (-0.9 + o), (-0.1 + o) - px),
                           dy = std::min(py + 0.4, 0.4 - py);
                    double m = std::min(dx, dy);
                    inside = inside || m > 0.03;
                    edge = edge || std::abs(m) <= 0.03;
                }
                e[y * kSize + x] = inside ? c : edge ? img.texel(x, y) : Texel{0, 0, 0, 1};
            }
        (void)expected;
        out.push_back({wide ? "u32_indices" : "u16_indices", img,
                       Image::fromTexels(kSize, kSize, Format::RGBA8, e)});
    }
    return out;
}

struct Params {
    float color[4];
    float depth[4];
};

std::vector<CaseImage> scissorViewportStencil(Device& d) {
    DeviceObjects objects(d);
    auto vs =
        objects.add(d.createShader({.stage = ShaderStage::Vertex,
                                    .binary = shaders::find("conformance/fullscreen_ubo.vert")}));
    auto fs = objects.add(d.createShader(
        {.stage = ShaderStage::Fragment, .binary = shaders::find("conformance/ubo_color.frag")}));
    const std::vector<BindingSlot> slots = {
        {0, BindingType::UniformBuffer, ShaderStage::AllGraphics}};
    Params params{{1, 0.5f, 0, 1}, {0.5f, 0, 0, 0}};
    BufferHandle ubo = objects.add(d.createBuffer(
        {.size = sizeof params, .usage = BufferUsage::Uniform}, gdi::bytesOf(params)));
    std::vector<CaseImage> out;
    auto rectImage = [&](Rect r, Texel inside) {
        std::vector<Texel> t(kSize * kSize, Texel{0, 0, 0, 1});
        for (uint32_t y = 0; y < kSize; ++y)
            for (uint32_t x = 0; x < kSize; ++x)
                if (int(x) >= r.x && x < r.x + r.width && int(y) >= r.y && y < r.y + r.height)
                    t[y * kSize + x] = inside;
        return Image::fromTexels(kSize, kSize, Format::RGBA8, t);
    };
    const Texel orange{1, 0.5f, 0, 1};
    {
        PipelineHandle p = objects.add(d.createGraphicsPipeline({.vertexShader = vs,
                                                                 .fragmentShader = fs,
                                                                 .colorFormats = {Format::RGBA8},
                                                                 .bindings = slots}));
        for (int mode = 0; mode < 2; ++mode) {
            TextureHandle t = colorTarget(objects);
            auto cmd = d.createCommandList();
            cmd->beginRenderPass({.colors = {{.texture = t, .clear = {0, 0, 0, 1}}}});
            cmd->setPipeline(p);
            cmd->setUniformBuffer(0, ubo);
            Rect expect;
            if (mode == 0) {
                expect = {16, 8, 20, 30};
                cmd->setScissor(expect);
            } else {
                expect = {32, 0, 32, 16};  // viewport: the full-screen triangle fills exactly it
                cmd->setViewport({32, 0, 32, 16, 0, 1});
            }
            cmd->draw(3);
            cmd->endRenderPass();
            d.wait(d.submit(*cmd));
            out.push_back(
                {mode == 0 ? "scissor" : "viewport", d.readTexture(t), rectImage(expect, orange)});
        }
    }
    {
        // Stencil: write 1 inside a scissor rect with colour writes off, then colour where == 1.
        TextureHandle t = colorTarget(objects);
        TextureHandle ds = objects.add(d.createTexture({.format = Format::D24S8,
                                                        .width = kSize,
                                                        .height = kSize,
                                                        .usage = TextureUsage::RenderTarget}));
        GraphicsPipelineDesc write{
            .vertexShader = vs,
            .fragmentShader = fs,
            .depthStencil = {.stencilTest = true,
                             .front = {.passOp = StencilOp::Replace, .compare = CompareOp::Always},
                             .back = {.passOp = StencilOp::Replace, .compare = CompareOp::Always},
                             .stencilReference = 1},
            .blend = {{.writeMask = ColorMask::None}},
            .colorFormats = {Format::RGBA8},
            .depthFormat = Format::D24S8,
            .bindings = slots};
        GraphicsPipelineDesc test = write;
        test.depthStencil.front = test.depthStencil.back = {.compare = CompareOp::Equal};
        test.blend = {};
        PipelineHandle pw = objects.add(d.createGraphicsPipeline(write)),
                       pt = objects.add(d.createGraphicsPipeline(test));
        auto cmd = d.createCommandList();
        cmd->beginRenderPass(
            {.colors = {{.texture = t, .clear = {0, 0, 0, 1}}}, .depth = {.texture = ds}});
        cmd->setPipeline(pw);
        cmd->setUniformBuffer(0, ubo);
        const Rect r{10, 20, 30, 12};
        cmd->setScissor(r);
        cmd->draw(3);
        cmd->setScissor({0, 0, kSize, kSize});
        cmd->setPipeline(pt);
        cmd->draw(3);
        cmd->endRenderPass();
        d.wait(d.submit(*cmd));
        out.push_back({"stencil_equal", d.readTexture(t), rectImage(r, orange)});
    }
    return out;
}

std::vector<CaseImage> mrtMixedFormats(Device& d) {
    DeviceObjects objects(d);
    auto vs =
        objects.add(d.createShader({.stage = ShaderStage::Vertex,
                                    .binary = shaders::find("conformance/fullscreen_ubo.vert")}));
    auto fs = objects.add(d.createShader(
        {.stage = ShaderStage::Fragment, .binary = shaders::find("conformance/mrt.frag")}));
    Params params{{0, 0, 0, 0}, {0.5f, 0, 0, 0}};
    BufferHandle ubo = objects.add(d.createBuffer(
        {.size = sizeof params, .usage = BufferUsage::Uniform}, gdi::bytesOf(params)));
    const std::vector<Format> formats = {Format::RGBA8, Format::RGBA16F, Format::RG16F,
                                         Format::R32F};
    PipelineHandle p = objects.add(d.createGraphicsPipeline(
        {.vertexShader = vs,
         .fragmentShader = fs,
         .colorFormats = formats,
         .bindings = {{0, BindingType::UniformBuffer, ShaderStage::Vertex}}}));
    std::vector<TextureHandle> ts;
    RenderPassDesc rp;
    for (Format f : formats) {
        ts.push_back(colorTarget(objects, f));
        rp.colors.push_back({.texture = ts.back()});
    }
    auto cmd = d.createCommandList();
    cmd->beginRenderPass(rp);
    cmd->setPipeline(p);
    cmd->setUniformBuffer(0, ubo);
    cmd->draw(3);
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
    const Texel values[4] = {{0.2f, 0.4f, 0.6f, 0.8f},
                             {1.5f, -2.0f, 3.25f, 1.0f},
                             {0.125f, 4.5f, 0, 1},
                             {-7.75f, 0, 0, 1}};
    std::vector<CaseImage> out;
    for (size_t i = 0; i < formats.size(); ++i) {
        CaseImage ci{"target" + std::to_string(i) + "_" + std::string(formatInfo(formats[i]).name),
                     d.readTexture(ts[i]),
                     Image::fromTexels(kSize, kSize, formats[i],
                                       std::vector<Texel>(kSize * kSize, values[i]))};
        if (formatInfo(formats[i]).isFloat) {
            ci.absTolerance = 1e-3;
            ci.maxFractionOver = 0;
            ci.toleranceReason =
                "values exact in the target's float format: 1e-3 absolute, no pixel over";
        }
        out.push_back(ci);
    }
    return out;
}

// DeviceCreateDesc::robustBufferAccess on a device of this backend: a compute shader writes 16
// floats past the end of one buffer and reads 24 past the end of another. Reads past the end
// give zero or values from inside the buffer, writes past it reach no other buffer (the
// neighbours made before and after keep their bytes), in-range results are exact. A backend
// that cannot promise it (gl-osmesa: OSMesa has no robust-access context) refuses to start.
std::vector<CaseImage> robustBufferAccess(Device& d) {
    const DeviceCreateDesc desc{.backend = d.info().backend,
                                .validation = d.info().features.validation,
                                .verbose = false,
                                .robustBufferAccess = true};
    std::unique_ptr<Device> robust;
    try {
        robust = createDevice(desc);
    } catch (const Error& e) {
        const std::string why = e.what();
        FE_CONFORMANCE_CHECK(why.find("robust buffer access is not available") != std::string::npos,
                             ("a backend without robust access says so: " + why).c_str());
        // Every Vulkan device has robustBufferAccess (the one feature Vulkan 1.0 requires).
        FE_CONFORMANCE_CHECK(d.info().backend.starts_with("gl"),
                             "only a GL backend may lack robust access");
        return {};
    }
    Device& r = *robust;
    FE_CONFORMANCE_CHECK(r.info().features.robustBufferAccess, "the started device reports it");
    DeviceObjects o(r);
    const std::vector<float> sentinel(64, 7.0f);
    auto buffer = [&](uint64_t size, std::span<const float> data = {}) {
        return o.add(
            r.createBuffer({.size = size, .usage = BufferUsage::Storage}, std::as_bytes(data)));
    };
    const BufferHandle before = buffer(256, sentinel);
    const BufferHandle written = buffer(64);
    const BufferHandle after = buffer(256, sentinel);
    std::vector<float> values(16);
    for (uint32_t i = 0; i < 16; ++i) values[i] = 100.0f + float(i);
    const BufferHandle source = buffer(64, values);
    const BufferHandle read = buffer(128);
    const BufferHandle last = buffer(256, sentinel);
    const PipelineHandle p = o.add(r.createComputePipeline(
        {.computeShader = registryShader(o, ShaderStage::Compute, "conformance/robust_access.comp"),
         .debugName = "robust access"}));
    auto cmd = r.createCommandList();
    cmd->setPipeline(p);
    cmd->setStorageBuffer(0, written);
    cmd->setStorageBuffer(1, source);
    cmd->setStorageBuffer(2, read);
    cmd->dispatch(1);
    r.wait(r.submit(*cmd));
    auto floats = [&](BufferHandle b, uint64_t size) {
        std::vector<float> f(size / 4);
        std::memcpy(f.data(), r.readBuffer(b, 0, size).data(), size);
        return f;
    };
    for (BufferHandle neighbour : {before, after, last})
        FE_CONFORMANCE_CHECK(floats(neighbour, 256) == sentinel,
                             "writes past the end reach no other buffer");
    const std::vector<float> w = floats(written, 64), got = floats(read, 128);
    for (uint32_t k = 0; k < 16; ++k)
        FE_CONFORMANCE_CHECK(w[k] == float(k + 1) || (w[k] >= 17.0f && w[k] <= 32.0f),
                             ("written[" + std::to_string(k) + "] is " + std::to_string(w[k]) +
                              ": its own value, or one written past the end that stayed inside")
                                 .c_str());
    for (uint32_t k = 0; k < 32; ++k) {
        const bool inRange = k < 8;
        const bool fromInside =
            got[k] >= 100.0f && got[k] <= 115.0f && got[k] == std::floor(got[k]);
        FE_CONFORMANCE_CHECK(inRange ? got[k] == 108.0f + float(k) : got[k] == 0.0f || fromInside,
                             ("read[" + std::to_string(k) + "] is " + std::to_string(got[k]) +
                              (inRange ? ", expected " + std::to_string(108 + k)
                                       : ": past the end, expected 0 or a value of the buffer"))
                                 .c_str());
    }
    FE_CONFORMANCE_CHECK(r.validationErrorCount() == 0,
                         "the robust device's validation stays silent");
    return {};
}

// Every format formatCaps calls storage is written by a compute shader that declares it (the
// base formats and, with DeviceFeatures::storageImageExtendedFormats, RG16F, R16F, RG32F and
// R11G11B10F), read back and compared: formatCaps and shader acceptance agree. A format said to
// be storage-capable without a shader here fails the case, so a new one cannot go untested.
std::vector<CaseImage> storageImageEveryFormat(Device& d) {
    struct StorageFormat {
        Format format;
        const char* shader;
        // 8-bit unorm: one step, since a float-to-unorm conversion may round either way (Vulkan
        // 1.3 "Conversion from Floating-Point to Normalized Fixed-Point"); x / 16 * 255 falls
        // on a tie for even x, and NVIDIA's GL rounds those down. Else exact.
        double tolerance;
    };
    const StorageFormat formats[] = {
        {Format::RGBA8, "conformance/storage_rgba8.comp", 1.0 / 255 + 1e-6},
        {Format::RGBA16F, "conformance/storage_rgba16f.comp", 0},
        {Format::RG16F, "conformance/storage_rg16f.comp", 0},
        {Format::R16F, "conformance/storage_r16f.comp", 0},
        {Format::RGBA32F, "conformance/storage_rgba32f.comp", 0},
        {Format::RG32F, "conformance/storage_rg32f.comp", 0},
        {Format::R32F, "conformance/storage_r32f.comp", 0},
        {Format::R32U, "conformance/storage_r32u.comp", 0},
        {Format::R11G11B10F, "conformance/storage_r11g11b10f.comp", 0}};
    for (uint32_t f = 1; f < uint32_t(Format::Count); ++f) {
        const bool covered =
            std::any_of(std::begin(formats), std::end(formats),
                        [&](const StorageFormat& s) { return s.format == Format(f); });
        FE_CONFORMANCE_CHECK(covered || !d.formatCaps(Format(f)).storage,
                             "every format formatCaps calls storage has a shader in this case");
    }
    FE_CONFORMANCE_CHECK(
        d.formatCaps(Format::RG16F).storage == d.info().features.storageImageExtendedFormats,
        "RG16F storage follows DeviceFeatures::storageImageExtendedFormats");
    constexpr uint32_t kSide = 16;
    std::vector<CaseImage> out;
    for (const StorageFormat& s : formats) {
        if (!d.formatCaps(s.format).storage) continue;
        DeviceObjects o(d);
        const ShaderHandle cs = registryShader(o, ShaderStage::Compute, s.shader);
        const PipelineHandle p = o.add(d.createComputePipeline(
            {.computeShader = cs,
             .bindings = {{0, BindingType::StorageTexture, ShaderStage::Compute}}}));
        const TextureHandle t =
            o.add(d.createTexture({.format = s.format,
                                   .width = kSide,
                                   .height = kSide,
                                   .usage = TextureUsage::Storage | TextureUsage::CopySrc}));
        auto cmd = d.createCommandList();
        cmd->setPipeline(p);
        cmd->setStorageTexture(0, t);
        cmd->dispatch(kSide / 8, kSide / 8);
        d.wait(d.submit(*cmd));
        const Image expected = expectImage(
            s.format,
            [&](uint32_t x, uint32_t y) -> Texel {
                if (s.format == Format::R32U) return {float(x + kSide * y + 1), 0, 0, 1};
                return {float(x) / kSide, float(y) / kSide, 0.25f, 1};
            },
            kSide, kSide);
        const std::string name(formatInfo(s.format).name);
        out.push_back(s.tolerance > 0 ? within(name, d.readTexture(t), expected, s.tolerance,
                                               "x / 16 rounded to 8 bits")
                                      : exact(name, d.readTexture(t), expected));
    }
    return out;
}

std::vector<CaseImage> computeBufferAndImage(Device& d) {
    DeviceObjects objects(d);
    auto cs = objects.add(d.createShader(
        {.stage = ShaderStage::Compute, .binary = shaders::find("conformance/fill.comp")}));
    PipelineHandle p = objects.add(d.createComputePipeline(
        {.computeShader = cs,
         .bindings = {{0, BindingType::StorageBuffer, ShaderStage::Compute},
                      {1, BindingType::StorageTexture, ShaderStage::Compute}}}));
    BufferHandle buf =
        objects.add(d.createBuffer({.size = kSize * kSize * 4, .usage = BufferUsage::Storage}));
    TextureHandle img =
        objects.add(d.createTexture({.format = Format::RGBA32F,
                                     .width = kSize,
                                     .height = kSize,
                                     .usage = TextureUsage::Storage | TextureUsage::CopySrc}));
    auto cmd = d.createCommandList();
    cmd->setPipeline(p);
    cmd->setStorageBuffer(0, buf);
    cmd->setStorageTexture(1, img);
    cmd->dispatch(kSize / 8, kSize / 8);
    d.wait(d.submit(*cmd));
    std::vector<uint8_t> bytes = d.readBuffer(buf, 0, kSize * kSize * 4);
    FE_CONFORMANCE_CHECK(bytes.size() == kSize * kSize * 4,
                         "readBuffer returns the bytes asked for");
    Image values{kSize, kSize, Format::R32U, bytes};
    std::vector<Texel> ev, ei;
    for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x) {
            ev.push_back({float(3 * (y * kSize + x) + 1), 0, 0, 1});
            ei.push_back({float(x) / 64.0f, float(y) / 64.0f, 0.5f, 1.0f});
        }
    CaseImage a{"buffer", values, Image::fromTexels(kSize, kSize, Format::R32U, ev)};
    a.absTolerance = 0;
    a.maxFractionOver = 0;
    a.toleranceReason = "integers: exact";
    CaseImage b{"image", d.readTexture(img), Image::fromTexels(kSize, kSize, Format::RGBA32F, ei)};
    b.absTolerance = 1e-6;
    b.maxFractionOver = 0;
    b.toleranceReason = "x/64 is exact in float32";
    return {a, b};
}

std::vector<CaseImage> copies(Device& d) {
    std::vector<uint8_t> pattern(kSize * kSize * 4);
    for (size_t i = 0; i < pattern.size(); ++i) pattern[i] = uint8_t((i * 37) ^ (i >> 7));
    const uint64_t bytes = pattern.size();
    DeviceObjects objects(d);
    BufferHandle src = objects.add(d.createBuffer({.size = bytes + 256})),
                 mid = objects.add(d.createBuffer({.size = bytes})),
                 dst = objects.add(d.createBuffer({.size = bytes}));
    d.writeBuffer(src, 256, gdi::bytesOf(pattern));
    TextureHandle a = objects.add(d.createTexture({.width = kSize, .height = kSize})),
                  b = objects.add(d.createTexture({.width = kSize, .height = kSize}));
    auto cmd = d.createCommandList();
    cmd->copyBufferToTexture(a, {}, src, 256);
    cmd->copyTexture(b, a);
    cmd->copyTextureToBuffer(mid, 0, b, {});
    cmd->copyBuffer(dst, 0, mid, 0, bytes);
    d.wait(d.submit(*cmd));
    Image expected{kSize, kSize, Format::RGBA8, pattern};
    std::vector<uint8_t> roundTrip = d.readBuffer(dst, 0, bytes);
    FE_CONFORMANCE_CHECK(roundTrip.size() == bytes, "readBuffer returns the bytes asked for");
    CaseImage ci{"buffer_texture_roundtrip",
                 Image{kSize, kSize, Format::RGBA8, std::move(roundTrip)}, expected};
    ci.absTolerance = 0;
    ci.maxFractionOver = 0;
    ci.toleranceReason = "copies are exact";
    CaseImage tex{"texture_after_copy", d.readTexture(b), expected};
    tex.absTolerance = 0;
    tex.maxFractionOver = 0;
    tex.toleranceReason = "copies are exact";
    return {ci, tex};
}

// ---- vertex formats, storage buffers, sampling, render-to-texture, blend modes -------------

CaseImage exactFloat(std::string name, Image img, Image expected, double tol, const char* why) {
    CaseImage ci{std::move(name), std::move(img), std::move(expected)};
    ci.absTolerance = tol;
    ci.maxFractionOver = 0;
    ci.toleranceReason = why;
    return ci;
}

Image solidImage(Format f, Texel c) {
    return Image::fromTexels(kSize, kSize, f, std::vector<Texel>(kSize * kSize, c));
}

uint16_t toHalf(float f) {  // exact for the small values used below
    Image one = Image::fromTexels(1, 1, Format::R16F, {{f, 0, 0, 1}});
    uint16_t h;
    std::memcpy(&h, one.data.data(), 2);
    return h;
}

std::vector<CaseImage> vertexFormats(Device& d) {
    DeviceObjects objects(d);
    auto vsF = objects.add(d.createShader(
        {.stage = ShaderStage::Vertex, .binary = shaders::find("conformance/vertex_attr.vert")}));
    auto vsU = objects.add(d.createShader(
        {.stage = ShaderStage::Vertex, .binary = shaders::find("conformance/vertex_uint.vert")}));
    auto fs = objects.add(d.createShader(
        {.stage = ShaderStage::Fragment, .binary = shaders::find("conformance/value.frag")}));
    std::vector<CaseImage> out;
    for (int fi = 0; fi < int(VertexFormat::Count); ++fi) {
        const VertexFormat vf = VertexFormat(fi);
        // Attribute bytes for value v = (0.25, 0.5, -0.5, 0.75) in this format, and what the
        // shader must see (missing components default to 0, 0, 0, 1).
        uint8_t attr[16] = {};
        Texel expect{0, 0, 0, 1};
        const float v[4] = {0.25f, 0.5f, -0.5f, 0.75f};
        const uint32_t n = vertexFormatInfo(vf).components;
        switch (vf) {
            case VertexFormat::Float:
            case VertexFormat::Float2:
            case VertexFormat::Float3:
            case VertexFormat::Float4:
                std::memcpy(attr, v, n * 4);
                for (uint32_t c = 0; c < n; ++c) expect[c] = v[c];
                break;
            case VertexFormat::Half2:
            case VertexFormat::Half4:
                for (uint32_t c = 0; c < n; ++c) {
                    uint16_t h = toHalf(v[c]);
                    std::memcpy(attr + 2 * c, &h, 2);
                    expect[c] = v[c];
                }
                break;
            case VertexFormat::UNorm8x4:
                for (int c = 0; c < 4; ++c) {
                    attr[c] = uint8_t(std::lround(std::fabs(v[c]) * 255));
                    expect[c] = attr[c] / 255.0f;
                }
                break;
            case VertexFormat::SNorm8x4:
                for (int c = 0; c < 4; ++c) {
                    int8_t q = int8_t(std::lround(v[c] * 127));
                    std::memcpy(attr + c, &q, 1);
                    expect[c] = std::max(q / 127.0f, -1.0f);
                }
                break;
            case VertexFormat::UNorm16x2:
                for (int c = 0; c < 2; ++c) {
                    uint16_t q = uint16_t(std::lround(std::fabs(v[c]) * 65535));
                    std::memcpy(attr + 2 * c, &q, 2);
                    expect[c] = q / 65535.0f;
                }
                break;
            case VertexFormat::SNorm16x2:
                for (int c = 0; c < 2; ++c) {
                    int16_t q = int16_t(std::lround(-v[c] * 32767));
                    std::memcpy(attr + 2 * c, &q, 2);
                    expect[c] = q / 32767.0f;
                }
                break;
            case VertexFormat::UInt32: {
                uint32_t q = 625;
                std::memcpy(attr, &q, 4);
                expect = {0.625f, 0, 0, 1};
                break;
            }
            default:
                break;
        }
        const uint32_t stride = 8 + 16;
        std::vector<uint8_t> vb(3 * stride);
        const float pos[6] = {-1, -1, 3, -1, -1, 3};
        for (int i = 0; i < 3; ++i) {
            std::memcpy(&vb[i * stride], &pos[i * 2], 8);
            std::memcpy(&vb[i * stride + 8], attr, 16);
        }
        DeviceObjects iteration(d);
        BufferHandle b = iteration.add(
            d.createBuffer({.size = vb.size(), .usage = BufferUsage::Vertex}, gdi::bytesOf(vb)));
        PipelineHandle p = iteration.add(d.createGraphicsPipeline(
            {.vertexShader = vf == VertexFormat::UInt32 ? vsU : vsF,
             .fragmentShader = fs,
             .vertexBuffers = {{.stride = stride,
                                .attributes = {{0, VertexFormat::Float2, 0}, {1, vf, 8}}}},
             .colorFormats = {Format::RGBA32F}}));
        TextureHandle t = colorTarget(iteration, Format::RGBA32F);
        auto cmd = d.createCommandList();
        cmd->beginRenderPass({.colors = {{.texture = t}}});
        cmd->setPipeline(p);
        cmd->setVertexBuffer(0, b);
        cmd->draw(3);
        cmd->endRenderPass();
        d.wait(d.submit(*cmd));
        out.push_back(exactFloat(std::string(vertexFormatInfo(vf).name), d.readTexture(t),
                                 solidImage(Format::RGBA32F, expect), 1e-5,
                                 "attribute decode is exact up to float rounding"));
    }
    return out;
}

// Full-screen helper for fragment-only cases: fullscreen_ubo.vert + `fragment`.
struct FullScreen {
    DeviceObjects objects;
    ShaderHandle vs, fs;
    BufferHandle ubo;
    FullScreen(Device& d, const char* fragment, Params params) : objects(d) {
        vs = objects.add(
            d.createShader({.stage = ShaderStage::Vertex,
                            .binary = shaders::find("conformance/fullscreen_ubo.vert")}));
        fs = objects.add(
            d.createShader({.stage = ShaderStage::Fragment, .binary = shaders::find(fragment)}));
        ubo = objects.add(d.createBuffer({.size = sizeof(Params), .usage = BufferUsage::Uniform},
                                         gdi::bytesOf(params)));
    }
};

std::vector<CaseImage> storageBufferInFragment(Device& d) {
    FullScreen fsq(d, "conformance/ssbo_read.frag", {{0, 0, 0, 0}, {0.5f, 0, 0, 0}});
    DeviceObjects objects(d);
    const float colors[16] = {1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1, 0.5f, 0.25f, 0.125f, 1};
    BufferHandle ssbo = objects.add(d.createBuffer(
        {.size = sizeof colors, .usage = BufferUsage::Storage}, gdi::bytesOf(colors)));
    PipelineHandle p = objects.add(d.createGraphicsPipeline(
        {.vertexShader = fsq.vs,
         .fragmentShader = fsq.fs,
         .colorFormats = {Format::RGBA32F},
         .bindings = {{0, BindingType::UniformBuffer, ShaderStage::Vertex},
                      {2, BindingType::StorageBuffer, ShaderStage::Fragment}}}));
    TextureHandle t = colorTarget(objects, Format::RGBA32F);
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = t}}});
    cmd->setPipeline(p);
    cmd->setUniformBuffer(0, fsq.ubo);
    cmd->setStorageBuffer(2, ssbo);
    cmd->draw(3);
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
    std::vector<Texel> e;
    for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x)
            e.push_back(
                {colors[(x / 16) * 4], colors[(x / 16) * 4 + 1], colors[(x / 16) * 4 + 2], 1});
    CaseImage ci =
        exactFloat("columns", d.readTexture(t), Image::fromTexels(kSize, kSize, Format::RGBA32F, e),
                   1e-6, "copied floats: exact");
    return {ci};
}

double wrapCoord(double u, AddressMode m) {
    if (m == AddressMode::ClampToEdge) return std::clamp(u, 0.0, 1.0 - 1e-9);
    if (m == AddressMode::MirroredRepeat) {
        double f = u - 2.0 * std::floor(u / 2.0);
        return f >= 1.0 ? 2.0 - f - 1e-9 : f;
    }
    return u - std::floor(u);
}

std::vector<CaseImage> samplingModes(Device& d) {
    std::vector<CaseImage> out;
    // A 4x4 texture of distinct texels, sampled with uv in [-1, 2) so wrapping shows.
    std::vector<uint8_t> px(4 * 4 * 4);
    for (int i = 0; i < 16; ++i) {
        px[i * 4] = uint8_t(i * 17);
        px[i * 4 + 1] = uint8_t(255 - i * 13);
        px[i * 4 + 2] = uint8_t((i * 71) % 256);
        px[i * 4 + 3] = 255;
    }
    DeviceObjects objects(d);
    TextureHandle tex =
        objects.add(d.createTexture({.format = Format::RGBA8, .width = 4, .height = 4}));
    d.writeTexture(tex, {}, gdi::bytesOf(px));
    for (AddressMode mode :
         {AddressMode::Repeat, AddressMode::MirroredRepeat, AddressMode::ClampToEdge}) {
        // uv = pixel/64 * 3 - 1: texel centres of the magnified texture land on pixel centres.
        FullScreen fsq(d, "conformance/textured_uv.frag", {{3, 3, -1, -1}, {0.5f, 0, 0, 0}});
        DeviceObjects iteration(d);
        SamplerHandle smp = iteration.add(d.createSampler({.minFilter = Filter::Nearest,
                                                           .magFilter = Filter::Nearest,
                                                           .addressU = mode,
                                                           .addressV = mode}));
        PipelineHandle p = iteration.add(d.createGraphicsPipeline(
            {.vertexShader = fsq.vs,
             .fragmentShader = fsq.fs,
             .colorFormats = {Format::RGBA32F},
             .bindings = {{0, BindingType::UniformBuffer, ShaderStage::AllGraphics},
                          {1, BindingType::SampledTexture, ShaderStage::Fragment}}}));
        TextureHandle t = colorTarget(iteration, Format::RGBA32F);
        auto cmd = d.createCommandList();
        cmd->beginRenderPass({.colors = {{.texture = t}}});
        cmd->setPipeline(p);
        cmd->setUniformBuffer(0, fsq.ubo);
        cmd->setTexture(1, tex, smp);
        cmd->draw(3);
        cmd->endRenderPass();
        d.wait(d.submit(*cmd));
        Image img = d.readTexture(t);
        std::vector<Texel> e;
        for (uint32_t y = 0; y < kSize; ++y)
            for (uint32_t x = 0; x < kSize; ++x) {
                double u = (x + 0.5) / 64.0 * 3 - 1, v = (y + 0.5) / 64.0 * 3 - 1;
                double fu = (u * 4) - std::floor(u * 4), fv = (v * 4) - std::floor(v * 4);
                // Texel boundaries: the rounding of the hardware decides; take the rendered value.
                if (std::min({fu, 1 - fu, fv, 1 - fv}) < 0.02) {
                    e.push_back(img.texel(x, y));
                    continue;
                }
                int tx = std::min(3, int(wrapCoord(u, mode) * 4)),
                    ty = std::min(3, int(wrapCoord(v, mode) * 4));
                const uint8_t* s = &px[(ty * 4 + tx) * 4];
                e.push_back({s[0] / 255.0f, s[1] / 255.0f, s[2] / 255.0f, 1});
            }
        const char* name = mode == AddressMode::Repeat           ? "nearest_repeat"
                           : mode == AddressMode::MirroredRepeat ? "nearest_mirrored"
                                                                 : "nearest_clamp";
        out.push_back(exactFloat(name, img, Image::fromTexels(kSize, kSize, Format::RGBA32F, e),
                                 1e-3, "8-bit texels: 1e-3 absolute"));
    }
    // Linear filtering: a 2x2 texture magnified over the target with clamping: bilinear ramps.
    {
        FullScreen fsq(d, "conformance/textured_uv.frag", {{1, 1, 0, 0}, {0.5f, 0, 0, 0}});
        DeviceObjects linear(d);
        const uint8_t q[16] = {0, 0, 0, 255, 255, 0, 0, 255, 0, 255, 0, 255, 255, 255, 255, 255};
        TextureHandle t2 =
            linear.add(d.createTexture({.format = Format::RGBA8, .width = 2, .height = 2}));
        d.writeTexture(t2, {}, gdi::bytesOf(q));
        SamplerHandle smp = linear.add(d.createSampler(
            {.addressU = AddressMode::ClampToEdge, .addressV = AddressMode::ClampToEdge}));
        PipelineHandle p = linear.add(d.createGraphicsPipeline(
            {.vertexShader = fsq.vs,
             .fragmentShader = fsq.fs,
             .colorFormats = {Format::RGBA32F},
             .bindings = {{0, BindingType::UniformBuffer, ShaderStage::AllGraphics},
                          {1, BindingType::SampledTexture, ShaderStage::Fragment}}}));
        TextureHandle t = colorTarget(linear, Format::RGBA32F);
        auto cmd = d.createCommandList();
        cmd->beginRenderPass({.colors = {{.texture = t}}});
        cmd->setPipeline(p);
        cmd->setUniformBuffer(0, fsq.ubo);
        cmd->setTexture(1, t2, smp);
        cmd->draw(3);
        cmd->endRenderPass();
        d.wait(d.submit(*cmd));
        std::vector<Texel> e;
        for (uint32_t y = 0; y < kSize; ++y)
            for (uint32_t x = 0; x < kSize; ++x) {
                double a = std::clamp((x + 0.5) / 64.0 * 2 - 0.5, 0.0, 1.0),
                       b = std::clamp((y + 0.5) / 64.0 * 2 - 0.5, 0.0, 1.0);
                double r = (1 - b) * a + b * a, g = b,
                       bl = a * b;  // corners: (0,0,0) (1,0,0) / (0,1,0) (1,1,1)
                e.push_back({float(r), float(g), float(bl), 1});
            }
        out.push_back(exactFloat(
            "linear_clamp", d.readTexture(t), Image::fromTexels(kSize, kSize, Format::RGBA32F, e),
            0.01,
            "filter weights have limited sub-texel precision (8 bits on llvmpipe): 0.01 absolute"));
    }
    // Mipmaps: each level uploaded with its own colour, chosen by an explicit level of detail.
    {
        DeviceObjects mips(d);
        TextureHandle mip = mips.add(
            d.createTexture({.format = Format::RGBA8, .width = 8, .height = 8, .mipLevels = 4}));
        const Texel levels[4] = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 0, 1}};
        for (uint32_t l = 0; l < 4; ++l) {
            uint32_t s = 8 >> l;
            Image lv = Image::fromTexels(s, s, Format::RGBA8, std::vector<Texel>(s * s, levels[l]));
            d.writeTexture(mip, {.mipLevel = l}, gdi::bytesOf(lv.data));
        }
        SamplerHandle smp = mips.add(d.createSampler({.mipFilter = MipFilter::Nearest}));
        for (uint32_t l = 0; l < 4; ++l) {
            FullScreen fsq(d, "conformance/textured_uv.frag",
                           {{1, 1, 0, 0}, {0.5f, float(l), 0, 0}});
            DeviceObjects level(d);
            PipelineHandle p = level.add(d.createGraphicsPipeline(
                {.vertexShader = fsq.vs,
                 .fragmentShader = fsq.fs,
                 .colorFormats = {Format::RGBA32F},
                 .bindings = {{0, BindingType::UniformBuffer, ShaderStage::AllGraphics},
                              {1, BindingType::SampledTexture, ShaderStage::Fragment}}}));
            TextureHandle t = colorTarget(level, Format::RGBA32F);
            auto cmd = d.createCommandList();
            cmd->beginRenderPass({.colors = {{.texture = t}}});
            cmd->setPipeline(p);
            cmd->setUniformBuffer(0, fsq.ubo);
            cmd->setTexture(1, mip, smp);
            cmd->draw(3);
            cmd->endRenderPass();
            d.wait(d.submit(*cmd));
            out.push_back(exactFloat("mip_level_" + std::to_string(l), d.readTexture(t),
                                     solidImage(Format::RGBA32F, levels[l]), 1e-3,
                                     "solid 8-bit level: 1e-3 absolute"));
        }
    }
    return out;
}

std::vector<CaseImage> renderToTextureThenSample(Device& d) {
    // Pass 1: a triangle into A. Pass 2: A sampled (nearest, 1:1) into B. B must equal A.
    FullScreen fsq(d, "conformance/textured_uv.frag", {{1, 1, 0, 0}, {0.5f, 0, 0, 0}});
    DeviceObjects objects(d);
    TextureHandle a = colorTarget(objects), b = colorTarget(objects);
    auto vs = objects.add(d.createShader(
        {.stage = ShaderStage::Vertex, .binary = shaders::find("conformance/triangle.vert")}));
    auto fs = objects.add(d.createShader(
        {.stage = ShaderStage::Fragment, .binary = shaders::find("conformance/color.frag")}));
    PipelineHandle tri = objects.add(d.createGraphicsPipeline(
        {.vertexShader = vs, .fragmentShader = fs, .colorFormats = {Format::RGBA8}}));
    SamplerHandle smp =
        objects.add(d.createSampler({.minFilter = Filter::Nearest, .magFilter = Filter::Nearest}));
    PipelineHandle copy = objects.add(d.createGraphicsPipeline(
        {.vertexShader = fsq.vs,
         .fragmentShader = fsq.fs,
         .colorFormats = {Format::RGBA8},
         .bindings = {{0, BindingType::UniformBuffer, ShaderStage::AllGraphics},
                      {1, BindingType::SampledTexture, ShaderStage::Fragment}}}));
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = a, .clear = {0.1f, 0.2f, 0.3f, 1}}}});
    cmd->setPipeline(tri);
    cmd->draw(3);
    cmd->endRenderPass();
    cmd->beginRenderPass({.colors = {{.texture = b}}});
    cmd->setPipeline(copy);
    cmd->setUniformBuffer(0, fsq.ubo);
    cmd->setTexture(1, a, smp);
    cmd->draw(3);
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
    CaseImage ci{"sampled_copy", d.readTexture(b), d.readTexture(a)};
    ci.absTolerance = 0;
    ci.maxFractionOver = 0;
    ci.toleranceReason = "nearest 1:1 sampling of an 8-bit target is exact";
    return {ci};
}

std::vector<CaseImage> blendModes(Device& d) {
    std::vector<CaseImage> out;
    const float dst[4] = {0.5f, 0.25f, 1.0f, 1.0f};
    const Texel src{0.25f, 0.75f, 0.5f, 0.25f};
    struct Mode {
        const char* name;
        BlendTargetState state;
        Texel expect;
    };
    const Mode modes[] = {
        {"alpha",
         {.enable = true,
          .srcColor = BlendFactor::SrcAlpha,
          .dstColor = BlendFactor::OneMinusSrcAlpha,
          .srcAlpha = BlendFactor::One,
          .dstAlpha = BlendFactor::Zero},
         {0.25f * 0.25f + 0.5f * 0.75f, 0.75f * 0.25f + 0.25f * 0.75f, 0.5f * 0.25f + 1.0f * 0.75f,
          0.25f}},
        {"min",
         {.enable = true, .colorOp = BlendOp::Min, .alphaOp = BlendOp::Min},
         {0.25f, 0.25f, 0.5f, 0.25f}},
        {"max",
         {.enable = true, .colorOp = BlendOp::Max, .alphaOp = BlendOp::Max},
         {0.5f, 0.75f, 1.0f, 1.0f}},
        {"reverse_subtract",
         {.enable = true,
          .srcColor = BlendFactor::One,
          .dstColor = BlendFactor::One,
          .colorOp = BlendOp::ReverseSubtract,
          .srcAlpha = BlendFactor::One,
          .dstAlpha = BlendFactor::Zero},
         {0.25f, -0.5f, 0.5f, 0.25f}},
    };
    for (const Mode& m : modes) {
        FullScreen fsq(d, "conformance/ubo_color.frag",
                       {{src[0], src[1], src[2], src[3]}, {0.5f, 0, 0, 0}});
        DeviceObjects iteration(d);
        PipelineHandle p = iteration.add(d.createGraphicsPipeline(
            {.vertexShader = fsq.vs,
             .fragmentShader = fsq.fs,
             .blend = {m.state},
             .colorFormats = {Format::RGBA16F},
             .bindings = {{0, BindingType::UniformBuffer, ShaderStage::AllGraphics}}}));
        TextureHandle t = colorTarget(iteration, Format::RGBA16F);
        auto cmd = d.createCommandList();
        cmd->beginRenderPass(
            {.colors = {{.texture = t, .clear = {dst[0], dst[1], dst[2], dst[3]}}}});
        cmd->setPipeline(p);
        cmd->setUniformBuffer(0, fsq.ubo);
        cmd->draw(3);
        cmd->endRenderPass();
        d.wait(d.submit(*cmd));
        out.push_back(exactFloat(m.name, d.readTexture(t), solidImage(Format::RGBA16F, m.expect),
                                 2e-3, "half-float target: 2e-3 absolute"));
    }
    return out;
}

}  // namespace

std::vector<Case> drawCases() {
    return {
        {"culling_winding", cullingWinding},
        {"indexed_instanced_base_vertex", indexedInstancedBaseVertex},
        {"scissor_viewport_stencil", scissorViewportStencil},
        {"mrt_mixed_formats", mrtMixedFormats},
        {"compute_buffer_and_image", computeBufferAndImage},
        {"storage_image_every_format", storageImageEveryFormat},
        {"robust_buffer_access", robustBufferAccess},
        {"copies", copies},
        {"vertex_formats", vertexFormats},
        {"storage_buffer_in_fragment", storageBufferInFragment},
        {"sampling_modes", samplingModes},
        {"render_to_texture_then_sample", renderToTextureThenSample},
        {"blend_modes", blendModes},
    };
}

}  // namespace fe::conformance

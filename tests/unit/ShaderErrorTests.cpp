// Shaders and pipelines: damaged or out-of-bounds SPIR-V, pipelines checked against their
// shaders' reflection, device limits on storage textures.
#include <chrono>
#include <mutex>

#include "DeviceErrors.h"
#include "fe/gdi/ShaderCompiler.h"

using namespace fe::gdi;
using fe::testing::errorOf;

TEST_P(DeviceErrors, BrokenShaderBinary) {
    const uint32_t garbage[] = {0xdeadbeef, 1, 2, 3, 4, 5};
    ShaderBinary bin{"garbage.frag", garbage, garbage};
    EXPECT_NE(errorOf([&] {
                  device->createShader({.stage = ShaderStage::Fragment, .binary = bin});
              }).find("garbage.frag"),
              std::string::npos);
    ShaderBinary empty{"empty.frag", {}, {}};
    EXPECT_NE(errorOf([&] {
                  device->createShader({.stage = ShaderStage::Fragment, .binary = empty});
              }).find("empty.frag"),
              std::string::npos);
}

// Pipelines are checked against their shaders' reflection, with the same gdi::Error on every
// backend before any native call: bindings the list omits or mistypes, vertex inputs without
// attributes or of another scalar kind, fragment outputs of the wrong kind for their target,
// and at setPipeline attachment formats that are not the pass's. An empty binding list takes
// the shaders' own.
TEST_P(DeviceErrors, PipelinesAreCheckedAgainstTheirShaders) {
    Device& d = *device;
    auto has = [](const std::string& error, const char* text) {
        return error.find(text) != std::string::npos
                   ? ::testing::AssertionSuccess()
                   : ::testing::AssertionFailure() << "got: " << error;
    };
    auto shader = [&](ShaderStage stage, const char* path) {
        return d.createShader({.stage = stage, .binary = fe::shaders::find(path)});
    };
    auto uboVs = shader(ShaderStage::Vertex, "conformance/fullscreen_ubo.vert");
    auto uboFs = shader(ShaderStage::Fragment, "conformance/ubo_color.frag");
    auto uintVs = shader(ShaderStage::Vertex, "conformance/vertex_uint.vert");
    auto valueFs = shader(ShaderStage::Fragment, "conformance/value.frag");
    auto err = [&](const GraphicsPipelineDesc& desc) {
        return errorOf([&] { d.destroy(d.createGraphicsPipeline(desc)); });
    };
    const GraphicsPipelineDesc ubo{.vertexShader = uboVs,
                                   .fragmentShader = uboFs,
                                   .colorFormats = {Format::RGBA8},
                                   .debugName = "ubo"};
    GraphicsPipelineDesc omitted = ubo;
    omitted.bindings = {{1, BindingType::UniformBuffer, ShaderStage::AllGraphics}};
    EXPECT_TRUE(has(
        err(omitted),
        "pipeline 'ubo': binding slot 0 (uniform buffer) is used by the vertex and fragment shader "
        "but missing from the pipeline's bindings"));
    GraphicsPipelineDesc mistyped = ubo;
    mistyped.bindings = {{0, BindingType::StorageBuffer, ShaderStage::AllGraphics}};
    EXPECT_TRUE(has(
        err(mistyped),
        "binding slot 0 is declared a storage buffer, but the vertex and fragment shader uses a uniform buffer"));
    GraphicsPipelineDesc stageless = ubo;
    stageless.bindings = {{0, BindingType::UniformBuffer, ShaderStage::Fragment}};
    EXPECT_TRUE(has(
        err(stageless),
        "binding slot 0 is used by the vertex and fragment shader, which its declared stages leave out"));
    const VertexBufferLayout uintLayout{
        .stride = 12,
        .attributes = {{.location = 0, .format = VertexFormat::Float2},
                       {.location = 1, .format = VertexFormat::UInt32, .offset = 8}}};
    GraphicsPipelineDesc noAttribute{
        .vertexShader = uintVs,
        .fragmentShader = valueFs,
        .vertexBuffers = {{.stride = 8,
                           .attributes = {{.location = 0, .format = VertexFormat::Float2}}}},
        .colorFormats = {Format::RGBA8},
        .debugName = "attrs"};
    EXPECT_TRUE(has(
        err(noAttribute),
        "pipeline 'attrs': vertex shader input 'inValue' (location 1) has no attribute in the vertex layout"));
    GraphicsPipelineDesc wrongKind = noAttribute;
    wrongKind.vertexBuffers = {
        {.stride = 12,
         .attributes = {{.location = 0, .format = VertexFormat::Float2},
                        {.location = 1, .format = VertexFormat::Float, .offset = 8}}}};
    EXPECT_TRUE(has(
        err(wrongKind),
        "vertex shader input 'inValue' (location 1) is uint, its attribute's format gives float"));
    GraphicsPipelineDesc intTarget = noAttribute;
    intTarget.vertexBuffers = {uintLayout};
    intTarget.colorFormats = {Format::R32U};
    EXPECT_TRUE(
        has(err(intTarget),
            "fragment output 'outColor' (location 0) is float, colour target 0 is R32U (uint)"));

    // Bindings taken from the shaders: the pipeline needs slot 0 bound, like a declared one.
    auto derived = d.createGraphicsPipeline(ubo);
    auto t = d.createTexture({.width = 8, .height = 8, .usage = TextureUsage::RenderTarget});
    auto t16 = d.createTexture(
        {.format = Format::RGBA16F, .width = 8, .height = 8, .usage = TextureUsage::RenderTarget});
    auto depth = d.createTexture(
        {.format = Format::D32F, .width = 8, .height = 8, .usage = TextureUsage::RenderTarget});
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = t}}});
    cmd->setPipeline(derived);
    EXPECT_TRUE(has(errorOf([&] { cmd->draw(3); }), "missing binding for slot(s) 0"));
    cmd->endRenderPass();
    cmd->beginRenderPass({.colors = {{.texture = t16}}});
    EXPECT_TRUE(has(
        errorOf([&] { cmd->setPipeline(derived); }),
        "setPipeline: pipeline 'ubo': renders to colour [RGBA8], depth none but the render pass has colour [RGBA16F], depth none"));
    cmd->endRenderPass();
    cmd->beginRenderPass({.colors = {{.texture = t}}, .depth = {.texture = depth}});
    EXPECT_TRUE(has(errorOf([&] { cmd->setPipeline(derived); }),
                    "but the render pass has colour [RGBA8], depth D32F"));
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
    EXPECT_EQ(d.validationErrorCount(), 0u);
    d.destroy(derived);
    for (auto tex : {t, t16, depth}) d.destroy(tex);
    for (auto sh : {uboVs, uboFs, uintVs, valueFs}) d.destroy(sh);
}

TEST_P(DamagedSpirv, IsAnErrorNeverACrash) {
    const ShaderBinary& good = fe::shaders::find("conformance/triangle.vert");
    std::mt19937 random(26);
    uint32_t refused = 0;
    for (int i = 0; i < 300; ++i) {
        std::vector<uint32_t> vulkan(good.vulkan.begin(), good.vulkan.end()),
            opengl(good.opengl.begin(), good.opengl.end());
        for (auto* words : {&vulkan, &opengl}) {
            // Header words kept (a wrong magic is refused early anyway): damage the instructions.
            for (int k = 0; k < 1 + i % 4; ++k) {
                const size_t at = 5 + random() % (words->size() - 5);
                (*words)[at] =
                    (i % 3 == 0) ? uint32_t(random()) : (*words)[at] ^ (1u << (random() % 32));
            }
        }
        const std::string e = fe::testing::errorOf([&] {
            const ShaderHandle s = device->createShader(
                {.stage = ShaderStage::Vertex,
                 .binary = {.name = "damaged", .vulkan = vulkan, .opengl = opengl}});
            device->destroy(s);
        });
        if (e != "(no error)") {
            ++refused;
            EXPECT_NE(e.find("shader 'damaged'"), std::string::npos) << e;
        }
    }
    EXPECT_GT(refused, 250u);
}

// A damaged binary is the same Error on every backend: each validates both halves of the binary,
// the Vulkan one first, so which backend reads which half does not change the message.
TEST(DamagedSpirvAcrossBackends, SameErrorOnEveryBackend) {
    std::vector<std::unique_ptr<Device>> devices;
    for (const char* name : {"vulkan", "gl-egl", "gl-osmesa"})
        if (BackendProbe p = probeBackend(name, true); p.available)
            devices.push_back(std::move(p.device));
    if (devices.size() < 2) GTEST_SKIP() << "fewer than two backends";
    const ShaderBinary& good = fe::shaders::find("conformance/ubo_color.frag");
    std::mt19937 random(27);
    uint32_t refused = 0;
    for (int i = 0; i < 200; ++i) {
        std::vector<uint32_t> vulkan(good.vulkan.begin(), good.vulkan.end()),
            opengl(good.opengl.begin(), good.opengl.end());
        auto* words =
            (i % 2) ? &vulkan : &opengl;  // one half damaged: the other backend must notice too
        const size_t at = 5 + random() % (words->size() - 5);
        (*words)[at] ^= 1u << (random() % 32);
        std::vector<std::string> errors;
        for (const auto& device : devices)
            errors.push_back(errorOf([&] {
                device->destroy(device->createShader(
                    {.stage = ShaderStage::Fragment,
                     .binary = {.name = "damaged", .vulkan = vulkan, .opengl = opengl}}));
            }));
        refused += errors[0] != "(no error)";
        for (size_t d = 1; d < devices.size(); ++d)
            EXPECT_EQ(errors[d], errors[0]) << "damage " << i << ": " << devices[d]->info().backend
                                            << " vs " << devices[0]->info().backend;
    }
    EXPECT_GT(refused, 100u);
    for (const auto& device : devices) EXPECT_EQ(device->validationErrorCount(), 0u);
}

// An output at a location beyond the 16 every device has is refused before the driver sees it
// (the Vulkan validation layer reported it, found by the capture-file fuzzer).
TEST_P(DamagedSpirv, LocationsBeyondSixteenAreRefused) {
    const ShaderBinary& good = fe::shaders::find("conformance/triangle.vert");
    auto patched = [](std::span<const uint32_t> words) {
        std::vector<uint32_t> w(words.begin(), words.end());
        // OpDecorate (opcode 71): word count 4, target, Location (30), the location.
        for (size_t i = 5; i < w.size(); i += std::max(1u, w[i] >> 16))
            if ((w[i] & 0xffffu) == 71 && (w[i] >> 16) == 4 && w[i + 2] == 30) w[i + 3] = 40;
        return w;
    };
    const std::vector<uint32_t> vulkan = patched(good.vulkan), opengl = patched(good.opengl);
    ASSERT_NE(vulkan, std::vector<uint32_t>(good.vulkan.begin(), good.vulkan.end()));
    const std::string e = errorOf([&] {
        device->createShader({.stage = ShaderStage::Vertex,
                              .binary = {.name = "far", .vulkan = vulkan, .opengl = opengl}});
    });
    EXPECT_NE(e.find("location 40; every device has 16 (0 to 15)"), std::string::npos) << e;
}

// gl_ClipDistance longer than the 8 distances every device has is refused before the driver sees
// it (the capture-file fuzzer made one of 14337; the validation layer reported it).
TEST_P(DamagedSpirv, ClipDistancesBeyondEightAreRefused) {
    const ShaderBinary& good = fe::shaders::find("conformance/triangle.vert");
    // The array length constant of gl_PerVertex's gl_ClipDistance: OpTypeArray (28) whose
    // element is the float type and whose length is the constant 1, made 14337.
    auto patched = [](std::span<const uint32_t> words) {
        std::vector<uint32_t> w(words.begin(), words.end());
        std::map<uint32_t, size_t> constantAt;  // id -> word index of its value
        for (size_t i = 5; i < w.size(); i += std::max(1u, w[i] >> 16)) {
            const uint32_t op = w[i] & 0xffffu, n = w[i] >> 16;
            if (op == 43 && n == 4 && w[i + 3] == 1)
                constantAt[w[i + 2]] = i + 3;  // OpConstant ... 1
            if (op == 28 && n == 4 && constantAt.count(w[i + 3])) w[constantAt[w[i + 3]]] = 14337;
        }
        return w;
    };
    const std::vector<uint32_t> vulkan = patched(good.vulkan), opengl = patched(good.opengl);
    ASSERT_NE(vulkan, std::vector<uint32_t>(good.vulkan.begin(), good.vulkan.end()));
    const std::string e = errorOf([&] {
        device->createShader({.stage = ShaderStage::Vertex,
                              .binary = {.name = "clip", .vulkan = vulkan, .opengl = opengl}});
    });
    // gl_ClipDistance and gl_CullDistance share the array type: 2 x 14337.
    EXPECT_NE(
        e.find("gl_ClipDistance and gl_CullDistance hold 28674 distances; every device has 8"),
        std::string::npos)
        << e;
}

// A uniform block member that straddles a 16-byte boundary is valid SPIR-V but not a layout any
// device reads (Vulkan's relaxed block layout, GL's std140): refused, not left to the validation
// layer or the GLSL compiler (found by the capture-file fuzzer).
TEST_P(DamagedSpirv, StraddlingBlockMembersAreRefused) {
    const ShaderBinary& good = fe::shaders::find("conformance/ubo_color.frag");
    // OpMemberDecorate (72): struct, member 1, Offset (35), 16 -> 24: the second vec4 straddles.
    auto patched = [](std::span<const uint32_t> words) {
        std::vector<uint32_t> w(words.begin(), words.end());
        for (size_t i = 5; i < w.size(); i += std::max(1u, w[i] >> 16))
            if ((w[i] & 0xffffu) == 72 && (w[i] >> 16) == 5 && w[i + 2] == 1 && w[i + 3] == 35 &&
                w[i + 4] == 16)
                w[i + 4] = 24;
        return w;
    };
    const std::vector<uint32_t> vulkan = patched(good.vulkan), opengl = patched(good.opengl);
    ASSERT_NE(vulkan, std::vector<uint32_t>(good.vulkan.begin(), good.vulkan.end()));
    ASSERT_NE(opengl, std::vector<uint32_t>(good.opengl.begin(), good.opengl.end()));
    const std::string e = errorOf([&] {
        device->createShader({.stage = ShaderStage::Fragment,
                              .binary = {.name = "straddle", .vulkan = vulkan, .opengl = opengl}});
    });
    EXPECT_NE(e.find("shader 'straddle': not a valid SPIR-V module for Vulkan:"), std::string::npos)
        << e;
    EXPECT_NE(e.find("improperly straddling vector at offset 24"), std::string::npos) << e;
}

// A capability the device does not enable is refused by name before the driver sees it (the
// capture-file fuzzer made a module declaring CullDistance: a validation-layer error on Vulkan).
TEST_P(DamagedSpirv, CapabilitiesTheDeviceLacksAreRefused) {
    const ShaderBinary& good = fe::shaders::find("conformance/triangle.vert");
    auto patched = [](std::span<const uint32_t> words) {
        std::vector<uint32_t> w(words.begin(), words.end());
        // After the first OpCapability (opcode 17): OpCapability CullDistance (33).
        for (size_t i = 5; i < w.size(); i += std::max(1u, w[i] >> 16))
            if ((w[i] & 0xffffu) == 17) {
                w.insert(w.begin() + std::ptrdiff_t(i + 2), {(2u << 16) | 17u, 33u});
                break;
            }
        return w;
    };
    const std::vector<uint32_t> vulkan = patched(good.vulkan), opengl = patched(good.opengl);
    ASSERT_EQ(vulkan.size(), good.vulkan.size() + 2);
    const std::string e = errorOf([&] {
        device->createShader({.stage = ShaderStage::Vertex,
                              .binary = {.name = "cull", .vulkan = vulkan, .opengl = opengl}});
    });
    EXPECT_NE(
        e.find(
            "shader 'cull': its Vulkan SPIR-V declares capability 33 (CullDistance), which the device does not offer"),
        std::string::npos)
        << e;
    // The GL half alone: refused the same way on every backend.
    const std::string gl = errorOf([&] {
        device->createShader({.stage = ShaderStage::Vertex,
                              .binary = {.name = "cull", .vulkan = good.vulkan, .opengl = opengl}});
    });
    EXPECT_NE(gl.find("shader 'cull': its OpenGL SPIR-V declares capability 33 (CullDistance)"),
              std::string::npos)
        << gl;
}

// The SPIR-V header's schema word must be 0: SPIRV-Tools lets other values through, Mesa's
// Vulkan driver refuses them with a validation error (found by the capture-file fuzzer).
TEST_P(DamagedSpirv, HeaderSchemaWordIsChecked) {
    const ShaderBinary& good = fe::shaders::find("conformance/triangle.vert");
    std::vector<uint32_t> vulkan(good.vulkan.begin(), good.vulkan.end()),
        opengl(good.opengl.begin(), good.opengl.end());
    vulkan[4] = opengl[4] = 40;
    const std::string e = errorOf([&] {
        device->createShader({.stage = ShaderStage::Vertex,
                              .binary = {.name = "schema", .vulkan = vulkan, .opengl = opengl}});
    });
    EXPECT_NE(
        e.find(
            "shader 'schema': not a valid SPIR-V module for Vulkan: header word 4 (schema) is 40, not 0"),
        std::string::npos)
        << e;
}

// An image write whose texel has fewer components than the image's format is refused at
// createShader on every backend alike (the validator lets it through, Vulkan's layer does not:
// the capture-file fuzzer found one). conformance/fill.comp writes a vec4 to an rgba32f image;
// here its texel becomes a float constant.
TEST(DamagedSpirvAcrossBackends, ImageWriteWithTooFewComponentsIsRefused) {
    const ShaderBinary& good = fe::shaders::find("conformance/fill.comp");
    auto narrowed = [](std::span<const uint32_t> in) {
        std::vector<uint32_t> w(in.begin(), in.end());
        uint32_t floatType = 0, scalar = 0;
        for (size_t i = 5; i < w.size(); i += w[i] >> 16) {
            const uint32_t op = w[i] & 0xffffu;
            if (op == 22 && w[i + 2] == 32) floatType = w[i + 1];  // OpTypeFloat 32
            if (op == 43 && floatType && w[i + 1] == floatType && !scalar)
                scalar = w[i + 2];                      // OpConstant
            if (op == 99 && scalar) w[i + 3] = scalar;  // OpImageWrite's texel
        }
        return w;
    };
    const std::vector<uint32_t> vulkan = narrowed(good.vulkan), opengl = narrowed(good.opengl);
    ASSERT_NE(vulkan, std::vector<uint32_t>(good.vulkan.begin(), good.vulkan.end()));
    for (const std::string& backend : backendNames()) {
        BackendProbe p = probeBackend(backend, true);
        if (!p.available) continue;
        EXPECT_EQ(
            errorOf([&] {
                p.device->createShader(
                    {.stage = ShaderStage::Compute,
                     .binary = {.name = "narrow", .vulkan = vulkan, .opengl = opengl}});
            }),
            "shader 'narrow': an image write gives 1 component(s) to an image whose format has 4")
            << backend;
        EXPECT_EQ(p.device->validationErrorCount(), 0u) << backend;
    }
}

// GL has as few as 8 image units (NVIDIA): a pipeline's storage textures are counted against
// limits.maxStorageTextures by the shared validation, so every backend refuses alike. Checked on
// the validation itself, since no device here has a limit a shader of the suite reaches.
TEST(StorageTextureLimit, MoreThanTheDeviceBindsIsRefusedAndSlotNumbersDoNotCount) {
    ShaderInterface cs;
    cs.stage = ShaderStage::Compute;
    cs.bindings = {{9, BindingType::StorageTexture, "a"},
                   {40, BindingType::StorageTexture, "b"},
                   {3, BindingType::StorageBuffer, "s"}};
    const DeviceLimits two{.maxStorageTextures = 2}, one{.maxStorageTextures = 1};
    EXPECT_EQ(validate::pipelineBindings({}, {&cs}, "images", two).size(),
              3u);  // slots 9 and 40 with 2 units
    EXPECT_EQ(
        errorOf([&] { validate::pipelineBindings({}, {&cs}, "images", one); }),
        "pipeline 'images': the shaders use 2 storage textures; this device binds at most 1 to one pipeline "
        "(limits.maxStorageTextures)");
}

// The GL backend renumbers storage textures to image units in the SPIR-V it hands the driver.
TEST(StorageTextureLimit, RenumberingChangesOnlyTheStorageTextureBindings) {
    const ShaderBinary& b = fe::shaders::find("conformance/storage_high_slots.comp");
    std::array<uint8_t, 64> units;
    units.fill(0xff);
    units[9] = 0, units[40] = 1;
    const std::vector<uint32_t> renumbered = withStorageTextureSlots(b.opengl, units);
    const ShaderInterface before = reflectShader(b.opengl, ShaderStage::Compute, "main", "before");
    const ShaderInterface after = reflectShader(renumbered, ShaderStage::Compute, "main", "after");
    std::map<std::string, uint32_t> slots;
    for (const auto& x : after.bindings) slots[x.name] = x.slot;
    ASSERT_EQ(before.bindings.size(), after.bindings.size());
    EXPECT_EQ(slots["first"], 0u);
    EXPECT_EQ(slots["second"], 1u);
    EXPECT_EQ(slots["Scale"], 3u);  // the storage buffer keeps its slot
    // Names get the stage's prefix, so two stages' blocks of one name stay apart on NVIDIA's GL.
    const std::vector<uint32_t> prefixed = withNamesPrefixed(b.opengl, "compute.");
    const ShaderInterface named =
        reflectShader(prefixed, ShaderStage::Compute, "main", "prefixed", SpirvRules::OpenGL45);
    std::set<std::string> names;
    for (const auto& x : named.bindings) names.insert(x.name);
    EXPECT_EQ(names, (std::set<std::string>{"compute.first", "compute.second", "compute.Scale"}));
}

// Creating a shader keeps what validating and reflecting a module gave (ShaderReflection.cpp's
// ModuleMemo), since renderers create the same modules on every device: the answer is reused
// only for the same module, word for word, under the same rules, stage and entry point.
TEST(ShaderModuleMemo, ReusesAnAnswerOnlyForTheSameModuleStageAndEntryPoint) {
    const ShaderBinary& b = fe::shaders::find("conformance/storage_high_slots.comp");
    const std::vector<uint32_t> words(b.opengl.begin(), b.opengl.end());
    for (int pass = 0; pass < 2; ++pass) {  // the second pass answers from the memo
        SCOPED_TRACE(pass);
        EXPECT_EQ(errorOf([&] { validateSpirv(words, SpirvRules::OpenGL45, "kept"); }),
                  "(no error)");
        EXPECT_EQ(errorOf([&] {
                      reflectShader(words, ShaderStage::Compute, "main", "kept",
                                    SpirvRules::OpenGL45);
                  }),
                  "(no error)");
        EXPECT_EQ(errorOf([&] {
                      reflectShader(words, ShaderStage::Fragment, "main", "kept",
                                    SpirvRules::OpenGL45);
                  }),
                  "shader 'kept': SPIR-V reflection failed: Entry point does not exist.");
        EXPECT_EQ(errorOf([&] {
                      reflectShader(words, ShaderStage::Compute, "other", "kept",
                                    SpirvRules::OpenGL45);
                  }),
                  "shader 'kept': SPIR-V reflection failed: Entry point does not exist.");
        // The same size, one word changed (the bound: every id must lie below it).
        std::vector<uint32_t> damaged = words;
        damaged[3] = 1;
        EXPECT_NE(errorOf([&] {
                      validateSpirv(damaged, SpirvRules::OpenGL45, "damaged");
                  }).find("shader 'damaged': not a valid SPIR-V module for OpenGL: "),
                  std::string::npos);
    }
}

// HLSL is translated in a forked child, so that a glslang crash costs only the child. Its
// include requests come back to the caller's process: the callback's locks and what it records
// are the caller's (run in the child, a lock another thread held at the fork stayed held there
// for good, and what the callback recorded was lost). A child that sleeps for good (a lock some
// library held at the fork) is killed and forked again in seconds, not at the 60 s limit; one that
// stalls every time is a clear Error.
namespace {
const char* kIncludingPixelShader =
    "#include \"value.hlsli\"\nfloat4 main() : SV_Target0 { return VALUE; }\n";
ShaderSourceCompile includingSource(
    std::function<std::optional<std::string>(const std::string&, const std::string&)> include) {
    return {.stage = ShaderStage::Fragment,
            .text = kIncludingPixelShader,
            .language = ShaderLanguage::HLSL,
            .name = "including.hlsl",
            .include = std::move(include)};
}
std::optional<std::string> valueHeader(const std::string& name) {
    if (name != "value.hlsli") return std::nullopt;
    return "#define VALUE float4(0.25, 0.5, 0.75, 1)\n";
}
double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
}  // namespace

TEST(HlslTranslation, TheIncludeCallbackRunsInTheCallersProcess) {
    std::mutex m;
    std::atomic<bool> held{false};
    std::vector<std::string> asked;  // what a hot-reloading tool would watch
    std::thread holder([&] {
        std::lock_guard lock(m);
        held = true;
        std::this_thread::sleep_for(std::chrono::milliseconds(500));
    });
    while (!held) std::this_thread::yield();
    std::string glsl, error;
    try {
        glsl = hlslToGlsl(includingSource([&](const std::string& name, const std::string&) {
            std::lock_guard lock(m);  // held by `holder` when the child is forked
            asked.push_back(name);
            return valueHeader(name);
        }));
    } catch (const Error& e) {
        error = e.what();
    }
    holder.join();
    EXPECT_EQ(error, "");
    EXPECT_NE(glsl.find("0.25"), std::string::npos) << glsl;
    EXPECT_EQ(asked, std::vector<std::string>{"value.hlsli"});
    EXPECT_THROW(hlslToGlsl(includingSource(
                     [](const std::string&, const std::string&) -> std::optional<std::string> {
                         throw std::runtime_error("the include's disk is gone");
                     })),
                 std::runtime_error);
}

TEST(HlslTranslation, AStalledChildIsForkedAgain) {
    // A stall is noticed after 0.5 s here (2 s in use), so the case waits less.
    stallHlslChildrenForTesting(1, std::chrono::milliseconds(500));
    const auto start = std::chrono::steady_clock::now();
    std::string glsl, error;
    try {
        glsl = hlslToGlsl(includingSource(
            [](const std::string& name, const std::string&) { return valueHeader(name); }));
    } catch (const Error& e) {
        error = e.what();
    }
    stallHlslChildrenForTesting(0);
    EXPECT_EQ(error, "");
    EXPECT_NE(glsl.find("0.25"), std::string::npos) << glsl;
    EXPECT_LT(secondsSince(start), 20.0) << "the stalled child was not noticed before 60 s";
}

TEST(HlslTranslation, AChildThatStallsEveryTimeIsAClearError) {
    stallHlslChildrenForTesting(3, std::chrono::milliseconds(500));
    const auto start = std::chrono::steady_clock::now();
    const std::string error = fe::testing::errorOf([&] {
        hlslToGlsl(includingSource(
            [](const std::string& name, const std::string&) { return valueHeader(name); }));
    });
    stallHlslChildrenForTesting(0);
    EXPECT_NE(error.find("shader 'including.hlsl': the HLSL compiler (glslang's HLSL front end) "
                         "stalled on each of its three tries"),
              std::string::npos)
        << error;
    EXPECT_LT(secondsSince(start), 20.0);
}

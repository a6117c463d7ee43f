// The render director (layer 8): for scenes that need each choice, what it chose, why, and
// what the scene renderer then built: passes and transient textures, not only the name.
#include <gtest/gtest.h>

#include <algorithm>

#include "BackendTest.h"
#include "assets/BuiltinScenes.h"
#include "integration/RenderDirector.h"
#include "integration/SceneRenderer.h"

using namespace fe;

namespace {

struct Built {
    std::string technique;
    std::vector<std::string> passes;    // surviving passes, in order
    std::vector<std::string> textures;  // transient textures the graph allocated
    std::vector<std::string> reasons;
};

Built build(gdi::Device& device, const assets::Scene& scene, render::RenderSettings request) {
    request.width = 64;
    request.height = 48;
    const render::DirectorChoice c = render::direct(scene, request, device.info());
    render::SceneRenderer r(device, scene, c.settings);
    r.renderFrame();
    Built b{c.settings.technique, {}, {}, c.reasons};
    for (const auto& p : r.graph().passes())
        if (!p.culled) b.passes.push_back(p.name);
    for (const auto& t : r.graph().textures())
        if (!t.imported && t.used()) b.textures.push_back(t.name);
    return b;
}

bool anyStartsWith(const std::vector<std::string>& v, const std::string& prefix) {
    return std::any_of(v.begin(), v.end(), [&](const std::string& s) { return s.rfind(prefix, 0) == 0; });
}

class RenderDirector : public fe::testing::BackendTest {};

}  // namespace

// One light: forward, with no G-buffer and no I-buffer allocated.
TEST_P(RenderDirector, FewLightsGetForwardAndNoGBuffer) {
    const assets::Scene scene = assets::makeBuiltinScene("plane");
    const Built b = build(*device, scene, {.technique = "auto"});
    EXPECT_EQ(b.technique, "forward");
    EXPECT_EQ(b.passes, (std::vector<std::string>{"forward"}));  // display culled: no image asked for
    EXPECT_EQ(b.textures, (std::vector<std::string>{"depth"}));
    EXPECT_NE(b.reasons[0].find("1 light(s)"), std::string::npos) << b.reasons[0];
}

// Many ranged lights: tiled deferred, whose G-buffer is built but no I-buffer.
TEST_P(RenderDirector, ManyLightsGetTiledDeferred) {
    const assets::Scene scene = assets::makeBuiltinScene("lights", {.lights = 64});
    const Built b = build(*device, scene, {.technique = "auto"});
    EXPECT_EQ(b.technique, "deferred-tiled");
    EXPECT_EQ(b.passes, (std::vector<std::string>{"gbuffer", "tiled-lighting"}));
    EXPECT_TRUE(anyStartsWith(b.textures, "gbuffer"));
    EXPECT_FALSE(anyStartsWith(b.textures, "ibuffer"));
    EXPECT_NE(b.reasons[0].find("64 lights (64 with a range"), std::string::npos) << b.reasons[0];
}

// BLEND primitives bring the transparent pass; without them there is none.
TEST_P(RenderDirector, TransparentPassOnlyForBlendPrimitives) {
    assets::Scene scene = assets::makeBuiltinScene("plane");
    Built opaque = build(*device, scene, {.technique = "auto"});
    EXPECT_EQ(std::count(opaque.passes.begin(), opaque.passes.end(), "transparent"), 0);
    EXPECT_EQ(opaque.reasons.back(), "no transparent pass: no BLEND primitives");
    for (auto& m : scene.materials) m.alphaMode = assets::AlphaMode::Blend;
    Built blend = build(*device, scene, {.technique = "auto"});
    EXPECT_EQ(std::count(blend.passes.begin(), blend.passes.end(), "transparent"), 1);
    EXPECT_EQ(blend.reasons.back(), "transparent pass: 1 BLEND primitive(s)");
}

// An asked-for technique is kept; a reduced illumination rate outside redeferred is dropped,
// with its reason, and only redeferred allocates an I-buffer.
TEST_P(RenderDirector, AskedTechniqueIsKept) {
    const assets::Scene scene = assets::makeBuiltinScene("plane");
    const Built r = build(*device, scene, {.technique = "redeferred", .illumScale = 2});
    EXPECT_EQ(r.technique, "redeferred");
    EXPECT_TRUE(anyStartsWith(r.textures, "ibuffer"));
    const Built f = build(*device, scene, {.technique = "deferred", .illumScale = 2});
    EXPECT_FALSE(anyStartsWith(f.textures, "ibuffer"));
    EXPECT_NE(f.reasons[1].find("illumination scale 2 ignored"), std::string::npos);
}

FE_INSTANTIATE_FOR_EVERY_BACKEND(RenderDirector);

// Without compute shaders many lights fall back to light volumes (no device needed).
TEST(RenderDirectorChoice, WithoutComputeShadersManyLightsGetDeferred) {
    const assets::Scene scene = assets::makeBuiltinScene("lights", {.lights = 64});
    gdi::DeviceInfo noCompute;
    noCompute.backend = "test";
    const render::DirectorChoice c = render::direct(scene, {.technique = "auto"}, noCompute);
    EXPECT_EQ(c.settings.technique, "deferred");
    EXPECT_NE(c.reasons[0].find("no compute shaders on test"), std::string::npos) << c.reasons[0];
}

// Every technique with an I-buffer keeps its illumination scale; the others drop it.
TEST(RenderDirectorChoice, IllumScaleKeptWhereThereIsAnIBuffer) {
    const assets::Scene scene = assets::makeBuiltinScene("plane");
    gdi::DeviceInfo device;
    for (const char* t : {"redeferred", "redeferred-tiled"})
        EXPECT_EQ(render::direct(scene, {.technique = t, .illumScale = 2}, device).settings.illumScale, 2u) << t;
    for (const char* t : {"deferred", "deferred-tiled", "forward", "light-prepass"})
        EXPECT_EQ(render::direct(scene, {.technique = t, .illumScale = 2}, device).settings.illumScale, 1u) << t;
}

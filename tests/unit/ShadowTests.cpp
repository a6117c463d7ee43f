// Shadow maps on every backend against the CPU reference's shadow rays (builtin:shadows: a sun
// with cascades, a spot and a point light's cube over a ground, a sphere, a cube and a thin pole):
// forward against the exact image, every technique against forward, the errors of map size and
// filtering measured, the maps aliased in transient memory, and the plan's choice of lights.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "BackendTest.h"
#include "assets/BuiltinScenes.h"
#include "integration/RenderDirector.h"
#include "integration/SceneRenderer.h"
#include "reference/CpuReference.h"
#include "render/ShadowPlan.h"

using namespace fe;

namespace {
constexpr uint32_t kW = 160, kH = 120;

render::RenderSettings shadowSettings(const std::string& technique, uint32_t mapSize = 1024,
                                      bool pcf = true) {
    render::RenderSettings s{.technique = technique, .width = kW, .height = kH};
    s.shadows = {.enabled = true, .mapSize = mapSize, .pcf = pcf};
    return s;
}

gdi::Image renderShadowed(gdi::Device& d, const assets::Scene& scene,
                          const render::RenderSettings& s) {
    render::SceneRenderer r(d, scene, s);
    r.renderFrame();
    return r.readOutput();
}

// A pixel is wrong when a channel differs by more than 2 % (relative, floored at 0.01): a
// shadow is either there or not, so shadow errors are far beyond it.
bool wrong(const std::array<float, 4>& a, const glm::dvec3& b) {
    for (int c = 0; c < 3; ++c) {
        const double rel =
            std::abs(a[c] - b[c]) / std::max({std::abs(double(a[c])), std::abs(b[c]), 0.01});
        if (!(rel <= 0.02)) return true;
    }
    return false;
}

struct ShadowError {
    double interior =
        0;  // fraction wrong away from silhouettes and shadow edges: acne, peter-panning, leaks
    double edges = 0;  // fraction wrong within 2 pixels of a shadow edge
    double all = 0;    // fraction wrong away from silhouettes
};

ShadowError compare(const gdi::Image& img, const render::ReferenceImage& ref) {
    uint32_t n = 0, nEdge = 0, bad = 0, badEdge = 0;
    for (uint32_t y = 0; y < kH; ++y)
        for (uint32_t x = 0; x < kW; ++x) {
            if (ref.nearEdge(x, y)) continue;
            const bool edge = ref.nearShadowEdge(x, y, 2);
            const bool w = wrong(img.texel(x, y), ref.radiance[size_t(y) * kW + x]);
            (edge ? nEdge : n)++;
            (edge ? badEdge : bad) += w;
        }
    return {n ? double(bad) / n : 0.0, nEdge ? double(badEdge) / nEdge : 0.0,
            double(bad + badEdge) / std::max(1u, n + nEdge)};
}

double fractionDiffering(const gdi::Image& a, const gdi::Image& b, double tol) {
    uint32_t over = 0;
    for (uint32_t y = 0; y < a.height; ++y)
        for (uint32_t x = 0; x < a.width; ++x) {
            auto ta = a.texel(x, y), tb = b.texel(x, y);
            for (int c = 0; c < 3; ++c)
                if (!(std::abs(ta[c] - tb[c]) <=
                      tol * std::max({std::abs(ta[c]), std::abs(tb[c]), 0.01f}))) {
                    ++over;
                    break;
                }
        }
    return double(over) / (a.width * a.height);
}

class Shadows : public fe::testing::BackendTest {
protected:
    Shadows() : BackendTest(true) {}  // the cases share a device (BackendTest.h)
    void SetUp() override {
        BackendTest::SetUp();
        if (!device) return;
        scene = assets::makeBuiltinScene("shadows");
        plan = render::planShadows(scene.lights, *scene.camera, scene.bounds, {.enabled = true});
        // The references depend on the scene alone: traced once for every case.
        static const render::ReferenceImage kReference = render::renderReference(
            scene, *scene.camera, kW, kH, {.castsShadow = plan.castsShadow()});
        static const render::ReferenceImage kSeparableReference = render::renderReference(
            scene, *scene.camera, kW, kH,
            {.castsShadow = plan.castsShadow(), .brdf = shading::Brdf::Separable});
        reference = kReference;
        separableReference = kSeparableReference;
    }
    // The exact image under the technique's BRDF (render::resolveBrdf).
    const render::ReferenceImage& referenceFor(const std::string& technique) const {
        return render::findTechnique(technique).separableBrdf ? separableReference : reference;
    }
    assets::Scene scene;
    render::ShadowPlan plan;
    render::ReferenceImage reference, separableReference;
};
}  // namespace

// The reference itself: every light of the scene shadows part of the visible ground.
TEST(ShadowReference, EveryLightShadowsSomething) {
    const assets::Scene scene = assets::makeBuiltinScene("shadows");
    const render::ShadowPlan plan =
        render::planShadows(scene.lights, *scene.camera, scene.bounds, {.enabled = true});
    ASSERT_EQ(plan.shadowed.size(), 3u);
    const render::ReferenceImage ref =
        render::renderReference(scene, *scene.camera, kW, kH, {.castsShadow = plan.castsShadow()});
    for (uint32_t bit = 0; bit < 3; ++bit) {
        const auto n = std::count_if(ref.occluded.begin(), ref.occluded.end(),
                                     [&](uint32_t m) { return (m >> bit) & 1u; });
        EXPECT_GT(n, 100) << "light " << bit << " shadows " << n << " pixels";
    }
    const render::ReferenceImage lit = render::renderReference(scene, *scene.camera, kW, kH);
    EXPECT_TRUE(
        std::all_of(lit.occluded.begin(), lit.occluded.end(), [](uint32_t m) { return m == 0; }));
}

// Forward with 2048-texel maps against the ray-cast shadows: away from shadow edges (2 pixels)
// the maps must agree everywhere but a few pixels, which is the acne / peter-panning bound.
TEST_P(Shadows, ForwardMatchesRayCastShadows) {
    const gdi::Image img = renderShadowed(*device, scene, shadowSettings("forward"));
    const ShadowError e = compare(img, reference);
    RecordProperty("interior_wrong", std::to_string(e.interior));
    RecordProperty("edge_wrong", std::to_string(e.edges));
    EXPECT_LE(e.interior, 0.005) << "acne, peter-panning or leaks away from shadow edges";
    EXPECT_LE(e.edges, 0.5);
    // And shadows were drawn at all: without them the image is far off.
    render::RenderSettings off{.technique = "forward", .width = kW, .height = kH};
    const ShadowError unshadowed = compare(renderShadowed(*device, scene, off), reference);
    EXPECT_GT(unshadowed.interior, 0.02);  // measured 3.5 %: the shadows' insides
}

// Every technique adds its shadowed lights in passes of its own; each must shadow as forward
// does: with shadows it may differ from forward no more than without them (the light pre-pass
// differs anyway: it rebuilds specular colour from one channel), plus 1 % of the pixels.
TEST_P(Shadows, EveryTechniqueShadowsLikeForward) {
    render::RenderSettings off{.technique = "forward", .width = kW, .height = kH};
    const gdi::Image fGltf = renderShadowed(*device, scene, shadowSettings("forward"));
    const gdi::Image fOffGltf = renderShadowed(*device, scene, off);
    render::RenderSettings separable = shadowSettings("forward");
    separable.shadingModel = off.shadingModel = render::ShadingModel::Separable;
    const gdi::Image fSeparable = renderShadowed(*device, scene, separable);
    const gdi::Image fOffSeparable = renderShadowed(*device, scene, off);
    off.shadingModel = render::ShadingModel::Auto;
    for (const render::TechniqueInfo& t : render::techniques()) {
        if (std::string(t.name) == "forward") continue;
        // Compared with forward under the technique's BRDF.
        const gdi::Image& f = t.separableBrdf ? fSeparable : fGltf;
        const gdi::Image& fOff = t.separableBrdf ? fOffSeparable : fOffGltf;
        if (std::string(t.name).find("tiled") != std::string::npos &&
            !device->info().features.computeShaders)
            continue;
        const gdi::Image img = renderShadowed(*device, scene, shadowSettings(t.name));
        render::RenderSettings o = off;
        o.technique = t.name;
        const double dOn = fractionDiffering(img, f, 0.02),
                     dOff = fractionDiffering(renderShadowed(*device, scene, o), fOff, 0.02);
        EXPECT_LE(dOn, dOff + 0.01) << t.name;
        const bool exact = std::string(t.name).find("light-prepass") == std::string::npos;
        if (exact) {
            EXPECT_LE(dOn, 0.01) << t.name;  // G-buffer rounding, as in DeferredMatchesForward
        }
        const ShadowError e = compare(img, referenceFor(t.name));
        if (exact) {
            EXPECT_LE(e.interior, 0.005) << t.name;
        }
        std::cout << "  " << t.name << ": " << std::fixed << std::setprecision(3) << dOn * 100
                  << " % of pixels differ from forward (" << dOff * 100
                  << " % without shadows); vs rays: interior " << e.interior * 100
                  << " %, shadow edges " << e.edges * 100 << " %\n";
    }
}

// What map size and filtering cost in accuracy (docs/BENCHMARKS.md): larger maps move fewer
// edge pixels; the filter trades hard-edge errors for soft ones.
TEST_P(Shadows, MapSizeAndFilterErrorIsMeasured) {
    std::ostringstream table;
    double edge512 = 0, edge2048 = 0;
    for (bool pcf : {false, true})
        for (uint32_t size : {512u, 1024u, 2048u}) {
            const ShadowError e = compare(
                renderShadowed(*device, scene, shadowSettings("forward", size, pcf)), reference);
            table << "map " << size << (pcf ? " pcf" : " nearest") << ": interior " << std::fixed
                  << std::setprecision(3) << e.interior * 100 << " %, shadow edges "
                  << e.edges * 100 << " %, all " << e.all * 100 << " %\n";
            if (!pcf && size == 512) edge512 = e.edges;
            if (!pcf && size == 2048) edge2048 = e.edges;
            EXPECT_LE(e.interior, 0.02) << size << (pcf ? " pcf" : " nearest");
        }
    std::cout << table.str();
    RecordProperty("table", table.str());
    EXPECT_LT(edge2048, edge512) << "a 4x larger map must place shadow edges better";
}

// The maps are transient: each shadowed light's map lives from its first layer's pass to its
// light's pass, so the three maps of builtin:shadows share memory (or texture objects).
TEST_P(Shadows, MapsShareTransientMemory) {
    render::SceneRenderer r(*device, scene, shadowSettings("deferred", 512));
    const graph::RenderGraph& g = r.graph();
    std::vector<const graph::TextureInfo*> maps;
    for (const graph::TextureInfo& t : g.textures())
        if (t.name.find("shadow") == 0) maps.push_back(&t);
    ASSERT_EQ(maps.size(), 3u);
    for (size_t i = 0; i + 1 < maps.size(); ++i)
        EXPECT_FALSE(maps[i]->overlaps(*maps[i + 1])) << maps[i]->name;
    EXPECT_EQ(maps[2]->desc.dimension, gdi::TextureDimension::TextureCube);  // the lamp
    EXPECT_EQ(maps[0]->desc.depthOrLayers, 4u);                              // the sun's cascades
    const graph::MemoryReport m = g.memory();
    render::SceneRenderer unaliased(*device, scene, [&] {
        auto s = shadowSettings("deferred", 512);
        s.aliasing = false;
        return s;
    }());
    RecordProperty("bytes_with_aliasing", std::to_string(m.withAliasing));
    RecordProperty("bytes_without", std::to_string(m.withoutAliasing));
    // Heaps: the cascades (4 MiB) and the spot map (1 MiB) live inside the cube's 6 MiB. Texture
    // object reuse (GL) shares only identical textures: these three maps differ in kind.
    const uint64_t cascadesAndSpot = 512ull * 512 * 4 * 5;
    if (g.aliasing() == graph::AliasingMode::Memory) {
        EXPECT_GE(m.withoutAliasing - m.withAliasing, cascadesAndSpot)
            << "the maps were not aliased";
    }
    EXPECT_EQ(unaliased.graph().memory().withAliasing, unaliased.graph().memory().withoutAliasing);
    r.renderFrame();
    const gdi::Image img = r.readOutput();
    EXPECT_LE(compare(img, render::renderReference(scene, *scene.camera, kW, kH,
                                                   {.castsShadow = plan.castsShadow()}))
                  .interior,
              0.02);
}

// Redeferred at reduced illumination rates: shadow edges are where the seed says a reduced rate
// fails; measured against the rays, interior kept.
TEST_P(Shadows, RedeferredReducedRateErrorAtShadowEdgesIsMeasured) {
    for (uint32_t scale : {1u, 2u, 4u}) {
        render::RenderSettings s = shadowSettings("redeferred");
        s.illumScale = scale;
        const ShadowError e = compare(renderShadowed(*device, scene, s), separableReference);
        std::cout << "  redeferred illum-scale " << scale << ": interior " << std::fixed
                  << std::setprecision(3) << e.interior * 100 << " %, shadow edges "
                  << e.edges * 100 << " %\n";
        RecordProperty("scale" + std::to_string(scale) + "_edges", std::to_string(e.edges));
        if (scale == 1) {
            EXPECT_LE(e.interior, 0.01);
        }
    }
}

// Per-source rates (the seed's "dedicated shading rate per illumination source"): with the sky
// lighting the scene too, the shadowed lights at full rate and the environment reduced keep the
// shadow edges that one reduced rate for everything loses. Against the rays and the same IBL
// estimator; each rate's I-buffer and its upsampling pass are in the graph.
TEST_P(Shadows, PerSourceRatesKeepShadowEdges) {
    assets::Scene lit = scene;
    lit.environment = assets::loadEnvironment("builtin:sky");
    const render::ReferenceImage ref = render::renderReference(
        lit, *lit.camera, kW, kH,
        {.iblSamples = 64, .castsShadow = plan.castsShadow(), .brdf = shading::Brdf::Separable});
    auto run = [&](uint32_t scale, render::SourceRates rates) {
        render::RenderSettings s = shadowSettings("redeferred");
        s.iblSamples = 64;
        s.illumScale = scale;
        s.rates = rates;
        render::SceneRenderer r(*device, lit, s);
        r.renderFrame();
        std::vector<std::string> passes;
        for (const auto& p : r.graph().passes())
            if (!p.culled) passes.push_back(p.name);
        return std::make_pair(compare(r.readOutput(), ref), passes);
    };
    const auto [full, fullPasses] = run(1, {});
    const auto [uniform, uniformPasses] = run(2, {});
    const auto [mixed, mixedPasses] =
        run(1, {.punctual = 2, .shadowed = 1, .iblDiffuse = 4, .iblSpecular = 2});
    const auto [same, samePasses] =
        run(1, {.punctual = 2, .shadowed = 2, .iblDiffuse = 2, .iblSpecular = 2});
    std::cout << std::fixed << std::setprecision(3) << "  full rate: interior "
              << full.interior * 100 << " %, edges " << full.edges * 100
              << " %\n  everything at 1/2: interior " << uniform.interior * 100 << " %, edges "
              << uniform.edges * 100
              << " %\n  shadowed 1, ibl-diffuse 1/4, ibl-specular 1/2: interior "
              << mixed.interior * 100 << " %, edges " << mixed.edges * 100 << " %\n";
    RecordProperty("uniform_half_edges", std::to_string(uniform.edges));
    RecordProperty("per_source_edges", std::to_string(mixed.edges));
    EXPECT_LE(full.interior, 0.02);
    EXPECT_LT(mixed.edges, uniform.edges * 0.75)
        << "the shadowed lights at full rate should keep their edges";
    // Every source at one rate is the plain reduced-rate path, pass for pass.
    EXPECT_EQ(samePasses, uniformPasses);
    for (const char* p :
         {"upsample I-buffer 1/2", "upsample I-buffer 1/4", "ibl-diffuse", "ibl-specular"})
        EXPECT_NE(std::find(mixedPasses.begin(), mixedPasses.end(), p), mixedPasses.end()) << p;
    EXPECT_EQ(std::find(uniformPasses.begin(), uniformPasses.end(), "upsample I-buffer 1/2"),
              uniformPasses.end());
}

// Temporal accumulation (the seed's consideration D): a still view converges to the full-rate
// image once every pixel of each I-buffer block has been the representative one (scale^2
// frames); a moving camera (an orbit) stays closer to the full-rate image than the plain
// reduced rate does when it moves slowly, and no worse when it moves fast. Shadow edges
// measured against the rays (maps of 512 texels: this test renders 100 frames).
TEST_P(Shadows, TemporalAccumulationConvergesAndDegradesGracefully) {
    const gdi::Image fullRate = renderShadowed(*device, scene, shadowSettings("redeferred", 512));
    for (uint32_t scale : {2u, 4u}) {
        render::RenderSettings s = shadowSettings("redeferred", 512);
        s.illumScale = scale;
        s.temporal = true;
        render::SceneRenderer r(*device, scene, s);
        std::vector<double> differing;
        for (uint32_t f = 0; f < scale * scale; ++f) {
            r.renderFrame();
            differing.push_back(fractionDiffering(r.readOutput(), fullRate, 1e-4));
        }
        const ShadowError e = compare(
            r.readOutput(),
            separableReference);  // maps of 512: edges as in MapSizeAndFilterErrorIsMeasured
        std::cout << "  still, scale " << scale
                  << ": pixels off the full-rate image by more than 0.01 %: frame 1 "
                  << differing.front() * 100 << " %, frame " << scale * scale << " "
                  << differing.back() * 100 << " %; shadow edges vs rays " << e.edges * 100
                  << " %\n";
        EXPECT_GT(differing.front(), 0.05) << "the first frame is the plain reduced rate";
        EXPECT_LE(differing.back(), 0.001)
            << "scale " << scale << " did not converge in " << scale * scale << " frames";
        EXPECT_LE(e.interior, 0.01);
    }
    // Orbits over 16 frames at scale 2, each frame against the full-rate image of the same
    // camera (the director's metric: pixels beyond 5/255 of the 8-bit image): a slow one (1.5
    // degrees, about a quarter pixel a frame), where history must still help, and a fast one
    // (12 degrees, about two pixels a frame), where it must at least not hurt.
    for (const float degrees : {1.5f, 12.0f}) {
        render::RenderSettings s = shadowSettings("redeferred", 512);
        s.illumScale = 2;
        render::RenderSettings t = s;
        t.temporal = true;
        render::RenderSettings exact = s;
        exact.illumScale = 1;
        render::SceneRenderer plain(*device, scene, s), temporal(*device, scene, t),
            full(*device, scene, exact);
        double sumPlain = 0, sumTemporal = 0;
        std::ostringstream perFrame;
        constexpr uint32_t kFrames = 16;
        for (uint32_t f = 0; f < kFrames; ++f) {
            const assets::Camera cam = scene.camera->orbited(
                scene.bounds.center(), glm::radians(degrees) * float(f) / kFrames);
            for (render::SceneRenderer* r : {&plain, &temporal, &full}) {
                r->setCamera(cam);
                r->renderFrame();
            }
            const gdi::Image want = full.readOutput();
            const double ep = render::percentPixelsOver5Of255(plain.readOutput(), want, 1.0f);
            const double et = render::percentPixelsOver5Of255(temporal.readOutput(), want, 1.0f);
            perFrame << std::fixed << std::setprecision(2) << (f ? ", " : "") << et << "/" << ep;
            if (f >= 4) sumPlain += ep, sumTemporal += et;
        }
        std::cout
            << "  orbit " << degrees
            << " degrees, scale 2, % of pixels beyond 5/255 of full rate per frame (temporal/plain): "
            << perFrame.str() << "\n";
        RecordProperty("orbit_" + std::to_string(int(degrees * 10)), perFrame.str());
        if (degrees < 2.0f) {
            EXPECT_LT(sumTemporal, sumPlain * 0.8) << perFrame.str();
        } else {
            EXPECT_LE(sumTemporal, sumPlain * 1.15) << perFrame.str();
        }
    }
}

FE_INSTANTIATE_FOR_EVERY_BACKEND(Shadows);

// The plan: directional and spot lights always; the point-light budget filled by importance.
TEST(ShadowPlan, PointBudgetTakesTheMostImportantLights) {
    const assets::Scene scene = assets::makeBuiltinScene("lights", {.lights = 64});
    const render::ShadowPlan plan =
        render::planShadows(scene.lights, *scene.camera, scene.bounds, {.enabled = true});
    ASSERT_EQ(plan.shadowed.size(), 4u);
    EXPECT_EQ(plan.unshadowedCount, 60u);
    double weakestChosen = 1e300;
    for (const auto& s : plan.shadowed) {
        EXPECT_EQ(s.kind, render::ShadowKind::Cube);
        EXPECT_EQ(s.layers, 6u);
        weakestChosen =
            std::min(weakestChosen,
                     render::shadowImportance(scene.lights[s.light], *scene.camera, scene.bounds));
    }
    const std::vector<bool> casts = plan.castsShadow();
    for (size_t i = 0; i < scene.lights.size(); ++i)
        if (!casts[i]) {
            EXPECT_LE(render::shadowImportance(scene.lights[i], *scene.camera, scene.bounds),
                      weakestChosen)
                << i;
        }
    // The GPU order: unshadowed first, every light exactly once.
    std::vector<uint32_t> sorted = plan.order;
    std::sort(sorted.begin(), sorted.end());
    for (uint32_t i = 0; i < sorted.size(); ++i) {
        EXPECT_EQ(sorted[i], i);
    }
    for (uint32_t k = plan.unshadowedCount; k < plan.order.size(); ++k) {
        EXPECT_TRUE(casts[plan.order[k]]);
    }

    const render::ShadowPlan none = render::planShadows(scene.lights, *scene.camera, scene.bounds,
                                                        {.enabled = true, .pointBudget = 0});
    EXPECT_TRUE(none.shadowed.empty());
    const assets::Scene shadows = assets::makeBuiltinScene("shadows");
    const render::ShadowPlan two =
        render::planShadows(shadows.lights, *shadows.camera, shadows.bounds,
                            {.enabled = true, .cascades = 2, .pointBudget = 0});
    ASSERT_EQ(two.shadowed.size(), 2u);  // the sun (2 cascades) and the spot, not the lamp
    EXPECT_EQ(two.shadowed[0].kind, render::ShadowKind::Cascades);
    EXPECT_EQ(two.shadowed[0].layers, 2u);
    EXPECT_EQ(two.shadowed[1].kind, render::ShadowKind::Spot);
    EXPECT_TRUE(
        render::planShadows(shadows.lights, *shadows.camera, shadows.bounds, {}).shadowed.empty());
}

// A cube face's projection puts a direction where the cube lookup of both APIs reads it.
TEST(ShadowPlan, CubeFacesMatchTheCubeMapLookup) {
    const glm::vec3 light(1, 2, 3);
    // Face selection and (s, t) of the Vulkan / OpenGL specifications (table "Cube map face
    // selection"): major axis, sc, tc per face.
    auto lookup = [](glm::vec3 d, int& face, glm::vec2& st) {
        const glm::vec3 a = glm::abs(d);
        float sc, tc, ma;
        if (a.x >= a.y && a.x >= a.z)
            face = d.x > 0 ? 0 : 1, sc = d.x > 0 ? -d.z : d.z, tc = -d.y, ma = a.x;
        else if (a.y >= a.z)
            face = d.y > 0 ? 2 : 3, sc = d.x, tc = d.y > 0 ? d.z : -d.z, ma = a.y;
        else
            face = d.z > 0 ? 4 : 5, sc = d.z > 0 ? d.x : -d.x, tc = -d.y, ma = a.z;
        st = glm::vec2(sc / ma + 1, tc / ma + 1) * 0.5f;
    };
    for (glm::vec3 d :
         {glm::vec3(1, 0.2f, -0.3f), glm::vec3(-1, 0.5f, 0.1f), glm::vec3(0.3f, 1, -0.4f),
          glm::vec3(0.2f, -1, 0.6f), glm::vec3(-0.1f, 0.3f, 1), glm::vec3(0.4f, -0.2f, -1)}) {
        int face;
        glm::vec2 st;
        lookup(d, face, st);
        const glm::vec4 c = render::cubeFaceProjection(uint32_t(face), light, 0.1f, 10.0f) *
                            glm::vec4(light + d * 2.0f, 1.0f);
        EXPECT_NEAR(c.x / c.w * 0.5f + 0.5f, st.x, 1e-5f) << face;
        EXPECT_NEAR(c.y / c.w * 0.5f + 0.5f, st.y, 1e-5f) << face;
        const float w = 2.0f * std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)});
        EXPECT_NEAR(c.z / c.w, 10.0f / 9.9f * (1.0f - 0.1f / w), 1e-5f) << face;
    }
}

// Environments (assets/Environment.h, render/EnvironmentMap.h) on every backend: the cube map
// built on the GPU and drawn as the background matches the environment's exact radiance along
// each pixel's ray (the CPU reference), for builtin:sky (a closed form) and a Radiance HDR
// file; every technique draws it; a scene without one builds no background pass; bad files
// end in a clear error.
#include <gtest/gtest.h>

#include <map>

#include <sstream>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>

#include "BackendTest.h"
#include "assets/AssetError.h"
#include "assets/BuiltinScenes.h"
#include "assets/Environment.h"
#include "integration/SceneRenderer.h"
#include "render/PrefilteredEnvironment.h"
#include "shading/ShadingModel.h"
#include "reference/CpuReference.h"
#include "render/TechniqueRenderer.h"

using namespace fe;

namespace {

constexpr uint32_t kW = 96, kH = 72;

gdi::Image renderImage(gdi::Device& d, const assets::Scene& scene,
                       const std::string& technique = "forward") {
    render::SceneRenderer r(d, scene, {.technique = technique, .width = kW, .height = kH});
    r.renderFrame();
    return r.readOutput();
}

struct BackgroundStats {
    uint32_t pixels = 0, over = 0;
    double maxRel = 0;
};

// Background pixels away from silhouettes, against the reference, per channel relative error.
BackgroundStats compareBackground(const gdi::Image& img, const render::ReferenceImage& ref,
                                  double tolerance) {
    BackgroundStats s;
    for (uint32_t y = 0; y < kH; ++y)
        for (uint32_t x = 0; x < kW; ++x) {
            if (ref.surface[size_t(y) * kW + x] != -1 || ref.nearEdge(x, y)) continue;
            ++s.pixels;
            const auto t = img.texel(x, y);
            const glm::dvec3 want = ref.radiance[size_t(y) * kW + x];
            bool bad = false;
            for (int c = 0; c < 3; ++c) {
                const double rel = std::abs(t[c] - want[c]) / std::max(std::abs(want[c]), 1e-3);
                s.maxRel = std::max(s.maxRel, rel);
                bad = bad || rel > tolerance;
            }
            s.over += bad;
        }
    return s;
}

// A Radiance HDR file written flat (uncompressed RGBE scanlines), as the format allows.
void writeHdr(const std::string& path, uint32_t w, uint32_t h,
              const std::function<glm::dvec3(uint32_t, uint32_t)>& texel) {
    std::ofstream f(path, std::ios::binary);
    f << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " << h << " +X " << w << "\n";
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const glm::dvec3 c = texel(x, y);
            const double m = std::max({c.r, c.g, c.b});
            unsigned char rgbe[4] = {0, 0, 0, 0};
            if (m > 1e-32) {
                int e;
                const double scale = std::frexp(m, &e) * 256.0 / m;
                rgbe[0] = (unsigned char)(c.r * scale), rgbe[1] = (unsigned char)(c.g * scale);
                rgbe[2] = (unsigned char)(c.b * scale), rgbe[3] = (unsigned char)(e + 128);
            }
            f.write(reinterpret_cast<const char*>(rgbe), 4);
        }
}

class Environment : public fe::testing::BackendTest {
protected:
    Environment() : BackendTest(true) {}  // the cases share a device (BackendTest.h)
};

}  // namespace

// builtin:sky seen level (horizon, sky and ground) and towards the sun (its disc and limb): the
// background is the sky's closed form to 2 % on 99 % of pixels (the cube map is 256 texels a
// face, sampled bilinearly from its top level), except on the sun's limb, where bilinear
// interpolation of the smoothstep across 0.35-degree texels errs by up to |f''| h^2 / 8 = 6 /
// (1 degree)^2 x (0.35 degree)^2 / 8 = 0.092 of the sun's radiance: bounded by 0.1 there.
TEST_P(Environment, SkyBackgroundMatchesItsClosedForm) {
    assets::Scene scene = assets::makeBuiltinScene("spheres", {.sphereGrid = 2});
    scene.environment = assets::loadEnvironment("builtin:sky");
    const assets::Camera level = *scene.camera;
    for (int view = 0; view < 2; ++view) {
        if (view == 1) {
            const glm::vec3 sun = glm::vec3(scene.environment->sky.sunDirection);
            scene.camera =
                assets::Camera::lookAlong(level.eye(), sun, {0, 1, 0}, 0.3f, 0.1f, 100.0f);
        }
        const render::ReferenceImage ref = render::renderReference(scene, *scene.camera, kW, kH);
        const gdi::Image img = renderImage(*device, scene);
        // The limb band (half a degree either side) is checked against the interpolation bound.
        const assets::SkyModel& sky = scene.environment->sky;
        const double pi = 3.14159265358979;
        render::ReferenceImage outsideLimb = ref;
        uint32_t limbPixels = 0;
        double limbMax = 0;
        const glm::dvec3 forward(scene.camera->forward()), up(scene.camera->up()),
            right = glm::cross(forward, up);
        const double tanHalf = std::tan(scene.camera->yfov / 2), aspect = double(kW) / kH;
        for (uint32_t y = 0; y < kH; ++y)
            for (uint32_t x = 0; x < kW; ++x) {
                const double nx = ((x + 0.5) / kW * 2 - 1) * tanHalf * aspect,
                             ny = (1 - (y + 0.5) / kH * 2) * tanHalf;
                const glm::dvec3 d = glm::normalize(forward + nx * right + ny * up);
                const double angle =
                    std::acos(std::clamp(glm::dot(d, sky.sunDirection), -1.0, 1.0)) * 180 / pi;
                if (angle < sky.sunInnerDegrees - 0.5 || angle > sky.sunOuterDegrees + 0.5)
                    continue;
                if (ref.surface[size_t(y) * kW + x] >= 0) continue;
                ++limbPixels;
                limbMax = std::max(
                    limbMax, std::abs(img.texel(x, y)[0] - ref.radiance[size_t(y) * kW + x].r));
                outsideLimb.surface[size_t(y) * kW + x] =
                    -2;  // excluded from the relative comparison
            }
        if (view == 1) {
            std::cout << "sun limb: " << limbPixels << " pixels, max absolute error " << limbMax
                      << " (sun radiance " << sky.sunRadiance.r << ")\n";
            EXPECT_GT(limbPixels, 50u);
            EXPECT_LE(limbMax, 0.1 * sky.sunRadiance.r);
        }
        const BackgroundStats s = compareBackground(img, outsideLimb, 0.02);
        std::cout << (view ? "towards the sun" : "level") << ": " << s.pixels
                  << " background pixels, " << s.over << " beyond 2 %, max relative error "
                  << s.maxRel << "\n";
        ASSERT_GT(s.pixels, kW * kH / 4);
        EXPECT_LE(s.over, s.pixels / 100);
        if (view == 1) {  // the sun disc is in view: its centre pixel holds the sun's radiance
            const double centre = ref.radiance[size_t(kH / 2) * kW + kW / 2].r;
            EXPECT_GT(centre, scene.environment->sky.sunRadiance.r)
                << "the sun is not at the centre";
        }
    }
}

// A Radiance HDR file: a smooth function of direction stored as a 64x32 equirectangular image;
// the GPU samples it into the cube and the cube along each ray, the reference samples the image
// once: 2 % on 99 % of pixels.
TEST_P(Environment, HdrBackgroundMatchesTheImage) {
    const std::string path =
        (std::filesystem::temp_directory_path() / ("fe_env_" + GetParam() + ".hdr")).string();
    writeHdr(path, 64, 32, [](uint32_t x, uint32_t y) {
        const glm::dvec3 d = assets::directionFromEquirect({(x + 0.5) / 64.0, (y + 0.5) / 32.0});
        return glm::dvec3(1.0 + 0.5 * d.x, 1.0 + 0.5 * d.y, 1.0 - 0.5 * d.z);
    });
    assets::Scene scene = assets::makeBuiltinScene("spheres", {.sphereGrid = 2});
    scene.environment = assets::loadEnvironment(path);
    EXPECT_EQ(scene.environment->kind, assets::Environment::Kind::Image);
    EXPECT_EQ(scene.environment->width, 64u);
    const render::ReferenceImage ref = render::renderReference(scene, *scene.camera, kW, kH);
    const BackgroundStats s = compareBackground(renderImage(*device, scene), ref, 0.02);
    std::cout << s.pixels << " background pixels, " << s.over << " beyond 2 %, max relative error "
              << s.maxRel << "\n";
    ASSERT_GT(s.pixels, kW * kH / 4);
    EXPECT_LE(s.over, s.pixels / 100);
    std::filesystem::remove(path);
}

// Every technique draws the same background (the scene renderer's pass, after the technique),
// and only when the scene has an environment.
TEST_P(Environment, EveryTechniqueDrawsItOnlyWithAnEnvironment) {
    assets::Scene scene = assets::makeBuiltinScene("spheres", {.sphereGrid = 2});
    {
        render::SceneRenderer r(*device, scene,
                                {.technique = "forward", .width = kW, .height = kH});
        for (const auto& p : r.graph().passes()) EXPECT_NE(p.name, "background");
    }
    scene.environment = assets::loadEnvironment("builtin:sky");
    const render::ReferenceImage ref = render::renderReference(scene, *scene.camera, kW, kH);
    for (const render::TechniqueInfo& t : render::techniques()) {
        if (std::string(t.name).find("tiled") != std::string::npos &&
            !device->info().features.computeShaders)
            continue;
        render::SceneRenderer r(*device, scene, {.technique = t.name, .width = kW, .height = kH});
        bool background = false;
        for (const auto& p : r.graph().passes())
            background = background || (p.name == "background" && !p.culled);
        EXPECT_TRUE(background) << t.name;
        r.renderFrame();
        const BackgroundStats s = compareBackground(r.readOutput(), ref, 0.02);
        EXPECT_LE(s.over, s.pixels / 100) << t.name;
    }
}

namespace {
// Lit pixels away from silhouettes: the fraction beyond `tolerance` relative error (floored at
// 1e-2 absolute), and the largest.
struct LitStats {
    double fractionOver = 0, maxRel = 0;
};
LitStats compareLit(const std::function<glm::dvec3(uint32_t, uint32_t)>& a,
                    const render::ReferenceImage& ref, double tolerance, uint32_t w, uint32_t h) {
    uint32_t n = 0, over = 0;
    LitStats s;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            if (ref.surface[size_t(y) * w + x] < 0 || ref.nearEdge(x, y)) continue;
            ++n;
            const glm::dvec3 p = a(x, y), q = ref.radiance[size_t(y) * w + x];
            bool bad = false;
            for (int c = 0; c < 3; ++c) {
                const double rel =
                    std::abs(p[c] - q[c]) / std::max({std::abs(p[c]), std::abs(q[c]), 1e-2});
                s.maxRel = std::max(s.maxRel, rel);
                bad = bad || rel > tolerance;
            }
            over += bad;
        }
    s.fractionOver = n ? double(over) / n : 1.0;
    return s;
}
}  // namespace

namespace {
// The 5x5 spheres at 48x36 lit by builtin:sky without its sun and no punctual light: the
// environment's light alone, smooth enough for 64 samples to mean something.
constexpr uint32_t kIblW = 48, kIblH = 36;
assets::Scene skyLitSpheres() {
    assets::Scene scene = assets::makeBuiltinScene("spheres", {.sphereGrid = 5});
    scene.lights.clear();
    scene.environment = assets::loadEnvironment("builtin:sky");
    scene.environment->sky.sunRadiance = glm::dvec3(0.0);
    return scene;
}
// L_o of `technique` with `samples` per term, or the fast path when samples is 0.
gdi::Image renderIbl(gdi::Device& device, const assets::Scene& scene, const std::string& technique,
                     uint32_t samples, render::ShadingModel model = render::ShadingModel::Auto,
                     uint32_t msaa = 1) {
    render::RenderSettings s{.technique = technique,
                             .width = kIblW,
                             .height = kIblH,
                             .msaa = msaa,
                             .iblSamples = samples};
    s.shadingModel = model;
    s.iblPrefiltered = samples == 0;
    render::SceneRenderer r(device, scene, s);
    r.renderFrame();
    return r.readOutput();
}
// An image as compareLit's pixel function.
std::function<glm::dvec3(uint32_t, uint32_t)> asFunction(const gdi::Image& img) {
    return [&img](uint32_t x, uint32_t y) {
        const auto t = img.texel(x, y);
        return glm::dvec3(t[0], t[1], t[2]);
    };
}
}  // namespace

// Image-based lighting (forward): the GPU evaluates the reference's estimator with the same
// Hammersley sequence and basis, so at the same sample count they differ only by single
// precision and the cube map's interpolation: 2 % on 99 % of lit pixels, for a sky without its
// sun (whose limb the cube blurs, see above). Against the converged integral (the reference
// at 4096 samples, itself within 1 % of 8192 on 99 % of pixels) the error falls as samples grow.
TEST_P(Environment, ForwardImageBasedLightingIsTheReferenceEstimator) {
    constexpr uint32_t W = kIblW, H = kIblH;
    const assets::Scene scene = skyLitSpheres();
    auto gpu = [&](uint32_t samples, const std::string& technique = "forward") {
        return renderIbl(*device, scene, technique, samples);
    };
    const gdi::Image g64 = gpu(64);
    const LitStats same = compareLit(
        asFunction(g64), render::renderReference(scene, *scene.camera, W, H, {.iblSamples = 64}),
        0.02, W, H);
    std::cout << "64 samples, GPU against the reference's same estimator: "
              << same.fractionOver * 100 << " % beyond 2 %, max " << same.maxRel << "\n";
    EXPECT_LE(same.fractionOver, 0.01);
    // The other forward techniques add the same term.
    for (const char* t : {"forward-zprepass", "forward-multipass"}) {
        const gdi::Image other = gpu(64, t);
        uint32_t differ = 0;
        for (uint32_t y = 0; y < H; ++y)
            for (uint32_t x = 0; x < W; ++x)
                for (int c = 0; c < 3; ++c)
                    differ += std::abs(other.texel(x, y)[c] - g64.texel(x, y)[c]) >
                              1e-4f * (1.0f + g64.texel(x, y)[c]);
        EXPECT_EQ(differ, 0u) << t;
    }
    // The G-buffer techniques add the same estimator in a pass of their own, from the G-buffer's
    // rounded inputs (8-bit sRGB base colour, half-float normal and roughness): within 2 % of
    // forward on 99 % of lit pixels, as their punctual lighting is.
    const render::ReferenceImage ref64 =
        render::renderReference(scene, *scene.camera, W, H, {.iblSamples = 64});
    const render::ReferenceImage ref64Separable = render::renderReference(
        scene, *scene.camera, W, H, {.iblSamples = 64, .brdf = shading::Brdf::Separable});
    // The two BRDFs light these spheres differently (so comparing each technique with its own is
    // a test): measured 2026-11-29, 63 % of lit pixels more than 2 % apart.
    const LitStats models = compareLit(
        [&](uint32_t x, uint32_t y) { return ref64Separable.radiance[size_t(y) * W + x]; }, ref64,
        0.02, W, H);
    std::cout << "separable against glTF image-based light: " << models.fractionOver * 100
              << " % beyond 2 %\n";
    EXPECT_GE(models.fractionOver, 0.2);
    // Forward under the separable model evaluates it too.
    const LitStats forwardSeparable = compareLit(
        asFunction(renderIbl(*device, scene, "forward", 64, render::ShadingModel::Separable)),
        ref64Separable, 0.02, W, H);
    EXPECT_LE(forwardSeparable.fractionOver, 0.01);
    // Redeferred accumulates it into the I-buffer as the seed derives L_dg, L_sg1 and L_sg2.
    // The light pre-pass adds it in its material pass, exactly (the pass has the whole material).
    // Every technique of the table, against the reference under its own BRDF (glTF's, or the
    // separable one where the technique needs it): a new one must light by the environment to pass.
    for (const render::TechniqueInfo& info : render::techniques()) {
        const std::string t = info.name;
        if (t.find("tiled") != std::string::npos && !device->info().features.computeShaders)
            continue;
        const gdi::Image other = gpu(64, t);
        const bool separable = render::resolveBrdf({.technique = t}) == shading::Brdf::Separable;
        const LitStats d =
            compareLit(asFunction(other), separable ? ref64Separable : ref64, 0.02, W, H);
        std::cout << t
                  << " at 64 samples against the reference's estimator: " << d.fractionOver * 100
                  << " % beyond 2 %\n";
        // Of the 144 lit pixels, the G-buffer's rounding puts one beyond 2 % on lavapipe and two
        // on an H100 (2026-11-27; forward: one on both): 2 % (2 pixels) for the deferred family.
        EXPECT_LE(d.fractionOver, t.find("deferred") != std::string::npos ? 0.02 : 0.01) << t;
    }
    // At a reduced illumination rate the environment's sums are upsampled like the lights':
    // measured (at 48x36 a sphere is about 7 pixels wide, 2 I-buffer texels at scale 4), and
    // bounded only against garbage.
    for (uint32_t scale : {2u, 4u}) {
        render::SceneRenderer r(*device, scene,
                                {.technique = "redeferred",
                                 .width = W,
                                 .height = H,
                                 .illumScale = scale,
                                 .iblSamples = 64});
        r.renderFrame();
        const gdi::Image img = r.readOutput();
        const LitStats d = compareLit(asFunction(img), ref64Separable, 0.05, W, H);
        std::cout << "redeferred illum-scale " << scale
                  << " at 64 samples: " << d.fractionOver * 100
                  << " % of lit pixels beyond 5 % of the reference's estimator\n";
        RecordProperty("ibl_redeferred_scale" + std::to_string(scale),
                       std::to_string(d.fractionOver));
        EXPECT_LT(d.fractionOver, 0.95);
    }
    // Every technique that takes it builds its passes for it.
    {
        render::SceneRenderer r(
            *device, scene, {.technique = "deferred", .width = W, .height = H, .iblSamples = 8});
        bool ibl = false;
        for (const auto& p : r.graph().passes()) ibl = ibl || (p.name == "ibl" && !p.culled);
        EXPECT_TRUE(ibl);
    }
    const render::ReferenceImage converged =
        render::renderReference(scene, *scene.camera, W, H, {.iblSamples = 4096});
    const render::ReferenceImage doubled =
        render::renderReference(scene, *scene.camera, W, H, {.iblSamples = 8192});
    const LitStats settle =
        compareLit([&](uint32_t x, uint32_t y) { return doubled.radiance[size_t(y) * W + x]; },
                   converged, 0.01, W, H);
    std::cout << "reference 4096 against 8192 samples: " << settle.fractionOver * 100
              << " % beyond 1 %\n";
    EXPECT_LE(settle.fractionOver, 0.01);
    double previous = 2.0;
    for (uint32_t n : {4u, 16u, 64u, 256u, 1024u}) {
        const gdi::Image g = n == 64 ? g64 : gpu(n);
        const LitStats e = compareLit(asFunction(g), converged, 0.02, W, H);
        std::cout << n << " samples against the converged integral: " << e.fractionOver * 100
                  << " % of lit pixels beyond 2 %\n";
        RecordProperty("ibl_fraction_over_" + std::to_string(n), std::to_string(e.fractionOver));
        EXPECT_LE(e.fractionOver, previous) << n;
        previous = e.fractionOver;
    }
    EXPECT_LT(previous, 0.05) << "1024 samples should be near the integral";
}

// The occlusion texture darkens the environment's light by 1 + strength (ao - 1) (glTF 2.0), on
// the techniques that shade the material where they add it (forward, forward-plus, the light
// pre-pass's material pass, the visibility buffer): each is the reference's estimator to 2 % on
// 99 % of lit pixels, and the occlusion is visible (the reference without it is not).
TEST_P(Environment, OcclusionTextureDarkensImageBasedLight) {
    constexpr uint32_t W = kIblW, H = kIblH;
    assets::Scene scene = skyLitSpheres();
    assets::TextureImage ao;  // a 4x4 checker of occlusion 0.25 and 1, linear, nearest
    ao.name = "occlusion checker";
    ao.width = ao.height = 4;
    for (uint32_t i = 0; i < 16; ++i) {
        const uint8_t v = ((i % 4) + (i / 4)) % 2 ? 255 : 64;
        ao.pixels.insert(ao.pixels.end(), {v, v, v, 255});
    }
    ao.sampler.magFilter = ao.sampler.minFilter = assets::Filter::Nearest;
    ao.sampler.mipFilter = assets::MipFilter::None;
    ao.sampler.mipmaps = false;
    scene.textures.push_back(ao);
    for (assets::Material& m : scene.materials) {
        m.occlusionTexture.index = int32_t(scene.textures.size() - 1);
        m.occlusionStrength = 0.8f;
    }
    const render::ReferenceImage ref =
        render::renderReference(scene, *scene.camera, W, H, {.iblSamples = 64});
    assets::Scene unoccluded = scene;
    for (assets::Material& m : unoccluded.materials) m.occlusionTexture = {};
    const render::ReferenceImage plain =
        render::renderReference(unoccluded, *unoccluded.camera, W, H, {.iblSamples = 64});
    const LitStats visible = compareLit(
        [&](uint32_t x, uint32_t y) { return plain.radiance[size_t(y) * W + x]; }, ref, 0.02, W, H);
    EXPECT_GE(visible.fractionOver, 0.2) << "the occlusion texture hardly changes the reference";
    const render::ReferenceImage refSeparable = render::renderReference(
        scene, *scene.camera, W, H, {.iblSamples = 64, .brdf = shading::Brdf::Separable});
    // Every technique of the table: the G-buffer ones store the occlusion in a fourth target
    // (GBuffer::gb3) for their image-based lighting pass; the G-buffer's rounding allows them 2 %.
    for (const render::TechniqueInfo& info : render::techniques()) {
        const std::string t = info.name;
        if (t.find("tiled") != std::string::npos && !device->info().features.computeShaders)
            continue;
        const gdi::Image img = renderIbl(*device, scene, t, 64);
        const bool separable = render::resolveBrdf({.technique = t}) == shading::Brdf::Separable;
        const LitStats d = compareLit(asFunction(img), separable ? refSeparable : ref, 0.02, W, H);
        std::cout << t << " with an occlusion texture, 64 samples: " << d.fractionOver * 100
                  << " % beyond 2 %\n";
        EXPECT_LE(d.fractionOver, t.find("deferred") != std::string::npos ? 0.02 : 0.01)
            << t << " max " << d.maxRel;
    }
    // The fourth target exists only where it is needed: with occlusion and image-based light.
    auto hasOcclusionTarget = [&](const assets::Scene& sc, uint32_t samples) {
        render::SceneRenderer r(
            *device, sc, {.technique = "deferred", .width = W, .height = H, .iblSamples = samples});
        for (const graph::TextureInfo& t : r.graph().textures())
            if (t.name == "gbuffer3 occlusion") return true;
        return false;
    };
    EXPECT_TRUE(hasOcclusionTarget(scene, 8));
    EXPECT_FALSE(hasOcclusionTarget(unoccluded, 8));
    // At 4 samples the G-buffer techniques read the occlusion target per sample (and, without
    // one, no occlusion): against forward at 4 samples, within their 2 % on 98 % of pixels.
    if (device->info().limits.colorSampleCounts & device->info().limits.depthSampleCounts & 4)
        for (const assets::Scene* sc : {&scene, &unoccluded}) {
            const gdi::Image forward = renderIbl(*device, *sc, "forward", 64, {}, 4);
            for (const char* t : {"deferred", "clustered-deferred"}) {
                const gdi::Image img = renderIbl(*device, *sc, t, 64, {}, 4);
                uint32_t over = 0;
                for (uint32_t y = 0; y < H; ++y)
                    for (uint32_t x = 0; x < W; ++x)
                        for (int c = 0; c < 3; ++c) {
                            const float a = img.texel(x, y)[c], b = forward.texel(x, y)[c];
                            if (std::abs(a - b) > 0.02f * std::max(std::abs(b), 0.01f)) {
                                ++over;
                                break;
                            }
                        }
                EXPECT_LE(over, W * H / 50)
                    << t << " at 4 samples, " << (sc == &scene ? "with" : "without")
                    << " the occlusion texture";
            }
        }
    assets::Scene noIbl = scene;
    noIbl.environment.reset();
    EXPECT_FALSE(hasOcclusionTarget(noIbl, 0));
}

// The fast path (prefiltered cube, split-sum table, SH irradiance) against the converged
// integral, beside the sampled estimator at 64 and 1024 samples: its bias is the price of its
// speed (docs/BENCHMARKS.md). Every technique takes it, and gives what forward gives.
TEST_P(Environment, PrefilteredFastPathBiasIsMeasured) {
    constexpr uint32_t W = kIblW, H = kIblH;
    const assets::Scene scene = skyLitSpheres();
    auto gpu = [&](const std::string& technique, uint32_t samples) {
        return renderIbl(*device, scene, technique, samples);
    };
    const render::ReferenceImage converged =
        render::renderReference(scene, *scene.camera, W, H, {.iblSamples = 4096});
    const gdi::Image fastGltf = gpu("forward", 0), &fast = fastGltf;
    const gdi::Image sampled64 = gpu("forward", 64);
    std::ostringstream table;
    for (double tolerance : {0.02, 0.05, 0.10}) {
        const LitStats f = compareLit(asFunction(fast), converged, tolerance, W, H);
        const LitStats s64 = compareLit(asFunction(sampled64), converged, tolerance, W, H);
        table << "beyond " << tolerance * 100 << " %: prefiltered " << f.fractionOver * 100
              << " % (max " << f.maxRel * 100 << " %), sampled 64: " << s64.fractionOver * 100
              << " %\n";
        if (tolerance == 0.10) {
            EXPECT_LE(f.fractionOver, 0.10)
                << "the fast path is off the integral by more than 10 % on many pixels";
            EXPECT_LT(f.maxRel, 0.5);
        }
    }
    std::cout << table.str();
    RecordProperty("prefiltered_bias", table.str());
    for (const render::TechniqueInfo& info : render::techniques()) {
        const std::string t = info.name;
        if (t == "forward" ||
            (t.find("tiled") != std::string::npos && !device->info().features.computeShaders))
            continue;
        const gdi::Image other = gpu(t, 0);
        // Against forward under the technique's own BRDF.
        const bool separable = render::resolveBrdf({.technique = t}) == shading::Brdf::Separable;
        const gdi::Image fast =
            separable ? renderIbl(*device, scene, "forward", 0, render::ShadingModel::Separable)
                      : fastGltf;
        uint32_t differ = 0, lit = 0;
        for (uint32_t y = 0; y < H; ++y)
            for (uint32_t x = 0; x < W; ++x) {
                if (converged.surface[size_t(y) * W + x] < 0 || converged.nearEdge(x, y)) continue;
                ++lit;
                for (int c = 0; c < 3; ++c)
                    if (std::abs(other.texel(x, y)[c] - fast.texel(x, y)[c]) >
                        0.02f * std::max(fast.texel(x, y)[c], 0.01f)) {
                        ++differ;
                        break;
                    }
            }
        EXPECT_LE(differ, lit / 100) << t;  // G-buffer rounding, as for the sampled estimator
    }
}

// Under a constant environment the fast path's approximations vanish (prefiltered radiance is
// the constant, SH irradiance pi times it): what is left is its table, which must be the BRDF's
// own. Each BRDF's fast path against the reference of its BRDF, and against the other's (the
// test would not notice a table read from the wrong half otherwise).
TEST_P(Environment, PrefilteredTablesAreEachBrdfs) {
    constexpr uint32_t W = kIblW, H = kIblH;
    assets::Scene scene = skyLitSpheres();
    assets::Environment white;
    white.kind = assets::Environment::Kind::Image;
    white.name = "constant";
    white.width = 16;
    white.height = 8;
    white.rgb.assign(16 * 8 * 3, 1.0f);
    scene.environment = white;
    using shading::Brdf;
    std::map<Brdf, render::ReferenceImage> reference;
    for (Brdf b : {Brdf::Gltf, Brdf::Separable})
        reference.emplace(b, render::renderReference(scene, *scene.camera, W, H,
                                                     {.iblSamples = 1024, .brdf = b}));
    for (Brdf b : {Brdf::Gltf, Brdf::Separable}) {
        const gdi::Image fast = renderIbl(
            *device, scene, "forward", 0,
            b == Brdf::Gltf ? render::ShadingModel::Gltf : render::ShadingModel::Separable);
        const LitStats own = compareLit(asFunction(fast), reference.at(b), 0.06, W, H);
        const LitStats other =
            compareLit(asFunction(fast),
                       reference.at(b == Brdf::Gltf ? Brdf::Separable : Brdf::Gltf), 0.06, W, H);
        std::cout << (b == Brdf::Gltf ? "glTF" : "separable")
                  << " fast path under a constant environment: " << own.fractionOver * 100
                  << " % beyond 6 % of its BRDF's reference (max " << own.maxRel * 100 << " %), "
                  << other.fractionOver * 100 << " % of the other's\n";
        EXPECT_LE(own.fractionOver, 0.02);
        EXPECT_GE(other.fractionOver, 0.2);
    }
}

// The irradiance harmonics: exact for a constant environment (E = pi L), and within a few
// percent of a brute-force cosine integral of builtin:sky (an L2 expansion's known error).
TEST(EnvironmentLoad, IrradianceHarmonics) {
    assets::Environment flat;
    flat.kind = assets::Environment::Kind::Image;
    flat.width = 64;
    flat.height = 32;
    flat.rgb.assign(64 * 32 * 3, 2.0f);
    const auto constant = render::radianceSH(flat);
    for (glm::dvec3 n :
         {glm::dvec3(0, 1, 0), glm::dvec3(1, 0, 0), glm::normalize(glm::dvec3(1, -2, 3))})
        EXPECT_NEAR(render::irradianceFromSH(constant, n).g, 2.0 * 3.14159265358979, 0.01)
            << n.x << n.y << n.z;
    const assets::Environment sky = assets::loadEnvironment("builtin:sky");
    const auto sh = render::radianceSH(sky);
    for (glm::dvec3 n : {glm::dvec3(0, 1, 0), glm::dvec3(0, -1, 0), glm::dvec3(1, 0, 0),
                         glm::normalize(glm::dvec3(0.3, 0.2, -1))}) {
        glm::dvec3 t, b, E(0.0);
        shading::basis(n, t, b);
        constexpr uint32_t kN = 200000;  // cosine-weighted: E = pi mean(L)
        for (uint32_t i = 0; i < kN; ++i) {
            const glm::dvec2 u = shading::hammersley(i, kN);
            const double phi = 2.0 * 3.14159265358979 * u.y, c = std::sqrt(1.0 - u.x),
                         s = std::sqrt(u.x);
            E += sky.radiance(t * (s * std::cos(phi)) + b * (s * std::sin(phi)) + n * c);
        }
        E *= 3.14159265358979 / kN;
        const glm::dvec3 approx = render::irradianceFromSH(sh, n);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(approx[c], E[c], 0.05 * E[c]) << "n " << n.x << " " << n.y << " " << n.z;
    }
}

// A sun of 1e5 (the sky's own sun is 40) over smooth spheres (the first column sits at the
// roughness clamp, every silhouette at grazing angles), lit by the environment, a shadowed key
// light and unshadowed lights: no technique may produce a non-finite pixel.
TEST_P(Environment, ExtremeDynamicRangeStaysFinite) {
    constexpr uint32_t W = 48, H = 36;
    assets::Scene scene = assets::makeBuiltinScene("spheres", {.sphereGrid = 4});
    scene.environment = assets::loadEnvironment("builtin:sky");
    scene.environment->sky.sunRadiance = glm::dvec3(1e5);
    scene.environment->sky.sunDirection =
        glm::normalize(glm::dvec3(0.2, 0.3, 1.0));  // facing the spheres
    for (const render::TechniqueInfo& info : render::techniques()) {
        const std::string t = info.name;
        if (t.find("tiled") != std::string::npos && !device->info().features.computeShaders)
            continue;
        for (uint32_t scale : {1u, 4u}) {
            if (scale > 1 && !info.illumScale) continue;
            render::RenderSettings s{
                .technique = t, .width = W, .height = H, .illumScale = scale, .iblSamples = 16};
            s.shadows = {.enabled = true, .mapSize = 256};
            render::SceneRenderer r(*device, scene, s);
            r.renderFrame();
            const gdi::Image img = r.readOutput();
            uint32_t bad = 0;
            for (uint32_t y = 0; y < H; ++y)
                for (uint32_t x = 0; x < W; ++x)
                    for (int c = 0; c < 4; ++c) bad += !std::isfinite(img.texel(x, y)[c]);
            EXPECT_EQ(bad, 0u) << t << " illum-scale " << scale;
        }
    }
}

// With a sun facing the spheres (3 degrees wide, 40x the sky's radiance, and 1000x as a sun
// that dominates): cosine-weighted diffuse samples seldom hit so small a source, so convergence
// is measured: the reference's own (4096 against 8192 samples) and the GPU's error at 64 and
// 256 (docs/BENCHMARKS.md).
TEST_P(Environment, SunlitImageBasedLightingIsMeasured) {
    for (double sun : {40.0, 40000.0}) {
        constexpr uint32_t W = 48, H = 36;
        assets::Scene scene = assets::makeBuiltinScene("spheres", {.sphereGrid = 5});
        scene.lights.clear();
        scene.environment = assets::loadEnvironment("builtin:sky");
        scene.environment->sky.sunRadiance = glm::dvec3(sun, sun * 0.95, sun * 0.85);
        // Behind the camera and above, so the spheres' visible sides face it (builtin:sky's own sun
        // is behind the spheres, lighting almost no visible pixel).
        scene.environment->sky.sunDirection = glm::normalize(glm::dvec3(0.3, 0.5, 0.81));
        std::cout << "sun radiance " << sun << ":\n";
        const render::ReferenceImage converged =
            render::renderReference(scene, *scene.camera, W, H, {.iblSamples = 8192});
        const render::ReferenceImage half =
            render::renderReference(scene, *scene.camera, W, H, {.iblSamples = 4096});
        const LitStats settle =
            compareLit([&](uint32_t x, uint32_t y) { return half.radiance[size_t(y) * W + x]; },
                       converged, 0.02, W, H);
        std::cout << "with the sun, reference 4096 against 8192 samples: "
                  << settle.fractionOver * 100 << " % beyond 2 %\n";
        RecordProperty("sun" + std::to_string(int(sun)) + "_reference_4096_vs_8192",
                       std::to_string(settle.fractionOver));
        for (uint32_t n : {64u, 256u}) {
            render::SceneRenderer r(*device, scene, {.width = W, .height = H, .iblSamples = n});
            r.renderFrame();
            const gdi::Image img = r.readOutput();
            const LitStats e = compareLit(
                [&](uint32_t x, uint32_t y) {
                    const auto t = img.texel(x, y);
                    return glm::dvec3(t[0], t[1], t[2]);
                },
                converged, 0.02, W, H);
            std::cout << "with the sun, " << n << " samples against 8192: " << e.fractionOver * 100
                      << " % of lit pixels beyond 2 % (max " << e.maxRel << ")\n";
            RecordProperty("sun" + std::to_string(int(sun)) + "_fraction_over_" + std::to_string(n),
                           std::to_string(e.fractionOver));
            EXPECT_TRUE(std::isfinite(e.maxRel));
        }
    }
}

// Image-based lighting needs an environment and a technique that takes it.
TEST_P(Environment, ImageBasedLightingRefusals) {
    assets::Scene scene = assets::makeBuiltinScene("spheres", {.sphereGrid = 2});
    EXPECT_NE(fe::testing::errorOf([&] {
                  render::SceneRenderer r(*device, scene, {.iblSamples = 16});
              }).find("--ibl-samples needs an environment"),
              std::string::npos);
    scene.environment = assets::loadEnvironment("builtin:sky");
    if (device->info().features.computeShaders) {
        EXPECT_NE(fe::testing::errorOf([&] {
                      render::SceneRenderer r(*device, scene,
                                              {.technique = "redeferred-tiled",
                                               .illumScale = 2,
                                               .illumSplit = true,
                                               .iblSamples = 16});
                  }).find("--illum-split does not take image-based lighting yet"),
                  std::string::npos);
    }
}

FE_INSTANTIATE_FOR_EVERY_BACKEND(Environment);

// Bad environments end in an AssetError naming the file and the fault.
TEST(EnvironmentLoad, BadFilesAreRefusedWithTheReason) {
    auto errorOf = [](const std::string& spec) {
        try {
            assets::loadEnvironment(spec);
        } catch (const assets::AssetError& e) {
            return std::string(e.what());
        }
        return std::string("(no error)");
    };
    EXPECT_NE(
        errorOf("/nonexistent/sky.hdr").find("/nonexistent/sky.hdr: environment file not found"),
        std::string::npos);
    EXPECT_NE(errorOf("builtin:moon").find("unknown environment 'builtin:moon' (builtin: sky)"),
              std::string::npos);
    const auto dir = std::filesystem::temp_directory_path();
    const std::string png = (dir / "fe_env_not_hdr.hdr").string();
    std::ofstream(png, std::ios::binary) << "\x89PNG\r\n\x1a\n";
    EXPECT_NE(errorOf(png).find("not a Radiance HDR file"), std::string::npos) << errorOf(png);
    const std::string truncated = (dir / "fe_env_truncated.hdr").string();
    std::ofstream(truncated, std::ios::binary)
        << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 4\n\x01\x02";
    EXPECT_NE(errorOf(truncated).find(
                  "truncated Radiance HDR image: 2 bytes of pixels, 64 needed for 4x4"),
              std::string::npos)
        << errorOf(truncated);
    const std::string garbage = (dir / "fe_env_garbage.hdr").string();
    std::ofstream(garbage, std::ios::binary) << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\nnonsense\n";
    EXPECT_NE(errorOf(garbage).find("cannot read the Radiance HDR image"), std::string::npos)
        << errorOf(garbage);
    std::filesystem::remove(garbage);
    std::filesystem::remove(png);
    std::filesystem::remove(truncated);
}

// The closed form and the equirectangular mapping (their inverse pairs and fixed points).
TEST(EnvironmentLoad, SkyAndMapping) {
    const assets::SkyModel sky;
    EXPECT_NEAR(sky.radiance({0, 1, 0}).b, sky.zenith.b, 1e-12);
    EXPECT_NEAR(sky.radiance({0, -1, 0}).r, sky.ground.r, 1e-12);
    EXPECT_GT(sky.radiance(sky.sunDirection).r, sky.sunRadiance.r);
    const glm::dvec2 centre = assets::equirectFromDirection({0, 0, -1});
    EXPECT_NEAR(centre.x, 0.5, 1e-12);
    EXPECT_NEAR(centre.y, 0.5, 1e-12);
    for (double u : {0.1, 0.4, 0.9})
        for (double v : {0.2, 0.5, 0.8}) {
            const glm::dvec2 back =
                assets::equirectFromDirection(assets::directionFromEquirect({u, v}));
            EXPECT_NEAR(back.x, u, 1e-9);
            EXPECT_NEAR(back.y, v, 1e-9);
        }
}

#include "integration/RenderDirector.h"

#include "render/ShadowPlan.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "integration/SceneRenderer.h"
#include "render/TechniqueRenderer.h"

namespace fe::render {

namespace {

std::string fixed(double v, int digits = 1) {
    char b[32];
    std::snprintf(b, sizeof b, "%.*f", digits, v);
    return b;
}

// Screen fraction covered by a light's range sphere seen from `cam` (see SceneNeeds).
double coverage(const assets::Light& l, const assets::Camera& cam, float aspect) {
    if (l.type == assets::LightType::Directional || !(l.range > 0.0f)) return 1.0;
    const glm::vec3 c = glm::vec3(cam.viewFromWorld() * glm::vec4(l.position, 1.0f));
    const double d = glm::length(c), r = l.range;
    if (d <= r) return 1.0;   // the eye is inside the volume
    if (c.z > r) return 0.0;  // wholly behind the eye
    const double rho =
        r / (std::sqrt(d * d - r * r) * std::tan(cam.yfov / 2));  // disc radius, NDC y units
    return std::min(1.0, 3.14159265358979 * rho * rho / (4.0 * aspect));
}

// Perceptual roughness range of a material: its factor times the range of its texture's G.
std::pair<float, float> roughnessRange(const assets::Scene& scene, const assets::Material& m) {
    float lo = 1.0f, hi = 1.0f;
    if (m.metallicRoughnessTexture.valid()) {
        const assets::TextureImage& t = scene.textures[m.metallicRoughnessTexture.index];
        lo = 1.0f, hi = 0.0f;
        for (size_t i = 1; i < t.pixels.size(); i += 4)
            lo = std::min(lo, t.pixels[i] / 255.0f), hi = std::max(hi, t.pixels[i] / 255.0f);
        if (t.pixels.empty()) lo = hi = 1.0f;
    }
    return {m.roughness * lo, m.roughness * hi};
}

bool hasComputeShaders(const gdi::DeviceInfo& info) { return info.features.computeShaders; }

// The lights a technique's lists walk per pixel in one probe frame of the scene (its statistics
// pass on, nothing the lists do not depend on: no shadows, no environment light, no image).
double probeLightsWalked(gdi::Device& device, const assets::Scene& scene, RenderSettings settings,
                         const char* technique) {
    settings.technique = technique;
    settings.iblSamples = 0;
    settings.iblPrefiltered = false;
    settings.shadows.enabled = false;
    return measureLightLists(device, scene, settings).mean;
}

// Many lights without MSAA on a CPU rasterizer: forward-plus, or clustered-forward where a probe
// frame shows the scene deep (its clusters walk about as many lights as the depth-bounded tiles).
void chooseForCpuRasterizer(const assets::Scene& scene, gdi::Device* probeDevice,
                            const std::string& what, DirectorChoice& c) {
    RenderSettings& s = c.settings;
    const std::string measured =
        "measured against deferred-tiled and clustered-forward at 32 to 512 lights on builtin:lights and the deep "
        "builtin:atrium (lavapipe and llvmpipe; docs/BENCHMARKS.md director crossovers)";
    s.technique = "forward-plus";
    std::string probe = "no probe device, so the scene's depth is not measured";
    if (probeDevice) {
        const double tiles = probeLightsWalked(*probeDevice, scene, s, "forward-plus");
        const double clusters = probeLightsWalked(*probeDevice, scene, s, "clustered-forward");
        probe = "a probe frame's lists walk " + fixed(clusters, 2) +
                " lights a pixel in clusters, " + fixed(tiles, 2) + " in tiles";
        if (tiles > 0.0 && clusters <= kDeepSceneClusterToTileRatio * tiles) {
            s.technique = "clustered-forward";
            c.reasons.push_back(
                "technique clustered-forward: " + what + " on a CPU rasterizer, and " + probe +
                " (at most " + fixed(kDeepSceneClusterToTileRatio, 2) +
                "x): a deep scene, whose tiles span near and far surfaces; " + measured +
                ": there clustered-forward was fastest, forward-plus 7-29 % slower");
            return;
        }
        probe += " (over " + fixed(kDeepSceneClusterToTileRatio, 2) +
                 "x: tiles hold their depth tightly)";
    }
    c.reasons.push_back(
        "technique forward-plus: " + what + " on a CPU rasterizer, and " + probe +
        ": a depth pre-pass, then each fragment shades once over the lights that reach its 8x8 "
        "tile (culled to the tile's depth bounds), with no G-buffer; " +
        measured +
        ": fastest on builtin:lights, where clustered-forward was 1.2-1.9x slower, and faster "
        "than deferred-tiled in all twelve cases");
}

}  // namespace

SceneNeeds sceneNeeds(const assets::Scene& scene, float aspect) {
    SceneNeeds n;
    n.lights = uint32_t(scene.lights.size());
    for (const assets::Light& l : scene.lights) {
        n.boundedLights += l.type != assets::LightType::Directional && l.range > 0.0f;
        if (scene.camera)
            n.lightCoverage +=
                coverage(l, *scene.camera, scene.camera->aspectRatio.value_or(aspect));
    }
    for (const assets::MeshInstance& i : scene.instances)
        for (const assets::Primitive& p : scene.meshes[i.meshIndex].primitives) {
            const assets::Material& m = scene.materials[p.material];
            n.blendPrimitives += m.alphaMode == assets::AlphaMode::Blend;
            if (m.unlit) continue;
            n.fullMaterialPrimitives += m.needsFullMaterial();
            const auto [lo, hi] = roughnessRange(scene, m);
            n.minRoughness = std::min(n.minRoughness, lo);
            n.maxRoughness = std::max(n.maxRoughness, hi);
        }
    if (n.minRoughness > n.maxRoughness) n.minRoughness = n.maxRoughness = 0.0f;  // nothing lit
    return n;
}

double percentPixelsOver5Of255(const gdi::Image& a, const gdi::Image& b, float exposure) {
    if (a.width != b.width || a.height != b.height)
        throw gdi::Error("error budget: images differ in size");
    auto encode = [exposure](float v) {
        const double x = std::clamp(double(v) * exposure, 0.0, 1.0);
        return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055;
    };
    uint64_t over = 0;
    for (uint32_t y = 0; y < a.height; ++y)
        for (uint32_t x = 0; x < a.width; ++x) {
            const auto p = a.texel(x, y), q = b.texel(x, y);
            bool differs = false;
            for (int c = 0; c < 3; ++c)
                differs = differs || std::abs(encode(p[c]) - encode(q[c])) > 5.0 / 255.0;
            over += differs;
        }
    return 100.0 * double(over) / double(uint64_t(a.width) * a.height);
}

DirectorChoice direct(const assets::Scene& scene, const RenderSettings& requested,
                      const gdi::DeviceInfo& info, gdi::Device* probeDevice,
                      const DirectorOptions& options) {
    DirectorChoice c{requested, {}};
    const SceneNeeds n = sceneNeeds(scene, float(requested.width) / float(requested.height));
    RenderSettings& s = c.settings;
    const std::string lights = std::to_string(n.lights) + " light(s)";
    const std::string cover = "covering the screen " + fixed(n.lightCoverage) + " times";
    bool exactOnly = true;
    if (s.technique != "auto") {
        c.reasons.push_back("technique " + s.technique + ": asked for");
        exactOnly = false;
    } else if (n.lights <= kVolumeCostPerForwardLight * n.lightCoverage) {
        s.technique = "forward";
        c.reasons.push_back("technique forward: " + lights + " " + cover +
                            ": most pixels shade most lights anyway, "
                            "so one pass with every light in its loop is cheapest (at most " +
                            fixed(kVolumeCostPerForwardLight, 0) +
                            " lights per screen covered), exact, with no G-buffer" +
                            (s.msaa > 1 ? "; it takes --msaa " + std::to_string(s.msaa) : ""));
    } else if (s.msaa > 1 && hasComputeShaders(info)) {
        s.technique = "clustered-forward";
        c.reasons.push_back(
            "technique clustered-forward: " + lights + " and --msaa " + std::to_string(s.msaa) +
            ": a forward pass over each fragment's cluster list keeps hardware MSAA, exact, and "
            "measured fastest with MSAA (builtin:atrium, 256 lights, 4x: 36.3 ms against forward-plus "
            "47.0, forward-zprepass 507.5 on lavapipe; at 640x360 52.2 ms against clustered-deferred "
            "63.7, deferred-tiled 80.7 and the visibility buffer 159.5, which shade edge pixels per "
            "sample; the light pre-pass is inexact there, docs/BENCHMARKS.md)");
    } else if (s.msaa > 1 && s.shadingModel == ShadingModel::Gltf) {
        s.technique = "forward";
        c.reasons.push_back(
            "technique forward: " + lights + ", --msaa " + std::to_string(s.msaa) +
            " and --brdf gltf without compute shaders: the light pre-pass, which would keep MSAA with "
            "lights drawn once per pixel, needs the separable BRDF");
    } else if (s.msaa > 1) {
        const bool packed = n.minRoughness >= kPackedNormalsMinRoughness;
        s.technique = packed ? "light-prepass" : "light-prepass-unpacked";
        c.reasons.push_back(
            "technique " + s.technique + ": " + lights + " and --msaa " + std::to_string(s.msaa) +
            ": without compute shaders the deferred choice is light volumes, which under MSAA test "
            "a pixel's samples in every volume covering it (builtin:atrium, 256 lights: 2.6x the "
            "one-sample frame at 4x on lavapipe); the light pre-pass keeps hardware MSAA in its "
            "material pass with lights drawn once per pixel");
        c.reasons.push_back(std::string(packed ? "packed RGBA8 normals" : "RGBA16F normals") +
                            ": smoothest material has roughness " + fixed(n.minRoughness, 2) +
                            (packed ? ", not below " : ", below ") +
                            fixed(kPackedNormalsMinRoughness, 2) +
                            " where 8-bit normals lose highlights");
    } else if (n.lightCoverage < kTiledMinCoverage) {
        s.technique = "deferred";
        c.reasons.push_back(
            "technique deferred: " + lights + " " + cover + ", under " + fixed(kTiledMinCoverage) +
            ": light volumes cost only the pixels they cover, tiles a fixed culling pass (measured "
            "against clustered-forward and forward-plus at 8 and 32 lights on builtin:lights and "
            "builtin:atrium: fastest in four cases of eight, clustered-forward up to 35 % faster in "
            "the others, mostly the deep atrium, which the director cannot tell apart yet; "
            "docs/BENCHMARKS.md director crossovers)");
    } else if (hasComputeShaders(info) && !info.softwareRasterizer) {
        s.technique = "visibility-buffer";
        c.reasons.push_back(
            "technique visibility-buffer: " + lights + " (" + std::to_string(n.boundedLights) +
            " with a range) " + cover +
            " on a GPU: 8 bytes a pixel written by the geometry, each pixel "
            "rebuilt from its triangle and shaded once over its cluster's lights; measured on an H200 at "
            "1280x720 against deferred-tiled: 0.46x its frame with 1024 lights in builtin:atrium and "
            "0.65x with 512 on builtin:lights (Vulkan; 0.52x and 0.86x on GL), the fastest of every "
            "technique there (docs/BENCHMARKS.md, On NVIDIA); on the CPU rasterizers forward-plus "
            "is faster");
    } else if (hasComputeShaders(info) && (options.errorBudgetPercent <= 0 || !probeDevice)) {
        chooseForCpuRasterizer(
            scene, probeDevice,
            lights + " (" + std::to_string(n.boundedLights) + " with a range) " + cover, c);
    } else if (hasComputeShaders(info)) {
        s.technique = "deferred-tiled";
        c.reasons.push_back(
            "technique deferred-tiled: " + lights + " (" + std::to_string(n.boundedLights) +
            " with a range) " + cover +
            " and an error budget: the exact technique the reduced "
            "illumination rates start from (its G-buffer feeds the I-buffer); each pixel reads the "
            "G-buffer once and shades only the lights that reach its 8x8 tile");
    } else {
        s.technique = "deferred";
        c.reasons.push_back("technique deferred: " + lights + " " + cover +
                            " and no compute shaders on " + info.backend +
                            ": lights drawn as volumes");
    }

    // Materials only the forward family and the visibility buffer show: never a G-buffer or
    // separable technique when the choice is ours.
    if (exactOnly && n.fullMaterialPrimitives && s.shadingModel != ShadingModel::Separable &&
        !findTechnique(s.technique).fullMaterial(resolveBrdf(s))) {
        const std::string was = s.technique;
        s.technique = hasComputeShaders(info) ? "clustered-forward" : "forward";
        c.reasons.push_back(
            "technique " + s.technique + " rather than " + was + ": " +
            std::to_string(n.fullMaterialPrimitives) +
            " primitive(s) set the dielectric's Fresnel or a clearcoat (KHR_materials_ior / specular / "
            "clearcoat), which " +
            was + " cannot show; " + s.technique + " shades the whole material, exactly" +
            (hasComputeShaders(info) ? ", walking each fragment's cluster list" : ""));
    }
    if (n.blendPrimitives)
        c.reasons.push_back(
            std::to_string(n.blendPrimitives) + " translucent primitive(s): " +
            (hasComputeShaders(info)
                 ? "their pass lights them from the light cluster grid whatever the technique, "
                   "so they do not change the choice (measured with builtin:atrium's banners)"
                 : "their pass shades every light (no compute shaders for a cluster grid)"));

    // A reduced illumination rate: only where a probe frame shows it within the error budget.
    const bool candidate =
        exactOnly && (s.technique == "deferred-tiled" || s.technique == "deferred");
    if (options.errorBudgetPercent > 0 && s.shadingModel == ShadingModel::Gltf) {
        c.reasons.push_back(
            "error budget " + fixed(options.errorBudgetPercent, 2) +
            " %: unused, --brdf gltf asked for and the reduced-rate techniques (redeferred) need the "
            "separable BRDF");
    } else if (options.errorBudgetPercent > 0 && !candidate) {
        c.reasons.push_back("error budget " + fixed(options.errorBudgetPercent, 2) +
                            " %: unused, " +
                            (exactOnly ? s.technique + " has no reduced-rate alternative here"
                                       : "technique asked for"));
    } else if (options.errorBudgetPercent > 0 && !probeDevice) {
        c.reasons.push_back("error budget: unused, no device to render probe frames on");
    } else if (options.errorBudgetPercent > 0) {
        const std::string technique = hasComputeShaders(info) ? "redeferred-tiled" : "redeferred";
        RenderSettings exact = s;
        exact.displayImage = false;
        SceneRenderer reference(*probeDevice, scene, exact);
        reference.renderFrame();
        const gdi::Image want = reference.readOutput();
        auto probe = [&](RenderSettings reduced) {
            reduced.technique = technique;
            SceneRenderer r(*probeDevice, scene, reduced);
            r.renderFrame();
            return percentPixelsOver5Of255(r.readOutput(), want, s.exposure);
        };
        // The illumination sources this frame has: with more than one, each gets its own rate.
        const ShadowPlan plan =
            scene.camera ? planShadows(scene.lights, *scene.camera, scene.bounds, s.shadows)
                         : ShadowPlan{};
        std::vector<std::pair<const char*, uint32_t SourceRates::*>> sources;
        if (s.ibl()) {
            sources.push_back({"ibl-diffuse", &SourceRates::iblDiffuse});
            sources.push_back({"ibl-specular", &SourceRates::iblSpecular});
        }
        if (plan.unshadowedCount > 0 || plan.shadowed.empty())
            sources.push_back({"punctual", &SourceRates::punctual});
        if (!plan.shadowed.empty()) sources.push_back({"shadowed", &SourceRates::shadowed});
        if (sources.size() <= 1) {
            std::string measured;
            for (uint32_t scale : {4u, 2u}) {
                RenderSettings reduced = exact;
                reduced.illumScale = scale;
                const double percent = probe(reduced);
                measured += (measured.empty() ? "" : ", ") + fixed(percent, 2) + " % at scale " +
                            std::to_string(scale);
                if (percent <= options.errorBudgetPercent) {
                    s.technique = technique;
                    s.illumScale = scale;
                    c.reasons.push_back(
                        "technique " + technique + " illum-scale " + std::to_string(scale) +
                        ": probe frame " + fixed(percent, 2) + " % of pixels beyond 5/255 of " +
                        exact.technique + ", within the budget of " +
                        fixed(options.errorBudgetPercent, 2) + " % (roughness " +
                        fixed(n.minRoughness, 2) + "-" + fixed(n.maxRoughness, 2) + ")");
                    break;
                }
            }
            if (s.technique != technique)
                c.reasons.push_back("no reduced illumination rate: probe frames " + measured +
                                    " of pixels beyond 5/255, over the budget of " +
                                    fixed(options.errorBudgetPercent, 2) +
                                    " % (smoothest roughness " + fixed(n.minRoughness, 2) +
                                    ": sharp highlights and edges are what a reduced rate misses)");
        } else {
            // Greedy, one source at a time (the smoothest first: the environment's diffuse light,
            // then its specular, the unshadowed lights, the shadowed ones last, whose hard edges
            // a reduced rate blurs): the lowest rate at which the probe frame, with the rates
            // already taken, stays within the budget.
            SourceRates rates{1, 1, 1, 1};
            double last = 0.0;
            for (const auto& [name, member] : sources) {
                std::string measured;
                for (uint32_t rate : {4u, 2u}) {
                    RenderSettings reduced = exact;
                    reduced.rates = rates;
                    reduced.rates.*member = rate;
                    const double percent = probe(reduced);
                    measured += (measured.empty() ? "" : ", ") + fixed(percent, 2) + " % at 1/" +
                                std::to_string(rate);
                    if (percent <= options.errorBudgetPercent) {
                        rates.*member = rate;
                        last = percent;
                        break;
                    }
                }
                c.reasons.push_back(std::string("source ") + name + ": rate 1/" +
                                    std::to_string(rates.*member) + " (probe frames " + measured +
                                    " of pixels beyond 5/255, budget " +
                                    fixed(options.errorBudgetPercent, 2) + " %)");
            }
            const bool reduced = rates.punctual > 1 || rates.shadowed > 1 || rates.iblDiffuse > 1 ||
                                 rates.iblSpecular > 1;
            if (reduced) {
                s.technique = technique;
                s.illumScale = 1;
                s.rates = rates;
                c.reasons.push_back("technique " + technique +
                                    " with per-source rates: probe frame " + fixed(last, 2) +
                                    " % of pixels beyond 5/255 of " + exact.technique +
                                    ", within the budget");
            } else {
                c.reasons.push_back(
                    "no reduced illumination rate: every source over the budget at 1/2");
            }
        }
    }

    if (!findTechnique(s.technique).illumScale && s.illumScale != 1) {
        c.reasons.push_back("illumination scale " + std::to_string(s.illumScale) +
                            " ignored: " + s.technique + " has no I-buffer");
        s.illumScale = 1;
    }
    c.reasons.push_back(n.blendPrimitives
                            ? "transparent pass: " + std::to_string(n.blendPrimitives) +
                                  " BLEND primitive(s)"
                            : "no transparent pass: no BLEND primitives");
    return c;
}

}  // namespace fe::render

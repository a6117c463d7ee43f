#include "integration/Bench.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <filesystem>
#include <cmath>
#include <map>
#include <sstream>

#include "assets/BuiltinScenes.h"
#include "assets/Environment.h"
#include "fe/gdi/Backend.h"
#include "fe/gdi/Image.h"
#include "integration/SceneRenderer.h"
#include "integration/StabilitySuite.h"
#include "assets/Animation.h"
#include "reference/CpuReference.h"
#include "reference/ImageMetrics.h"
#include "render/ShadowPlan.h"

namespace fe::render {

namespace {

// The lights the technique's loop walked per pixel, from a renderer of its own with the
// statistics pass (kept out of the timed frames): mean, 95th percentile and max, and the mean of
// the lights that reach each pixel (the least exact culling walks).
gdi::Json lightsEvaluated(gdi::Device& device, const assets::Scene& scene,
                          const RenderSettings& settings) {
    const LightListStatistics l = measureLightLists(device, scene, settings);
    gdi::Json j = {{"lists", l.lists}, {"measured", l.measured}};
    if (l.measured)
        j.update({{"mean", l.mean},
                  {"p95", l.p95},
                  {"max", l.max},
                  {"pixels", l.pixels},
                  {"reaching", l.reaching},
                  {"pixelsMissingALight", l.pixelsMissingALight}});
    return j;
}

BenchCase make(const std::string& scene, const std::string& technique, uint32_t w = 96,
               uint32_t h = 72) {
    BenchCase c;
    c.scene = scene;
    c.settings.technique = technique;
    c.settings.width = w;
    c.settings.height = h;
    return c;
}

assets::BuiltinOptions builtinOptions(const BenchCase& c) {
    assets::BuiltinOptions o;
    if (c.lights) o.lights = c.lights;
    if (c.crowd) o.crowd = c.crowd;
    o.sphereGrid = c.sphereGrid;
    return o;
}

gdi::Json stats(std::vector<double> v) {
    if (v.empty()) return nullptr;
    std::sort(v.begin(), v.end());
    return {
        {"median", v[v.size() / 2]}, {"min", v.front()}, {"max", v.back()}, {"samples", v.size()}};
}

const char* shadingModelName(ShadingModel m) {
    return m == ShadingModel::Gltf ? "gltf" : m == ShadingModel::Separable ? "separable" : "auto";
}

gdi::Json settingsJson(const BenchCase& c) {
    const RenderSettings& s = c.settings;
    return {{"scene", c.scene},
            {"environment", c.environment},
            {"lights", c.lights},
            {"sphereGrid", c.sphereGrid},
            {"crowd", c.crowd},
            {"animation", c.animation},
            {"time", c.time},
            {"technique", s.technique},
            {"width", s.width},
            {"height", s.height},
            {"illumScale", s.illumScale},
            {"msaa", s.msaa},
            {"illumSplit", s.illumSplit},
            {"precomputedNoV", s.precomputedNoV},
            {"tileCullingPass", s.tileCullingPass},
            {"clusterDepthBounds", s.clusterDepthBounds},
            {"asyncCompute", s.asyncCompute},
            {"brdf", shadingModelName(s.shadingModel)},
            {"iblSamples", s.iblSamples},
            {"iblPrefiltered", s.iblPrefiltered},
            {"shadows",
             {{"enabled", s.shadows.enabled},
              {"mapSize", s.shadows.mapSize},
              {"cascades", s.shadows.cascades},
              {"pointBudget", s.shadows.pointBudget},
              {"pcf", s.shadows.pcf}}},
            {"rates",
             {{"punctual", s.rates.punctual},
              {"shadowed", s.rates.shadowed},
              {"iblDiffuse", s.rates.iblDiffuse},
              {"iblSpecular", s.rates.iblSpecular}}},
            {"temporal", s.temporal},
            {"exposure", s.exposure},
            {"tonemap", shading::tonemapName(s.tonemap)},
            {"aa", s.antiAliasing == AntiAliasing::Fxaa  ? "fxaa"
                   : s.antiAliasing == AntiAliasing::Taa ? "taa"
                                                         : "none"}};
}

// A file name from a case key ("spheres/redeferred/scale2/96x72" -> "spheres_redeferred_scale2_96x72").
std::string fileName(std::string key) {
    for (char& ch : key)
        if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '-') ch = '_';
    return key;
}

gdi::Image displayToImage(const DisplayImage& d) {
    std::vector<std::array<float, 4>> t;
    t.reserve(d.rgb.size());
    for (const glm::vec3& c : d.rgb) t.push_back({c.r, c.g, c.b, 1.0f});
    return gdi::Image::fromTexels(d.width, d.height, gdi::Format::RGBA8, t);
}

// FLIP's map as the paper shows it: black (no difference) through red and yellow to white.
gdi::Image heatMap(uint32_t w, uint32_t h, const std::vector<float>& map) {
    std::vector<std::array<float, 4>> t;
    t.reserve(map.size());
    for (float v : map) {
        const float x = std::clamp(v, 0.0f, 1.0f);
        t.push_back({std::min(1.0f, 3.0f * x), std::clamp(3.0f * x - 1.0f, 0.0f, 1.0f),
                     std::clamp(3.0f * x - 2.0f, 0.0f, 1.0f), 1.0f});
    }
    return gdi::Image::fromTexels(w, h, gdi::Format::RGBA8, t);
}

// Cases whose display image is post-processed on the GPU (a tone mapper other than clamp, FXAA):
// their error is measured on that image, against the reference through the same tone mapper.
bool postProcessed(const RenderSettings& s) {
    return s.tonemap != shading::Tonemap::Clamp || s.antiAliasing != AntiAliasing::None;
}

// JSON has no infinity: identical images have PSNR null.
gdi::Json finite(double v) { return std::isfinite(v) ? gdi::Json(v) : gdi::Json(nullptr); }

}  // namespace

std::string BenchCase::key() const {
    std::string name = scene.rfind("builtin:", 0) == 0 ? scene.substr(8) : scene;
    if (lights) name += std::to_string(lights);
    if (crowd) name += std::to_string(crowd);
    if (!animation.empty()) name += "/animation-" + animation;
    std::string k = name + "/" + settings.technique;
    const RenderSettings& s = settings;
    if (s.illumScale != 1) k += "/scale" + std::to_string(s.illumScale);
    if (s.msaa > 1) k += "/msaa" + std::to_string(s.msaa);
    if (s.shadows.enabled) k += "/shadows" + std::to_string(s.shadows.mapSize);
    if (!environment.empty()) k += "/env";
    if (s.iblSamples) k += "/ibl" + std::to_string(s.iblSamples);
    if (s.iblPrefiltered) k += "/ibl-prefiltered";
    if (s.temporal) k += "/temporal";
    if (s.illumSplit) k += "/split";
    if (!s.precomputedNoV) k += "/rebuild-nov";
    if (!s.tileCullingPass) k += "/one-pass-culling";
    if (!s.clusterDepthBounds) k += "/no-cluster-bounds";
    if (!s.asyncCompute) k += "/no-async-compute";
    if (s.shadingModel != ShadingModel::Auto)
        k += std::string("/brdf-") + shadingModelName(s.shadingModel);
    if (s.tonemap != shading::Tonemap::Clamp)
        k += std::string("/") + shading::tonemapName(s.tonemap);
    if (s.antiAliasing == AntiAliasing::Fxaa) k += "/fxaa";
    if (s.antiAliasing == AntiAliasing::Taa) k += "/taa";
    k += "/" + std::to_string(s.width) + "x" + std::to_string(s.height);
    return k;
}

std::vector<BenchCase> quickSweep() {
    std::vector<BenchCase> cases;
    for (const TechniqueInfo& t : techniques()) {
        for (uint32_t scale : {1u, 2u, 4u}) {
            if (scale > 1 && !t.illumScale) continue;
            BenchCase c = make("builtin:spheres", t.name);
            c.settings.illumScale = scale;
            cases.push_back(c);
        }
        if (t.msaa) {
            BenchCase c = make("builtin:spheres", t.name);
            c.settings.msaa = 4;
            cases.push_back(c);
        }
    }
    for (const TechniqueInfo& t : techniques()) {
        BenchCase c = make("builtin:shadows", t.name);
        c.settings.shadows = {.enabled = true, .mapSize = 512};
        cases.push_back(c);
    }
    // Image-based lighting: convergence with the sample count, and the fast path.
    for (const TechniqueInfo& t : techniques()) {
        for (uint32_t n : {16u, 64u, 256u}) {
            BenchCase c = make("builtin:spheres", t.name);
            c.environment = "builtin:sky";
            c.settings.iblSamples = n;
            cases.push_back(c);
        }
        BenchCase c = make("builtin:spheres", t.name);
        c.environment = "builtin:sky";
        c.settings.iblPrefiltered = true;
        cases.push_back(c);
    }
    // Scaling with the light count.
    for (uint32_t lights : {16u, 64u, 256u})
        for (const TechniqueInfo& t : techniques()) {
            BenchCase c = make("builtin:lights", t.name);
            c.lights = lights;
            cases.push_back(c);
        }
    return cases;
}

namespace {

// A cap on the time-based warm-up, for cases so fast that a second is thousands of frames.
constexpr uint32_t kMaxTimedWarmupFrames = 2000;

// One case object whose values are all scalars -> a BenchCase (unknown keys are errors).
BenchCase caseFromJson(const gdi::Json& j) {
    BenchCase c;
    RenderSettings& s = c.settings;
    s.width = 96;
    s.height = 72;
    for (const auto& item :
         j.items()) {  // not a structured binding: lambdas capture `v` (clang 14)
        const std::string& key = item.key();
        const gdi::Json& v = item.value();
        auto uint = [&, k = key](uint32_t lo, uint32_t hi) {
            if (!v.is_number_unsigned() || v.get<uint64_t>() < lo || v.get<uint64_t>() > hi)
                throw gdi::Error("sweep: \"" + k + "\" must be an integer in [" +
                                 std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
                                 v.dump());
            return v.get<uint32_t>();
        };
        auto boolean = [&, k = key]() {
            if (!v.is_boolean())
                throw gdi::Error("sweep: \"" + k + "\" must be true or false, got " + v.dump());
            return v.get<bool>();
        };
        auto text = [&, k = key]() {
            if (!v.is_string())
                throw gdi::Error("sweep: \"" + k + "\" must be a string, got " + v.dump());
            return v.get<std::string>();
        };
        if (key == "scene")
            c.scene = text();
        else if (key == "technique")
            s.technique = findTechnique(text()).name;
        else if (key == "environment")
            c.environment = text();
        else if (key == "size") {
            const std::string size = text();
            const size_t x = size.find('x');
            char* end = nullptr;
            const unsigned long w =
                x == std::string::npos ? 0 : std::strtoul(size.c_str(), &end, 10);
            const unsigned long h =
                x == std::string::npos ? 0 : std::strtoul(size.c_str() + x + 1, &end, 10);
            if (w == 0 || h == 0 || w > 8192 || h > 8192 || *end)
                throw gdi::Error("sweep: \"size\" must be WxH, got " + size);
            s.width = uint32_t(w);
            s.height = uint32_t(h);
        } else if (key == "illumScale")
            s.illumScale = uint(1, 4);
        else if (key == "illumSplit")
            s.illumSplit = boolean();
        else if (key == "precomputedNoV")
            s.precomputedNoV = boolean();
        else if (key == "tileCullingPass")
            s.tileCullingPass = boolean();
        else if (key == "clusterDepthBounds")
            s.clusterDepthBounds = boolean();
        else if (key == "asyncCompute")
            s.asyncCompute = boolean();
        else if (key == "brdf") {
            const std::string b = text();
            if (b != "auto" && b != "gltf" && b != "separable")
                throw gdi::Error("sweep: \"brdf\" must be auto, gltf or separable, got " +
                                 v.dump());
            s.shadingModel = b == "gltf"        ? ShadingModel::Gltf
                             : b == "separable" ? ShadingModel::Separable
                                                : ShadingModel::Auto;
        } else if (key == "tonemap") {
            const auto t = shading::parseTonemap(text());
            if (!t)
                throw gdi::Error("sweep: \"tonemap\" must be clamp, aces or pbr-neutral, got " +
                                 v.dump());
            s.tonemap = *t;
        } else if (key == "aa") {
            const std::string aa = text();
            if (aa != "none" && aa != "fxaa" && aa != "taa")
                throw gdi::Error("sweep: \"aa\" must be none, fxaa or taa, got " + v.dump());
            s.antiAliasing = aa == "fxaa"  ? AntiAliasing::Fxaa
                             : aa == "taa" ? AntiAliasing::Taa
                                           : AntiAliasing::None;
        } else if (key == "msaa")
            s.msaa = uint(1, 8);
        else if (key == "shadows")
            s.shadows.enabled = boolean();
        else if (key == "shadowMapSize")
            s.shadows.mapSize = uint(16, 16384);
        else if (key == "iblSamples")
            s.iblSamples = uint(0, 65536);
        else if (key == "iblPrefiltered")
            s.iblPrefiltered = boolean();
        else if (key == "temporal")
            s.temporal = boolean();
        else if (key == "lights")
            c.lights = uint(0, 100000);
        else if (key == "sphereGrid")
            c.sphereGrid = uint(2, 16);
        else if (key == "crowd")
            c.crowd = uint(1, 100000);
        else if (key == "animation")
            c.animation = v.is_number_unsigned() ? std::to_string(v.get<uint64_t>()) : text();
        else if (key == "time") {
            if (!v.is_number() || !std::isfinite(v.get<double>()))
                throw gdi::Error("sweep: \"time\" must be a number, got " + v.dump());
            c.time = v.get<double>();
        } else
            throw gdi::Error("sweep: unknown key \"" + key + "\" in a case");
    }
    return c;
}

// Whether a case's options apply to its technique (an expanded matrix skips those that do not:
// the deferred techniques take no MSAA, only I-buffer techniques an illumination scale).
std::string inapplicable(const BenchCase& c) {
    const TechniqueInfo& t = findTechnique(c.settings.technique);
    if (c.settings.msaa > 1 && !t.msaa) return "takes no --msaa";
    if ((c.settings.illumScale > 1 || c.settings.illumSplit) && !t.illumScale)
        return "has no I-buffer (--illum-scale)";
    if (!c.settings.clusterDepthBounds && !t.clusters)
        return "reads no cluster grid (--no-cluster-bounds)";
    if (c.settings.shadingModel == ShadingModel::Gltf && t.separableBrdf)
        return "shades with the separable BRDF only (--brdf)";
    return {};
}

}  // namespace

std::vector<BenchCase> sweepFromJson(const gdi::Json& sweep) {
    if (!sweep.is_object() || !sweep.contains("cases") || !sweep["cases"].is_array())
        throw gdi::Error("sweep: expected an object with a \"cases\" array");
    for (const auto& [key, v] : sweep.items())
        if (key != "cases" && key != "description")
            throw gdi::Error("sweep: unknown top-level key \"" + key + "\"");
    std::vector<BenchCase> cases;
    std::map<std::string, bool> keys;
    for (const gdi::Json& j : sweep["cases"]) {
        if (!j.is_object()) throw gdi::Error("sweep: every case must be an object");
        // A value given as an array (or "technique": "all") makes a matrix: one case per
        // combination, in the order the keys are written.
        std::vector<std::pair<std::string, std::vector<gdi::Json>>> axes;
        bool matrix = false;
        for (const auto& item :
             j.items()) {  // not a structured binding: lambdas capture `v` (clang 14)
            const std::string& key = item.key();
            const gdi::Json& v = item.value();
            std::vector<gdi::Json> values;
            if (key == "technique" && v == "all") {
                for (const TechniqueInfo& t : techniques()) values.emplace_back(t.name);
                matrix = true;
            } else if (v.is_array()) {
                if (v.empty()) throw gdi::Error("sweep: \"" + key + "\" lists no values");
                values.assign(v.begin(), v.end());
                matrix = true;
            } else
                values.push_back(v);
            axes.emplace_back(key, std::move(values));
        }
        std::vector<size_t> at(axes.size(), 0);
        for (;;) {
            gdi::Json one = gdi::Json::object();
            for (size_t i = 0; i < axes.size(); ++i) one[axes[i].first] = axes[i].second[at[i]];
            BenchCase c = caseFromJson(one);
            if (const std::string why = inapplicable(c); why.empty()) {
                if (keys[c.key()]) throw gdi::Error("sweep: case " + c.key() + " is listed twice");
                keys[c.key()] = true;
                cases.push_back(c);
            } else if (!matrix)
                throw gdi::Error("sweep: case " + c.key() + ": " + c.settings.technique + " " +
                                 why);
            // Odometer over the axes, the last key fastest.
            size_t i = axes.size();
            while (i > 0 && ++at[i - 1] == axes[i - 1].second.size()) at[--i] = 0;
            if (i == 0) break;
        }
    }
    if (cases.empty()) throw gdi::Error("sweep: no cases");
    return cases;
}

gdi::Json runBench(const std::vector<BenchCase>& cases, const std::vector<std::string>& backends,
                   const BenchOptions& options,
                   const std::function<void(const BenchProgress&)>& progress) {
    gdi::Json doc = {{"schema", "fe-results/1"},
                     {"kind", "bench"},
                     {"engine", gdi::engineJson()},
                     {"date", gdi::utcTimestamp()},
                     {"options",
                      {{"warmupFrames", options.warmupFrames},
                       {"warmupSeconds", options.warmupSeconds},
                       {"frames", options.frames},
                       {"referenceIblSamples", options.referenceIblSamples},
                       {"validation", options.validation},
                       {"interleave", options.interleave}}},
                     {"backends", gdi::Json::array()},
                     {"results", gdi::Json::array()}};
    // The exact images, one per distinct scene, camera, size and light set, shared by backends.
    struct Reference {
        DisplayImage image;
        std::string label, file;
    };
    std::map<std::string, Reference> references;
    const auto start = std::chrono::steady_clock::now();
    const size_t total = cases.size() * backends.size();
    size_t done = 0;
    for (const std::string& backend : backends) {
        gdi::BackendProbe probe = gdi::probeBackend(backend, options.validation);
        doc["backends"].push_back(gdi::probeJson(probe));
        if (!probe.available) {
            done += cases.size();
            continue;
        }
        gdi::Device& device = *probe.device;
        // The first case once over, untimed: on a fresh lavapipe device the first case's frames
        // measured 35-44 ms where the same case later took 6 (two warm-up frames of a small
        // forward render did not help); a fresh device's start-up must not land in its figures.
        try {
            assets::Scene scene =
                assets::loadScene(cases.front().scene, {}, builtinOptions(cases.front()));
            if (!cases.front().environment.empty())
                scene.environment = assets::loadEnvironment(cases.front().environment);
            SceneRenderer warm(device, scene, cases.front().settings);
            for (uint32_t f = 0; f < options.warmupFrames + options.frames; ++f) {
                warm.renderFrame();
                warm.passTimings();
            }
        } catch (const std::exception&) {
            // the case itself will report what is wrong
        }
        // Each case: its scene and renderer, then its timed frames (in alternation with the other
        // cases' when interleaving), then its results.
        struct Measurement {
            const BenchCase* c = nullptr;
            gdi::Json r;
            assets::Scene scene;
            std::unique_ptr<SceneRenderer> renderer;
            std::vector<double> cpu;
            std::map<std::string, std::vector<double>> gpu;
            std::vector<std::string> order;
            int32_t animation = -1;  // BenchCase::animation, found in the scene
        };
        auto refuse = [](Measurement& m, const char* why) {
            m.r["refused"] = why;  // e.g. a technique the backend cannot run: reported, not fatal
            m.renderer.reset();
        };
        auto measure = [&](std::vector<Measurement>& group) {
            for (Measurement& m : group) {
                ++done;
                if (progress) {
                    const double elapsed =
                        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
                            .count();
                    progress(
                        {done, total, elapsed,
                         done > 1 ? elapsed / double(done - 1) * double(total - done + 1) : 0.0,
                         backend + " " + m.c->key()});
                }
                m.r = {{"backend", backend},
                       {"key", m.c->key()},
                       {"settings", settingsJson(*m.c)},
                       {"softwareRasterizer", device.info().softwareRasterizer}};
                try {
                    m.scene = assets::loadScene(m.c->scene, {}, builtinOptions(*m.c));
                    if (!m.c->environment.empty())
                        m.scene.environment = assets::loadEnvironment(m.c->environment);
                    if (!m.c->animation.empty()) {
                        m.animation = assets::findAnimation(m.scene, m.c->animation);
                        assets::poseScene(
                            m.scene,
                            {.animation = m.animation, .seconds = m.c->time, .loop = true});
                    }
                    RenderSettings settings = m.c->settings;
                    settings.displayImage = postProcessed(m.c->settings);
                    m.renderer = std::make_unique<SceneRenderer>(device, m.scene, settings);
                } catch (const std::exception& e) {
                    refuse(m, e.what());
                }
            }
            uint32_t firstTimed = 0;  // the first timed frame's number
            auto frame = [&](Measurement& m, uint32_t f, bool timed) {
                if (!m.renderer) return;
                if (options.onFrame) options.onFrame(m.c->key(), f);
                try {
                    const auto t0 = std::chrono::steady_clock::now();
                    // Posing is part of an animated frame's cost. Warm-up frames (as many as a
                    // GPU's clocks need) hold the first pose; timed frame f shows time + f / 30 s,
                    // so the last image, the one measured, is the same pose on every backend.
                    if (m.animation != -1) {
                        assets::poseScene(
                            m.scene,
                            {.animation = m.animation,
                             .seconds = m.c->time + (timed ? (f - firstTimed) / 30.0 : 0.0),
                             .loop = true});
                        m.renderer->updatePose();
                    }
                    m.renderer->renderFrame();
                    const auto timings = m.renderer->passTimings();  // waits for the frame
                    const double ms = std::chrono::duration<double, std::milli>(
                                          std::chrono::steady_clock::now() - t0)
                                          .count();
                    if (!timed) return;
                    m.cpu.push_back(ms);
                    for (const auto& t : timings) {
                        if (!m.gpu.count(t.name)) m.order.push_back(t.name);
                        m.gpu[t.name].push_back(t.gpuMilliseconds);
                    }
                } catch (const std::exception& e) {
                    refuse(m, e.what());
                }
            };
            // A GPU idling between waited frames stays at its lowest clock: on an H200 two warm-up
            // frames left the median frame at 5x the fastest. Hardware warms up for a time as well.
            const double warmupSeconds =
                device.info().softwareRasterizer ? 0.0 : options.warmupSeconds;
            const auto warmStart = std::chrono::steady_clock::now();
            uint32_t f = 0;
            auto warming = [&] {
                return f < options.warmupFrames ||
                       (std::chrono::duration<double>(std::chrono::steady_clock::now() - warmStart)
                                .count() < warmupSeconds &&
                        f < options.warmupFrames + kMaxTimedWarmupFrames);
            };
            for (; warming(); ++f)
                for (Measurement& m : group) frame(m, f, false);
            firstTimed = f;
            for (const uint32_t end = f + options.frames; f < end; ++f)
                for (Measurement& m : group) frame(m, f, true);
            for (Measurement& m : group) {
                if (m.renderer) {
                    try {
                        const BenchCase& c = *m.c;
                        m.r["cpuFrameMs"] = stats(m.cpu);
                        const graph::RenderGraph& g = m.renderer->graph();
                        gdi::Json textures = gdi::Json::array();
                        const double pixels = double(c.settings.width) * c.settings.height;
                        for (const graph::TextureInfo& t : g.textures())
                            if (!t.imported && t.used())
                                textures.push_back({{"name", t.name},
                                                    {"format", gdi::formatInfo(t.desc.format).name},
                                                    {"bytes", t.size},
                                                    {"bytesPerPixel", double(t.size) / pixels}});
                        m.r["memory"] = {
                            {"transientWithAliasing", g.memory().withAliasing},
                            {"transientWithoutAliasing", g.memory().withoutAliasing},
                            {"bytesPerPixelWithAliasing", double(g.memory().withAliasing) / pixels},
                            {"bytesPerPixelWithoutAliasing",
                             double(g.memory().withoutAliasing) / pixels},
                            {"textures", textures}};
                        // The exact image of this scene, camera, size, light set and BRDF.
                        const ShadowPlan plan = planShadows(m.scene.lights, *m.scene.camera,
                                                            m.scene.bounds, c.settings.shadows);
                        const shading::Brdf brdf = resolveBrdf(c.settings);
                        const bool separable = brdf == shading::Brdf::Separable;
                        auto reference = [&](shading::Brdf brdf) {
                            ReferenceOptions ro;
                            ro.castsShadow = plan.castsShadow();
                            ro.iblSamples = c.settings.ibl() ? options.referenceIblSamples : 0;
                            ro.brdf = brdf;
                            const bool gltf = brdf == shading::Brdf::Gltf;
                            std::ostringstream refKey;
                            refKey << c.scene << "|" << c.environment << "|" << c.lights << "|"
                                   << c.sphereGrid << "|" << c.crowd << "|" << c.animation << "@"
                                   << c.time << "+" << options.frames << "|" << c.settings.width
                                   << "x" << c.settings.height << "|" << ro.iblSamples << "|"
                                   << c.settings.exposure << "|" << int(c.settings.tonemap) << "|"
                                   << (gltf ? "gltf" : "separable") << "|";
                            for (bool b : ro.castsShadow) refKey << b;
                            auto found = references.find(refKey.str());
                            if (found != references.end()) return found;
                            const ReferenceImage ref = renderReference(
                                m.scene, *m.scene.camera, c.settings.width, c.settings.height, ro);
                            std::string label =
                                gltf ? "cpu reference" : "cpu reference, separable BRDF";
                            if (ro.iblSamples)
                                label += ", image-based lighting at " +
                                         std::to_string(ro.iblSamples) + " samples";
                            if (std::count(ro.castsShadow.begin(), ro.castsShadow.end(), true))
                                label += ", shadow rays";
                            Reference made{
                                toDisplay(c.settings.width, c.settings.height, ref.radiance,
                                          c.settings.exposure, c.settings.tonemap),
                                label,
                                "reference/" + fileName(c.key()) + (gltf ? "" : ".separable") +
                                    ".png"};
                            if (!options.imageDir.empty()) {
                                std::filesystem::create_directories(options.imageDir +
                                                                    "/reference");
                                gdi::writePng(displayToImage(made.image),
                                              options.imageDir + "/" + made.file);
                            }
                            return references.emplace(refKey.str(), std::move(made)).first;
                        };
                        // A technique is measured against the exact image of its own BRDF ("error") and,
                        // where that is the separable one, against glTF's too ("errorAgainstGltf"): what
                        // the redeferred factorisation costs against the standard BRDF.
                        const auto it = reference(brdf);
                        const auto gltfReference = separable ? reference(shading::Brdf::Gltf) : it;
                        if (!options.imageDir.empty()) m.r["referenceImage"] = it->second.file;
                        const gdi::Image out = m.renderer->readOutput();
                        DisplayImage shown{out.width, out.height, {}};
                        if (postProcessed(c.settings)) {
                            // The GPU's own display image: tone mapping and antialiasing are what is measured.
                            const gdi::Image d = m.renderer->readDisplay();
                            for (uint32_t y = 0; y < d.height; ++y)
                                for (uint32_t x = 0; x < d.width; ++x) {
                                    const auto t =
                                        d.texel(x, y);  // sRGB-encoded, as DisplayImage holds
                                    shown.rgb.emplace_back(t[0], t[1], t[2]);
                                }
                        } else {
                            std::vector<glm::dvec3> linear;
                            linear.reserve(size_t(out.width) * out.height);
                            for (uint32_t y = 0; y < out.height; ++y)
                                for (uint32_t x = 0; x < out.width; ++x) {
                                    const auto t = out.texel(x, y);
                                    linear.push_back(glm::dvec3(t[0], t[1], t[2]));
                                }
                            shown = toDisplay(out.width, out.height, linear, c.settings.exposure);
                        }
                        const ImageMetrics metrics = compareImages(shown, it->second.image);
                        // Pass times, saying which method made them: the timestamps when they
                        // account for the frame, else three flush-and-wait frames (timestamps kept);
                        // after the image is read: profiling frames add to temporal histories.
                        SceneRenderer::PassSamples timestamps;
                        for (const std::string& p : m.order) timestamps.push_back({p, m.gpu[p]});
                        const SceneRenderer::PassTimes times = m.renderer->measurePassTimes(
                            timestamps, m.cpu, std::min(options.frames, 3u));
                        auto json = [](const SceneRenderer::PassSamples& samples) {
                            gdi::Json j = gdi::Json::object();
                            for (const auto& [name, v] : samples) j[name] = stats(v);
                            return j;
                        };
                        m.r["passTimeMethod"] = times.method;
                        m.r["timestampShareOfFrame"] = times.timestampShare;
                        m.r["gpuPassMs"] = json(times.passes);
                        if (times.method != "gpu-timestamps")
                            m.r["timestampPassMs"] = json(times.timestamps);
                        if (!options.imageDir.empty()) {
                            const std::string dir = options.imageDir + "/" + backend;
                            std::filesystem::create_directories(dir);
                            const std::string name = backend + "/" + fileName(c.key());
                            gdi::writePng(displayToImage(shown),
                                          options.imageDir + "/" + name + ".png");
                            gdi::writePng(heatMap(out.width, out.height,
                                                  flipErrorMap(shown, it->second.image)),
                                          options.imageDir + "/" + name + ".flip.png");
                            m.r["image"] = name + ".png";
                            m.r["flipImage"] = name + ".flip.png";
                        }
                        m.r["reference"] = it->second.label;
                        auto errorJson = [&](const ImageMetrics& e) -> gdi::Json {
                            return {{"psnr", finite(e.psnr)},
                                    {"ssim", e.ssim},
                                    {"flip", e.flip},
                                    {"percentOver5", e.percentOver5},
                                    {"maxAbs", e.maxAbs}};
                        };
                        m.r["brdf"] = separable ? "separable" : "gltf";
                        m.r["error"] = errorJson(metrics);
                        m.r["errorAgainstGltf"] =
                            separable ? errorJson(compareImages(shown, gltfReference->second.image))
                                      : m.r["error"];
                        m.r["lightsEvaluated"] = lightsEvaluated(device, m.scene, c.settings);
                    } catch (const std::exception& e) {
                        refuse(m, e.what());
                    }
                }
                m.renderer.reset();
                doc["results"].push_back(std::move(m.r));
                if (options.onResult) options.onResult(doc);
            }
        };
        if (options.interleave) {
            std::vector<Measurement> group(cases.size());
            for (size_t i = 0; i < cases.size(); ++i) group[i].c = &cases[i];
            measure(group);
        } else {
            for (const BenchCase& c : cases) {
                std::vector<Measurement> one(1);
                one[0].c = &c;
                measure(one);
            }
        }
        if (options.validation)
            doc["backends"].back()["validationErrors"] = device.validationErrorCount();
    }
    return doc;
}

gdi::Json runStability(const std::vector<std::string>& backends, uint32_t width, uint32_t height,
                       const std::function<void(const BenchProgress&)>& progress,
                       const std::string& caseNames) {
    gdi::Json records = gdi::Json::array();
    const std::vector<StabilityCase> cases = stabilityCases(caseNames);
    const auto start = std::chrono::steady_clock::now();
    size_t done = 0;
    const size_t total = cases.size() * backends.size();
    std::map<std::string, std::vector<glm::dvec3>> references;
    for (const std::string& backend : backends) {
        gdi::BackendProbe probe = gdi::probeBackend(backend, false);
        if (!probe.available) continue;
        for (const StabilityCase& c : cases) {
            ++done;
            if (progress) {
                const double elapsed =
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
                progress({done, total, elapsed,
                          done > 1 ? elapsed / double(done - 1) * double(total - done + 1) : 0.0,
                          backend + " stability: " + c.name});
            }
            const assets::Scene scene = c.scene();
            static const std::vector<glm::dvec3> none;
            for (const TechniqueInfo& t : techniques()) {
                if (std::string(t.name).find("tiled") != std::string::npos &&
                    !probe.device->info().features.computeShaders)
                    continue;
                // The exact image under the technique's BRDF.
                const std::string key = c.name + (t.separableBrdf ? "|separable" : "|gltf");
                if (c.refusal.empty() && c.exactBound >= 0.0 && !references.count(key))
                    references[key] = renderReference(scene, *scene.camera, c.width(width),
                                                      c.height(height), {.brdf = t.defaultBrdf()})
                                          .radiance;
                const auto ref = references.find(key);
                const StabilityOutcome o =
                    runStabilityCase(*probe.device, scene, t.name, c.width(width), c.height(height),
                                     ref == references.end() ? none : ref->second);
                gdi::Json r = {{"backend", backend},      {"case", c.name},
                               {"technique", t.name},     {"bound", c.exactBound},
                               {"width", c.width(width)}, {"height", c.height(height)}};
                if (o.refused)
                    r["refused"] = o.message;
                else if (o.nonFinite)
                    r["nonFinite"] = o.nonFinite;
                else if (o.percentOver5 >= 0.0)
                    r["percentOver5"] = o.percentOver5;
                else
                    r["finite"] = true;
                records.push_back(r);
            }
        }
    }
    return records;
}

std::string resultsCsv(const gdi::Json& doc) {
    std::ostringstream o;
    o << "backend,key,scene,technique,width,height,illumScale,msaa,shadows,iblSamples,iblPrefiltered,lights,brdf,"
         "cpuMedianMs,cpuMinMs,cpuMaxMs,gpuSumMedianMs,transientBytes,transientBytesNoAliasing,psnr,ssim,flip,"
         "percentOver5,maxAbs,percentOver5AgainstGltf,refused\n";
    auto num = [](const gdi::Json& v) { return v.is_null() ? std::string() : v.dump(); };
    for (const gdi::Json& r : doc.at("results")) {
        const gdi::Json& s = r.at("settings");
        o << r.at("backend").get<std::string>() << "," << r.at("key").get<std::string>() << ","
          << s.at("scene").get<std::string>() << "," << s.at("technique").get<std::string>() << ","
          << s.at("width") << "," << s.at("height") << "," << s.at("illumScale") << ","
          << s.at("msaa") << "," << s.at("shadows").at("enabled") << "," << s.at("iblSamples")
          << "," << s.at("iblPrefiltered") << "," << s.at("lights") << "," << r.value("brdf", "")
          << ",";
        if (r.contains("refused")) {
            std::string why = r.at("refused").get<std::string>();
            std::replace(why.begin(), why.end(), ',', ';');
            std::replace(why.begin(), why.end(), '\n', ' ');
            o << ",,,,,,,,,,,," << why << "\n";
            continue;
        }
        double gpuSum = 0.0;
        for (const auto& [name, p] : r.at("gpuPassMs").items())
            gpuSum += p.at("median").get<double>();
        const gdi::Json& e = r.at("error");
        o << num(r.at("cpuFrameMs").at("median")) << "," << num(r.at("cpuFrameMs").at("min")) << ","
          << num(r.at("cpuFrameMs").at("max")) << "," << gpuSum << ","
          << r.at("memory").at("transientWithAliasing") << ","
          << r.at("memory").at("transientWithoutAliasing") << "," << num(e.at("psnr")) << ","
          << num(e.at("ssim")) << "," << num(e.at("flip")) << "," << num(e.at("percentOver5"))
          << "," << num(e.at("maxAbs")) << "," << num(r.at("errorAgainstGltf").at("percentOver5"))
          << ",\n";
    }
    return o.str();
}

BenchComparison compareResults(const gdi::Json& a, const gdi::Json& b, double timeRatio,
                               double errorPoints) {
    BenchComparison c;
    std::map<std::string, const gdi::Json*> before;
    for (const gdi::Json& r : a.at("results"))
        before[r.at("backend").get<std::string>() + " " + r.at("key").get<std::string>()] = &r;
    std::ostringstream o;
    o.setf(std::ios::fixed);
    o.precision(2);
    size_t matched = 0, slower = 0, worse = 0;
    for (const gdi::Json& r : b.at("results")) {
        const std::string k =
            r.at("backend").get<std::string>() + " " + r.at("key").get<std::string>();
        const auto it = before.find(k);
        if (it == before.end()) {
            o << k << ": new\n";
            continue;
        }
        const gdi::Json& p = *it->second;
        if (p.contains("refused") || r.contains("refused")) {
            if (p.contains("refused") != r.contains("refused")) {
                o << k << ": "
                  << (r.contains("refused") ? "now refused: " + r.at("refused").get<std::string>()
                                            : "no longer refused")
                  << "\n";
                c.regression = c.regression || r.contains("refused");
            }
            continue;
        }
        ++matched;
        const double ratio = r.at("cpuFrameMs").at("median").get<double>() /
                             p.at("cpuFrameMs").at("median").get<double>();
        const double dErr = r.at("error").at("percentOver5").get<double>() -
                            p.at("error").at("percentOver5").get<double>();
        const bool timeBad = ratio > timeRatio, errorBad = dErr > errorPoints;
        slower += timeBad;
        worse += errorBad;
        if (timeBad || errorBad || std::abs(ratio - 1.0) > 0.05 || std::abs(dErr) > 0.01)
            o << k << ": frame time x" << ratio << ", pixels over 5/255 " << (dErr >= 0 ? "+" : "")
              << dErr << " points" << (timeBad ? "  SLOWER" : "")
              << (errorBad ? "  LESS EXACT" : "") << "\n";
    }
    c.regression = c.regression || slower || worse;
    o << matched << " measurements matched; " << slower << " slower than x" << timeRatio << ", "
      << worse << " with more than " << errorPoints << " points more pixels over 5/255\n";
    c.report = o.str();
    return c;
}

}  // namespace fe::render

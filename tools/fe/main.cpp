// fe: the engine's command-line tool.
//   fe info [--json]             every backend: available or why not, device, API, limits
//   fe render [SCENE] [...]      render a scene with a lighting technique to .png / .pfm
//   fe conformance [...]         the cross-backend conformance suite
#include <unistd.h>
#include <sys/wait.h>

#include <CLI/CLI.hpp>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "Conformance.h"
#include "assets/AssetError.h"
#include "assets/BuiltinScenes.h"
#include "fe/gdi/Backend.h"
#include "fe/gdi/Capture.h"
#include "fe/gdi/InfoJson.h"
#include "CaptureCommands.h"
#include "Cli.h"
#include "Viewer.h"
#include "integration/Bench.h"
#include "integration/RenderDirector.h"
#include "integration/FrameWarnings.h"
#include "integration/SceneRenderer.h"
#include "integration/StabilitySuite.h"

namespace {

using namespace fe;
using cli::Args;
using cli::commandUsage;
using cli::HelpShown;
using cli::parse;
using cli::parseUint;
using cli::usage;
using cli::UsageError;

// The device summaries of --backend's backends (default: every backend, the window one too).
gdi::Json probeAll(const Args& a) {
    std::vector<std::string> names;
    if (a.options.count("--backend")) {
        names = gdi::expandBackendList(a.options.at("--backend"));
    } else {
        names = gdi::backendNames();
        for (const std::string& w : gdi::windowBackendNames()) names.push_back(w);
    }
    gdi::Json backends = gdi::Json::array();
    for (const std::string& n : names)
        backends.push_back(gdi::probeJson(gdi::probeBackend(n, false)));
    return backends;
}

int cmdInfo(const Args& a) {
    if (!a.positional.empty()) throw UsageError("info takes no positional arguments");
    const gdi::Json backends = probeAll(a);
    if (a.options.count("--json")) {
        std::cout << gdi::Json{{"engine", gdi::engineJson()}, {"backends", backends}}.dump(2)
                  << "\n";
        return 0;
    }
    // The text form prints the same document, so both list every field.
    auto fields = [](const gdi::Json& object) {
        std::string s;
        for (const auto& [name, value] : object.items())
            s += (s.empty() ? "" : ", ") + name + " " + value.dump();
        return s;
    };
    for (const gdi::Json& b : backends) {
        const std::string name = b["name"];
        if (!b["available"]) {
            std::cout << name << ": unavailable: " << b["reason"].get<std::string>() << "\n";
            continue;
        }
        const gdi::Json& d = b["device"];
        std::cout << name << ": available\n"
                  << "  device: " << d["deviceName"].get<std::string>()
                  << (d["softwareRasterizer"].get<bool>() ? " (software rasterizer)" : "") << "\n"
                  << "  api: " << d["apiVersion"].get<std::string>() << "\n"
                  << "  driver: " << d["driverInfo"].get<std::string>() << "\n"
                  << "  limits: " << fields(d["limits"]) << "\n"
                  << "  features: " << fields(d["features"]) << "\n";
        if (!d["presentMode"].get<std::string>().empty())
            std::cout << "  present mode: " << d["presentMode"].get<std::string>() << "\n";
        std::cout
            << "  formats (s sampled, l linear filter, r render target, b blend, w storage; sample counts):\n";
        for (const auto& [format, c] : d["formats"].items()) {
            std::string flags;
            for (const auto& [key, letter] : {std::pair{"sampled", 's'},
                                              {"linearFilter", 'l'},
                                              {"renderTarget", 'r'},
                                              {"blend", 'b'},
                                              {"storage", 'w'}})
                flags += c[key].get<bool>() ? letter : '-';
            std::string counts;
            for (uint32_t n = 1; n <= 8; n *= 2)
                if (c["sampleCounts"].get<uint32_t>() & n)
                    counts += (counts.empty() ? "" : ",") + std::to_string(n);
            std::cout << "    " << format << " " << flags << (counts.empty() ? "" : " " + counts)
                      << "\n";
        }
    }
    return 0;
}
// Pass times, saying which method made them (SceneRenderer::measurePassTimes): the GPU
// timestamps where they account for the frame, else `profiled` flush-and-wait frames (medians).
void printPassTimes(render::SceneRenderer& renderer, const std::vector<std::string>& order,
                    std::map<std::string, std::vector<double>>& timestamps,
                    const std::vector<double>& frameMs, uint32_t profiled) {
    auto median = [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        return v.empty() ? 0.0 : v[v.size() / 2];
    };
    render::SceneRenderer::PassSamples samples;
    for (const std::string& name : order) samples.push_back({name, timestamps[name]});
    const render::SceneRenderer::PassTimes t =
        renderer.measurePassTimes(samples, frameMs, profiled);
    const int share = int(100.0 * t.timestampShare + 0.5);
    if (t.method == "gpu-timestamps") {
        std::cout << "pass times (GPU timestamps; they sum to " << share << " % of the frame):\n";
        for (const auto& [name, v] : t.passes)
            std::cout << "  pass " << name << ": " << median(v) << " ms GPU\n";
        return;
    }
    std::cout << "pass times (flush-and-wait profiling, median of " << profiled
              << " frame(s): the GPU timestamps "
              << (order.empty() ? std::string("are unavailable")
                                : "sum to only " + std::to_string(share) + " % of the frame")
              << "):\n";
    for (const auto& [name, v] : t.passes)
        std::cout << "  pass " << name << ": " << median(v) << " ms (flush-and-wait"
                  << (timestamps.count(name)
                          ? "; timestamps " + std::to_string(median(timestamps[name])) + " ms"
                          : std::string())
                  << ")\n";
}

// An output file can be written, before anything is rendered: its directory is created, and a
// path that cannot be opened for writing is an error naming the option, the path and why.
void checkWritableFile(const std::filesystem::path& path, const char* option) {
    std::error_code ec;
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), ec);
    if (ec)
        throw gdi::Error("cannot create the directory " + path.parent_path().string() + " for " +
                         option + ": " + ec.message());
    if (std::filesystem::is_directory(path, ec))
        throw gdi::Error(std::string(option) + " " + path.string() + " is a directory");
    const bool existed = std::filesystem::exists(path, ec);
    std::ofstream probe(path, std::ios::app);
    if (!probe) throw gdi::Error("cannot write " + path.string() + ": " + std::strerror(errno));
    probe.close();
    if (!existed) std::filesystem::remove(path, ec);
}

void checkWritable(const cli::RenderJob& job, uint32_t frames) {
    for (uint32_t k : {0u, frames - 1}) checkWritableFile(job.outPath(k), "--out");
    if (!job.dumpGraph.empty()) checkWritableFile(job.dumpGraph, "--dump-graph");
}

int cmdRender(const Args& a) {
    cli::RenderJob job = cli::renderJob(a);
    const std::string& spec = job.spec;
    render::RenderSettings& s = job.settings;
    const render::DirectorOptions& director = job.director;
    const bool window = job.window, untilClosed = job.untilClosed, pfm = job.pfm;
    const std::string &backend = job.backend, &out = job.out, &dumpGraph = job.dumpGraph;
    const uint32_t frames = job.frames;
    const assets::BuiltinOptions& builtin = job.builtin;
    const double orbitDegrees = job.orbitDegrees;
    assets::Scene scene = assets::loadScene(spec, {}, builtin);
    // What the loader skipped or approximated, on stderr; --strict makes any of it an error.
    for (const std::string& w : scene.warnings) spdlog::warn("{}: {}", spec, w);
    if (a.options.count("--strict") && !scene.warnings.empty())
        throw assets::AssetError(spec + ": --strict: " + std::to_string(scene.warnings.size()) +
                                 " warning(s), the first: " + scene.warnings.front());
    job.applyScene(scene);
    checkWritable(job, frames);
    if (const auto& c = scene.camera;
        c && c->aspectRatio && std::abs(*c->aspectRatio * s.height / s.width - 1.0f) > 0.01f)
        spdlog::warn(
            "{}: camera '{}' has aspectRatio {}: the {}x{} image stretches its view, as glTF asks (a --size of that "
            "ratio shows it undistorted)",
            spec, c->name, *c->aspectRatio, s.width, s.height);
    // RenderDoc joins before the device exists (its Vulkan layer is enabled at instance creation).
    std::unique_ptr<gdi::FrameCapture> capture;
    if (!job.renderdocCapture.empty()) capture = gdi::FrameCapture::load(job.renderdocCapture);
    std::string captured;
    const auto startup = std::chrono::steady_clock::now();
    auto device = gdi::createDevice({.backend = backend,
                                     .validation = false,
                                     .window = window,
                                     .vsync = job.vsync,
                                     .pipelineCache = job.pipelineCache});
    const double deviceMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - startup)
            .count();
    const render::DirectorChoice choice =
        render::direct(scene, s, device->info(), device.get(), director);
    if (a.options.count("--verbose") && spdlog::get_level() > spdlog::level::info)
        spdlog::set_level(spdlog::level::info);
    for (const std::string& r : choice.reasons) spdlog::info("director: {}", r);
    s = choice.settings;
    for (const std::string& w : render::materialWarnings(scene, s)) spdlog::warn("{}: {}", spec, w);
    const bool verbose = a.options.count("--verbose") > 0;
    const auto rendererStart = std::chrono::steady_clock::now();
    render::SceneRenderer renderer(*device, scene, s);
    const double rendererMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - rendererStart)
            .count();
    if (!dumpGraph.empty()) {
        std::ofstream f(dumpGraph);
        f << renderer.graph().toDot();
        if (!f) throw gdi::Error("cannot write " + dumpGraph);
    }
    std::vector<double> cpu;
    std::map<std::string, std::vector<double>> gpu;
    std::vector<std::string> passOrder;  // execution order
    bool open = true;
    uint32_t presented = 0, lastFrame = 0;
    // What changes from frame to frame: an --animation poses the scene at its frame's instant;
    // builtin:lights animates (light positions are a function of the frame index); --orbit turns
    // the camera about the scene's vertical axis over the frames.
    auto animate = [&](render::SceneRenderer& r, uint32_t f) {
        if (job.poseFrame(scene, f)) r.updatePose();
        if (spec == "builtin:lights") r.updateLights(assets::lightsSceneLights(builtin.lights, f));
        if (orbitDegrees != 0.0) {
            const double t = frames > 1 ? double(f) / double(frames) : 0.0;
            r.setCamera(scene.camera->orbited(scene.bounds.center(),
                                              float(orbitDegrees * t * 3.14159265358979 / 180.0)));
        }
    };
    // A sequence (--out with {frame}) writes each frame as it is rendered.
    auto writeFrame = [&](render::SceneRenderer& r, const std::string& path) {
        if (pfm) return gdi::writePfm(r.readOutput(), path);
        gdi::writePng(r.readDisplay(), path, 1.0f,
                      s.background.kind == render::Background::Kind::Transparent);
    };
    // One warm-up frame when timing (frame 0 again), so frame k of the output is loop index k + 1.
    const uint32_t warmup = frames > 1 ? 1 : 0;
    for (uint32_t f = 0; open && (untilClosed || f < frames + warmup); ++f) {
        auto t0 = std::chrono::steady_clock::now();
        const uint32_t k = f < warmup ? 0 : f - warmup;
        animate(renderer, k);
        lastFrame = f;
        if (capture && f == 0) capture->begin(*device);
        renderer.renderFrame();
        auto timings = renderer.passTimings();  // waits for the frame
        if (capture && f == 0) captured = capture->end(*device);
        double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                        .count();
        if (window) open = device->present(renderer.displayTexture()), ++presented;
        if (f < warmup) continue;
        if (job.sequence) writeFrame(renderer, job.outPath(k));
        cpu.push_back(ms);
        for (auto& t : timings) {
            if (!gpu.count(t.name)) passOrder.push_back(t.name);
            gpu[t.name].push_back(t.gpuMilliseconds);
        }
    }
    auto median = [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        return v[v.size() / 2];
    };
    gdi::Image img = renderer.readOutput();
    for (float v :
         std::vector<float>(reinterpret_cast<const float*>(img.data.data()),
                            reinterpret_cast<const float*>(img.data.data() + img.data.size())))
        if (!std::isfinite(v))
            throw gdi::Error("the rendered image contains NaN or infinite values");
    const bool transparent = s.background.kind == render::Background::Kind::Transparent;
    if (job.sequence) {
        if (!pfm)
            for (const std::string& w :
                 render::frameWarnings(scene, *scene.camera, s, renderer.readDisplay()))
                spdlog::warn("{}: {}", spec, w);
    } else if (pfm)
        gdi::writePfm(img, out);
    else {
        const gdi::Image display = renderer.readDisplay();
        gdi::writePng(display, out, 1.0f, transparent);
        // A black frame, or one showing none of the scene, exits 0 like any other: say why.
        for (const std::string& w : render::frameWarnings(scene, *scene.camera, s, display))
            spdlog::warn("{}: {}", spec, w);
    }
    const bool soft = device->info().softwareRasterizer;
    std::cout << "backend " << device->info().backend << " (" << device->info().deviceName << ")"
              << (soft ? " [software rasterizer timings]" : "") << "\n";
    if (window)
        std::cout << "window: " << presented << " frame(s) presented, "
                  << device->info().presentMode << "\n";
    std::cout << "technique " << s.technique;
    if (render::findTechnique(s.technique).illumScale) {
        std::cout << " illum-scale " << s.illumScale << (s.illumSplit ? " split" : "")
                  << (s.precomputedNoV ? "" : " rebuild-nov");
        if (s.perSourceRates())
            std::cout << " rates punctual " << s.rate(s.rates.punctual) << " shadowed "
                      << s.rate(s.rates.shadowed) << " ibl-diffuse " << s.rate(s.rates.iblDiffuse)
                      << " ibl-specular " << s.rate(s.rates.iblSpecular);
    }
    if (s.msaa > 1) std::cout << " msaa " << s.msaa;
    if (!pfm && s.tonemap != shading::Tonemap::Clamp)
        std::cout << ", tonemap " << shading::tonemapName(s.tonemap);
    if (!pfm && s.antiAliasing == render::AntiAliasing::Fxaa) std::cout << ", fxaa";
    if (s.antiAliasing == render::AntiAliasing::Taa) std::cout << ", taa";
    if (s.ibl())
        std::cout << ", environment light "
                  << (s.iblPrefiltered ? std::string("prefiltered")
                                       : std::to_string(s.iblSamples) + " samples");
    if (job.defaultLookApplied)
        std::cout << ", default look (builtin:sky and a sun: the scene has no lights)";
    if (!pfm) {
        const char* kinds[] = {"black", "environment", "colour", "transparent"};
        const render::Background::Kind kind = renderer.background().kind();
        std::cout << ", background " << kinds[int(kind)];
        if (kind == render::Background::Kind::Color)
            std::cout << " " << s.background.color.r << "," << s.background.color.g << ","
                      << s.background.color.b;
    }
    if (s.shadows.enabled)
        std::cout << ", shadows " << renderer.shadowPlan().shadowed.size() << " light(s), map "
                  << s.shadows.mapSize << (s.shadows.pcf ? " pcf" : " nearest");
    std::cout << ", size " << s.width << "x" << s.height << ", scene " << spec << " ("
              << scene.lights.size() << " lights)\n"
              << "frame time (CPU wall, median of " << cpu.size() << "): " << median(cpu)
              << " ms\n";
    if (!job.pipelineCache.empty()) {
        const gdi::PipelineCacheStats c = device->pipelineCacheStats();
        std::cout << "start-up: device " << deviceMs << " ms, renderer (pipelines and resources) "
                  << rendererMs << " ms; pipeline cache "
                  << (c.loaded ? "loaded " + std::to_string(c.loadedBytes) + " bytes"
                               : std::string("empty"))
                  << ", " << c.hits << " hit(s), " << c.misses << " compiled\n";
    }
    printPassTimes(renderer, passOrder, gpu, cpu, std::min<uint32_t>(uint32_t(cpu.size()), 3));
    const graph::MemoryReport mem = renderer.graph().memory();
    static const char* modes[] = {"none", "heap memory aliasing", "texture object reuse"};
    std::cout << "transient memory: " << mem.withAliasing << " bytes with aliasing ("
              << modes[int(renderer.graph().aliasing())] << "), " << mem.withoutAliasing
              << " without; " << mem.transientTextures << " transient textures in "
              << mem.allocations << " allocation(s)\n";
    if (verbose) {
        // From a renderer of its own set up as the last frame was: the statistics pass walks every
        // light at every pixel, so it stays out of the timed frames above.
        const render::LightListStatistics l = render::measureLightLists(
            *device, scene, s, [&](render::SceneRenderer& r) { animate(r, lastFrame); });
        std::cout << "lights evaluated per pixel (" << l.lists << ")";
        if (l.measured) {
            std::cout
                << ": mean " << l.mean << ", 95th percentile " << l.p95 << ", max " << l.max
                << " over " << l.pixels
                << " pixels; lights reaching a pixel (what exact culling walks at least): mean "
                << l.reaching;
            // Always said when it happens: a dropped light is a wrong picture, not a slow one.
            if (l.pixelsMissingALight)
                std::cout << "; " << l.pixelsMissingALight
                          << " pixels MISS a light that reaches them";
        }
        std::cout << "\n";
    }
    if (const render::ClusterLightGrid* grid = renderer.clusters()) {
        // Always printed: a cluster that overflowed shades every light, which must not pass unseen.
        const render::ClusterLightGrid::Statistics c = grid->statistics();
        std::cout << "light clusters: " << c.clusters << " ("
                  << render::ClusterLightGrid::kTilePixels << "x"
                  << render::ClusterLightGrid::kTilePixels << " px x "
                  << render::ClusterLightGrid::kSlices << " slices), " << c.nonEmpty
                  << " with lights, " << c.meanLights << " lights per such cluster (max "
                  << c.maxLights << ")";
        if (c.bounded)
            std::cout << ", " << c.meanBoundedLights
                      << " of them reaching its opaque surfaces' depths";
        std::cout << ", " << c.entries << " of " << grid->listCapacity() << " index entries used, "
                  << c.overflowed << " overflowed (no room left: shade every light)\n";
    }
    if (!dumpGraph.empty()) std::cout << "wrote " << dumpGraph << "\n";
    if (!captured.empty()) std::cout << "RenderDoc capture of frame 0: " << captured << "\n";
    if (job.sequence)
        std::cout << "wrote " << frames << " frame(s): " << job.outPath(0) << " ... "
                  << job.outPath(frames - 1) << "\n";
    else
        std::cout << "wrote " << out << "\n";
    return 0;
}

// What a conformance run found: the report's sections and the pass/fail counts.
struct ConformanceRun {
    int passed = 0, failed = 0;
    gdi::Json backends = gdi::Json::array();     // device summary per backend
    gdi::Json cases = gdi::Json::array();        // per backend and case, with per-image metrics
    gdi::Json comparisons = gdi::Json::array();  // cross-backend image comparisons
    std::map<std::string, std::vector<conformance::CaseResult>> results;
};

gdi::Json toleranceJson(const conformance::CaseImage& ci) {
    return {{"absolute", ci.absTolerance},
            {"maxFractionOver", ci.maxFractionOver},
            {"reason", ci.toleranceReason}};
}

gdi::Json metricsJson(const gdi::ImageDiff& d) { return d; }

gdi::Json caseJson(const std::string& backend, const conformance::CaseResult& r) {
    gdi::Json images = gdi::Json::array();
    for (const auto& ci : r.images)
        images.push_back({{"name", ci.name},
                          {"width", ci.image.width},
                          {"height", ci.image.height},
                          {"format", std::string(gdi::formatInfo(ci.image.format).name)},
                          {"passed", ci.passed()},
                          // null: the case gives no analytic expectation for this image
                          {"metrics", ci.diff ? metricsJson(*ci.diff) : gdi::Json(nullptr)},
                          {"tolerance", toleranceJson(ci)}});
    return {{"backend", backend},
            {"case", r.caseName},
            {"passed", r.passed},
            {"message", r.message},
            {"images", images}};
}

// Runs the suite on one backend in this process.
void conformanceOne(const std::string& backend, const Args& a,
                    const std::vector<conformance::Case>& cases, ConformanceRun& run) {
    const std::string outDir = a.options.count("--out-dir") ? a.options.at("--out-dir") : "";
    const std::string filter = a.options.count("--case") ? a.options.at("--case") : "";
    gdi::BackendProbe p = gdi::probeBackend(backend, !a.options.count("--no-validation"));
    run.backends.push_back(gdi::probeJson(p));
    if (!p.available) {
        std::cout << "FAIL " << backend << ": backend unavailable: " << p.reason << "\n";
        ++run.failed;
        return;
    }
    if (!outDir.empty()) std::filesystem::create_directories(outDir + "/" + backend);
    for (const auto& c : cases) {
        if (!filter.empty() && c.name.find(filter) == std::string::npos) continue;
        conformance::CaseResult r = conformance::runCase(*p.device, c);
        std::cout << (r.passed ? "PASS " : "FAIL ") << backend << " " << c.name
                  << (r.message.empty() ? "" : ": " + r.message) << "\n";
        (r.passed ? run.passed : run.failed)++;
        run.cases.push_back(caseJson(backend, r));
        if (!outDir.empty())
            for (const auto& ci : r.images)
                gdi::writePng(ci.image,
                              outDir + "/" + backend + "/" + c.name + "_" + ci.name + ".png");
        run.results[backend].push_back(std::move(r));
    }
}

// Every backend's images against the first backend's, with each image's own tolerance.
void crossBackend(const std::vector<std::string>& backends, const std::string& outDir,
                  ConformanceRun& run) {
    if (backends.size() < 2 || !run.results.count(backends[0])) return;
    for (size_t b = 1; b < backends.size(); ++b) {
        if (!run.results.count(backends[b])) continue;
        for (const auto& ref : run.results[backends[0]])
            for (const auto& other : run.results[backends[b]]) {
                if (other.caseName != ref.caseName) continue;
                // Images pair by name: a backend may produce images another cannot (a sample count
                // or feature only one supports); those are checked against their expectations only.
                for (const auto& ri : ref.images) {
                    const auto oi = std::find_if(
                        other.images.begin(), other.images.end(),
                        [&](const conformance::CaseImage& o) { return o.name == ri.name; });
                    if (oi == other.images.end()) continue;
                    gdi::Image diff;
                    gdi::ImageDiff d =
                        gdi::compareImages(ri.image, oi->image, ri.absTolerance, 0.0, &diff);
                    const bool ok = d.fractionOver() <= ri.maxFractionOver;
                    (ok ? run.passed : run.failed)++;
                    const std::string what =
                        backends[0] + " vs " + backends[b] + " " + ref.caseName + "/" + ri.name;
                    std::cout << (ok ? "PASS " : "FAIL ") << what << ": " << d.pixelsOverTolerance
                              << " pixels over, max error " << d.maxAbsError << "\n";
                    run.comparisons.push_back({{"name", what},
                                               {"reference", backends[0]},
                                               {"backend", backends[b]},
                                               {"case", ref.caseName},
                                               {"image", ri.name},
                                               {"passed", ok},
                                               {"metrics", metricsJson(d)},
                                               {"tolerance", toleranceJson(ri)}});
                    if (!outDir.empty())
                        gdi::writePng(diff, outDir + "/diff_" + backends[0] + "_" + backends[b] +
                                                "_" + ref.caseName + "_" + ri.name + ".png");
                }
            }
    }
}

gdi::Json readJsonFile(const std::string& path) {
    std::ifstream f(path);
    if (!f) throw gdi::Error("cannot read " + path);
    try {
        return gdi::Json::parse(f);
    } catch (const std::exception& e) {
        throw gdi::Error(path + ": not valid JSON: " + e.what());
    }
}

double parsePositive(const std::string& text, const char* what) {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (*end || !std::isfinite(v) || v <= 0)
        throw UsageError(std::string(what) + " must be a positive number, got '" + text + "'");
    return v;
}

// fe view: the interactive viewer (Viewer.h).
int cmdView(const Args& a) {
    if (a.positional.size() > 1) throw UsageError("view takes one scene");
    auto opt = [&](const char* name, const std::string& fallback) {
        return a.options.count(name) ? a.options.at(name) : fallback;
    };
    tools::ViewerOptions o;
    if (!a.positional.empty())
        o.scene = a.positional[0];
    else
        o.scene = cli::kQuickStartScene, o.quickStartLighting = !a.options.count("--environment");
    o.backend = opt("--backend", "auto");
    if (gdi::windowCandidates(o.backend).empty())
        throw UsageError(
            "view needs a backend with a window (auto, vulkan, gl, vulkan-glfw, gl-glfw); " +
            o.backend + " is headless");
    o.technique = render::findTechnique(opt("--technique", "deferred-tiled")).name;
    const std::string size = opt("--size", "640x480");
    const size_t x = size.find('x');
    if (x == std::string::npos) throw UsageError("--size must be WxH, got '" + size + "'");
    o.width = parseUint(size.substr(0, x), "width", 64, 8192);
    o.height = parseUint(size.substr(x + 1), "height", 64, 8192);
    o.environment = opt("--environment", o.quickStartLighting ? cli::kQuickStartEnvironment : "");
    o.frames = a.options.count("--frames")
                   ? parseUint(a.options.at("--frames"), "--frames", 1, 1000000)
                   : 0;
    o.screenshot = opt("--screenshot", "");
    if (!o.screenshot.empty() &&
        !(o.screenshot.size() > 4 && o.screenshot.substr(o.screenshot.size() - 4) == ".png"))
        throw UsageError("--screenshot must end in .png, got '" + o.screenshot + "'");
    o.debugView = opt("--debug-view", "");
    o.ui = !a.options.count("--no-ui");
    o.validation = a.options.count("--validation") > 0;
    o.animation = opt("--animation", "");
    o.camera = opt("--camera", "");
    if (a.options.count("--switch-backend-at"))
        o.switchBackendAt =
            parseUint(a.options.at("--switch-backend-at"), "--switch-backend-at", 1, 1000000);
    return tools::runViewer(o);
}

// The report script: an installed fe's (PREFIX/share/fe/bench/report.py beside PREFIX/bin/fe),
// else the source tree's this fe was built from.
std::string reportScript() {
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        const std::filesystem::path installed =
            exe.parent_path().parent_path() / "share/fe/bench/report.py";
        if (std::filesystem::exists(installed, ec)) return installed.string();
    }
    return FE_BENCH_REPORT_SCRIPT;
}

// fe bench: a sweep on the backends asked for, results.json and results.csv in --out; or
// --compare A.json B.json, exit 1 on a regression beyond the thresholds.
int cmdBench(const Args& a, const std::vector<std::string>& arguments) {
    if (a.options.count("--compare")) {
        if (a.positional.size() != 1)
            throw UsageError("bench --compare A.json B.json: two result files, got " +
                             std::to_string(a.positional.size() + 1));
        const double time =
            parsePositive(a.options.count("--time-ratio") ? a.options.at("--time-ratio") : "1.25",
                          "--time-ratio");
        const double error = parsePositive(
            a.options.count("--error-points") ? a.options.at("--error-points") : "0.5",
            "--error-points");
        const render::BenchComparison c = render::compareResults(
            readJsonFile(a.options.at("--compare")), readJsonFile(a.positional[0]), time, error);
        std::cout << c.report;
        return c.regression ? 1 : 0;
    }
    if (!a.positional.empty())
        throw UsageError(
            "bench takes no positional arguments (did you mean --compare A.json B.json?)");
    if (a.options.count("--sweep") && a.options.count("--quick"))
        throw UsageError("--sweep and --quick: take one");
    // A --stability-cases part that names no case is a usage error, before anything runs.
    const std::string stabilityNames =
        a.options.count("--stability-cases") ? a.options.at("--stability-cases") : "";
    try {
        render::stabilityCases(stabilityNames);
    } catch (const gdi::Error& e) {
        throw UsageError(std::string("--stability-cases: ") + e.what());
    }
    const auto started = std::chrono::steady_clock::now();
    const gdi::Json sweep =
        a.options.count("--sweep") ? readJsonFile(a.options.at("--sweep")) : gdi::Json();
    const std::vector<render::BenchCase> cases =
        a.options.count("--sweep") ? render::sweepFromJson(sweep) : render::quickSweep();
    const std::vector<std::string> backends =
        gdi::expandBackendList(a.options.count("--backend") ? a.options.at("--backend") : "all");
    render::BenchOptions options;
    if (a.options.count("--frames"))
        options.frames = parseUint(a.options.at("--frames"), "--frames", 1, 1000);
    if (a.options.count("--warmup-ms"))
        options.warmupSeconds =
            parseUint(a.options.at("--warmup-ms"), "--warmup-ms", 0, 60000) / 1000.0;
    options.interleave = a.options.count("--interleave") > 0;
    const std::string out = a.options.count("--out") ? a.options.at("--out") : "bench";
    std::filesystem::create_directories(out);
    options.imageDir = out + "/images";
    const bool tty = isatty(2);
    const auto showProgress = [&](const render::BenchProgress& p) {
        std::ostringstream line;
        line << "[" << p.index << "/" << p.count << "] " << p.what << "  elapsed "
             << int(p.elapsedSeconds) << " s, about " << int(p.remainingSeconds + 0.5) << " s left";
        std::cerr << (tty ? "\r\033[K" : "") << line.str() << (tty ? "" : "\n") << std::flush;
    };
    // What is measured so far, rewritten after each measurement: a run stopped by a time limit
    // leaves results.partial.json (removed once results.json is written).
    const std::string partial = out + "/results.partial.json";
    options.onResult = [&](const gdi::Json& doc) {
        std::ofstream(partial + ".tmp") << doc.dump(2) << "\n";
        std::filesystem::rename(partial + ".tmp", partial);
    };
    const gdi::Json bench = render::runBench(cases, backends, options, showProgress);
    gdi::Json results = bench;
    // The stability table: with --quick, --stability or --stability-cases.
    if (!a.options.count("--sweep") || a.options.count("--stability") ||
        a.options.count("--stability-cases"))
        results["stability"] = render::runStability(backends, 48, 36, showProgress, stabilityNames);
    // The conformance suite and its cross-backend image comparisons, for the report's triplets.
    if (!a.options.count("--sweep") || a.options.count("--conformance")) {
        Args conformanceArgs;
        conformanceArgs.options["--out-dir"] = out + "/conformance";
        ConformanceRun run;
        std::ostringstream quiet;  // its PASS / FAIL lines: the report has them
        std::streambuf* saved = std::cout.rdbuf(quiet.rdbuf());
        for (const std::string& b : backends)
            conformanceOne(b, conformanceArgs, conformance::cases(), run);
        crossBackend(backends, out + "/conformance", run);
        std::cout.rdbuf(saved);
        results["conformance"] = {{"cases", run.cases},
                                  {"comparisons", run.comparisons},
                                  {"summary", {{"passed", run.passed}, {"failed", run.failed}}}};
    }
    if (tty) std::cerr << "\n";
    results["arguments"] = arguments;
    results["description"] = sweep.is_object() && sweep.contains("description")
                                 ? sweep["description"]
                                 : gdi::Json("the quick sweep (fe bench --quick)");
    results["elapsedSeconds"] =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    {
        std::ofstream f(out + "/results.json");
        f << results.dump(2) << "\n";
        if (!f) throw gdi::Error("cannot write " + out + "/results.json");
    }
    {
        std::ofstream f(out + "/results.csv");
        f << render::resultsCsv(results);
        if (!f) throw gdi::Error("cannot write " + out + "/results.csv");
    }
    std::filesystem::remove(partial);
    size_t refused = 0;
    for (const auto& r : results["results"]) refused += r.contains("refused");
    std::cout << results["results"].size() << " measurements (" << refused << " refused) on "
              << backends.size() << " backend(s); wrote " << out << "/results.json and " << out
              << "/results.csv\n";
    // The charts and report.html, drawn by tools/bench/report.py with Debian's python3-matplotlib.
    // Debian's interpreter, whose python3-matplotlib it is (a python3 earlier on PATH may lack it).
    const std::string python =
        std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
    const std::string command = python + " '" + reportScript() + "' '" + out + "/results.json'";
    const int rc = std::system(command.c_str());
    if (rc != 0)
        throw gdi::Error("the charts and report were not drawn: '" + command + "' failed (exit " +
                         std::to_string(WIFEXITED(rc) ? WEXITSTATUS(rc) : rc) +
                         "); python3 and python3-matplotlib are needed (tools/install-deps.sh)");
    return 0;
}

int cmdConformance(const Args& a, const std::vector<std::string>& arguments) {
    if (!a.positional.empty()) throw UsageError("conformance takes no positional arguments");
    std::string which = a.options.count("--backend") ? a.options.at("--backend") : "all";
    std::vector<std::string> backends = gdi::expandBackendList(which);
    const std::string date = gdi::utcTimestamp();  // when the run started
    // --capture FILE[,FILE...]: those captures are the cases (each replayed on every backend).
    std::vector<conformance::Case> cases;
    if (a.options.count("--capture")) {
        const std::string list = a.options.at("--capture");
        for (size_t start = 0; start <= list.size();) {
            const size_t comma = std::min(list.find(',', start), list.size());
            const std::string file = list.substr(start, comma - start);
            if (file.empty())
                throw UsageError("--capture takes FILE[,FILE...], got '" + list + "'");
            gdi::summarizeCapture(
                file);  // a file that is not a capture fails here, once, not per backend
            cases.push_back(conformance::captureCase(file));
            start = comma + 1;
        }
    } else {
        cases = conformance::cases();
    }
    ConformanceRun run;
    for (const std::string& b : backends) conformanceOne(b, a, cases, run);
    crossBackend(backends, a.options.count("--out-dir") ? a.options.at("--out-dir") : "", run);
    std::cout << run.passed << " passed, " << run.failed << " failed\n";
    if (a.options.count("--report")) {
        const std::string path = a.options.at("--report");
        const gdi::Json report = {
            {"schema",
             "fe-results/1"},  // as fe bench's results: engine, date, device summaries, then records
            {"kind", "conformance"},
            {"engine", gdi::engineJson()},
            {"date", date},
            {"arguments", arguments},
            {"backends", run.backends},
            {"cases", run.cases},
            {"comparisons", run.comparisons},
            {"summary", {{"passed", run.passed}, {"failed", run.failed}}}};
        std::ofstream f(path);
        f << report.dump(2) << "\n";
        if (!f) throw gdi::Error("cannot write the report " + path);
    }
    return run.failed ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
    // Diagnostics go through spdlog to stderr ("fe info: ..."); results go to stdout. The level:
    // warn unless FE_LOG_LEVEL or a command's --log-level (or render's --verbose) says otherwise.
    auto logger = spdlog::stderr_color_mt("fe");
    logger->set_pattern("fe %l: %v");
    spdlog::set_default_logger(logger);
    spdlog::set_level(spdlog::level::warn);
    if (const char* env = std::getenv("FE_LOG_LEVEL"); env && *env) {
        const spdlog::level::level_enum level = spdlog::level::from_str(env);
        if (level == spdlog::level::off && std::string(env) != "off")
            spdlog::warn(
                "FE_LOG_LEVEL must be trace, debug, info, warn, error or off, got '{}': kept warn",
                env);
        else
            spdlog::set_level(level);
    }
    if (argc < 2) {
        std::cerr << usage();
        return 2;
    }
    const std::string command = argv[1];
    if (command == "--version") {
        const gdi::Json engine = gdi::engineJson();
        std::cout << "fe " << engine.value("version", std::string("?")) << " ("
                  << engine.value("commit", std::string("?")) << ")\n";
        return 0;
    }
    try {
        if (command == "info") return cmdInfo(parse(argc, argv, 2, {"--backend"}, {"--json"}));
        if (command == "render")
            return cmdRender(parse(argc, argv, 2, cli::kRenderOptions, cli::kRenderFlags));
        if (command == "view")
            return cmdView(parse(
                argc, argv, 2,
                {"--backend", "--technique", "--size", "--environment", "--frames", "--screenshot",
                 "--debug-view", "--switch-backend-at", "--animation", "--camera"},
                {"--no-ui", "--validation"}));
        if (command == "bench")
            return cmdBench(
                parse(argc, argv, 2,
                      {"--sweep", "--backend", "--out", "--frames", "--warmup-ms", "--compare",
                       "--time-ratio", "--error-points", "--stability-cases"},
                      {"--quick", "--stability", "--conformance", "--interleave"}),
                std::vector<std::string>(argv + 1, argv + argc));
        if (command == "conformance")
            return cmdConformance(
                parse(argc, argv, 2, {"--backend", "--report", "--out-dir", "--case", "--capture"},
                      {"--no-validation"}),
                std::vector<std::string>(argv + 1, argv + argc));
        if (command == "capture") return cli::cmdCapture(argc, argv);
        if (command == "replay")
            return cli::cmdReplay(parse(argc, argv, 2, {"--backend", "--out", "--pass", "--draw"},
                                        {"--validation", "--present"}));
        if (command == "bisect")
            return cli::cmdBisect(
                parse(argc, argv, 2, {"--backends", "--tolerance", "--out", "--perturb"}, {}),
                std::vector<std::string>(argv + 1, argv + argc));
        if (command == "--help" || command == "help") {
            std::cout << usage();
            return 0;
        }
        throw UsageError("unknown command '" + command + "'");
    } catch (const HelpShown&) {
        return 0;
    } catch (const UsageError& e) {
        // A known command's own usage lines (its --help lists every option); else everything.
        const std::string own = commandUsage(command);
        std::cerr << "fe: " << e.what() << "\n"
                  << (own.empty() ? usage()
                                  : "usage:\n" + own + "run 'fe " + command +
                                        " --help' for every option\n");
        return 2;
    } catch (const assets::AssetError& e) {
        std::cerr << "fe: " << e.what() << "\n";
        return 3;
    } catch (const gdi::DeviceLostError& e) {
        std::cerr << "fe: " << e.what() << "\nfe: the GPU device was lost (exit code 4)\n";
        return 4;
    } catch (const std::exception& e) {
        std::cerr << "fe: " << e.what() << "\n";
        return 1;
    }
}

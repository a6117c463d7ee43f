#include "RenderCommand.h"

#include <unistd.h>

#include <spdlog/sinks/base_sink.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sstream>

#include "assets/AssetError.h"
#include "fe/gdi/Capture.h"
#include "fe/gdi/InfoJson.h"
#include "integration/FrameWarnings.h"
#include "integration/RenderDirector.h"
#include "integration/SceneRenderer.h"
#include "render/TechniqueRenderer.h"

namespace fe::cli {

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

// Every warning of the run (spdlog's, from any layer), for --json's "warnings"; they still go
// to stderr as they happen.
class WarningRecorder : public spdlog::sinks::base_sink<std::mutex> {
public:
    std::vector<std::string> warnings() {
        std::lock_guard<std::mutex> lock(mutex_);
        return recorded_;
    }

protected:
    void sink_it_(const spdlog::details::log_msg& msg) override {
        if (msg.level >= spdlog::level::warn)
            recorded_.emplace_back(msg.payload.data(), msg.payload.size());
    }
    void flush_() override {}

private:
    std::vector<std::string> recorded_;
};

// Installs a recorder on the default logger for the scope of a command.
struct RecordWarnings {
    std::shared_ptr<WarningRecorder> sink = std::make_shared<WarningRecorder>();
    RecordWarnings() { spdlog::default_logger()->sinks().push_back(sink); }
    ~RecordWarnings() {
        auto& sinks = spdlog::default_logger()->sinks();
        sinks.erase(std::remove(sinks.begin(), sinks.end(), sink), sinks.end());
    }
};

// A progress line on stderr once a run has taken a second: rewritten in place on a terminal,
// else a line at most every second.
class Progress {
public:
    explicit Progress(bool enabled) : enabled_(enabled), tty_(isatty(2)) {}
    void frame(uint32_t done, uint32_t total) {
        if (!enabled_) return;
        const double elapsed = msSince(start_) / 1000.0;
        if (elapsed < 1.0 || elapsed - last_ < (tty_ ? 0.1 : 1.0)) return;
        last_ = elapsed;
        shown_ = true;
        char line[96];
        std::snprintf(line, sizeof line, "frame %u/%u, %.1f s", done, total, elapsed);
        std::cerr << (tty_ ? "\r\033[K" : "") << "fe render: " << line << (tty_ ? "" : "\n")
                  << std::flush;
    }
    ~Progress() {
        if (shown_ && tty_) std::cerr << "\r\033[K" << std::flush;
    }

private:
    bool enabled_, tty_, shown_ = false;
    Clock::time_point start_ = Clock::now();
    double last_ = 0;
};

// The options only some techniques use. Each given to a technique that does not use it is one
// warning of one form, and dropped: the render goes on as the technique draws.
struct TechniqueOption {
    const char* option;
    bool (*uses)(const render::TechniqueInfo&);
    void (*drop)(render::RenderSettings&);
};
const TechniqueOption kTechniqueOptions[] = {
    {"--illum-scale", [](const render::TechniqueInfo& t) { return t.illumScale; },
     [](render::RenderSettings& s) { s.illumScale = 1; }},
    {"--rates", [](const render::TechniqueInfo& t) { return t.illumScale; },
     [](render::RenderSettings& s) { s.rates = {}; }},
    {"--temporal", [](const render::TechniqueInfo& t) { return t.illumScale; },
     [](render::RenderSettings& s) { s.temporal = false; }},
    {"--rebuild-nov", [](const render::TechniqueInfo& t) { return t.illumScale; },
     [](render::RenderSettings& s) { s.precomputedNoV = true; }},
    {"--illum-split",
     [](const render::TechniqueInfo& t) { return std::string(t.name) == "redeferred-tiled"; },
     [](render::RenderSettings& s) { s.illumSplit = false; }},
    {"--msaa", [](const render::TechniqueInfo& t) { return t.msaa; },
     [](render::RenderSettings& s) { s.msaa = 1; }},
    {"--one-pass-culling",
     [](const render::TechniqueInfo& t) { return std::string(t.name) == "deferred-tiled"; },
     [](render::RenderSettings& s) { s.tileCullingPass = true; }},
    {"--no-cluster-bounds", [](const render::TechniqueInfo& t) { return t.clusters; },
     [](render::RenderSettings& s) { s.clusterDepthBounds = true; }},
};

}  // namespace

std::vector<std::string> dropUnusedTechniqueOptions(const Args& a, render::RenderSettings& s) {
    std::vector<std::string> warnings;
    const render::TechniqueInfo& technique = render::findTechnique(s.technique);
    for (const TechniqueOption& o : kTechniqueOptions) {
        if (!a.options.count(o.option) || o.uses(technique)) continue;
        // A count of 1 asks for nothing a technique could ignore.
        const std::string given = a.options.at(o.option);
        if ((std::string(o.option) == "--msaa" || std::string(o.option) == "--illum-scale") &&
            given == "1")
            continue;
        std::string users;
        for (const render::TechniqueInfo& t : render::techniques())
            if (o.uses(t)) users += (users.empty() ? "" : ", ") + std::string(t.name);
        warnings.push_back(std::string(o.option) + " has no effect on technique " + s.technique +
                           " (it applies to " + users + "): ignored");
        o.drop(s);
    }
    return warnings;
}

namespace {

// What one run of fe render did, for --json and the text summary alike.
struct RenderRun {
    gdi::Json report = gdi::Json::object();
    std::string summary;  // the technique line
};

// Pass times, saying which method made them (SceneRenderer::measurePassTimes): the GPU
// timestamps where they account for the frame, else `profiled` flush-and-wait frames (medians).
gdi::Json passTimesJson(render::SceneRenderer& renderer, const std::vector<std::string>& order,
                        std::map<std::string, std::vector<double>>& timestamps,
                        const std::vector<double>& frameMs, uint32_t profiled) {
    render::SceneRenderer::PassSamples samples;
    for (const std::string& name : order) samples.push_back({name, timestamps[name]});
    const render::SceneRenderer::PassTimes t =
        renderer.measurePassTimes(samples, frameMs, profiled);
    gdi::Json passes = gdi::Json::array();
    for (const auto& [name, v] : t.passes) {
        gdi::Json p = {{"name", name}, {"ms", median(v)}};
        if (t.method != "gpu-timestamps" && timestamps.count(name))
            p["timestampMs"] = median(timestamps[name]);
        passes.push_back(p);
    }
    return {{"method", t.method},
            {"profiledFrames", t.method == "gpu-timestamps" ? 0 : profiled},
            {"timestampsAvailable", !order.empty()},
            {"timestampShare", t.timestampShare},
            {"passes", passes}};
}

void printPassTimes(const gdi::Json& t) {
    const int share = int(100.0 * t["timestampShare"].get<double>() + 0.5);
    if (t["method"] == "gpu-timestamps") {
        std::cout << "pass times (GPU timestamps; they sum to " << share << " % of the frame):\n";
        for (const gdi::Json& p : t["passes"])
            std::cout << "  pass " << p["name"].get<std::string>() << ": " << p["ms"].get<double>()
                      << " ms GPU\n";
        return;
    }
    std::cout << "pass times (flush-and-wait profiling, median of "
              << t["profiledFrames"].get<uint32_t>() << " frame(s): the GPU timestamps "
              << (t["timestampsAvailable"].get<bool>()
                      ? "sum to only " + std::to_string(share) + " % of the frame"
                      : std::string("are unavailable"))
              << "):\n";
    for (const gdi::Json& p : t["passes"])
        std::cout << "  pass " << p["name"].get<std::string>() << ": " << p["ms"].get<double>()
                  << " ms (flush-and-wait"
                  << (p.contains("timestampMs")
                          ? "; timestamps " + std::to_string(p["timestampMs"].get<double>()) + " ms"
                          : std::string())
                  << ")\n";
}

// The technique line: what was rendered, with the options that shaped it.
std::string techniqueSummary(const cli::RenderJob& job, const render::RenderSettings& s,
                             render::SceneRenderer& renderer, const assets::Scene& scene) {
    std::ostringstream line;
    line << "technique " << s.technique;
    if (render::findTechnique(s.technique).illumScale) {
        line << " illum-scale " << s.illumScale << (s.illumSplit ? " split" : "")
             << (s.precomputedNoV ? "" : " rebuild-nov");
        if (s.perSourceRates())
            line << " rates punctual " << s.rate(s.rates.punctual) << " shadowed "
                 << s.rate(s.rates.shadowed) << " ibl-diffuse " << s.rate(s.rates.iblDiffuse)
                 << " ibl-specular " << s.rate(s.rates.iblSpecular);
    }
    if (s.msaa > 1) line << " msaa " << s.msaa;
    if (!job.pfm && s.tonemap != shading::Tonemap::Clamp)
        line << ", tonemap " << shading::tonemapName(s.tonemap);
    if (!job.pfm && s.antiAliasing == render::AntiAliasing::Fxaa) line << ", fxaa";
    if (s.antiAliasing == render::AntiAliasing::Taa) line << ", taa";
    if (s.ibl())
        line << ", environment light "
             << (s.iblPrefiltered ? std::string("prefiltered")
                                  : std::to_string(s.iblSamples) + " samples");
    if (job.defaultLookApplied)
        line << ", default look (builtin:sky and a sun: the scene has no lights)";
    if (!job.pfm) {
        const char* kinds[] = {"black", "environment", "colour", "transparent"};
        const render::Background::Kind kind = renderer.background().kind();
        line << ", background " << kinds[int(kind)];
        if (kind == render::Background::Kind::Color)
            line << " " << s.background.color.r << "," << s.background.color.g << ","
                 << s.background.color.b;
    }
    if (s.shadows.enabled)
        line << ", shadows " << renderer.shadowPlan().shadowed.size() << " light(s), map "
             << s.shadows.mapSize << (s.shadows.pcf ? " pcf" : " nearest");
    line << ", size " << s.width << "x" << s.height << ", scene " << job.spec << " ("
         << scene.lights.size() << " lights)";
    return line.str();
}

gdi::Json memoryJson(render::SceneRenderer& renderer) {
    static const char* modes[] = {"none", "heap memory aliasing", "texture object reuse"};
    const graph::MemoryReport mem = renderer.graph().memory();
    return {{"withAliasingBytes", mem.withAliasing},
            {"withoutAliasingBytes", mem.withoutAliasing},
            {"aliasing", modes[int(renderer.graph().aliasing())]},
            {"transientTextures", mem.transientTextures},
            {"allocations", mem.allocations}};
}

gdi::Json clustersJson(const render::ClusterLightGrid& grid) {
    const render::ClusterLightGrid::Statistics c = grid.statistics();
    gdi::Json j = {{"clusters", c.clusters},
                   {"tilePixels", render::ClusterLightGrid::kTilePixels},
                   {"slices", render::ClusterLightGrid::kSlices},
                   {"withLights", c.nonEmpty},
                   {"meanLights", c.meanLights},
                   {"maxLights", c.maxLights},
                   {"entries", c.entries},
                   {"capacity", grid.listCapacity()},
                   {"overflowed", c.overflowed}};
    if (c.bounded) j["meanBoundedLights"] = c.meanBoundedLights;
    return j;
}

void printClusters(const gdi::Json& c) {
    std::cout << "light clusters: " << c["clusters"] << " (" << c["tilePixels"] << "x"
              << c["tilePixels"] << " px x " << c["slices"] << " slices), " << c["withLights"]
              << " with lights, " << c["meanLights"].get<double>()
              << " lights per such cluster (max " << c["maxLights"] << ")";
    if (c.contains("meanBoundedLights"))
        std::cout << ", " << c["meanBoundedLights"].get<double>()
                  << " of them reaching its opaque surfaces' depths";
    std::cout << ", " << c["entries"] << " of " << c["capacity"] << " index entries used, "
              << c["overflowed"] << " overflowed (no room left: shade every light)\n";
}

gdi::Json lightListsJson(const render::LightListStatistics& l) {
    gdi::Json j = {{"lists", l.lists}, {"measured", l.measured}};
    if (l.measured) {
        j["pixels"] = l.pixels;
        j["mean"] = l.mean;
        j["p95"] = l.p95;
        j["max"] = l.max;
        j["reaching"] = l.reaching;
        j["pixelsMissingALight"] = l.pixelsMissingALight;
    }
    return j;
}

void printLightLists(const gdi::Json& l) {
    std::cout << "lights evaluated per pixel (" << l["lists"].get<std::string>() << ")";
    if (l["measured"].get<bool>()) {
        std::cout << ": mean " << l["mean"].get<double>() << ", 95th percentile " << l["p95"]
                  << ", max " << l["max"] << " over " << l["pixels"]
                  << " pixels; lights reaching a pixel (what exact culling walks at least): mean "
                  << l["reaching"].get<double>();
        // Always said when it happens: a dropped light is a wrong picture, not a slow one.
        if (l["pixelsMissingALight"].get<uint32_t>())
            std::cout << "; " << l["pixelsMissingALight"]
                      << " pixels MISS a light that reaches them";
    }
    std::cout << "\n";
}

// The text form: a short summary by default, the passes and memory with --verbose.
void printRun(const RenderRun& run, bool verbose) {
    const gdi::Json& r = run.report;
    const gdi::Json& d = r["device"];
    std::cout << "backend " << d["backend"].get<std::string>() << " ("
              << d["deviceName"].get<std::string>() << ")"
              << (d["softwareRasterizer"].get<bool>() ? " [software rasterizer timings]" : "")
              << "\n";
    if (r.contains("window"))
        std::cout << "window: " << r["window"]["presented"] << " frame(s) presented, "
                  << r["window"]["presentMode"].get<std::string>() << "\n";
    std::cout << run.summary << "\n"
              << "frame time (CPU wall, median of " << r["frameTimeMs"]["samples"].size()
              << "): " << r["frameTimeMs"]["median"].get<double>() << " ms\n";
    if (r.contains("startup")) {
        const gdi::Json& st = r["startup"];
        const gdi::Json& c = st["pipelineCache"];
        std::cout << "start-up: device " << st["deviceMs"].get<double>()
                  << " ms, renderer (pipelines and resources) " << st["rendererMs"].get<double>()
                  << " ms; pipeline cache "
                  << (c["loaded"].get<bool>()
                          ? "loaded " + std::to_string(c["loadedBytes"].get<uint64_t>()) + " bytes"
                          : std::string("empty"))
                  << ", " << c["hits"] << " hit(s), " << c["misses"] << " compiled\n";
    }
    if (verbose) {
        printPassTimes(r["passTimes"]);
        const gdi::Json& m = r["memory"];
        std::cout << "transient memory: " << humanBytes(m["withAliasingBytes"].get<double>())
                  << " with aliasing (" << m["aliasing"].get<std::string>() << "), "
                  << humanBytes(m["withoutAliasingBytes"].get<double>()) << " without; "
                  << m["transientTextures"] << " transient textures in " << m["allocations"]
                  << " allocation(s)\n";
        if (r.contains("lightsEvaluated")) printLightLists(r["lightsEvaluated"]);
    }
    // A cluster that overflowed shades every light: said without --verbose, never unseen.
    if (r.contains("lightClusters") &&
        (verbose || r["lightClusters"]["overflowed"].get<uint32_t>() > 0))
        printClusters(r["lightClusters"]);
    for (const gdi::Json& f : r["outputs"]) std::cout << "wrote " << f.get<std::string>() << "\n";
    if (r.contains("sequence"))
        std::cout << "wrote " << r["sequence"]["frames"]
                  << " frame(s): " << r["sequence"]["first"].get<std::string>() << " ... "
                  << r["sequence"]["last"].get<std::string>() << "\n";
}

void checkWritable(const cli::RenderJob& job, uint32_t frames) {
    for (uint32_t k : {0u, frames - 1}) checkWritableFile(job.outPath(k), "--out");
    if (!job.dumpGraph.empty()) checkWritableFile(job.dumpGraph, "--dump-graph");
}

}  // namespace

int cmdRender(const Args& a) {
    const RecordWarnings recorder;
    cli::RenderJob job = cli::renderJob(a);
    const bool json = a.options.count("--json") > 0, quiet = a.options.count("--quiet") > 0;
    const bool verbose = a.options.count("--verbose") > 0;
    if (quiet && (json || verbose)) throw UsageError("--quiet: not with --json or --verbose");
    // The run's clock starts here: loading and start-up count towards "longer than a second".
    Progress progress(!quiet && !json && !job.untilClosed);
    const std::string& spec = job.spec;
    render::RenderSettings& s = job.settings;
    const bool window = job.window, untilClosed = job.untilClosed, pfm = job.pfm;
    const uint32_t frames = job.frames;
    const assets::BuiltinOptions& builtin = job.builtin;
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
    const auto startup = Clock::now();
    auto device = gdi::createDevice({.backend = job.backend,
                                     .validation = false,
                                     .window = window,
                                     .vsync = job.vsync,
                                     .pipelineCache = job.pipelineCache});
    const double deviceMs = msSince(startup);
    const render::DirectorChoice choice =
        render::direct(scene, s, device->info(), device.get(), job.director);
    if (verbose && spdlog::get_level() > spdlog::level::info)
        spdlog::set_level(spdlog::level::info);
    for (const std::string& r : choice.reasons) spdlog::info("director: {}", r);
    s = choice.settings;
    for (const std::string& w : dropUnusedTechniqueOptions(a, s)) spdlog::warn("{}", w);
    for (const std::string& w : render::materialWarnings(scene, s)) spdlog::warn("{}: {}", spec, w);
    const auto rendererStart = Clock::now();
    render::SceneRenderer renderer(*device, scene, s);
    const double rendererMs = msSince(rendererStart);
    if (!job.dumpGraph.empty()) {
        std::ofstream f(job.dumpGraph);
        f << renderer.graph().toDot();
        if (!f) throw gdi::Error("cannot write " + job.dumpGraph);
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
        if (job.orbitDegrees != 0.0) {
            const double t = frames > 1 ? double(f) / double(frames) : 0.0;
            r.setCamera(scene.camera->orbited(
                scene.bounds.center(), float(job.orbitDegrees * t * 3.14159265358979 / 180.0)));
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
        const auto t0 = Clock::now();
        const uint32_t k = f < warmup ? 0 : f - warmup;
        animate(renderer, k);
        lastFrame = f;
        if (capture && f == 0) capture->begin(*device);
        renderer.renderFrame();
        auto timings = renderer.passTimings();  // waits for the frame
        if (capture && f == 0) captured = capture->end(*device);
        const double ms = msSince(t0);
        if (window) open = device->present(renderer.displayTexture()), ++presented;
        progress.frame(f + 1, frames + warmup);
        if (f < warmup) continue;
        if (job.sequence) writeFrame(renderer, job.outPath(k));
        cpu.push_back(ms);
        for (auto& t : timings) {
            if (!gpu.count(t.name)) passOrder.push_back(t.name);
            gpu[t.name].push_back(t.gpuMilliseconds);
        }
    }
    gdi::Image img = renderer.readOutput();
    for (float v :
         std::vector<float>(reinterpret_cast<const float*>(img.data.data()),
                            reinterpret_cast<const float*>(img.data.data() + img.data.size())))
        if (!std::isfinite(v))
            throw gdi::Error("the rendered image contains NaN or infinite values");
    const bool transparent = s.background.kind == render::Background::Kind::Transparent;
    RenderRun run;
    gdi::Json& r = run.report;
    r["outputs"] = gdi::Json::array();
    if (job.sequence) {
        if (!pfm)
            for (const std::string& w :
                 render::frameWarnings(scene, *scene.camera, s, renderer.readDisplay()))
                spdlog::warn("{}: {}", spec, w);
        r["sequence"] = {
            {"frames", frames}, {"first", job.outPath(0)}, {"last", job.outPath(frames - 1)}};
    } else if (pfm) {
        gdi::writePfm(img, job.out);
    } else {
        const gdi::Image display = renderer.readDisplay();
        gdi::writePng(display, job.out, 1.0f, transparent);
        // A black frame, or one showing none of the scene, exits 0 like any other: say why.
        for (const std::string& w : render::frameWarnings(scene, *scene.camera, s, display))
            spdlog::warn("{}: {}", spec, w);
    }
    r["engine"] = gdi::engineJson();
    const gdi::DeviceInfo& info = device->info();
    r["device"] = {{"backend", info.backend},
                   {"deviceName", info.deviceName},
                   {"apiVersion", info.apiVersion},
                   {"driverName", info.driverName},
                   {"softwareRasterizer", info.softwareRasterizer}};
    if (window) r["window"] = {{"presented", presented}, {"presentMode", info.presentMode}};
    run.summary = techniqueSummary(job, s, renderer, scene);
    r["technique"] = s.technique;
    r["summary"] = run.summary;
    r["scene"] = {{"spec", spec}, {"lights", scene.lights.size()}};
    r["size"] = {s.width, s.height};
    r["frameTimeMs"] = {{"median", median(cpu)}, {"samples", cpu}};
    if (!job.pipelineCache.empty()) {
        const gdi::PipelineCacheStats c = device->pipelineCacheStats();
        r["startup"] = {{"deviceMs", deviceMs},
                        {"rendererMs", rendererMs},
                        {"pipelineCache",
                         {{"loaded", c.loaded},
                          {"loadedBytes", c.loadedBytes},
                          {"hits", c.hits},
                          {"misses", c.misses}}}};
    }
    r["passTimes"] =
        passTimesJson(renderer, passOrder, gpu, cpu, std::min<uint32_t>(uint32_t(cpu.size()), 3));
    r["memory"] = memoryJson(renderer);
    if (verbose) {
        // From a renderer of its own set up as the last frame was: the statistics pass walks every
        // light at every pixel, so it stays out of the timed frames above.
        r["lightsEvaluated"] = lightListsJson(render::measureLightLists(
            *device, scene, s, [&](render::SceneRenderer& rr) { animate(rr, lastFrame); }));
    }
    if (const render::ClusterLightGrid* grid = renderer.clusters())
        r["lightClusters"] = clustersJson(*grid);
    if (!job.dumpGraph.empty()) r["outputs"].push_back(job.dumpGraph);
    if (!captured.empty()) r["renderdocCapture"] = captured;
    if (!job.sequence) r["outputs"].push_back(job.out);
    r["warnings"] = recorder.sink->warnings();
    if (json)
        std::cout << r.dump(2) << "\n";
    else if (!quiet) {
        printRun(run, verbose);
        if (!captured.empty()) std::cout << "RenderDoc capture of frame 0: " << captured << "\n";
    }
    return 0;
}

}  // namespace fe::cli

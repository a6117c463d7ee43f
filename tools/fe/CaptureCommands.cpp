#include "CaptureCommands.h"

#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <numeric>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "fe/gdi/Backend.h"
#include "fe/gdi/Capture.h"
#include "fe/gdi/InfoJson.h"

extern char** environ;

namespace fe::cli {

namespace {

void printSummary(const std::string& path) {
    const gdi::CaptureSummary s = gdi::summarizeCapture(path);
    std::cout << path << ": captured on " << s.backend << " (" << s.device << "), format "
              << s.formatVersion << "\n"
              << "  " << s.frames << " frame(s)"
              << (s.firstFrame ? " from frame " + std::to_string(s.firstFrame) : "") << ", "
              << s.submits << " submission(s), " << s.records << " calls, " << s.blobs
              << " data blocks\n"
              << "  " << s.fileBytes << " bytes on disk (" << s.rawBytes << " uncompressed)";
    if (s.frames) std::cout << ", " << s.fileBytes / s.frames << " bytes per frame";
    std::cout << "\n";
}

std::string fileName(std::string name) {
    for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
    return name;
}

// PNG where the format allows (not integer or depth formats): false when it does not.
bool writeImage(const gdi::Image& image, const std::string& path) {
    try {
        std::filesystem::create_directories(std::filesystem::path(path).parent_path());
        gdi::writePng(image, path);
        return true;
    } catch (const gdi::Error&) {
        return false;
    }
}

void printDraw(const gdi::DrawContext& d) {
    std::cout << "draw " << d.draw << " (" << d.command << ", draw " << d.drawInPass << " of pass "
              << d.pass << " '" << d.passName << "')\n";
    std::string path;
    for (const std::string& g : d.groups) path += (path.empty() ? "" : " > ") + g;
    if (!path.empty()) std::cout << "  debug groups: " << path << "\n";
    std::cout << "  pipeline: " << (d.pipeline.empty() ? "(none)" : d.pipeline);
    if (!d.shaders.empty()) {
        std::cout << " (shaders:";
        for (const std::string& s : d.shaders) std::cout << " " << s;
        std::cout << ")";
    }
    std::cout << "\n";
    for (const std::string& r : d.resources) std::cout << "  bound " << r << "\n";
}

double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

}  // namespace

// A heat map of two images' difference scaled to the largest (white), so that a difference of
// 3e-5 shows as clearly as one of 1: each pixel's largest channel difference over `largest`.
gdi::Image scaledHeatMap(const gdi::Image& a, const gdi::Image& b, double largest) {
    std::vector<std::array<float, 4>> texels(size_t(a.width) * a.height);
    for (uint32_t y = 0; y < a.height; ++y)
        for (uint32_t x = 0; x < a.width; ++x) {
            const auto ta = a.texel(x, y), tb = b.texel(x, y);
            double err = 0;
            for (int c = 0; c < 4; ++c) {
                const double e = std::fabs(double(ta[c]) - double(tb[c]));
                err = std::max(err, std::isfinite(e) ? e : largest);
            }
            const float v = largest > 0 ? float(std::min(1.0, err / largest)) : 0.0f;
            texels[size_t(y) * a.width + x] = {v, v, v, 1.0f};
        }
    return gdi::Image::fromTexels(a.width, a.height, gdi::Format::RGBA8, texels);
}

int cmdCapture(int argc, char** argv) {
    int dashes = 2;
    while (dashes < argc && std::strcmp(argv[dashes], "--") != 0) ++dashes;
    const Args a = parse(dashes, argv, 2, {"--out", "--frames", "--frame"}, {"--no-compress"},
                         {"PROGRAM", "after --: the program to run and its arguments"});
    if (!a.positional.empty())
        throw UsageError("capture: put the program after --, e.g. fe capture -- fe render");
    if (dashes + 1 >= argc)
        throw UsageError("capture: no program to run (fe capture [options] -- PROGRAM [ARGS...])");
    const std::string out = a.options.count("--out") ? a.options.at("--out") : "capture.fecap";
    checkWritableFile(out, "--out");
    if (a.options.count("--frames") && a.options.count("--frame"))
        throw UsageError("capture: --frames N or --frame K, not both");
    uint32_t frames = a.options.count("--frames")
                          ? parseUint(a.options.at("--frames"), "--frames", 1, 1000000)
                          : 0;
    uint32_t first = 0;
    if (a.options.count("--frame"))
        first = parseUint(a.options.at("--frame"), "--frame", 0, 1000000), frames = 1;
    setenv("FE_CAPTURE", out.c_str(), 1);
    setenv("FE_CAPTURE_FRAMES", std::to_string(frames).c_str(), 1);
    setenv("FE_CAPTURE_FIRST_FRAME", std::to_string(first).c_str(), 1);
    if (a.options.count("--no-compress")) setenv("FE_CAPTURE_COMPRESS", "0", 1);
    pid_t child = 0;
    if (const int e =
            posix_spawnp(&child, argv[dashes + 1], nullptr, nullptr, argv + dashes + 1, environ);
        e != 0)
        throw gdi::Error(std::string("capture: cannot run '") + argv[dashes + 1] +
                         "': " + std::strerror(e));
    int status = 0;
    while (waitpid(child, &status, 0) < 0 && errno == EINTR) {}
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    if (code != 0)
        std::cerr << "fe: capture: " << argv[dashes + 1] << " ended with exit code " << code
                  << "\n";
    printSummary(out);
    return code;
}

int cmdReplay(const Args& a) {
    if (a.positional.size() != 1) throw UsageError("replay takes one capture FILE");
    const std::string& path = a.positional[0];
    if (a.options.count("--out")) makeOutputDirectory(a.options.at("--out"), "--out");
    auto device = gdi::createDevice(
        {.backend = a.options.count("--backend") ? a.options.at("--backend") : "auto",
         .validation = a.options.count("--validation") > 0,
         .window = a.options.count("--present") > 0});
    gdi::ReplayOptions options{.outDir = a.options.count("--out") ? a.options.at("--out") : "",
                               .present = a.options.count("--present") > 0,
                               .passTimes = true};
    if (a.options.count("--pass") && a.options.count("--draw"))
        throw UsageError("replay: --pass or --draw, not both");
    const bool list = a.options.count("--list") > 0;
    if (list && (a.options.count("--pass") || a.options.count("--draw")))
        throw UsageError("replay: --list names every pass and draw: not with --pass or --draw");
    options.snapshotPasses = list;
    if (a.options.count("--pass")) options.stopAfterPass = a.options.at("--pass");
    if (a.options.count("--draw"))
        options.stopAfterDraw = parseUint(a.options.at("--draw"), "--draw", 0, UINT32_MAX);
    const gdi::ReplayResult r = gdi::replayCapture(path, *device, options);
    if (options.stopAfterPass || options.stopAfterDraw) {
        if (!r.stopTargets) {
            std::cerr << "fe: replay: the capture has no "
                      << (options.stopAfterPass
                              ? "render pass named '" + *options.stopAfterPass + "'"
                              : "draw " + std::to_string(*options.stopAfterDraw) +
                                    " inside a render pass")
                      << " (" << r.passes << " passes, " << r.draws << " draws)\n";
            return 1;
        }
        if (r.stoppedAt) printDraw(*r.stoppedAt);
        std::cout << "stopped after pass " << r.stopTargets->pass << " '" << r.stopTargets->name
                  << "'; its targets:\n";
        for (const gdi::ReplayImage& t : r.stopTargets->targets) {
            std::cout << "  " << t.name << " (" << t.image.width << "x" << t.image.height << ")";
            if (!options.outDir.empty()) {
                const std::string file = options.outDir + "/" + fileName(t.name) + ".png";
                if (writeImage(t.image, file)) std::cout << " -> " << file;
            }
            std::cout << "\n";
        }
        return 0;
    }
    if (list) {
        // The names --pass takes and the numbers --draw takes, in the capture's order.
        std::cout << path << ": captured on " << r.capturedBackend << ": " << r.frames
                  << " frame(s), " << r.passes << " render pass(es), " << r.draws << " draw(s)\n";
        for (const gdi::PassSnapshot& p : r.passSnapshots) {
            std::cout << "  pass " << p.pass << " '" << p.name << "': ";
            if (p.draws == 0)
                std::cout << "no draws\n";
            else
                std::cout << p.draws << " draw(s), " << p.firstDraw << " to "
                          << p.firstDraw + p.draws - 1 << "\n";
        }
        return 0;
    }
    std::cout << path << ": captured on " << r.capturedBackend << ", replayed on "
              << device->info().backend << ": " << r.frames << " frame(s), " << r.submits
              << " submission(s), " << r.commandLists << " command list(s), " << r.images.size()
              << " image(s)";
    if (!options.outDir.empty()) std::cout << " in " << options.outDir;
    std::cout << "\n";
    if (r.unrestored)
        std::cerr << "fe: replay: " << r.unrestored
                  << " texture subresource(s) of the captured state could not be written on "
                  << device->info().backend << " (left undefined)\n";
    if (!r.frameMilliseconds.empty()) {
        const double total =
            std::accumulate(r.frameMilliseconds.begin(), r.frameMilliseconds.end(), 0.0);
        std::cout << "  frame time: median " << median(r.frameMilliseconds) << " ms, total "
                  << total << " ms"
                  << (device->info().softwareRasterizer ? " (software rasterizer)" : "") << "\n";
    }
    // Each pass's GPU time, the median over the frames it ran in (passes keep their order).
    std::vector<std::pair<std::string, std::vector<double>>> passes;
    for (const gdi::PassTime& t : r.passTimes) {
        auto it = std::find_if(passes.begin(), passes.end(),
                               [&](const auto& p) { return p.first == t.name; });
        if (it == passes.end()) it = passes.insert(passes.end(), {t.name, {}});
        it->second.push_back(t.gpuMilliseconds);
    }
    for (const auto& [name, ms] : passes)
        std::cout << "  pass " << name << ": " << median(ms) << " ms GPU (median of " << ms.size()
                  << ")\n";
    if (const uint32_t errors = device->validationErrorCount()) {
        std::cerr << "fe: replay: " << errors << " validation error(s)\n";
        return 1;
    }
    return 0;
}

int cmdBisect(const Args& a, const std::vector<std::string>& arguments) {
    if (a.positional.size() != 1) throw UsageError("bisect takes one capture FILE");
    const std::string& path = a.positional[0];
    const std::string pair =
        a.options.count("--backends") ? a.options.at("--backends") : "vulkan,gl-egl";
    const auto comma = pair.find(',');
    if (comma == std::string::npos || pair.find(',', comma + 1) != std::string::npos)
        throw UsageError("--backends takes two backends, A,B (e.g. vulkan,gl-egl), got '" + pair +
                         "'");
    const std::string nameA = pair.substr(0, comma), nameB = pair.substr(comma + 1);
    gdi::BisectOptions options;
    if (a.options.count("--tolerance")) {
        const std::string t = a.options.at("--tolerance");
        char* end = nullptr;
        options.absTolerance = std::strtod(t.c_str(), &end);
        if (*end == ',') options.maxFractionOver = std::strtod(end + 1, &end);
        if (*end || !(options.absTolerance >= 0) || !(options.maxFractionOver >= 0) ||
            options.maxFractionOver > 1)
            throw UsageError(
                "--tolerance takes ABS[,FRACTION] (default 0.0196,0.001: 5/255, 0.1 % of pixels), got '" +
                t + "'");
    }
    if (a.options.count("--perturb")) {
        const std::string p = a.options.at("--perturb");
        const auto colon = p.find(':');
        const std::string backend = p.substr(0, colon);
        if (colon == std::string::npos || (backend != nameA && backend != nameB))
            throw UsageError(
                "--perturb takes BACKEND:DRAW with BACKEND one of the two bisected, got '" + p +
                "'");
        options.perturb = {{backend == nameA ? 0 : 1,
                            parseUint(p.substr(colon + 1), "--perturb's DRAW", 0, UINT32_MAX)}};
    }
    auto deviceA = gdi::createDevice({.backend = nameA, .validation = true, .verbose = false});
    auto deviceB = gdi::createDevice({.backend = nameB, .validation = true, .verbose = false});
    const gdi::BisectResult r = gdi::bisectCapture(path, *deviceA, *deviceB, options);
    const std::string out = a.options.count("--out") ? a.options.at("--out") : "bisect";
    makeOutputDirectory(out, "--out");

    std::cout << path << ": " << nameA << " against " << nameB << ", " << r.passesCompared
              << " pass(es) and " << r.drawsCompared << " draw(s) compared in " << r.replays
              << " replays\n";
    // Images where fe bench's report page looks for a conformance comparison's (report.py:
    // conformance/A/CASE_IMAGE.png, conformance/B/..., conformance/diff_A_B_CASE_IMAGE.png).
    gdi::Json comparisons = gdi::Json::array();
    for (const gdi::TargetDiff& d : r.diffs) {
        const std::string image = fileName(d.target);
        const std::string fileA = out + "/conformance/" + nameA + "/bisect_" + image + ".png";
        const std::string fileB = out + "/conformance/" + nameB + "/bisect_" + image + ".png";
        const std::string heat =
            out + "/conformance/diff_" + nameA + "_" + nameB + "_bisect_" + image + ".png";
        writeImage(d.a, fileA);
        writeImage(d.b, fileB);
        const bool heatWritten =
            d.a.width && writeImage(scaledHeatMap(d.a, d.b, d.diff.maxAbsError), heat);
        comparisons.push_back({{"name", nameA + " vs " + nameB + " bisect/" + d.target},
                               {"reference", nameA},
                               {"backend", nameB},
                               {"case", "bisect"},
                               {"image", image},
                               {"passed", false},
                               {"metrics", d.diff},
                               {"tolerance",
                                {{"absolute", options.absTolerance},
                                 {"maxFractionOver", options.maxFractionOver},
                                 {"reason", "fe bisect --tolerance"}}},
                               {"files", {fileA, fileB, heatWritten ? heat : ""}},
                               {"heatMapWhite", d.diff.maxAbsError}});
    }
    gdi::Json divergence = nullptr;
    if (!r.diverged) {
        std::cout << "no divergence: every render pass and read-back agrees within "
                  << options.absTolerance << " on all but " << options.maxFractionOver * 100
                  << " % of pixels\n";
    } else {
        if (r.pass)
            std::cout << "first divergent pass: " << r.pass->pass << " '" << r.pass->name
                      << "' (draws " << r.pass->firstDraw << " to "
                      << r.pass->firstDraw + r.pass->draws - 1 << ")\n";
        else
            std::cout << "no render pass differs; the read-backs do\n";
        if (r.draw) {
            std::cout << "first divergent ";
            printDraw(*r.draw);
        } else if (r.pass) {
            std::cout
                << "no single draw's targets differ: the difference comes at the end of the pass (resolve or store)\n";
        }
        for (const gdi::TargetDiff& d : r.diffs)
            std::cout << "  " << d.target << ": " << d.diff.pixelsOverTolerance << " of "
                      << d.diff.pixels << " pixels differ (" << d.diff.fractionOver() * 100
                      << " %), max error " << d.diff.maxAbsError << "\n"
                      << "    heat map (white: a difference of " << d.diff.maxAbsError
                      << ", black: none): " << out << "/conformance/diff_" << nameA << "_" << nameB
                      << "_bisect_" << fileName(d.target) << ".png\n";
        divergence = {{"pass", r.pass ? gdi::Json(r.pass->pass) : gdi::Json(nullptr)},
                      {"passName", r.pass ? r.pass->name : ""}};
        if (r.draw) {
            divergence["draw"] = r.draw->draw;
            divergence["drawInPass"] = r.draw->drawInPass;
            divergence["command"] = r.draw->command;
            divergence["groups"] = r.draw->groups;
            divergence["pipeline"] = r.draw->pipeline;
            divergence["shaders"] = r.draw->shaders;
            divergence["resources"] = r.draw->resources;
        }
    }
    // fe bench's results schema with a conformance section: `python3 tools/bench/report.py
    // DIR/bisect.json` draws the comparison page.
    const gdi::Json summary = {{"passed", r.diverged ? 0 : 1}, {"failed", r.diverged ? 1 : 0}};
    const gdi::Json report = {
        {"schema", "fe-results/1"},
        {"kind", "bisect"},
        {"engine", gdi::engineJson()},
        {"date", gdi::utcTimestamp()},
        {"arguments", arguments},
        {"capture", path},
        {"backends",
         {{{"name", nameA}, {"available", true}, {"device", deviceA->info()}},
          {{"name", nameB}, {"available", true}, {"device", deviceB->info()}}}},
        {"results", gdi::Json::array()},
        {"divergence", divergence},
        {"conformance", {{"summary", summary}, {"comparisons", comparisons}}},
        {"summary", summary}};
    std::ofstream(out + "/bisect.json") << report.dump(2) << "\n";
    std::cout << "report: " << out << "/bisect.json (" << reportCommand(out + "/bisect.json")
              << " draws it)\n";
    return r.diverged ? 1 : 0;
}

}  // namespace fe::cli

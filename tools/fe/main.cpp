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
#include "RenderCommand.h"
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
using cli::humanBytes;
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
        backends.push_back(gdi::probeJson(gdi::probeBackend(n, false), true));
    return backends;
}

std::string joinedCounts(const gdi::Json& counts) {
    std::string s;
    for (const gdi::Json& n : counts) s += (s.empty() ? "" : ",") + std::to_string(n.get<int>());
    return s;
}

// One available backend as `fe info` prints it, in vulkaninfo's terms.
void printDeviceText(const gdi::Json& d) {
    auto fields = [](const gdi::Json& object) {
        std::string s;
        for (const auto& [name, value] : object.items())
            s += (s.empty() ? "" : ", ") + name + " " +
                 (name.ends_with("SampleCounts") ? joinedCounts(value) : value.dump());
        return s;
    };
    std::cout << "  device: " << d["deviceName"].get<std::string>() << " ("
              << d["deviceType"].get<std::string>()
              << (d["softwareRasterizer"].get<bool>() ? ", software rasterizer" : "") << ")\n"
              << "  api: " << d["apiVersion"].get<std::string>() << "\n"
              << "  driver: " << d["driverName"].get<std::string>() << ", "
              << d["driverInfo"].get<std::string>();
    if (!d["conformanceVersion"].get<std::string>().empty())
        std::cout << "; conformance version " << d["conformanceVersion"].get<std::string>();
    std::cout << "\n";
    if (!d["memoryHeaps"].empty()) {
        std::string heaps;
        for (const gdi::Json& h : d["memoryHeaps"])
            heaps += (heaps.empty() ? "" : ", ") + humanBytes(h["bytes"].get<double>()) +
                     (h["deviceLocal"].get<bool>() ? " device-local" : " host");
        std::cout << "  memory heaps: " << heaps << "\n";
    }
    std::cout << "  extensions: " << d["extensions"].size() << " (fe info --json lists them)\n"
              << "  limits: " << fields(d["limits"]) << "\n"
              << "  features: " << fields(d["features"]) << "\n";
    if (!d["presentMode"].get<std::string>().empty())
        std::cout << "  present mode: " << d["presentMode"].get<std::string>() << "\n";
    std::cout << "  formats (s sampled, l linear filter, r render target, b blend, w storage; "
                 "sample counts):\n";
    for (const auto& [format, c] : d["formats"].items()) {
        std::string flags;
        for (const auto& [key, letter] : {std::pair{"sampled", 's'},
                                          {"linearFilter", 'l'},
                                          {"renderTarget", 'r'},
                                          {"blend", 'b'},
                                          {"storage", 'w'}})
            flags += c[key].get<bool>() ? letter : '-';
        const std::string counts = joinedCounts(c["sampleCounts"]);
        std::cout << "    " << format << " " << flags << (counts.empty() ? "" : " " + counts)
                  << "\n";
    }
}

int cmdInfo(const Args& a) {
    const gdi::Json backends = probeAll(a);
    if (a.options.count("--json")) {
        std::cout << gdi::Json{{"engine", gdi::engineJson()}, {"backends", backends}}.dump(2)
                  << "\n";
        return 0;
    }
    for (const gdi::Json& b : backends) {
        const std::string name = b["name"];
        if (!b["available"]) {
            std::cout << name << ": unavailable: " << b["reason"].get<std::string>() << "\n";
            continue;
        }
        std::cout << name << ": available\n";
        printDeviceText(b["device"]);
    }
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

// fe view's own options; the rest are fe render's look options (cli::kLookOptions), in its units.
const std::vector<std::string> kViewOptions = {
    "--backend",      "--technique",  "--size",       "--environment",
    "--frames",       "--screenshot", "--debug-view", "--switch-backend-at",
    "--input-script", "--animation",  "--camera",     "--post-shader"};

std::vector<std::string> joined(std::vector<std::string> a, const std::vector<std::string>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
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
    o.inputScript = opt("--input-script", "");
    o.postShader = opt("--post-shader", "");
    if (!o.postShader.empty() && !std::filesystem::is_regular_file(o.postShader))
        throw UsageError("--post-shader: no such file '" + o.postShader + "'");
    {  // FRAME:KEY or FRAME:drop=PATH, comma-separated: checked here, a usage error
        std::stringstream script(o.inputScript);
        for (std::string entry; std::getline(script, entry, ',');) {
            const size_t colon = entry.find(':');
            const std::string what = colon == std::string::npos ? "" : entry.substr(colon + 1);
            if (colon == std::string::npos || entry.find_first_not_of("0123456789") != colon ||
                colon == 0 ||
                !(what == "Esc" || what == "F12" || what == "F1" || what == "R" || what == "F" ||
                  what.rfind("drop=", 0) == 0))
                throw UsageError(
                    "--input-script takes FRAME:KEY (Esc, F12, F1, R, F) or "
                    "FRAME:drop=PATH, comma-separated; got '" +
                    entry + "'");
        }
    }
    if (!o.screenshot.empty()) cli::checkWritableFile(o.screenshot, "--screenshot");
    // The look as fe render reads it: the same options, units and checks (fe render's --size
    // and --frames mean other things here, and a window's technique starts as deferred-tiled).
    Args look = a;
    for (const char* viewOnly :
         {"--size", "--frames", "--screenshot", "--switch-backend-at", "--input-script",
          "--backend", "--no-ui", "--validation", "--post-shader"})
        look.options.erase(viewOnly);
    look.options["--technique"] = o.technique;
    look.options["--size"] = std::to_string(o.width) + "x" + std::to_string(o.height);
    o.look = cli::renderJob(look);
    if (o.quickStartLighting) o.look->environment = cli::kQuickStartEnvironment;
    return tools::runViewer(o);
}

// fe bench: a sweep on the backends asked for, results.json and results.csv in --out; or
// --compare A.json B.json, exit 1 on a regression beyond the thresholds.
// The conformance cases whose name contains one of the comma-separated parts of `names` (empty:
// all); a part that names no case is a usage error, before anything runs.
std::vector<conformance::Case> conformanceCasesNamed(const std::string& names) {
    std::vector<conformance::Case> all = conformance::cases();
    if (names.empty()) return all;
    std::vector<conformance::Case> chosen;
    for (size_t begin = 0; begin <= names.size();) {
        const size_t end = std::min(names.find(',', begin), names.size());
        const std::string part = names.substr(begin, end - begin);
        begin = end + 1;
        bool named = false;
        for (const conformance::Case& c : all)
            if (!part.empty() && c.name.find(part) != std::string::npos) {
                named = true;
                const bool taken = std::any_of(chosen.begin(), chosen.end(),
                                               [&](const auto& t) { return t.name == c.name; });
                if (!taken) chosen.push_back(c);
            }
        if (!named)
            throw UsageError("--conformance-cases: no conformance case's name contains '" + part +
                             "' (fe conformance --list names them)");
    }
    return chosen;
}

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
    // Likewise --conformance-cases (its report section from some cases, not the whole suite).
    const std::vector<conformance::Case> conformanceCases = conformanceCasesNamed(
        a.options.count("--conformance-cases") ? a.options.at("--conformance-cases")
                                               : std::string());
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
    cli::makeOutputDirectory(out, "--out");
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
    if (!a.options.count("--sweep") || a.options.count("--conformance") ||
        a.options.count("--conformance-cases")) {
        Args conformanceArgs;
        conformanceArgs.options["--out-dir"] = out + "/conformance";
        ConformanceRun run;
        std::ostringstream quiet;  // its PASS / FAIL lines: the report has them
        std::streambuf* saved = std::cout.rdbuf(quiet.rdbuf());
        for (const std::string& b : backends)
            conformanceOne(b, conformanceArgs, conformanceCases, run);
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
    const std::string command = cli::reportCommand(out + "/results.json");
    const int rc = std::system(command.c_str());
    if (rc != 0)
        throw gdi::Error("the charts and report were not drawn: '" + command + "' failed (exit " +
                         std::to_string(WIFEXITED(rc) ? WEXITSTATUS(rc) : rc) +
                         "); python3 and python3-matplotlib are needed (tools/install-deps.sh)");
    return 0;
}

int cmdConformance(const Args& a, const std::vector<std::string>& arguments) {
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
    if (a.options.count("--list")) {  // the names --case matches, without running anything
        size_t listed = 0;
        const std::string filter = a.options.count("--case") ? a.options.at("--case") : "";
        for (const conformance::Case& c : cases)
            if (c.name.find(filter) != std::string::npos) std::cout << c.name << "\n", ++listed;
        std::cout << listed << " case(s)\n";
        return 0;
    }
    // Outputs are checked before any case runs.
    if (a.options.count("--report")) cli::checkWritableFile(a.options.at("--report"), "--report");
    if (a.options.count("--out-dir"))
        cli::makeOutputDirectory(a.options.at("--out-dir"), "--out-dir");
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
    gdi::keepFreedMemory();  // before any backend allocates (fe::gdi::keepFreedMemory says why)
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
            return cli::cmdRender(parse(argc, argv, 2, cli::kRenderOptions, cli::kRenderFlags,
                                        cli::kScenePositional));
        if (command == "view")
            return cmdView(parse(argc, argv, 2, joined(kViewOptions, cli::kLookOptions),
                                 joined({"--no-ui", "--validation"}, cli::kLookFlags),
                                 cli::kScenePositional));
        if (command == "bench")
            return cmdBench(parse(argc, argv, 2,
                                  {"--sweep", "--backend", "--out", "--frames", "--warmup-ms",
                                   "--compare", "--time-ratio", "--error-points",
                                   "--stability-cases", "--conformance-cases"},
                                  {"--quick", "--stability", "--conformance", "--interleave"},
                                  {"B.json", "with --compare A.json: the results compared with A"}),
                            std::vector<std::string>(argv + 1, argv + argc));
        if (command == "conformance")
            return cmdConformance(
                parse(argc, argv, 2, {"--backend", "--report", "--out-dir", "--case", "--capture"},
                      {"--no-validation", "--list"}),
                std::vector<std::string>(argv + 1, argv + argc));
        if (command == "capture") return cli::cmdCapture(argc, argv);
        if (command == "replay")
            return cli::cmdReplay(parse(argc, argv, 2, {"--backend", "--out", "--pass", "--draw"},
                                        {"--validation", "--present", "--list"},
                                        {"FILE", "the capture to replay (fe capture makes them)"}));
        if (command == "bisect")
            return cli::cmdBisect(
                parse(argc, argv, 2, {"--backends", "--tolerance", "--out", "--perturb"}, {},
                      {"FILE", "the capture to replay on both backends"}),
                std::vector<std::string>(argv + 1, argv + argc));
        if (command == "--help" || command == "help") {
            std::cout << usage();
            return 0;
        }
        throw UsageError("unknown command '" + command + "'");
    } catch (const HelpShown&) {
        return 0;
    } catch (const UsageError& e) {
        // One line, then where help is: the error stays on screen.
        const bool known = !commandUsage(command).empty();
        std::cerr << "fe: " << e.what() << "\n"
                  << "see 'fe " << (known ? command + " " : std::string()) << "--help'\n";
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

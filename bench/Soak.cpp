// fe_soak: a long run, not a timed test. Per backend:
//   frames: one renderer draws --frames frames of the scene;
//   churn:  --cycles times, the scene is loaded, a renderer made, one frame drawn, all released.
// Reported for each: resident memory at the start and end, its least-squares slope (bytes per
// frame or per cycle, over the second half, after warm-up), the same for the malloc heap in use
// (what is allocated and not freed: resident memory also moves with the allocator's retention and
// fragmentation, the heap only with what someone holds), minor page faults per frame or cycle
// (pages the process mapped afresh), and the device's live gdi objects before and after.
// --check exits 1 when live objects grew (CI runs a short version with it); --out writes JSON.
//   fe_soak [--backend all|NAME] [--frames 10000] [--cycles 1000] [--scene builtin:shadows]
//           [--technique deferred] [--size 64x64] [--out soak.json] [--check]
#include <malloc.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "assets/BuiltinScenes.h"
#include "fe/gdi/Backend.h"
#include "fe/gdi/Faults.h"  // toString(LiveObjects)
#include <nlohmann/json.hpp>

#include "fe/gdi/InfoJson.h"
#include "integration/SceneRenderer.h"

using namespace fe;

namespace {

double residentBytes() {
    long pages = 0, resident = 0;
    std::ifstream("/proc/self/statm") >> pages >> resident;
    return double(resident) * double(sysconf(_SC_PAGESIZE));
}

// Bytes handed out by malloc and not yet freed, over every arena (glibc): the arenas' chunks in
// use plus the large blocks malloc maps on their own.
double heapInUseBytes() {
    const struct mallinfo2 m = mallinfo2();
    return double(m.uordblks + m.hblkhd);
}

long minorFaults() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return u.ru_minflt;
}

// Least-squares slope of y over x = 0, 1, 2, ... (the second half of the samples).
double slope(const std::vector<double>& all) {
    const std::vector<double> y(all.begin() + std::ptrdiff_t(all.size() / 2), all.end());
    const double n = double(y.size());
    if (n < 2) return 0;
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (size_t i = 0; i < y.size(); ++i) {
        sx += double(i);
        sy += y[i];
        sxx += double(i) * double(i);
        sxy += double(i) * y[i];
    }
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

struct Phase {
    std::string name;
    uint32_t steps = 0;
    std::vector<double> resident, heap;  // after each step
    double faultsPerStep = 0;
    gdi::LiveObjects before, after;

    // Before the first sample: the samples' own storage growing would count as heap growth
    // (16 bytes a step, measured as +36 bytes/step on every backend before this).
    void reserve() {
        resident.reserve(steps);
        heap.reserve(steps);
    }

    gdi::Json json() const {
        return {{"steps", steps},
                {"residentStartMiB", resident.front() / 1048576.0},
                {"residentEndMiB", resident.back() / 1048576.0},
                {"slopeBytesPerStep", slope(resident)},
                {"heapInUseStartMiB", heap.front() / 1048576.0},
                {"heapInUseEndMiB", heap.back() / 1048576.0},
                {"heapSlopeBytesPerStep", slope(heap)},
                {"minorFaultsPerStep", faultsPerStep},
                {"liveBefore", gdi::toString(before)},
                {"liveAfter", gdi::toString(after)},
                {"liveObjectsGrew", !(before == after)}};
    }
};

struct Options {
    std::string backend = "all", scene = "builtin:shadows", technique = "deferred", out;
    uint32_t frames = 10000, cycles = 1000, width = 64, height = 64;
    bool check = false;
};

render::RenderSettings settingsOf(const Options& o) {
    render::RenderSettings s;
    s.technique = o.technique;
    s.width = o.width;
    s.height = o.height;
    return s;
}

Phase frames(gdi::Device& device, const Options& o) {
    Phase p{.name = "frames", .steps = o.frames};
    const assets::Scene scene = assets::loadScene(o.scene);
    render::SceneRenderer renderer(device, scene, settingsOf(o));
    renderer.renderFrame();  // warm-up: the graph's and the queue's first allocations
    renderer.passTimings();
    p.reserve();
    p.before = device.liveObjects();
    const long faults = minorFaults();
    for (uint32_t f = 0; f < o.frames; ++f) {
        renderer.renderFrame();
        renderer.passTimings();  // waits for the frame
        p.resident.push_back(residentBytes());
        p.heap.push_back(heapInUseBytes());
    }
    p.faultsPerStep = double(minorFaults() - faults) / o.frames;
    p.after = device.liveObjects();
    return p;
}

Phase churn(gdi::Device& device, const Options& o) {
    Phase p{.name = "churn", .steps = o.cycles};
    p.reserve();
    p.before = device.liveObjects();
    const long faults = minorFaults();
    for (uint32_t c = 0; c < o.cycles; ++c) {
        const assets::Scene scene = assets::loadScene(o.scene);
        render::SceneRenderer renderer(device, scene, settingsOf(o));
        renderer.renderFrame();
        renderer.passTimings();
        p.resident.push_back(residentBytes());
        p.heap.push_back(heapInUseBytes());
    }
    p.faultsPerStep = double(minorFaults() - faults) / o.cycles;
    p.after = device.liveObjects();
    return p;
}

uint32_t number(const char* flag, const char* text) {
    char* end = nullptr;
    const unsigned long v = std::strtoul(text, &end, 10);
    if (*end || v > 10000000 || text[0] == '-') {
        std::cerr << "fe_soak: " << flag << " takes a count, got '" << text << "'\n";
        std::exit(2);
    }
    return uint32_t(v);
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&] {
            if (i + 1 >= argc) {
                std::cerr << "fe_soak: " << a << " needs a value\n";
                std::exit(2);
            }
            return argv[++i];
        };
        if (a == "--backend")
            o.backend = value();
        else if (a == "--frames")
            o.frames = number("--frames", value());
        else if (a == "--cycles")
            o.cycles = number("--cycles", value());
        else if (a == "--scene")
            o.scene = value();
        else if (a == "--technique")
            o.technique = value();
        else if (a == "--out")
            o.out = value();
        else if (a == "--check")
            o.check = true;
        else if (a == "--size") {
            const std::string s = value();
            const size_t x = s.find('x');
            if (x == std::string::npos) {
                std::cerr << "fe_soak: --size takes WxH\n";
                return 2;
            }
            o.width = number("--size", s.substr(0, x).c_str());
            o.height = number("--size", s.substr(x + 1).c_str());
        } else {
            std::cerr << "fe_soak: unknown option '" << a << "'\n";
            return 2;
        }
    }
    try {
        gdi::Json results = gdi::Json::object();
        bool grew = false;
        for (const std::string& backend : gdi::expandBackendList(o.backend)) {
            auto device = gdi::createDevice({.backend = backend});
            const bool soft = device->info().softwareRasterizer;
            gdi::Json b = gdi::Json::object();
            b["device"] = device->info().deviceName + (soft ? " [software rasterizer]" : "");
            for (const Phase& p : {frames(*device, o), churn(*device, o)}) {
                if (p.steps == 0) continue;
                const gdi::Json j = p.json();
                grew = grew || j["liveObjectsGrew"].get<bool>();
                std::printf(
                    "%-10s %-6s %6u steps: resident %.1f -> %.1f MiB, slope %+.1f bytes/step; heap in use %.1f -> %.1f MiB, "
                    "slope %+.1f bytes/step; %.1f minor faults/step, live objects %s -> %s\n",
                    backend.c_str(), p.name.c_str(), p.steps, j["residentStartMiB"].get<double>(),
                    j["residentEndMiB"].get<double>(), j["slopeBytesPerStep"].get<double>(),
                    j["heapInUseStartMiB"].get<double>(), j["heapInUseEndMiB"].get<double>(),
                    j["heapSlopeBytesPerStep"].get<double>(), p.faultsPerStep,
                    j["liveBefore"].get<std::string>().c_str(),
                    j["liveAfter"].get<std::string>().c_str());
                b[p.name] = j;
            }
            results[backend] = b;
        }
        if (!o.out.empty()) std::ofstream(o.out) << results.dump(2) << "\n";
        if (o.check && grew) {
            std::cerr << "fe_soak: live gdi objects grew\n";
            return 1;
        }
    } catch (const std::exception& e) {
        std::cerr << "fe_soak: " << e.what() << "\n";
        return 1;
    }
    return 0;
}

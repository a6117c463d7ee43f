// What capturing costs (issue 27), per backend and scene: frame time of fe render's renderer
// with the device captured and not, frames alternating between the two devices in one run (so
// the ratio is steady), medians; and the bytes a captured frame adds to the file. Prints a
// markdown table; on lavapipe/llvmpipe these are software-rasterizer figures.
//   fe_bench_capture [--backend NAME|all] [--size WxH] [--frames N] [--technique NAME] [--scenes spheres,lights]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "assets/BuiltinScenes.h"
#include "fe/gdi/Backend.h"
#include "fe/gdi/Capture.h"
#include "integration/SceneRenderer.h"

using namespace fe;
using Clock = std::chrono::steady_clock;

namespace {

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0 : v[v.size() / 2];
}

struct Row {
    double plainMs = 0, capturedMs = 0;
    double rawBytesPerFrame = 0, fileBytes = 0, rawBytes = 0;
};

Row measure(const std::string& backend, const assets::Scene& scene,
            const render::RenderSettings& settings, uint32_t frames) {
    const std::string file =
        (std::filesystem::temp_directory_path() / "fe_bench_capture.fecap").string();
    auto plainDevice = gdi::createDevice({.backend = backend, .verbose = false});
    auto capturedDevice =
        gdi::createDevice({.backend = backend, .verbose = false, .capture = file});
    render::SceneRenderer plain(*plainDevice, scene, settings);
    render::SceneRenderer captured(*capturedDevice, scene, settings);
    auto frame = [](render::SceneRenderer& r, gdi::Device& d) {
        const auto start = Clock::now();
        r.renderFrame();
        d.waitIdle();
        return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    };
    for (int i = 0; i < 3; ++i) frame(plain, *plainDevice), frame(captured, *capturedDevice);
    const uint64_t rawBefore = gdi::captureStats(*capturedDevice)->rawBytes;
    std::vector<double> plainMs, capturedMs;
    // Alternating which goes first, so neither gains from running after the other.
    for (uint32_t i = 0; i < frames; ++i) {
        if (i % 2) {
            plainMs.push_back(frame(plain, *plainDevice));
            capturedMs.push_back(frame(captured, *capturedDevice));
        } else {
            capturedMs.push_back(frame(captured, *capturedDevice));
            plainMs.push_back(frame(plain, *plainDevice));
        }
    }
    Row row{median(plainMs), median(capturedMs)};
    row.rawBytesPerFrame =
        double(gdi::captureStats(*capturedDevice)->rawBytes - rawBefore) / frames;
    gdi::finishCapture(*capturedDevice);
    const gdi::CaptureStats s = *gdi::captureStats(*capturedDevice);
    row.fileBytes = double(s.fileBytes), row.rawBytes = double(s.rawBytes);
    std::filesystem::remove(file);
    return row;
}

}  // namespace

int main(int argc, char** argv) {
    std::string which = "all", technique = "forward", scenes = "spheres,lights";
    uint32_t width = 1280, height = 720, frames = 20;
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string a = argv[i], v = argv[i + 1];
        if (a == "--backend")
            which = v;
        else if (a == "--technique")
            technique = v;
        else if (a == "--scenes")
            scenes = v;
        else if (a == "--frames")
            frames = uint32_t(std::stoul(v));
        else if (a == "--size" && std::sscanf(v.c_str(), "%ux%u", &width, &height) == 2) {
        } else {
            std::fprintf(
                stderr,
                "usage: fe_bench_capture [--backend NAME|all] [--size WxH] [--frames N] [--technique NAME] [--scenes spheres,lights]\n");
            return 2;
        }
    }
    try {
        std::printf(
            "| backend | scene | %ux%u %s: frame, not captured | captured | ratio | bytes a frame adds (raw) | file: setup + frames, zstd |\n",
            width, height, technique.c_str());
        std::printf("|---|---|---|---|---|---|---|\n");
        for (const std::string& backend : gdi::expandBackendList(which)) {
            for (const std::string& name : {std::string("spheres"), std::string("lights")}) {
                if (scenes.find(name) == std::string::npos) continue;
                const assets::Scene scene = assets::makeBuiltinScene(name, {});
                const Row r =
                    measure(backend, scene,
                            {.technique = technique, .width = width, .height = height}, frames);
                std::printf(
                    "| %s | builtin:%s | %.2f ms | %.2f ms | %.3fx | %.0f | %.0f KiB of %.0f KiB |\n",
                    backend.c_str(), name.c_str(), r.plainMs, r.capturedMs,
                    r.capturedMs / r.plainMs, r.rawBytesPerFrame, r.fileBytes / 1024,
                    r.rawBytes / 1024);
            }
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fe_bench_capture: %s\n", e.what());
        return 1;
    }
    return 0;
}

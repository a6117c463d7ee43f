#include "CaptureCommands.h"

#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <numeric>

#include "fe/gdi/Backend.h"
#include "fe/gdi/Capture.h"

extern char** environ;

namespace fe::cli {

namespace {

void printSummary(const std::string& path) {
    const gdi::CaptureSummary s = gdi::summarizeCapture(path);
    std::cout << path << ": captured on " << s.backend << " (" << s.device << "), format " << s.formatVersion << "\n"
              << "  " << s.frames << " frame(s), " << s.submits << " submission(s), " << s.records << " calls, " << s.blobs
              << " data blocks\n"
              << "  " << s.fileBytes << " bytes on disk (" << s.rawBytes << " uncompressed)";
    if (s.frames) std::cout << ", " << s.fileBytes / s.frames << " bytes per frame";
    std::cout << "\n";
}

double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

}  // namespace

int cmdCapture(int argc, char** argv) {
    int dashes = 2;
    while (dashes < argc && std::strcmp(argv[dashes], "--") != 0) ++dashes;
    const Args a = parse(dashes, argv, 2, {"--out", "--frames"}, {"--no-compress"});
    if (!a.positional.empty()) throw UsageError("capture: put the program after --, e.g. fe capture -- fe render");
    if (dashes + 1 >= argc) throw UsageError("capture: no program to run (fe capture [options] -- PROGRAM [ARGS...])");
    const std::string out = a.options.count("--out") ? a.options.at("--out") : "capture.fecap";
    const uint32_t frames = a.options.count("--frames") ? parseUint(a.options.at("--frames"), "--frames", 1, 1000000) : 0;
    setenv("FE_CAPTURE", out.c_str(), 1);
    setenv("FE_CAPTURE_FRAMES", std::to_string(frames).c_str(), 1);
    if (a.options.count("--no-compress")) setenv("FE_CAPTURE_COMPRESS", "0", 1);
    pid_t child = 0;
    if (const int e = posix_spawnp(&child, argv[dashes + 1], nullptr, nullptr, argv + dashes + 1, environ); e != 0)
        throw gdi::Error(std::string("capture: cannot run '") + argv[dashes + 1] + "': " + std::strerror(e));
    int status = 0;
    while (waitpid(child, &status, 0) < 0 && errno == EINTR) {
    }
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    if (code != 0) std::cerr << "fe: capture: " << argv[dashes + 1] << " ended with exit code " << code << "\n";
    printSummary(out);
    return code;
}

int cmdReplay(const Args& a) {
    if (a.positional.size() != 1) throw UsageError("replay takes one capture FILE");
    const std::string& path = a.positional[0];
    auto device = gdi::createDevice({.backend = a.options.count("--backend") ? a.options.at("--backend") : "auto",
                                     .validation = a.options.count("--validation") > 0,
                                     .window = a.options.count("--present") > 0});
    gdi::ReplayOptions options{.outDir = a.options.count("--out") ? a.options.at("--out") : "",
                               .present = a.options.count("--present") > 0};
    const gdi::ReplayResult r = gdi::replayCapture(path, *device, options);
    std::cout << path << ": captured on " << r.capturedBackend << ", replayed on " << device->info().backend << ": "
              << r.frames << " frame(s), " << r.submits << " submission(s), " << r.commandLists << " command list(s), "
              << r.images.size() << " image(s)";
    if (!options.outDir.empty()) std::cout << " in " << options.outDir;
    std::cout << "\n";
    if (!r.frameMilliseconds.empty()) {
        const double total = std::accumulate(r.frameMilliseconds.begin(), r.frameMilliseconds.end(), 0.0);
        std::cout << "  frame time: median " << median(r.frameMilliseconds) << " ms, total " << total << " ms"
                  << (device->info().softwareRasterizer ? " (software rasterizer)" : "") << "\n";
    }
    if (const uint32_t errors = device->validationErrorCount()) {
        std::cerr << "fe: replay: " << errors << " validation error(s)\n";
        return 1;
    }
    return 0;
}

}  // namespace fe::cli

#include <atomic>
#include <cstdlib>
#include <iostream>

#include "fe/gdi/Backend.h"
#include "fe/gdi/Capture.h"
#include "fe/gdi/Faults.h"
#include "gl/GlBackend.h"
#include "vulkan/VulkanBackend.h"

namespace fe::gdi {

const std::vector<std::string>& backendNames() {
    static const std::vector<std::string> names = {"vulkan", "gl-egl", "gl-osmesa"};
    return names;
}

const std::vector<std::string>& windowBackendNames() {
    static const std::vector<std::string> names = {"vulkan-glfw", "gl-glfw"};
    return names;
}

std::string validBackendList() {
    return "auto, vulkan, gl, gl-egl, gl-osmesa, vulkan-glfw, gl-glfw";
}

namespace {

// `path` (with `frames`), else FE_CAPTURE for the first device of the process (a program that
// makes several would otherwise write them all over one file).
uint32_t frameCount(const char* variable) {
    const char* text = std::getenv(variable);
    if (!text || !*text) return 0;
    char* end = nullptr;
    const unsigned long n = std::strtoul(text, &end, 10);
    if (*end || n > UINT32_MAX)
        throw Error(std::string(variable) + ": not a frame count: '" + text + "'");
    return uint32_t(n);
}

std::unique_ptr<Device> withCapture(std::unique_ptr<Device> device, const std::string& path,
                                    uint32_t frames, uint32_t firstFrame, bool verbose) {
    CaptureDesc capture{.path = path, .frames = frames, .firstFrame = firstFrame};
    static std::atomic<bool> environmentUsed = false;
    if (capture.path.empty()) {
        const char* env = std::getenv("FE_CAPTURE");
        if (!env || !*env || environmentUsed.exchange(true)) return device;
        capture.path = env;
        capture.frames = frameCount("FE_CAPTURE_FRAMES");
        capture.firstFrame = frameCount("FE_CAPTURE_FIRST_FRAME");
        if (const char* c = std::getenv("FE_CAPTURE_COMPRESS"); c && std::string(c) == "0")
            capture.compress = false;
        if (verbose)
            std::cerr << "fe: capturing " << device->info().backend << " into " << capture.path
                      << "\n";
    }
    return makeCaptureDevice(std::move(device), capture);
}

// Starts one backend as it is (createDevice adds its own capture).
BackendProbe probeUncaptured(const std::string& name, bool validation, bool vsync, bool robust) {
    BackendProbe p;
    p.name = name;
    try {
        fault::fired(
            fault::Site::
                Allocation);  // a bad FE_FAULT_* value is reported here, before any device work
        if (name == "vulkan")
            p.device = vk::createVulkanDevice(validation, robust);
        else if (name == "gl-egl")
            p.device = gl::createGlDevice(gl::PlatformKind::Egl, validation);
        else if (name == "gl-osmesa")
            p.device = gl::createGlDevice(gl::PlatformKind::OSMesa, validation);
        else if (name == "vulkan-glfw")
            p.device = vk::createVulkanWindowDevice(validation, vsync, robust);
        else if (name == "gl-glfw")
            p.device = gl::createGlDevice(gl::PlatformKind::Glfw, validation, vsync);
        else
            throw Error("unknown backend '" + name + "' (valid: " + validBackendList() + ")");
        if (robust && !p.device->info().features.robustBufferAccess)
            throw Error(name + ": robust buffer access is not available (" +
                        (name.starts_with("gl") ? "no robust-access GL context"
                                                : "no robustBufferAccess feature") +
                        ")");
        p.available = true;
    } catch (const std::exception& e) {
        p.reason = e.what();
    }
    return p;
}

}  // namespace

BackendProbe probeBackend(const std::string& name, bool validation, bool vsync,
                          bool robustBufferAccess) {
    BackendProbe p = probeUncaptured(name, validation, vsync, robustBufferAccess);
    if (p.available) {
        try {
            p.device = withCapture(std::move(p.device), "", 0, 0, true);
        } catch (const std::exception& e) {
            p = {.name = name, .reason = e.what()};
        }
    }
    return p;
}

static std::vector<std::string> candidates(const std::string& name) {
    if (name == "auto") return backendNames();
    if (name == "gl") return {"gl-egl", "gl-osmesa"};
    if (name == "vulkan" || name == "gl-egl" || name == "gl-osmesa" || name == "vulkan-glfw" ||
        name == "gl-glfw")
        return {name};
    throw Error("unknown backend '" + name + "' (valid: " + validBackendList() + ")");
}

std::vector<std::string> windowCandidates(const std::string& name) {
    if (name == "auto") return windowBackendNames();
    if (name == "vulkan") return {"vulkan-glfw"};
    if (name == "gl") return {"gl-glfw"};
    candidates(name);  // throws for unknown names
    if (name == "vulkan-glfw" || name == "gl-glfw") return {name};
    return {};  // gl-egl, gl-osmesa: headless only
}

std::unique_ptr<Device> createDevice(const DeviceCreateDesc& desc) {
    std::string name = desc.backend;
    if (name.empty() || name == "auto") {
        if (const char* env = std::getenv("FE_BACKEND"); env && *env) name = env;
    }
    if (name.empty()) name = "auto";
    std::vector<std::string> list = desc.window ? windowCandidates(name) : candidates(name);
    if (list.empty())
        throw Error("backend '" + name +
                    "' is headless; a window needs auto, vulkan, gl, vulkan-glfw or gl-glfw");
    std::string failures;
    for (const std::string& c : list) {
        BackendProbe p = probeUncaptured(c, desc.validation, desc.vsync, desc.robustBufferAccess);
        if (p.available) {
            if (desc.verbose && list.size() > 1)
                std::cerr << "fe: backend '" << name << "' picked " << c << failures << "\n";
            // The one place a cache's warning is printed: the program asked for this file at
            // creation; openPipelineCache itself only returns it in the stats.
            if (!desc.pipelineCache.empty()) {
                const PipelineCacheStats cache = p.device->openPipelineCache(desc.pipelineCache);
                if (!cache.warning.empty()) std::cerr << "fe: " << cache.warning << "\n";
            }
            return withCapture(std::move(p.device), desc.capture, desc.captureFrames,
                               desc.captureFirstFrame, desc.verbose);
        }
        failures += "\n  " + c + " unavailable: " + p.reason;
    }
    throw Error("no backend could start for '" + name + "':" + failures);
}

std::vector<std::string> expandBackendList(const std::string& nameOrAll) {
    if (nameOrAll == "all") return backendNames();
    std::vector<std::string> out;
    size_t start = 0;
    while (start <= nameOrAll.size()) {
        size_t comma = nameOrAll.find(',', start);
        std::string item =
            nameOrAll.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        if (item == "auto" || item == "gl") {
            for (auto& c : candidates(item)) out.push_back(c);
        } else {
            candidates(item);  // throws for unknown names
            out.push_back(item);
        }
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return out;
}

}  // namespace fe::gdi

// libFuzzer harness: a glTF file loaded, then uploaded to a real device (Vulkan on lavapipe,
// validation on) as the renderer does it (GpuScene: vertex and index buffers, textures with
// their mips, samplers, lights). What loads must upload or fail with a gdi::Error (a texture
// larger than the device allows, say), never a validation error, and must leave no device
// object behind. A violation aborts, so libFuzzer records the input.
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "FuzzSupport.h"
#include "assets/AssetError.h"
#include "assets/GltfLoader.h"
#include "fe/gdi/Backend.h"
#include "fe/gdi/Faults.h"  // toString(LiveObjects)
#include "render/GpuScene.h"

namespace {
fe::gdi::Device& device() {
    static std::unique_ptr<fe::gdi::Device> d = fe::gdi::createDevice({.backend = "vulkan", .validation = true});
    return *d;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    fe::gdi::Device& d = device();
    const fe::gdi::LiveObjects before = d.liveObjects();
    const uint32_t validationBefore = d.validationErrorCount();
    std::string lost;  // a device loss: uploading must never cause one
    try {
        fe::assets::Scene scene = fe::assets::loadGltf(fe::fuzz::writeInput(data, size));
        fe::render::GpuScene uploaded(d, scene);
        d.waitIdle();
    } catch (const fe::assets::AssetError&) {
    } catch (const fe::gdi::DeviceLostError& e) {
        lost = e.what();
    } catch (const fe::gdi::Error&) {
    }
    FUZZ_CHECK(lost.empty(), "device lost:", lost);
    FUZZ_CHECK(d.liveObjects() == before, "device objects left behind:", fe::gdi::toString(d.liveObjects()));
    FUZZ_CHECK(d.validationErrorCount() == validationBefore, "validation errors while uploading", "");
    return 0;
}

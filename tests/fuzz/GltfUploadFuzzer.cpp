// libFuzzer harness: a glTF file loaded, then uploaded to a real device (Vulkan on lavapipe,
// validation on) as the renderer does it (GpuScene: vertex and index buffers, textures with
// their mips, samplers, lights). What loads must upload or fail with a gdi::Error (a texture
// larger than the device allows, say), never a validation error, and must leave no device
// object behind. A violation aborts, so libFuzzer records the input.
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "FuzzDevice.h"
#include "assets/AssetError.h"
#include "assets/GltfLoader.h"
#include "render/GpuScene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    fe::gdi::Device& d = fe::fuzz::vulkanDevice();
    const fe::fuzz::DeviceContract contract{d};
    std::string lost;  // a device loss: uploading must never cause one
    try {
        fe::assets::Scene scene = fe::assets::loadGltf(fe::fuzz::writeInput(data, size));
        fe::render::GpuScene uploaded(d, scene);
        d.waitIdle();
    } catch (const fe::assets::AssetError&) {
    } catch (const fe::gdi::DeviceLostError& e) {
        lost = e.what();
    } catch (const fe::gdi::Error&) {}
    FUZZ_CHECK_DEVICE(contract, lost, "while uploading");
    return 0;
}

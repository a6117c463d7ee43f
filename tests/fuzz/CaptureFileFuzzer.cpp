// libFuzzer harness: whole capture files (Capture.h), summarized and replayed on a real device
// (Vulkan on lavapipe, validation on). Any bytes either replay or are refused with a
// CaptureError; never a crash, a hang, a device loss, a validation error (the device's own
// checks must stop every bad call a file can make before the driver sees it) or an object left
// behind. A violation aborts, so libFuzzer records the input.
#include <cstdint>
#include <memory>

#include "FuzzDevice.h"
#include "fe/gdi/Capture.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    fe::gdi::Device& d = fe::fuzz::vulkanDevice();
    const fe::fuzz::DeviceContract contract{d};
    const std::string path = fe::fuzz::writeInput(data, size);
    std::string lost;
    try {
        fe::gdi::summarizeCapture(path);
        // Work bounded so that each input replays in well under the harness's timeout on
        // lavapipe under ASan (the seeds draw a few thousand vertices).
        fe::gdi::replayCapture(path, d,
                               {.maxDrawVertices = 1u << 20, .maxDispatchGroups = 1u << 16});
    } catch (const fe::gdi::CaptureError&) {
    } catch (const fe::gdi::DeviceLostError& e) {
        lost = e.what();
    }
    d.waitIdle();
    FUZZ_CHECK_DEVICE(contract, lost, "while replaying");
    return 0;
}

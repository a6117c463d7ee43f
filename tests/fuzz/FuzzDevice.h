// The device side of the harnesses that feed a real device (GltfUploadFuzzer, CaptureFileFuzzer):
// one Vulkan device (lavapipe, validation on) for the whole run, and the contract each input is
// held to: no device loss, no device object left behind, no validation error.
#pragma once
#include <memory>
#include <string>

#include "FuzzSupport.h"
#include "fe/gdi/Backend.h"
#include "fe/gdi/Faults.h"  // toString(LiveObjects)

namespace fe::fuzz {

inline gdi::Device& vulkanDevice() {
    static std::unique_ptr<gdi::Device> d =
        gdi::createDevice({.backend = "vulkan", .validation = true});
    return *d;
}

// Taken before an input; check() after it (`lost`: a DeviceLostError's message, if any).
struct DeviceContract {
    gdi::Device& device;
    gdi::LiveObjects before = device.liveObjects();
    uint32_t validationBefore = device.validationErrorCount();
    void check(const std::string& lost, const char* while_) const {
        FUZZ_CHECK(lost.empty(), "device lost:", lost);
        FUZZ_CHECK(device.liveObjects() == before,
                   "device objects left behind:", gdi::toString(device.liveObjects()));
        FUZZ_CHECK(device.validationErrorCount() == validationBefore, "validation errors", while_);
    }
};

}  // namespace fe::fuzz

// The harness's assertion after each input: aborts (libFuzzer keeps the input) on a violation.
#define FUZZ_CHECK_DEVICE(contract, lost, while_) (contract).check(lost, while_)

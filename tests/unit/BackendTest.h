// A test fixture parameterised by backend name: the device is created with the validation
// layer / GL debug output on, the test is skipped (with the reason) where the backend cannot
// start, and any validation error during the test fails it.
#pragma once
#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <string>

#include "fe/gdi/Backend.h"

namespace fe::testing {

class BackendTest : public ::testing::TestWithParam<std::string> {
protected:
    BackendTest() = default;
    // A suite whose cases only make objects and render with them (no device loss, no injected
    // faults, no misuse) passes true: its cases take turns with one device per backend, as an
    // application keeps one device for many scenes, instead of opening one each (65 ms with the
    // Vulkan validation layer), and each case must leave the device as it found it (no object
    // left alive, no validation error): a case that does not gets a fresh device after it.
    explicit BackendTest(bool sharedDevice) : sharedDevice_(sharedDevice) {}

    void SetUp() override {
        if (sharedDevice_) {
            auto it = idleDevices().find(GetParam());
            if (it != idleDevices().end()) device = std::move(it->second), idleDevices().erase(it);
        }
        if (!device) {
            gdi::BackendProbe p = gdi::probeBackend(GetParam(), true);
            if (!p.available) GTEST_SKIP() << GetParam() << " unavailable: " << p.reason;
            device = std::move(p.device);
        }
        errorsBefore_ = device->validationErrorCount();
        objectsBefore_ = device->liveObjects();
    }
    void TearDown() override {
        if (!device) return;
        const uint32_t errors = device->validationErrorCount() - errorsBefore_;
        EXPECT_EQ(errors, 0u);
        if (!sharedDevice_) return;
        const gdi::LiveObjects objects = device->liveObjects();
        EXPECT_TRUE(objects == objectsBefore_)
            << "the case left objects alive on a device its suite shares: " << objects.buffers
            << " buffers, " << objects.textures << " textures, " << objects.pipelines
            << " pipelines, " << objects.shaders << " shaders (before: " << objectsBefore_.buffers
            << ", " << objectsBefore_.textures << ", " << objectsBefore_.pipelines << ", "
            << objectsBefore_.shaders << ")";
        if (errors == 0 && objects == objectsBefore_ && !HasFailure())
            idleDevices()[GetParam()] = std::move(device);
    }
    // The devices of a suite go with it.
    static void TearDownTestSuite() { idleDevices().clear(); }

    std::unique_ptr<gdi::Device> device;

private:
    static std::map<std::string, std::unique_ptr<gdi::Device>>& idleDevices() {
        static std::map<std::string, std::unique_ptr<gdi::Device>> devices;
        return devices;
    }
    bool sharedDevice_ = false;
    uint32_t errorsBefore_ = 0;
    gdi::LiveObjects objectsBefore_;
};

// The message of the gdi::Error f throws, or "(no error)": tests match on the message text.
template <class F>
std::string errorOf(F&& f) {
    try {
        f();
    } catch (const gdi::Error& e) {
        return e.what();
    }
    return "(no error)";
}

// gtest names may not contain '-': gl-egl -> gl_egl.
inline std::string backendTestName(const ::testing::TestParamInfo<std::string>& info) {
    std::string n = info.param;
    for (char& c : n)
        if (c == '-') c = '_';
    return n;
}

}  // namespace fe::testing

#define FE_INSTANTIATE_FOR_EVERY_BACKEND(Fixture)                                             \
    INSTANTIATE_TEST_SUITE_P(Backends, Fixture, ::testing::ValuesIn(fe::gdi::backendNames()), \
                             fe::testing::backendTestName)

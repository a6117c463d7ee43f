// A test fixture parameterised by backend name: the device is created with the validation
// layer / GL debug output on, the test is skipped (with the reason) where the backend cannot
// start, and any validation error during the test fails it.
#pragma once
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "fe/gdi/Backend.h"

namespace fe::testing {

class BackendTest : public ::testing::TestWithParam<std::string> {
protected:
    void SetUp() override {
        gdi::BackendProbe p = gdi::probeBackend(GetParam(), true);
        if (!p.available) GTEST_SKIP() << GetParam() << " unavailable: " << p.reason;
        device = std::move(p.device);
    }
    void TearDown() override {
        if (device) {
            EXPECT_EQ(device->validationErrorCount(), 0u);
        }
    }
    std::unique_ptr<gdi::Device> device;
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

// The execution-model conformance cases that use threads, as a small test program of its own:
// `tools/run-thread-sanitized-tests.sh` builds just this under ThreadSanitizer (CI), and the
// normal suite runs it too. Each case runs on every backend that starts here.
#include <gtest/gtest.h>

#include "Conformance.h"
#include "fe/gdi/Backend.h"

namespace fe::conformance {
namespace {

class ExecutionModel : public ::testing::TestWithParam<std::string> {};

const Case& caseNamed(const std::string& name) {
    for (const Case& c : cases())
        if (c.name == name) return c;
    throw std::runtime_error("no conformance case " + name);
}

TEST_P(ExecutionModel, ThreadedCasesPass) {
    const std::string backend = GetParam();
    if (!gdi::probeBackend(backend, false).available) GTEST_SKIP() << backend << " is not available here";
    auto device = gdi::createDevice({.backend = backend, .validation = true});
    for (const char* name : {"submission_order", "record_on_threads", "create_while_recording", "destroy_while_in_flight",
                             "mapped_upload_ring", "async_readback", "data_read_at_execution"}) {
        const CaseResult r = runCase(*device, caseNamed(name));
        EXPECT_TRUE(r.passed) << backend << " " << name << ": " << r.message;
    }
    EXPECT_EQ(device->validationErrorCount(), 0u);
}

INSTANTIATE_TEST_SUITE_P(Backends, ExecutionModel, ::testing::Values("vulkan", "gl-egl", "gl-osmesa"),
                         [](const auto& info) {
                             std::string n = info.param;
                             for (char& c : n) c = c == '-' ? '_' : c;
                             return n;
                         });

}  // namespace
}  // namespace fe::conformance

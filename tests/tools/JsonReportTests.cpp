// `fe info --json` and the conformance report are JSON documents that describe every backend
// the same way (fe/gdi/InfoJson.h); these tests parse what the fe tool writes.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <string>
#include <type_traits>

#include "fe/gdi/DeviceInfoFields.h"
#include "fe/gdi/InfoJson.h"

using nlohmann::json;

namespace {

// Runs the fe tool with `args`; returns its stdout (and stderr when asked) and sets `exitCode`.
std::string runFe(const std::string& args, int& exitCode, bool withStderr = false) {
    const std::string command =
        std::string(FE_TOOL) + " " + args + (withStderr ? " 2>&1" : " 2>/dev/null");
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) throw std::runtime_error("cannot run " + command);
    std::string out;
    char buffer[4096];
    while (size_t n = fread(buffer, 1, sizeof buffer, pipe)) out.append(buffer, n);
    const int status = pclose(pipe);
    exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return out;
}

// The headless backends the test machine has (lavapipe, llvmpipe through EGL and OSMesa).
const std::set<std::string> kHeadless = {"vulkan", "gl-egl", "gl-osmesa"};

// A device summary: the DeviceInfo fields, every limit and every feature.
void expectDeviceSummary(const json& d, const std::string& backend) {
    ASSERT_TRUE(d.is_object()) << backend;
    EXPECT_EQ(d["backend"], backend);
    for (const char* key : {"deviceName", "apiVersion", "driverName", "driverInfo", "deviceType"}) {
        ASSERT_TRUE(d[key].is_string()) << backend << " " << key;
        EXPECT_FALSE(d[key].get<std::string>().empty()) << backend << " " << key;
    }
    EXPECT_TRUE(d["softwareRasterizer"].is_boolean()) << backend;
    EXPECT_TRUE(d["conformanceVersion"].is_string()) << backend;
    ASSERT_TRUE(d["memoryHeaps"].is_array()) << backend;
    for (const json& h : d["memoryHeaps"])
        EXPECT_TRUE(h["bytes"].is_number_unsigned() && h["deviceLocal"].is_boolean()) << backend;
    size_t limits = 0, features = 0;
    fe::gdi::forEachField(fe::gdi::DeviceLimits{}, [&](const char* name, const auto& value) {
        ++limits;
        if (std::string(name).ends_with("SampleCounts")) {  // the counts, as vulkaninfo lists them
            ASSERT_TRUE(d["limits"][name].is_array()) << backend << " limit " << name;
            for (const json& n : d["limits"][name])
                EXPECT_TRUE(n == 1 || n == 2 || n == 4 || n == 8 || n == 16 || n == 32 || n == 64)
                    << backend << " limit " << name << ": " << n;
            return;
        }
        if constexpr (std::is_floating_point_v<std::decay_t<decltype(value)>>)
            EXPECT_TRUE(d["limits"][name].is_number()) << backend << " limit " << name;
        else if constexpr (!std::is_arithmetic_v<std::decay_t<decltype(value)>>)  // x, y, z
            EXPECT_TRUE(d["limits"][name].is_array() && d["limits"][name].size() == value.size())
                << backend << " limit " << name;
        else
            EXPECT_TRUE(d["limits"][name].is_number_unsigned()) << backend << " limit " << name;
    });
    fe::gdi::forEachField(fe::gdi::DeviceFeatures{}, [&](const char* name, const auto&) {
        ++features;
        EXPECT_TRUE(d["features"][name].is_boolean()) << backend << " feature " << name;
    });
    EXPECT_EQ(d["limits"].size(), limits) << backend;
    EXPECT_EQ(d["features"].size(), features) << backend;
    EXPECT_GE(d["limits"]["maxTextureSize2D"].get<uint32_t>(), 4096u) << backend;
}

}  // namespace

// The conversion itself: every limit and feature appears under its name with its value.
TEST(InfoJson, DeviceInfoCarriesEveryField) {
    fe::gdi::DeviceInfo info{.backend = "test",
                             .deviceName = "dev",
                             .apiVersion = "api",
                             .driverName = "driver",
                             .driverInfo = "drv",
                             .conformanceVersion = "1.3.1.1",
                             .deviceType = "cpu"};
    info.memoryHeaps = {{.bytes = 1ull << 33, .deviceLocal = true}};
    info.limits = {.maxTextureSize2D = 16384,
                   .maxColorAttachments = 8,
                   .maxComputeWorkGroupInvocations = 1024,
                   .maxUniformBufferRange = 65536,
                   .maxStorageBufferRange = 1ull << 31,
                   .uniformBufferOffsetAlignment = 256,
                   .storageBufferOffsetAlignment = 64};
    info.features.computeShaders = true;
    info.features.window = true;
    const fe::gdi::Json ordered = info;
    const json j = json::parse(ordered.dump());  // as a reader of the document sees it
    expectDeviceSummary(j, "test");
    fe::gdi::forEachField(info.limits, [&](const char* name, const auto& value) {
        if (!std::string(name).ends_with("SampleCounts")) {
            EXPECT_EQ(j["limits"][name], value) << name;
        }
    });
    info.limits.colorSampleCounts = 1 | 4 | 8;
    EXPECT_EQ(json::parse(fe::gdi::Json(info).dump())["limits"]["colorSampleCounts"],
              json::array({1, 4, 8}))
        << "a sample-count bit set is listed as its counts";
    EXPECT_EQ(j["memoryHeaps"][0]["bytes"].get<uint64_t>(), 1ull << 33);
    EXPECT_EQ(j["driverName"], "driver");
    fe::gdi::forEachField(info.features, [&](const char* name, const auto& value) {
        EXPECT_EQ(j["features"][name], value) << name;
    });
    EXPECT_EQ(j["limits"]["maxStorageBufferRange"].get<uint64_t>(), 1ull << 31);
}

TEST(FeInfoJson, ListsEveryBackendWithItsDevice) {
    int exitCode = -1;
    const std::string out = runFe("info --json", exitCode);
    EXPECT_EQ(exitCode, 0);
    const json doc = json::parse(out);  // throws, failing the test, if the output is not JSON
    EXPECT_EQ(doc["engine"]["name"], "Fools Engine");
    EXPECT_FALSE(doc["engine"]["commit"].get<std::string>().empty());
    std::set<std::string> available, listed;
    for (const json& b : doc["backends"]) {
        const std::string name = b["name"];
        listed.insert(name);
        if (b["available"].get<bool>()) {
            available.insert(name);
            expectDeviceSummary(b["device"], name);
        } else {
            EXPECT_FALSE(b["reason"].get<std::string>().empty())
                << name << ": unavailable without a reason";
        }
    }
    EXPECT_EQ(listed,
              (std::set<std::string>{"vulkan", "gl-egl", "gl-osmesa", "vulkan-glfw", "gl-glfw"}));
    for (const std::string& b : kHeadless)
        EXPECT_TRUE(available.count(b)) << b << " is not available";
}

TEST(FeInfoJson, BackendOptionSelectsAndUnknownNamesFail) {
    int exitCode = -1;
    const json doc = json::parse(runFe("info --json --backend gl", exitCode));
    EXPECT_EQ(exitCode, 0);
    ASSERT_EQ(doc["backends"].size(), 2u);
    EXPECT_EQ(doc["backends"][0]["name"], "gl-egl");
    EXPECT_EQ(doc["backends"][1]["name"], "gl-osmesa");
    const std::string out = runFe("info --json --backend metal", exitCode, true);
    EXPECT_EQ(exitCode, 1);
    EXPECT_NE(out.find("unknown backend 'metal'"), std::string::npos) << out;
}

// The report of a run on every backend: the device summary per backend, each case with its
// images' metrics, each cross-backend comparison with its metrics.
TEST(ConformanceReport, CarriesDevicesCasesAndComparisons) {
    const std::string path = std::string(FE_TEST_OUT_DIR) + "/report_test.json";
    std::filesystem::remove(path);
    int exitCode = -1;
    runFe("conformance --backend all --case triangle --report " + path, exitCode);
    EXPECT_EQ(exitCode, 0);
    std::ifstream f(path);
    ASSERT_TRUE(f) << "no report written at " << path;
    const json report = json::parse(f);

    EXPECT_EQ(report["schema"], "fe-results/1");  // the bench's schema too
    EXPECT_EQ(report["kind"], "conformance");
    EXPECT_EQ(report["engine"]["name"], "Fools Engine");
    EXPECT_TRUE(std::regex_match(report["date"].get<std::string>(),
                                 std::regex(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ)")))
        << report["date"];
    std::set<std::string> backends;
    for (const json& b : report["backends"]) {
        ASSERT_TRUE(b["available"].get<bool>()) << b.dump();
        expectDeviceSummary(b["device"], b["name"]);
        EXPECT_TRUE(b["device"]["features"]["validation"].get<bool>())
            << "conformance runs with validation";
        backends.insert(b["name"]);
    }
    EXPECT_EQ(backends, kHeadless);

    ASSERT_EQ(report["cases"].size(), 3u);
    for (const json& c : report["cases"]) {
        EXPECT_EQ(c["case"], "triangle");
        EXPECT_TRUE(c["passed"].get<bool>()) << c.dump();
        ASSERT_EQ(c["images"].size(), 1u);
        const json& image = c["images"][0];
        EXPECT_EQ(image["metrics"]["pixels"], 64 * 64);
        EXPECT_EQ(image["metrics"]["pixelsOverTolerance"], 0);
        EXPECT_TRUE(image["metrics"]["maxAbsError"].is_number());
        EXPECT_GT(image["tolerance"]["absolute"].get<double>(), 0.0);
        EXPECT_FALSE(image["tolerance"]["reason"].get<std::string>().empty());
    }

    ASSERT_EQ(report["comparisons"].size(), 2u);  // gl-egl and gl-osmesa against vulkan
    for (const json& c : report["comparisons"]) {
        EXPECT_EQ(c["reference"], "vulkan");
        EXPECT_TRUE(c["passed"].get<bool>()) << c.dump();
        EXPECT_EQ(c["metrics"]["pixels"], 64 * 64);
        EXPECT_TRUE(c["metrics"]["pixelsOverTolerance"].is_number_unsigned());
        EXPECT_TRUE(c["metrics"]["maxAbsError"].is_number());
        EXPECT_FALSE(c["tolerance"]["reason"].get<std::string>().empty());
    }
    EXPECT_EQ(report["summary"]["passed"], 5);
    EXPECT_EQ(report["summary"]["failed"], 0);
}

// A report that cannot be written is an error naming it and why, before any case runs (a
// directory under a regular file cannot be made, even by root).
TEST(ConformanceReport, UnwritablePathIsAnError) {
    int exitCode = -1;
    const std::string report = std::string(FE_TOOL) + "/dir/report.json";
    const std::string out =
        runFe("conformance --backend vulkan --case triangle --report " + report, exitCode, true);
    EXPECT_EQ(exitCode, 1);
    EXPECT_NE(out.find("cannot create the directory " + std::string(FE_TOOL) +
                       "/dir for --report: Not a directory"),
              std::string::npos)
        << out;
    EXPECT_EQ(out.find("PASS"), std::string::npos) << "a case ran before the check: " << out;
}

#include "fe/gdi/InfoJson.h"

#include <chrono>
#include <ctime>
#include <nlohmann/json.hpp>

#include "fe/gdi/DeviceInfoFields.h"
#include "fe_version.h"  // generated at build time (cmake/FeVersion.cmake)

namespace fe::gdi {

namespace {
// A sample-count bit set as the counts it holds ({1, 4}), as vulkaninfo lists them.
Json sampleCountList(uint32_t bits) {
    Json counts = Json::array();
    for (uint32_t n = 1; n <= 64; n *= 2)
        if (bits & n) counts.push_back(n);
    return counts;
}
}  // namespace

void to_json(Json& j, const DeviceLimits& limits) {
    j = Json::object();
    forEachField(limits, [&](const char* name, const auto& value) { j[name] = value; });
    j["colorSampleCounts"] = sampleCountList(limits.colorSampleCounts);
    j["depthSampleCounts"] = sampleCountList(limits.depthSampleCounts);
}

void to_json(Json& j, const DeviceFeatures& features) {
    j = Json::object();
    forEachField(features, [&](const char* name, const auto& value) { j[name] = value; });
}

void to_json(Json& j, const DeviceInfo& info) {
    j = {{"backend", info.backend},         {"deviceName", info.deviceName},
         {"apiVersion", info.apiVersion},   {"driverName", info.driverName},
         {"driverInfo", info.driverInfo},   {"conformanceVersion", info.conformanceVersion},
         {"deviceType", info.deviceType},   {"softwareRasterizer", info.softwareRasterizer},
         {"presentMode", info.presentMode}, {"limits", info.limits},
         {"features", info.features}};
    Json heaps = Json::array();
    for (const DeviceInfo::MemoryHeap& h : info.memoryHeaps)
        heaps.push_back({{"bytes", h.bytes}, {"deviceLocal", h.deviceLocal}});
    j["memoryHeaps"] = heaps;
}

void to_json(Json& j, const ImageDiff& d) {
    j = {{"pixels", d.pixels},
         {"pixelsOverTolerance", d.pixelsOverTolerance},
         {"fractionOver", d.fractionOver()},
         {"maxAbsError", d.maxAbsError}};
}

Json probeJson(const BackendProbe& probe, bool withExtensions) {
    Json j = {{"name", probe.name}, {"available", probe.available && probe.device}};
    if (probe.available && probe.device) {
        j["device"] = probe.device->info();
        if (withExtensions) j["device"]["extensions"] = probe.device->info().extensions;
        // Device::formatCaps per format: what each can do here.
        Json formats = Json::object();
        for (uint32_t i = 1; i < uint32_t(Format::Count); ++i) {
            const FormatCaps c = probe.device->formatCaps(Format(i));
            formats[std::string(formatInfo(Format(i)).name)] = {
                {"sampled", c.sampled},
                {"linearFilter", c.linearFilter},
                {"renderTarget", c.renderTarget},
                {"blend", c.blend},
                {"storage", c.storage},
                {"sampleCounts", sampleCountList(c.sampleCounts)}};
        }
        j["device"]["formats"] = formats;
    } else {
        j["reason"] = probe.reason;
    }
    return j;
}

Json engineJson() {
    return {{"name", "Fools Engine"}, {"version", FE_VERSION}, {"commit", FE_GIT_DESCRIBE}};
}

std::string utcTimestamp() {
    const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
    std::tm utc{};
    gmtime_r(&now, &utc);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
    return text;
}

}  // namespace fe::gdi

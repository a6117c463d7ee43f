// JSON forms of what devices report (nlohmann::json), shared by `fe info --json`, the
// conformance report and benchmarks, so every report describes a device the same way.
// Limits and features are written field by field from DeviceInfoFields.h.
#pragma once
#include <nlohmann/json_fwd.hpp>
#include <string>

#include "fe/gdi/Backend.h"
#include "fe/gdi/Image.h"
#include "fe/gdi/Device.h"

namespace fe::gdi {

// Keys stay in the order they are written, so documents read like the structs they describe.
using Json = nlohmann::ordered_json;

// nlohmann's hooks, found by argument-dependent lookup: `gdi::Json j = device.info();`
// DeviceInfo: backend, deviceName, apiVersion, driverName, driverInfo, conformanceVersion,
// deviceType, softwareRasterizer, presentMode, limits, features, memoryHeaps (extensions only
// through probeJson's withExtensions: reports that carry a device summary stay short).
void to_json(Json& j, const DeviceLimits& limits);
void to_json(Json& j, const DeviceFeatures& features);
void to_json(Json& j, const DeviceInfo& info);

// An image comparison, as reports carry it: pixels, pixelsOverTolerance, fractionOver, maxAbsError.
void to_json(Json& j, const ImageDiff& diff);

// One backend: {"name", "available", and "device" (its DeviceInfo, with the formats' caps and,
// withExtensions, the driver's extensions) or "reason" (why not)}.
Json probeJson(const BackendProbe& probe, bool withExtensions = false);

// The engine build: {"name", "version", "commit" (git describe of the source tree when built)}.
Json engineJson();

// The current UTC time in ISO 8601, e.g. "2024-05-01T12:34:56Z".
std::string utcTimestamp();

}  // namespace fe::gdi

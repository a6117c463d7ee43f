// Layer 2 (GDI abstraction): the file behind DeviceCreateDesc::pipelineCache. The backend's data
// (Vulkan: vkGetPipelineCacheData; GL: program binaries) is wrapped in a header that keys it to
// one backend, device, driver and engine build, with a checksum, so a file from another machine,
// driver or build, or a damaged one, is ignored with one warning and never reaches the driver.
//
//   file := magic "FEPIPE01" | u32 identity bytes | identity | u64 payload bytes | u64 FNV-1a of
//           the payload | payload                     (little-endian, no padding)
//   GL payload := u32 entries | entries x (u64 key | u32 binary format | u32 bytes | bytes)
#pragma once
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "fe/gdi/Device.h"

namespace fe::gdi {

// What a cache is valid for: backend, device, API and driver versions, engine version and commit.
std::string pipelineCacheIdentity(const DeviceInfo& info);
uint64_t fnv1a(std::span<const uint8_t> bytes, uint64_t seed = 0xcbf29ce484222325ull);

struct PipelineCacheLoad {
    std::vector<uint8_t> payload;  // empty when nothing usable was found
    std::string warning;           // why a file that exists was ignored (empty: loaded, or no file)
};
// Reads and checks `bytes` (a whole file) against `identity`.
PipelineCacheLoad parsePipelineCache(std::span<const uint8_t> bytes, const std::string& identity);
PipelineCacheLoad readPipelineCache(const std::string& path, const std::string& identity);
std::vector<uint8_t> encodePipelineCache(const std::string& identity,
                                         std::span<const uint8_t> payload);
// Writes the file whole or not at all (a temporary file renamed over it). Throws Error on failure.
void writePipelineCache(const std::string& path, const std::string& identity,
                        std::span<const uint8_t> payload);

// GL program binaries by key; decode refuses (false, `why`) a payload whose sizes do not add up.
struct ProgramBinary {
    uint32_t format = 0;
    std::vector<uint8_t> bytes;
};
std::vector<uint8_t> encodeProgramBinaries(const std::map<uint64_t, ProgramBinary>& programs);
bool decodeProgramBinaries(std::span<const uint8_t> payload, std::map<uint64_t, ProgramBinary>& out,
                           std::string& why);

}  // namespace fe::gdi

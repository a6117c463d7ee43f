#include "fe/gdi/PipelineCacheFile.h"

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "fe_version.h"

namespace fe::gdi {

namespace {
constexpr char kMagic[8] = {'F', 'E', 'P', 'I', 'P', 'E', '0', '1'};

// Bounds-checked little-endian reading: every read says whether the bytes were there.
struct Reader {
    std::span<const uint8_t> bytes;
    size_t at = 0;
    template <class T>
    bool read(T& v) {
        if (bytes.size() - at < sizeof(T)) return false;
        std::memcpy(&v, bytes.data() + at, sizeof(T));
        at += sizeof(T);
        return true;
    }
    bool take(size_t n, std::span<const uint8_t>& out) {
        if (bytes.size() - at < n) return false;
        out = bytes.subspan(at, n);
        at += n;
        return true;
    }
};
template <class T>
void put(std::vector<uint8_t>& out, T v) {
    const auto* p = reinterpret_cast<const uint8_t*>(&v);
    out.insert(out.end(), p, p + sizeof(T));
}
}  // namespace

uint64_t fnv1a(std::span<const uint8_t> bytes, uint64_t seed) {
    uint64_t h = seed;
    for (uint8_t b : bytes) h = (h ^ b) * 0x100000001b3ull;
    return h;
}

std::string pipelineCacheIdentity(const DeviceInfo& info) {
    return info.backend + "|" + info.deviceName + "|" + info.apiVersion + "|" + info.driverName +
           "|" + info.driverInfo + "|" FE_VERSION "|" FE_GIT_DESCRIBE;
}

PipelineCacheLoad parsePipelineCache(std::span<const uint8_t> bytes, const std::string& identity) {
    PipelineCacheLoad r;
    Reader in{bytes};
    char magic[8];
    uint32_t identityBytes = 0;
    std::span<const uint8_t> id, payload;
    uint64_t payloadBytes = 0, hash = 0;
    if (!in.read(magic) || std::memcmp(magic, kMagic, 8) != 0)
        return {{}, "not a pipeline cache file of this engine"};
    if (!in.read(identityBytes) || !in.take(identityBytes, id)) return {{}, "truncated header"};
    if (std::string(id.begin(), id.end()) != identity)
        return {{},
                "made for another device, driver or engine build (" +
                    std::string(id.begin(), id.end()) + ")"};
    if (!in.read(payloadBytes) || !in.read(hash)) return {{}, "truncated header"};
    if (payloadBytes != bytes.size() - in.at)
        return {{},
                "truncated or extended: the header states " + std::to_string(payloadBytes) +
                    " bytes of data"};
    in.take(payloadBytes, payload);
    if (fnv1a(payload) != hash) return {{}, "checksum mismatch (the file is damaged)"};
    r.payload.assign(payload.begin(), payload.end());
    return r;
}

PipelineCacheLoad readPipelineCache(const std::string& path, const std::string& identity) {
    // A directory (or a device) opens as a stream and then throws from the read: a path that
    // exists must be a file, which is then written back there.
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    if (!ec && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
        throw Error("pipeline cache '" + path +
                    "': not a regular file (give a file path; it is created if missing)");
    std::ifstream f(path, std::ios::binary);
    if (!f) return {};  // no cache yet: not worth a warning
    std::vector<uint8_t> bytes;
    try {
        bytes.assign(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
    } catch (const std::exception& e) {
        throw Error("pipeline cache '" + path + "': cannot be read (" + e.what() + ")");
    }
    PipelineCacheLoad r = parsePipelineCache(bytes, identity);
    if (!r.warning.empty()) r.warning = "pipeline cache '" + path + "' ignored: " + r.warning;
    return r;
}

std::vector<uint8_t> encodePipelineCache(const std::string& identity,
                                         std::span<const uint8_t> payload) {
    std::vector<uint8_t> out(kMagic, kMagic + 8);
    put(out, uint32_t(identity.size()));
    out.insert(out.end(), identity.begin(), identity.end());
    put(out, uint64_t(payload.size()));
    put(out, fnv1a(payload));
    out.insert(out.end(), payload.begin(), payload.end());
    return out;
}

void writePipelineCache(const std::string& path, const std::string& identity,
                        std::span<const uint8_t> payload) {
    const std::vector<uint8_t> bytes = encodePipelineCache(identity, payload);
    const std::string temporary = path + ".tmp";
    {
        std::ofstream f(temporary, std::ios::binary | std::ios::trunc);
        f.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
        if (!f) throw Error("pipeline cache '" + path + "': cannot write " + temporary);
    }
    if (std::rename(temporary.c_str(), path.c_str()) != 0) {
        std::remove(temporary.c_str());
        throw Error("pipeline cache '" + path + "': cannot replace it");
    }
}

std::vector<uint8_t> encodeProgramBinaries(const std::map<uint64_t, ProgramBinary>& programs) {
    std::vector<uint8_t> out;
    put(out, uint32_t(programs.size()));
    for (const auto& [key, p] : programs) {
        put(out, key);
        put(out, p.format);
        put(out, uint32_t(p.bytes.size()));
        out.insert(out.end(), p.bytes.begin(), p.bytes.end());
    }
    return out;
}

bool decodeProgramBinaries(std::span<const uint8_t> payload, std::map<uint64_t, ProgramBinary>& out,
                           std::string& why) {
    Reader in{payload};
    uint32_t count = 0;
    if (!in.read(count)) return why = "no entry count", false;
    for (uint32_t i = 0; i < count; ++i) {
        uint64_t key = 0;
        uint32_t format = 0, size = 0;
        std::span<const uint8_t> bytes;
        if (!in.read(key) || !in.read(format) || !in.read(size) || !in.take(size, bytes))
            return why = "entry " + std::to_string(i) + " of " + std::to_string(count) +
                         " is truncated",
                   false;
        out[key] = {format, {bytes.begin(), bytes.end()}};
    }
    if (in.at != payload.size())
        return why = std::to_string(payload.size() - in.at) + " bytes after the last entry", false;
    return true;
}

}  // namespace fe::gdi

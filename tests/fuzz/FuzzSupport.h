// Shared by the libFuzzer harnesses: each input is written to a file in a private directory,
// because the glTF loader reads files (and resolves a file's relative URIs beside it).
#pragma once
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

namespace fe::fuzz {

// A harness's contract: when `ok` is false the input is a finding. Aborting makes libFuzzer
// keep the input in build-fuzz/findings/ and fail the run (tools/fuzz/run.sh). The message
// names the broken condition and where it is checked.
#define FUZZ_CHECK(ok, what, detail) \
    ::fe::fuzz::checkContract(bool(ok), #ok, __FILE__, __LINE__, what, detail)
inline void checkContract(bool ok, const char* condition, const char* file, int line,
                          const char* what, const std::string& detail) {
    if (ok) return;
    std::fprintf(stderr, "fuzz finding: %s %s\n  (%s:%d: %s)\n", what, detail.c_str(), file, line,
                 condition);
    std::abort();
}

// scene.glb when the input starts with the GLB magic, else scene.gltf.
inline std::string writeInput(const uint8_t* data, size_t size) {
    static const std::filesystem::path dir = [] {
        auto d = std::filesystem::temp_directory_path() / ("fe_fuzz_" + std::to_string(getpid()));
        std::filesystem::create_directories(d);
        return d;
    }();
    const bool glb = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    const std::filesystem::path p = dir / (glb ? "scene.glb" : "scene.gltf");
    std::ofstream(p, std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(data), std::streamsize(size));
    return p.string();
}

}  // namespace fe::fuzz

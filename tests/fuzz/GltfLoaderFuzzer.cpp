// libFuzzer harness: the glTF loader, text (.gltf) and binary (.glb). The loader's contract: any
// input ends in a Scene or an AssetError naming the problem. Any other exception escapes and
// aborts, and a crash, hang, leak or sanitizer report is a finding (docs/RELIABILITY.md).
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "FuzzSupport.h"
#include "assets/AssetError.h"
#include "assets/GltfLoader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = fe::fuzz::writeInput(data, size);
    try {
        fe::assets::Scene scene = fe::assets::loadGltf(path);
    } catch (const fe::assets::AssetError&) {
    } catch (const std::exception& e) {  // the contract broken: a finding
        fe::fuzz::fuzzAssert(false, "the loader threw something other than AssetError:", e.what());
    }
    return 0;
}

// libFuzzer harness: the glTF loader, text (.gltf) and binary (.glb). The loader's contract: any
// input ends in a Scene or an AssetError naming the problem. Any other exception is a finding,
// as is a crash, hang, leak or sanitizer report (docs/RELIABILITY.md).
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "FuzzSupport.h"
#include "assets/AssetError.h"
#include "assets/GltfLoader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = fe::fuzz::writeInput(data, size);
    std::string undocumented;  // what escaped other than an AssetError
    try {
        fe::assets::Scene scene = fe::assets::loadGltf(path);
    } catch (const fe::assets::AssetError&) {
    } catch (const std::exception& e) {
        undocumented = e.what();
    }
    FUZZ_CHECK(undocumented.empty(),
               "the loader threw something other than AssetError:", undocumented);
    return 0;
}

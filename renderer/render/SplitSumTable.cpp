#include "render/SplitSumTable.h"

#include <algorithm>

#include "shading/ShadingModel.h"

namespace fe::render {

std::vector<float> computeSplitSumTable() {
    std::vector<float> texels;
    texels.reserve(size_t(kSplitSumSize) * 2 * kSplitSumSize * 4);
    for (uint32_t y = 0; y < 2 * kSplitSumSize; ++y)
        for (uint32_t x = 0; x < kSplitSumSize; ++x) {
            const bool gltf = y >= kSplitSumSize;
            const double NoV = std::max((x + 0.5) / kSplitSumSize, 1e-4),
                         roughness = ((gltf ? y - kSplitSumSize : y) + 0.5) / kSplitSumSize;
            const glm::dvec3 terms = shading::splitSumTerms(
                NoV, roughness, gltf ? shading::Brdf::Gltf : shading::Brdf::Separable,
                kSplitSumSamples);
            texels.insert(texels.end(), {float(terms.x), float(terms.y), float(terms.z), 1.0f});
        }
    return texels;
}

}  // namespace fe::render

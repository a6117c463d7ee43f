// Layer 7 (Render): the table of the prefiltered fast path's split sum (PrefilteredEnvironment,
// fe_ibl.glsl's FE_IBL_PREFILTERED): for each BRDF, shading::splitSumTerms at each (NoV,
// roughness) texel centre by 1,024 samples, in double precision. It depends on no environment,
// so it is computed once, by fe_bake_split_sum (tools/bake/), and compiled in
// (SplitSumTableData.cpp): a renderer uploads it rather than drawing it, which took 0.12 s of
// CPU per renderer on a software rasterizer. The SplitSumTable tests keep the two equal.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

namespace fe::render {

constexpr uint32_t kSplitSumSize = 32;  // NoV across, roughness down, each BRDF's table
constexpr uint32_t kSplitSumSamples = 1024;

// RGBA texels, kSplitSumSize wide and 2 kSplitSumSize high: rows [0, size) the separable BRDF's,
// [size, 2 size) glTF's; x, y, z splitSumTerms at the texel's centre (NoV at least 1e-4), w 1.
std::vector<float> computeSplitSumTable();
// The table as compiled in.
std::span<const float> bakedSplitSumTable();

}  // namespace fe::render

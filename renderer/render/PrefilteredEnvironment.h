// Layer 7 (Render): the fast path of image-based lighting, the one most engines ship: the
// environment prefiltered per roughness into a cube (GGX, n = v = r), a table of what the
// sampled estimator weighs radiance by per (NoV, roughness) (the split sum), and the irradiance
// as L2 spherical harmonics. The cube is made once per environment on the GPU, the harmonics on
// the CPU (a quadrature of the environment's radiance: nine numbers, no GPU reduction needed);
// the table depends on no environment and is compiled in (render/SplitSumTable.h).
// shaders/include/fe_ibl.glsl (FE_IBL_PREFILTERED) shades with them; docs/BENCHMARKS.md has
// their bias against the sampled estimator.
#pragma once
#include <glm/glm.hpp>

#include <array>
#include <vector>

#include "assets/Environment.h"
#include "fe/gdi/Device.h"
#include "fe/gdi/DeviceObjects.h"

namespace fe::render {

// The radiance's projection on the 9 real spherical harmonics of bands 0-2, in the order of
// Ramamoorthi and Hanrahan 2001 (L00, L1-1, L10, L11, L2-2, L2-1, L20, L21, L22); directions
// with their x, y, z as R&H's. The sky by a 512 x 1024 quadrature in (theta, phi), an image
// texel by texel.
std::array<glm::dvec3, 9> radianceSH(const assets::Environment& environment);
// The irradiance about unit n from those coefficients (R&H eq. 13; clamped at 0).
glm::dvec3 irradianceFromSH(const std::array<glm::dvec3, 9>& sh, const glm::dvec3& n);

class PrefilteredEnvironment {
public:
    static constexpr uint32_t kLevels =
        6;  // roughness 0, 0.2, ... 1 (fe_ibl.glsl's FE_PREFILTER_LEVELS)
    static constexpr uint32_t kFaceSize = 128;  // level 0
    static constexpr uint32_t kLutSize =
        32;  // NoV x roughness, for each BRDF (two tables in one texture)
    static constexpr uint32_t kPrefilterSamples = 64;
    static constexpr uint32_t kLutSamples = 1024;

    // `cube`: the environment's cube with its mips (EnvironmentMap), sampled by `cubeSampler`.
    PrefilteredEnvironment(gdi::Device& device, const assets::Environment& environment,
                           gdi::TextureHandle cube, gdi::SamplerHandle cubeSampler,
                           gdi::ShaderHandle fullscreenVs);
    PrefilteredEnvironment(const PrefilteredEnvironment&) = delete;
    PrefilteredEnvironment& operator=(const PrefilteredEnvironment&) = delete;

    gdi::TextureHandle cube() const { return prefiltered_; }
    gdi::SamplerHandle sampler() const {
        return sampler_;
    }  // trilinear, clamped: the cube and the table
    gdi::TextureHandle lut() const { return lut_; }
    gdi::BufferHandle sh() const { return sh_; }  // vec4 sh[9], std140

private:
    gdi::DeviceObjects objects_;
    gdi::TextureHandle prefiltered_, lut_;
    gdi::SamplerHandle sampler_;
    gdi::BufferHandle sh_;
};

}  // namespace fe::render

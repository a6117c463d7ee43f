// Layer 5 (Communication: Asset Loader): the light arriving from infinitely far away, drawn as
// the background (and, with image-based lighting, lighting the scene). Either an equirectangular
// Radiance HDR image or an analytic sky, which a CPU reference can evaluate exactly.
//
// Directions are world space (glTF: +Y up). Equirectangular mapping: u = atan2(d.x, -d.z) /
// (2 pi) + 1/2 (so -Z, the default view direction, is the image's centre column), v = acos(d.y)
// / pi (the top row looks up). Radiance in the image's own units (W / (sr m^2) nominal).
#pragma once
#include <glm/glm.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace fe::assets {

// builtin:sky: a sky that brightens from the horizon to the zenith, a darker ground, and a sun
// disc with a soft limb (smooth across a degree, so a cube map of a few hundred texels a face
// resolves it). Every term is a closed form: SkyModel::radiance is the exact answer.
struct SkyModel {
    glm::dvec3 zenith{0.25, 0.45, 0.95};
    glm::dvec3 horizon{0.85, 0.9, 1.0};
    glm::dvec3 ground{0.25, 0.22, 0.2};
    glm::dvec3 sunDirection = glm::normalize(glm::dvec3(0.4, 0.5, -0.77));  // towards the sun
    glm::dvec3 sunRadiance{40.0, 38.0, 34.0};
    double sunInnerDegrees = 2.0, sunOuterDegrees = 3.0;  // full radiance inside, none outside

    glm::dvec3 radiance(const glm::dvec3& direction) const;
};

struct Environment {
    enum class Kind { Image, Sky };
    std::string name;  // the file, or "builtin:sky"
    Kind kind = Kind::Sky;
    SkyModel sky;  // Kind::Sky
    uint32_t width = 0, height = 0;
    std::vector<float> rgb;  // Kind::Image: width x height RGB, rows top to bottom

    // Radiance arriving from `direction` (unit): the sky's closed form, or the image sampled
    // bilinearly (wrapping in u, clamped in v).
    glm::dvec3 radiance(const glm::dvec3& direction) const;
};

// "builtin:sky" or a path to a Radiance .hdr file. Throws AssetError naming the file and what
// is wrong (missing, not a Radiance HDR, empty, non-finite or negative texels).
Environment loadEnvironment(std::string_view spec);

// The equirectangular coordinates (u, v in [0, 1]) of a direction, and back.
glm::dvec2 equirectFromDirection(const glm::dvec3& direction);
glm::dvec3 directionFromEquirect(const glm::dvec2& uv);

}  // namespace fe::assets

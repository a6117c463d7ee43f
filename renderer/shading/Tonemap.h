// Tone mapping: scene-linear radiance times exposure -> display-linear [0, 1], before the sRGB
// encoding. The CPU twin of shaders/include/fe_tonemap.glsl (the two must stay in step; the
// PostProcess tests compare the GPU's display image with these functions on every backend).
#pragma once
#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

namespace fe::shading {

enum class Tonemap : uint32_t {
    Clamp,       // min(x, 1): exact below 1, what the accuracy figures compare (the default)
    Aces,        // Narkowicz's fit of the ACES RRT+ODT ("ACES Filmic Tone Mapping Curve", 2016)
    PbrNeutral,  // Khronos PBR Neutral (2024): hue-preserving, exact base colours under 0.76
};

inline const char* tonemapName(Tonemap t) {
    switch (t) {
        case Tonemap::Clamp:
            return "clamp";
        case Tonemap::Aces:
            return "aces";
        case Tonemap::PbrNeutral:
            return "pbr-neutral";
    }
    return "?";
}

inline std::optional<Tonemap> parseTonemap(const std::string& name) {
    for (Tonemap t : {Tonemap::Clamp, Tonemap::Aces, Tonemap::PbrNeutral})
        if (name == tonemapName(t)) return t;
    return std::nullopt;
}

inline glm::dvec3 tonemap(Tonemap op, glm::dvec3 c) {
    c = glm::max(c, glm::dvec3(0.0));
    switch (op) {
        case Tonemap::Clamp:
            return glm::min(c, glm::dvec3(1.0));
        case Tonemap::Aces: {
            // The fit is to the ACES curve at its own exposure, which reads 0.6x darker: scaled so
            // that mid grey lands where the reference transform puts it (Narkowicz).
            const glm::dvec3 x = 0.6 * c;
            return glm::clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
        }
        case Tonemap::PbrNeutral: {
            // The Khronos PBR Neutral specification's steps: a small toe offset, then the peak
            // channel compressed toward 1 above 0.76 and the colour desaturated by what was lost.
            constexpr double kStartCompression = 0.8 - 0.04, kDesaturation = 0.15;
            const double x = std::min({c.r, c.g, c.b});
            const double offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
            c -= offset;
            const double peak = std::max({c.r, c.g, c.b});
            if (peak < kStartCompression) return c;
            constexpr double d = 1.0 - kStartCompression;
            const double newPeak = 1.0 - d * d / (peak + d - kStartCompression);
            c *= newPeak / peak;
            const double g = 1.0 - 1.0 / (kDesaturation * (peak - newPeak) + 1.0);
            return glm::mix(c, glm::dvec3(newPeak), g);
        }
    }
    return c;
}

}  // namespace fe::shading

#include "assets/Environment.h"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "assets/AssetError.h"
#include "assets/ImageDecode.h"

namespace fe::assets {

namespace {
constexpr double kPi = 3.14159265358979323846;

double smoothstep(double e0, double e1, double x) {
    const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}
}  // namespace

glm::dvec3 SkyModel::radiance(const glm::dvec3& d) const {
    // Sky: horizon to zenith by the square root of the elevation's sine; ground: constant.
    glm::dvec3 l = d.y >= 0.0 ? glm::mix(horizon, zenith, std::sqrt(d.y)) : ground;
    const double c = glm::dot(d, sunDirection);
    // The limb's cosines, kept for the last sun this thread asked about: a reference asks about
    // one sun millions of times, and two cos per call were 7 % of an image-based-lighting test.
    struct LimbCosines {
        double outerDegrees = std::numeric_limits<double>::quiet_NaN(), innerDegrees = 0.0;
        double outer = 0.0, inner = 0.0;
    };
    thread_local LimbCosines limbCos;
    if (!(limbCos.outerDegrees == sunOuterDegrees && limbCos.innerDegrees == sunInnerDegrees))
        limbCos = {sunOuterDegrees, sunInnerDegrees, std::cos(sunOuterDegrees * kPi / 180.0),
                   std::cos(sunInnerDegrees * kPi / 180.0)};
    const double limb = smoothstep(limbCos.outer, limbCos.inner, c);
    return l + limb * sunRadiance;
}

glm::dvec2 equirectFromDirection(const glm::dvec3& d) {
    return {std::atan2(d.x, -d.z) / (2.0 * kPi) + 0.5, std::acos(std::clamp(d.y, -1.0, 1.0)) / kPi};
}

glm::dvec3 directionFromEquirect(const glm::dvec2& uv) {
    const double phi = (uv.x - 0.5) * 2.0 * kPi, theta = uv.y * kPi;
    return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

glm::dvec3 Environment::radiance(const glm::dvec3& d) const {
    if (kind == Kind::Sky) return sky.radiance(d);
    // Bilinear, texel centres at (i + 0.5) / width; wrap in u, clamp in v (as the GPU samples).
    const glm::dvec2 uv = equirectFromDirection(d);
    const double x = uv.x * width - 0.5,
                 y = std::clamp(uv.y * height - 0.5, 0.0, double(height - 1));
    const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    const double fx = x - x0, fy = y - y0;
    auto texel = [&](int xi, int yi) {
        xi = ((xi % int(width)) + int(width)) % int(width);
        yi = std::clamp(yi, 0, int(height) - 1);
        const float* p = &rgb[(size_t(yi) * width + xi) * 3];
        return glm::dvec3(p[0], p[1], p[2]);
    };
    return glm::mix(glm::mix(texel(x0, y0), texel(x0 + 1, y0), fx),
                    glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), fx), fy);
}

Environment loadEnvironment(std::string_view spec) {
    Environment e;
    e.name = std::string(spec);
    if (spec == "builtin:sky") return e;
    if (spec.rfind("builtin:", 0) == 0)
        throw AssetError("unknown environment '" + e.name + "' (builtin: sky)");
    const std::string path(spec);
    if (!std::filesystem::is_regular_file(path))
        throw AssetError(path + ": environment file not found");
    // stb_image would also read PNG or JPEG as floats; an environment must be a Radiance HDR.
    std::ifstream f(path, std::ios::binary);
    char magic[10] = {};
    f.read(magic, 10);
    if (std::string(magic, 2) != "#?")
        throw AssetError(path + ": not a Radiance HDR file (no '#?' signature)");
    // stb_image reads a truncated uncompressed (flat) file as zeros: check its length first. Run-
    // length encoded scanlines (2, 2 and the width) it checks itself.
    {
        std::ifstream in(path, std::ios::binary);
        std::string line;
        while (std::getline(in, line) && !line.empty()) {}
        std::string resolution;
        std::getline(in, resolution);
        int h = 0, w = 0;
        char ys[4] = {}, xs[4] = {};
        if (std::sscanf(resolution.c_str(), "%2s %d %2s %d", ys, &h, xs, &w) == 4 && w > 0 &&
            h > 0) {
            const std::streampos data = in.tellg();
            in.seekg(0, std::ios::end);
            const uint64_t bytes = uint64_t(in.tellg() - data);
            in.seekg(data);
            unsigned char head[2] = {};
            in.read(reinterpret_cast<char*>(head), 2);
            const bool rle = w >= 8 && w < 32768 && head[0] == 2 && head[1] == 2;
            if (!rle && bytes < uint64_t(w) * uint64_t(h) * 4)
                throw AssetError(path + ": truncated Radiance HDR image: " + std::to_string(bytes) +
                                 " bytes of pixels, " + std::to_string(uint64_t(w) * h * 4) +
                                 " needed for " + std::to_string(w) + "x" + std::to_string(h));
        }
    }
    HdrImage img = decodeRadianceHdr(path);
    e.kind = Environment::Kind::Image;
    e.width = img.width;
    e.height = img.height;
    e.rgb = std::move(img.rgb);
    const int w = int(e.width), h = int(e.height);
    if (w < 2 || h < 1)
        throw AssetError(path + ": environment image of " + std::to_string(w) + "x" +
                         std::to_string(h));
    for (size_t i = 0; i < e.rgb.size(); ++i)
        if (!std::isfinite(e.rgb[i]) || e.rgb[i] < 0.0f)
            throw AssetError(path + ": texel " + std::to_string(i / 3 % e.width) + "," +
                             std::to_string(i / 3 / e.width) +
                             " is not a finite non-negative radiance");
    return e;
}

}  // namespace fe::assets

// The bench's error measures (renderer/reference/ImageMetrics.h) against values worked out by
// hand from their definitions.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "reference/ImageMetrics.h"

using namespace fe;
using render::DisplayImage;

namespace {
DisplayImage constant(uint32_t w, uint32_t h, glm::vec3 c) {
    return {w, h, std::vector<glm::vec3>(size_t(w) * h, c)};
}

// A smooth gradient with detail, so structure measures have something to see.
DisplayImage pattern(uint32_t w, uint32_t h) {
    DisplayImage d{w, h, {}};
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x)
            d.rgb.push_back(glm::vec3(float(x) / w, float(y) / h,
                                      0.5f + 0.4f * float(std::sin(x * 0.7) * std::cos(y * 0.5))));
    return d;
}

DisplayImage noisy(DisplayImage d, float amplitude, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-amplitude, amplitude);
    for (glm::vec3& c : d.rgb) c = glm::clamp(c + glm::vec3(u(rng), u(rng), u(rng)), 0.0f, 1.0f);
    return d;
}
}  // namespace

TEST(ImageMetrics, IdenticalImagesAreExact) {
    const DisplayImage a = pattern(48, 32);
    const render::ImageMetrics m = render::compareImages(a, a);
    EXPECT_TRUE(std::isinf(m.psnr));
    EXPECT_NEAR(m.ssim, 1.0, 1e-12);
    EXPECT_EQ(m.flip, 0.0);
    EXPECT_EQ(m.percentOver5, 0.0);
    EXPECT_EQ(m.maxAbs, 0.0);
}

// An offset of 0.1 in every channel: MSE 0.01, PSNR 20 dB; every pixel over 5/255.
TEST(ImageMetrics, PsnrAndCountsOfAKnownOffset) {
    const render::ImageMetrics m =
        render::compareImages(constant(16, 16, glm::vec3(0.5f)), constant(16, 16, glm::vec3(0.4f)));
    EXPECT_NEAR(m.psnr, 20.0, 1e-4);
    EXPECT_NEAR(m.maxAbs, 0.1, 1e-6);
    EXPECT_EQ(m.percentOver5, 100.0);
}

// SSIM falls as structure is lost; a uniform brightness shift of flat images only touches the
// luminance term: (2 mu_x mu_y + C1) / (mu_x^2 + mu_y^2 + C1).
TEST(ImageMetrics, SsimFollowsStructure) {
    const DisplayImage a = pattern(64, 48);
    const double slight = render::ssim(noisy(a, 0.02f, 1), a),
                 strong = render::ssim(noisy(a, 0.2f, 2), a);
    EXPECT_LT(slight, 1.0);
    EXPECT_LT(strong, slight);
    EXPECT_GT(slight, 0.9);
    const double x = 0.6, y = 0.4, C1 = 1e-4;
    EXPECT_NEAR(render::ssim(constant(16, 16, glm::vec3(0.6f)), constant(16, 16, glm::vec3(0.4f))),
                (2 * x * y + C1) / (x * x + y * y + C1), 1e-6);
    EXPECT_THROW(render::ssim(constant(8, 8, glm::vec3(0)), constant(8, 8, glm::vec3(0))),
                 std::invalid_argument);
}

// FLIP between flat black and flat white: no features, so the colour term alone. HyAB between
// Hunt-adjusted black and white Lab is 100, 100^0.7 = 25.1; the paper's cmax (green against
// blue) is 203.3^0.7 = 41.1; above pc cmax the remap gives 0.95 + (25.1 - 16.4) / (41.1 - 16.4)
// x 0.05 = 0.968. A small change gives a small value; a displaced edge is seen.
TEST(ImageMetrics, FlipOfKnownCases) {
    EXPECT_NEAR(render::flip(constant(24, 24, glm::vec3(1.0f)), constant(24, 24, glm::vec3(0.0f))),
                0.968, 0.003);
    const DisplayImage a = pattern(48, 32);
    const double small = render::flip(noisy(a, 0.01f, 3), a),
                 large = render::flip(noisy(a, 0.3f, 4), a);
    EXPECT_GT(small, 0.0);
    EXPECT_LT(small, 0.05);
    EXPECT_GT(large, 3 * small);
    EXPECT_LE(large, 1.0);
    DisplayImage edge = constant(32, 32, glm::vec3(0.1f)), moved = edge;
    for (uint32_t y = 0; y < 32; ++y)
        for (uint32_t x = 0; x < 32; ++x) {
            if (x >= 16) edge.rgb[y * 32 + x] = glm::vec3(0.9f);
            if (x >= 17) moved.rgb[y * 32 + x] = glm::vec3(0.9f);
        }
    const std::vector<float> map = render::flipErrorMap(moved, edge);
    EXPECT_GT(map[10 * 32 + 16], 0.5f);  // where the edge was
    EXPECT_LT(map[10 * 32 + 2], 0.05f);  // far from it
}

TEST(ImageMetrics, DisplayEncodingClampsAndShowsNonFiniteAsWhite) {
    const DisplayImage d =
        render::toDisplay(2, 1, {glm::dvec3(2.0, 0.5, -1.0), glm::dvec3(NAN, INFINITY, 0.0)});
    EXPECT_FLOAT_EQ(d.rgb[0].r, 1.0f);
    EXPECT_NEAR(d.rgb[0].g, 0.7354, 1e-3);  // sRGB of 0.5
    EXPECT_FLOAT_EQ(d.rgb[0].b, 0.0f);
    EXPECT_FLOAT_EQ(d.rgb[1].r, 1.0f);
    EXPECT_FLOAT_EQ(d.rgb[1].g, 1.0f);
}

// FLIP stays in [0, 1] for images that differ by almost nothing, black backgrounds included.
TEST(ImageMetrics, FlipOfNearlyIdenticalImagesIsNearZero) {
    DisplayImage a = constant(40, 30, glm::vec3(0.0f));
    for (uint32_t y = 8; y < 22; ++y)
        for (uint32_t x = 10; x < 30; ++x) a.rgb[y * 40 + x] = glm::vec3(0.8f, 0.3f, 0.1f);
    DisplayImage b = a;
    b.rgb[15 * 40 + 15] += glm::vec3(1e-6f);
    const std::vector<float> map = render::flipErrorMap(b, a);
    float worst = 0.0f;
    for (float v : map) worst = std::max(worst, v);
    EXPECT_LE(worst, 0.01f);
    EXPECT_LE(render::flip(b, a), 0.001);
}

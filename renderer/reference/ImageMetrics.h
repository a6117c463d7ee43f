// Layer 7 test oracle: how far a rendered image is from the exact one, by the measures the bench
// reports (fe bench). Every measure compares display-referred images: sRGB(clamp(exposure x
// L_o)) in [0, 1], what a person sees, so a difference in a blown-out highlight or under the
// 8-bit step counts as it looks.
//   PSNR   10 log10(1 / MSE) over the RGB channels (infinite for identical images)
//   SSIM   Wang et al. 2004 on luma (Rec. 709 weights of the sRGB values): 11x11 Gaussian window,
//          sigma 1.5, K1 0.01, K2 0.03, L 1; the mean over the windows that fit in the image
//   FLIP   LDR-FLIP (Andersson, Nilsson, Akenine-Moller, Oskarsson, Astrom and Fairchild, "FLIP: A
//          Difference Evaluator for Alternating Images", HPG 2020), written from the paper (no
//          Debian package has it): the mean of its per-pixel error map, in [0, 1]
//   percentOver5   pixels where some channel differs by more than 5/255
//   maxAbs         the largest channel difference
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

#include "shading/Tonemap.h"

namespace fe::render {

struct DisplayImage {
    uint32_t width = 0, height = 0;
    std::vector<glm::vec3> rgb;  // sRGB-encoded values in [0, 1], rows top to bottom
};

// sRGB(tonemap(exposure x linear)); non-finite values show as 1 (white), as a display would clip.
DisplayImage toDisplay(uint32_t width, uint32_t height, const std::vector<glm::dvec3>& linear,
                       double exposure = 1.0, shading::Tonemap tonemap = shading::Tonemap::Clamp);

struct ImageMetrics {
    double psnr = 0;  // dB; +inf when identical
    double ssim = 0;
    double flip = 0;
    double percentOver5 = 0;
    double maxAbs = 0;
};

double psnr(const DisplayImage& a, const DisplayImage& b);
double ssim(const DisplayImage& a, const DisplayImage& b);
// FLIP's per-pixel error map of `test` against `reference`; `pixelsPerDegree` is the viewing
// condition (the paper's default 67: a 0.7 m wide 4K monitor seen from 0.7 m).
std::vector<float> flipErrorMap(const DisplayImage& test, const DisplayImage& reference,
                                double pixelsPerDegree = 67.0);
double flip(const DisplayImage& test, const DisplayImage& reference, double pixelsPerDegree = 67.0);
ImageMetrics compareImages(const DisplayImage& test, const DisplayImage& reference);

}  // namespace fe::render

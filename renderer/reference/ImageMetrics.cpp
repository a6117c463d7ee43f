#include "reference/ImageMetrics.h"

#include "reference/ParallelRows.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace fe::render {

namespace {
constexpr double kPi = 3.14159265358979323846;

void checkSizes(const DisplayImage& a, const DisplayImage& b) {
    if (a.width != b.width || a.height != b.height || a.rgb.size() != size_t(a.width) * a.height ||
        b.rgb.size() != a.rgb.size())
        throw std::invalid_argument("image metrics: the images differ in size");
}

double srgbToLinear(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}
double linearToSrgb(double l) {
    return l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055;
}

// A single-channel image and a 2D convolution with clamped edges (the kernels here are small
// and the images bench-sized: written out, no FFT).
struct Plane {
    int w = 0, h = 0;
    std::vector<double> v;
    double at(int x, int y) const {
        return v[size_t(std::clamp(y, 0, h - 1)) * w + size_t(std::clamp(x, 0, w - 1))];
    }
};
struct Kernel {
    int radius = 0;
    std::vector<double> k;  // (2r + 1)^2, rows
    double at(int dx, int dy) const {
        return k[size_t(dy + radius) * (2 * radius + 1) + size_t(dx + radius)];
    }
};
Plane convolve(const Plane& p, const Kernel& k) {
    Plane out{p.w, p.h, std::vector<double>(p.v.size(), 0.0)};
    // FLIP's kernels are wide (a 720p image takes seconds a plane): rows on every core.
    forEachRowInParallel(uint32_t(p.h), [&](uint32_t row) {
        const int y = int(row);
        for (int x = 0; x < p.w; ++x) {
            double s = 0.0;
            for (int dy = -k.radius; dy <= k.radius; ++dy)
                for (int dx = -k.radius; dx <= k.radius; ++dx)
                    s += k.at(dx, dy) * p.at(x + dx, y + dy);
            out.v[size_t(y) * p.w + x] = s;
        }
    });
    return out;
}

// ---- FLIP (Andersson et al. 2020), the LDR form ----------------------------------------------
// Reference white (D65) of the paper's colour transforms.
const glm::dvec3 kWhite{0.950428545, 1.0, 1.088900371};

glm::dvec3 linearRgbToXyz(const glm::dvec3& c) {
    return {0.4124564 * c.r + 0.3575761 * c.g + 0.1804375 * c.b,
            0.2126729 * c.r + 0.7151522 * c.g + 0.0721750 * c.b,
            0.0193339 * c.r + 0.1191920 * c.g + 0.9503041 * c.b};
}
glm::dvec3 xyzToLinearRgb(const glm::dvec3& c) {
    return {3.2404542 * c.x - 1.5371385 * c.y - 0.4985314 * c.z,
            -0.9692660 * c.x + 1.8760108 * c.y + 0.0415560 * c.z,
            0.0556434 * c.x - 0.2040259 * c.y + 1.0572252 * c.z};
}
// YCxCz: the linearized opponent space the contrast sensitivity filters work in.
glm::dvec3 xyzToYcxcz(const glm::dvec3& c) {
    const glm::dvec3 n = c / kWhite;
    return {116.0 * n.y - 16.0, 500.0 * (n.x - n.y), 200.0 * (n.y - n.z)};
}
glm::dvec3 ycxczToXyz(const glm::dvec3& c) {
    const double y = (c.x + 16.0) / 116.0;
    return glm::dvec3(c.y / 500.0 + y, y, y - c.z / 200.0) * kWhite;
}
glm::dvec3 xyzToLab(const glm::dvec3& c) {
    const double d = 6.0 / 29.0;
    auto f = [d](double t) {
        return t > d * d * d ? std::cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
    };
    const glm::dvec3 n = c / kWhite;
    return {116.0 * f(n.y) - 16.0, 500.0 * (f(n.x) - f(n.y)), 200.0 * (f(n.y) - f(n.z))};
}
// The Hunt effect: chroma matters less in the dark.
glm::dvec3 hunt(const glm::dvec3& lab) {
    return {lab.x, 0.01 * lab.x * lab.y, 0.01 * lab.x * lab.z};
}
double hyab(const glm::dvec3& a, const glm::dvec3& b) {
    return std::abs(a.x - b.x) + std::sqrt((a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z));
}

// The contrast sensitivity function of one opponent channel as a spatial kernel: a sum of two
// Gaussians in visual degrees (the paper's a1, b1, a2, b2), normalised to sum 1.
Kernel csfKernel(double a1, double b1, double a2, double b2, int radius, double ppd) {
    Kernel k{radius, {}};
    double sum = 0.0;
    for (int y = -radius; y <= radius; ++y)
        for (int x = -radius; x <= radius; ++x) {
            const double d2 = (x * x + y * y) / (ppd * ppd);
            const double g = a1 * std::sqrt(kPi / b1) * std::exp(-kPi * kPi * d2 / b1) +
                             a2 * std::sqrt(kPi / b2) * std::exp(-kPi * kPi * d2 / b2);
            k.k.push_back(g);
            sum += g;
        }
    for (double& g : k.k) g /= sum;
    return k;
}

// Gaussian derivative kernels of the feature detectors: first (edges) or second (points) order
// along x, positive and negative weights each normalised to sum to 1 in magnitude.
Kernel featureKernel(int order, double sigma, int radius, bool alongY) {
    Kernel k{radius, {}};
    double pos = 0.0, neg = 0.0;
    for (int y = -radius; y <= radius; ++y)
        for (int x = -radius; x <= radius; ++x) {
            const double u = alongY ? y : x;
            const double g = std::exp(-(x * x + y * y) / (2.0 * sigma * sigma));
            const double v = order == 1 ? -u * g : (u * u / (sigma * sigma) - 1.0) * g;
            k.k.push_back(v);
            (v > 0 ? pos : neg) += v;
        }
    for (double& v : k.k) v /= v > 0 ? pos : -neg;
    return k;
}
}  // namespace

DisplayImage toDisplay(uint32_t width, uint32_t height, const std::vector<glm::dvec3>& linear,
                       double exposure, shading::Tonemap tonemap) {
    DisplayImage d{width, height, {}};
    d.rgb.reserve(linear.size());
    for (const glm::dvec3& l : linear) {
        const glm::dvec3 mapped = shading::tonemap(tonemap, l * exposure);
        glm::vec3 c;
        for (int i = 0; i < 3; ++i) {
            const double v = l[i] * exposure;
            c[i] = std::isfinite(v) ? float(linearToSrgb(std::clamp(mapped[i], 0.0, 1.0))) : 1.0f;
        }
        d.rgb.push_back(c);
    }
    return d;
}

double psnr(const DisplayImage& a, const DisplayImage& b) {
    checkSizes(a, b);
    double se = 0.0;
    for (size_t i = 0; i < a.rgb.size(); ++i)
        for (int c = 0; c < 3; ++c)
            se += double(a.rgb[i][c] - b.rgb[i][c]) * double(a.rgb[i][c] - b.rgb[i][c]);
    const double mse = se / (3.0 * double(a.rgb.size()));
    return mse > 0.0 ? 10.0 * std::log10(1.0 / mse) : std::numeric_limits<double>::infinity();
}

double ssim(const DisplayImage& a, const DisplayImage& b) {
    checkSizes(a, b);
    constexpr int kRadius = 5;  // 11 x 11
    constexpr double kSigma = 1.5, C1 = 0.01 * 0.01, C2 = 0.03 * 0.03;
    std::array<double, 2 * kRadius + 1> g{};
    double gs = 0.0;
    for (int i = -kRadius; i <= kRadius; ++i)
        gs += g[i + kRadius] = std::exp(-i * i / (2.0 * kSigma * kSigma));
    auto luma = [](const glm::vec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; };
    const int w = int(a.width), h = int(a.height);
    if (w < 2 * kRadius + 1 || h < 2 * kRadius + 1)
        throw std::invalid_argument("SSIM needs images of at least 11x11 pixels");
    double sum = 0.0;
    size_t n = 0;
    for (int y = kRadius; y < h - kRadius; ++y)
        for (int x = kRadius; x < w - kRadius; ++x) {
            double mx = 0, my = 0, xx = 0, yy = 0, xy = 0;
            for (int dy = -kRadius; dy <= kRadius; ++dy)
                for (int dx = -kRadius; dx <= kRadius; ++dx) {
                    const double wgt = g[dx + kRadius] * g[dy + kRadius] / (gs * gs);
                    const size_t i = size_t(y + dy) * w + size_t(x + dx);
                    const double va = luma(a.rgb[i]), vb = luma(b.rgb[i]);
                    mx += wgt * va, my += wgt * vb;
                    xx += wgt * va * va, yy += wgt * vb * vb, xy += wgt * va * vb;
                }
            const double sx = xx - mx * mx, sy = yy - my * my, sxy = xy - mx * my;
            sum +=
                ((2 * mx * my + C1) * (2 * sxy + C2)) / ((mx * mx + my * my + C1) * (sx + sy + C2));
            ++n;
        }
    return sum / double(n);
}

std::vector<float> flipErrorMap(const DisplayImage& test, const DisplayImage& reference,
                                double ppd) {
    checkSizes(test, reference);
    const int w = int(test.width), h = int(test.height);
    // The paper's constants.
    constexpr double qc = 0.7, qf = 0.5, pc = 0.4, pt = 0.95, featureWidth = 0.082;
    // Both images in YCxCz, per channel.
    auto opponent = [&](const DisplayImage& img) {
        std::array<Plane, 3> p;
        for (Plane& q : p) q = {w, h, std::vector<double>(size_t(w) * h)};
        for (size_t i = 0; i < img.rgb.size(); ++i) {
            const glm::dvec3 lin(srgbToLinear(img.rgb[i].r), srgbToLinear(img.rgb[i].g),
                                 srgbToLinear(img.rgb[i].b));
            const glm::dvec3 o = xyzToYcxcz(linearRgbToXyz(lin));
            for (int c = 0; c < 3; ++c) p[c].v[i] = o[c];
        }
        return p;
    };
    const std::array<Plane, 3> ot = opponent(test), orf = opponent(reference);
    // Colour pipeline: contrast sensitivity filtering, then Hunt-adjusted Lab and HyAB.
    const double bMax = 0.04;  // the widest of the three CSFs
    const int csfRadius = int(std::ceil(3.0 * std::sqrt(bMax / (2.0 * kPi * kPi)) * ppd));
    const std::array<Kernel, 3> csf = {csfKernel(1.0, 0.0047, 0.0, 1e-5, csfRadius, ppd),
                                       csfKernel(1.0, 0.0053, 0.0, 1e-5, csfRadius, ppd),
                                       csfKernel(34.1, 0.04, 13.5, 0.025, csfRadius, ppd)};
    std::array<Plane, 3> ft, fr;
    for (int c = 0; c < 3; ++c) {
        ft[c] = convolve(ot[c], csf[c]);
        fr[c] = convolve(orf[c], csf[c]);
    }
    auto huntLab = [](const glm::dvec3& ycxcz) {
        const glm::dvec3 rgb = glm::clamp(xyzToLinearRgb(ycxczToXyz(ycxcz)), 0.0, 1.0);
        return hunt(xyzToLab(linearRgbToXyz(rgb)));
    };
    const double cmax = std::pow(
        hyab(hunt(xyzToLab(linearRgbToXyz({0, 1, 0}))), hunt(xyzToLab(linearRgbToXyz({0, 0, 1})))),
        qc);
    // Feature pipeline on the achromatic channel, normalised to [0, 1].
    const double sigma = 0.5 * featureWidth * ppd;
    const int featureRadius = int(std::ceil(3.0 * sigma));
    auto features = [&](const Plane& y) {
        Plane n{w, h, y.v};
        for (double& v : n.v) v = (v + 16.0) / 116.0;
        return std::array<Plane, 4>{convolve(n, featureKernel(1, sigma, featureRadius, false)),
                                    convolve(n, featureKernel(1, sigma, featureRadius, true)),
                                    convolve(n, featureKernel(2, sigma, featureRadius, false)),
                                    convolve(n, featureKernel(2, sigma, featureRadius, true))};
    };
    const std::array<Plane, 4> et = features(ot[0]), er = features(orf[0]);
    std::vector<float> map(size_t(w) * h);
    for (size_t i = 0; i < map.size(); ++i) {
        const double dE = std::pow(hyab(huntLab({ft[0].v[i], ft[1].v[i], ft[2].v[i]}),
                                        huntLab({fr[0].v[i], fr[1].v[i], fr[2].v[i]})),
                                   qc);
        const double colour = dE < pc * cmax
                                  ? pt / (pc * cmax) * dE
                                  : pt + (dE - pc * cmax) / (cmax - pc * cmax) * (1.0 - pt);
        const double edge =
            std::abs(std::hypot(et[0].v[i], et[1].v[i]) - std::hypot(er[0].v[i], er[1].v[i]));
        const double point =
            std::abs(std::hypot(et[2].v[i], et[3].v[i]) - std::hypot(er[2].v[i], er[3].v[i]));
        const double feature = std::pow(std::max(edge, point) / std::sqrt(2.0), qf);
        map[i] = float(std::pow(colour, 1.0 - feature));
    }
    return map;
}

double flip(const DisplayImage& test, const DisplayImage& reference, double ppd) {
    const std::vector<float> map = flipErrorMap(test, reference, ppd);
    double sum = 0.0;
    for (float v : map) sum += v;
    return map.empty() ? 0.0 : sum / double(map.size());
}

ImageMetrics compareImages(const DisplayImage& test, const DisplayImage& reference) {
    checkSizes(test, reference);
    ImageMetrics m;
    m.psnr = psnr(test, reference);
    m.ssim = ssim(test, reference);
    m.flip = flip(test, reference);
    size_t over = 0;
    for (size_t i = 0; i < test.rgb.size(); ++i) {
        double d = 0.0;
        for (int c = 0; c < 3; ++c)
            d = std::max(d, double(std::abs(test.rgb[i][c] - reference.rgb[i][c])));
        m.maxAbs = std::max(m.maxAbs, d);
        over += d > 5.0 / 255.0;
    }
    m.percentOver5 = 100.0 * double(over) / double(test.rgb.size());
    return m;
}

}  // namespace fe::render

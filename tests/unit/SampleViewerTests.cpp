// The Khronos glTF Sample Viewer as the reference renderer: the sample models rendered
// by fe with the cameras and lights the Sample Viewer was given (tools/sample-viewer/views.json),
// tone mapped as it does (Khronos PBR Neutral, then its 2.2 gamma), compared with its images
// (tests/data/sample-viewer/, made by tools/sample-viewer/render.sh; docs/SAMPLE_VIEWER.md).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC  // this test's own reader of the committed PNGs (the engine's is private to its loader)
#include <stb/stb_image.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include "assets/GltfLoader.h"
#include "fe/gdi/Backend.h"
#include "integration/SceneRenderer.h"
#include "shading/Tonemap.h"

using namespace fe;
namespace fs = std::filesystem;

namespace {

const fs::path kViewerDir = fs::path(FE_TEST_DATA) / "sample-viewer";
const fs::path kViews =
    fs::path(FE_TEST_DATA) / ".." / ".." / "tools" / "sample-viewer" / "views.json";

glm::vec3 vec3Of(const nlohmann::json& j) {
    return {j.at(0).get<float>(), j.at(1).get<float>(), j.at(2).get<float>()};
}

// The model as the Sample Viewer saw it: the manifest's camera and, where the file has none of
// its own, the manifest's lights instead of fe's default rig.
assets::Scene viewerScene(const nlohmann::json& view) {
    assets::Scene scene =
        assets::loadGltf((fs::path(FE_SHARED_ASSETS) / view.at("gltf").get<std::string>()).string(),
                         {.scene = view.value("scene", -1)});
    const nlohmann::json& c = view.at("camera");
    const glm::vec3 eye = vec3Of(c.at("eye"));
    scene.camera = assets::Camera::lookAlong(eye, glm::normalize(vec3Of(c.at("target")) - eye),
                                             vec3Of(c.at("up")), c.at("yfov").get<float>(),
                                             c.at("znear").get<float>(), c.at("zfar").get<float>());
    if (!view.value("lightsFromFile", false)) {
        scene.lights.clear();
        for (const nlohmann::json& l : view.at("lights")) {
            EXPECT_EQ(l.at("type"), "directional") << "only the directional rig is read here";
            scene.lights.push_back({.name = l.at("name").get<std::string>(),
                                    .type = assets::LightType::Directional,
                                    .color = vec3Of(l.at("color")),
                                    .intensity = l.at("intensity").get<float>(),
                                    .direction = glm::normalize(vec3Of(l.at("direction")))});
        }
    }
    return scene;
}

// The viewer's output of a linear radiance: PBR Neutral, pow(1/2.2), 8 bits.
uint8_t encode(double toneMapped) {
    return uint8_t(
        std::lround(std::clamp(std::pow(std::max(toneMapped, 0.0), 1.0 / 2.2), 0.0, 1.0) * 255.0));
}

struct Diff {
    uint32_t over = 0, pixels = 0;
    double percent() const { return pixels ? 100.0 * over / pixels : 100.0; }
};

// Pixels where a channel differs by more than `tolerance` / 255. With `written` (the
// FE_SAMPLE_VIEWER_OUT folder, for looking at a difference), fe's encoded image as a binary PPM.
Diff compareWithViewer(const gdi::Image& linear, const fs::path& reference, int tolerance,
                       const fs::path& written = {}) {
    int w = 0, h = 0, n = 0;
    std::unique_ptr<stbi_uc, void (*)(void*)> ref(
        stbi_load(reference.string().c_str(), &w, &h, &n, 3), stbi_image_free);
    Diff d;
    if (!ref || uint32_t(w) != linear.width || uint32_t(h) != linear.height) return d;
    d.pixels = uint32_t(w * h);
    std::ofstream ppm;
    if (!written.empty()) {
        ppm.open(written, std::ios::binary);
        ppm << "P6\n" << w << " " << h << "\n255\n";
    }
    for (uint32_t y = 0; y < linear.height; ++y)
        for (uint32_t x = 0; x < linear.width; ++x) {
            const auto t = linear.texel(x, y);
            const glm::dvec3 mapped =
                shading::tonemap(shading::Tonemap::PbrNeutral, glm::dvec3(t[0], t[1], t[2]));
            const stbi_uc* r = &ref.get()[(size_t(y) * w + x) * 3];
            bool bad = false;
            for (int c = 0; c < 3; ++c)
                bad = bad || std::abs(int(encode(mapped[c])) - int(r[c])) > tolerance;
            if (ppm.is_open()) ppm << encode(mapped.r) << encode(mapped.g) << encode(mapped.b);
            d.over += bad;
        }
    return d;
}

}  // namespace

// Every model the Sample Viewer drew, with the fraction of pixels (%) where fe's forward image
// differs from its image by more than 8/255, measured 2026-11-29 (the same on vulkan, gl-egl and
// gl-osmesa; lavapipe / llvmpipe against SwiftShader): silhouettes, texture filtering (the
// textured boxes: mip selection) and float rounding. The bound is 1.5x, at least 0.05 %. Each
// real difference fixed since showed far over its bound first (docs/SAMPLE_VIEWER.md).
struct ViewerCase {
    const char* name;
    double measuredPercent;  // < 0: a known real difference, measured and printed, not bounded
    const char* why = "";
};
const ViewerCase kViewerCases[] = {
    {"AlphaBlendModeTest", 0.551},
    {"Box", 0.013},
    {"Box With Spaces", 3.27},
    {"BoxAnimated", 0.022},
    {"BoxInterleaved", 0.014},
    {"BoxTextured", 2.99},
    {"BoxTexturedNonPowerOfTwo", 3.47},
    {"BoxVertexColors", 0.014},
    {"Cameras", 0.0},
    {"CesiumMilkTruck", 1.78},
    {"EmissiveStrengthTest", 0.186},
    {"Fox", 0.191},
    {"LightsPunctualLamp", 2.06},
    {"MeshPrimitiveModes", 0.471},
    {"MetalRoughSpheresNoTextures", 0.107},
    {"MultiUVTest", 1.27},
    {"MultipleScenes", 0.010},
    {"NegativeScaleTest", 0.092},
    {"NormalTangentTest", 0.836},
    {"OrientationTest", 0.070},
    {"RiggedSimple", 0.004},
    {"SimpleInstancing", 0.051},
    {"SimpleMeshes", 0.009},
    {"SimpleMorph", 0.008},
    {"SimpleSkin", 0.008},
    {"SimpleSparseAccessor", 0.003},
    {"Suzanne", 0.023},
    {"TextureCoordinateTest", 0.113},
    {"TextureEncodingTest", 0.042},
    {"TextureLinearInterpolationTest", 0.072},
    {"TextureSettingsTest", 1.76},
    {"TextureTransformTest", 0.083},
    {"Triangle", 0.004},
    {"TriangleWithoutIndices", 0.004},
    {"TwoSidedPlane", 1.03},
    {"Unicode❤♻Test", 0.018},
    {"UnlitTest", 0.013},
    {"VertexColorTest", 0.104},
};

void PrintTo(const ViewerCase& c, std::ostream* os) { *os << c.name; }

class SampleViewer : public ::testing::TestWithParam<ViewerCase> {};

TEST_P(SampleViewer, MatchesTheReferenceRenderer) {
    const ViewerCase& c = GetParam();
    if (!fs::exists(kViews) || !fs::exists(FE_SHARED_ASSETS))
        GTEST_SKIP() << "no views.json or sample assets";
    nlohmann::json views;
    std::ifstream(kViews) >> views;
    const nlohmann::json* view = nullptr;
    for (const nlohmann::json& v : views.at("models"))
        if (v.at("name") == c.name) view = &v;
    ASSERT_NE(view, nullptr) << c.name << " is not in views.json";
    const assets::Scene scene = viewerScene(*view);
    for (const std::string& b : gdi::backendNames()) {
        gdi::BackendProbe p = gdi::probeBackend(b, true);
        if (!p.available) continue;
        render::SceneRenderer r(*p.device, scene,
                                {.technique = "forward", .width = 320, .height = 240});
        r.renderFrame();
        const char* out = std::getenv("FE_SAMPLE_VIEWER_OUT");
        const Diff d = compareWithViewer(
            r.readOutput(), kViewerDir / view->at("reference").get<std::string>(), 8,
            out ? fs::path(out) / (std::string(c.name) + "_" + b + ".ppm") : fs::path());
        std::cout << b << " " << c.name << ": " << d.percent()
                  << " % of pixels beyond 8/255 of the Sample Viewer"
                  << (c.measuredPercent < 0 ? std::string(" (not bounded: ") + c.why + ")" : "")
                  << "\n";
        if (c.measuredPercent >= 0) {
            EXPECT_LE(d.percent(), std::max(1.5 * c.measuredPercent, 0.05)) << b << " " << c.name;
        }
        EXPECT_EQ(p.device->validationErrorCount(), 0u) << b;
    }
}

INSTANTIATE_TEST_SUITE_P(Models, SampleViewer, ::testing::ValuesIn(kViewerCases),
                         [](const auto& info) {
                             std::string n;
                             for (const char ch : std::string(info.param.name))
                                 n += std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
                             return n;
                         });

// The gl-glfw backend: a GL context owned by a GLFW window, and Device::present showing a
// texture in it. CTest runs this binary under xvfb-run (a virtual X server), so the window is
// real; without a display the backend must say why it cannot start.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <optional>
#include <string>

#include "Conformance.h"
#include "fe/gdi/Backend.h"
#include "assets/BuiltinScenes.h"
#include "render/SceneRenderer.h"

using namespace fe;

namespace {

bool haveDisplay() {
    const char* x = std::getenv("DISPLAY");
    const char* w = std::getenv("WAYLAND_DISPLAY");
    return (x && *x) || (w && *w);
}

// Unsets an environment variable for the life of the object.
class ScopedUnsetEnv {
public:
    explicit ScopedUnsetEnv(const char* name) : name_(name) {
        if (const char* v = std::getenv(name)) old_ = v;
        unsetenv(name);
    }
    ~ScopedUnsetEnv() {
        if (old_) setenv(name_, old_->c_str(), 1);
    }

private:
    const char* name_;
    std::optional<std::string> old_;
};

// A pattern that is different in every row and column, so a flip or a shift shows.
gdi::Image pattern(uint32_t w, uint32_t h, gdi::Format f) {
    gdi::Image img;
    img.width = w, img.height = h, img.format = f;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x)
            for (uint8_t v : {uint8_t(x * 255 / (w - 1)), uint8_t(y * 255 / (h - 1)), uint8_t((x * 7 + y * 3) & 255), uint8_t(255)})
                img.data.push_back(v);
    return img;
}

class GlfwWindow : public ::testing::Test {
protected:
    void SetUp() override {
        if (!haveDisplay()) GTEST_SKIP() << "no display: CTest runs this binary under xvfb-run";
        gdi::BackendProbe p = gdi::probeBackend("gl-glfw", true);
        ASSERT_TRUE(p.available) << p.reason;
        device = std::move(p.device);
    }
    void TearDown() override {
        if (device) {
            EXPECT_EQ(device->validationErrorCount(), 0u);
        }
    }
    std::unique_ptr<gdi::Device> device;
};

}  // namespace

TEST(GlfwPlatform, WithoutADisplaySaysWhy) {
    ScopedUnsetEnv x("DISPLAY"), w("WAYLAND_DISPLAY");
    gdi::BackendProbe p = gdi::probeBackend("gl-glfw", false);
    EXPECT_FALSE(p.available);
    EXPECT_NE(p.reason.find("no display"), std::string::npos) << p.reason;
    EXPECT_THROW(gdi::createDevice({.backend = "gl-glfw", .verbose = false}), gdi::Error);
}

TEST(GlfwPlatform, HeadlessBackendsRefuseToPresent) {
    int tried = 0;
    for (const std::string& name : gdi::backendNames()) {
        gdi::BackendProbe p = gdi::probeBackend(name, true);
        if (!p.available) continue;
        EXPECT_FALSE(p.device->info().features.window) << name;
        gdi::TextureHandle t = p.device->createTexture({.width = 4, .height = 4});
        try {
            p.device->present(t);
            ADD_FAILURE() << name << " presented without a window";
        } catch (const gdi::Error& e) {
            EXPECT_NE(std::string(e.what()).find("no window"), std::string::npos) << e.what();
        }
        EXPECT_THROW(p.device->readWindow(), gdi::Error) << name;
        ++tried;
    }
    EXPECT_GT(tried, 0);
}

TEST_F(GlfwWindow, IsAGlDeviceWithAWindow) {
    EXPECT_EQ(device->info().backend, "gl-glfw");
    EXPECT_TRUE(device->info().features.window);
    EXPECT_NE(device->info().apiVersion.find("4.5"), std::string::npos) << device->info().apiVersion;
}

// The window shows the texture's bytes unchanged (no sRGB re-encoding), upright, at its size.
TEST_F(GlfwWindow, PresentShowsTheTextureBytesUpright) {
    for (gdi::Format f : {gdi::Format::RGBA8, gdi::Format::RGBA8_SRGB}) {
        for (auto [w, h] : {std::pair{64u, 48u}, std::pair{96u, 80u}}) {  // the second presents into a resized window
            const gdi::Image src = pattern(w, h, f);
            gdi::TextureHandle t = device->createTexture({.format = f, .width = w, .height = h});
            device->writeTexture(t, {}, gdi::bytesOf(src.data));
            EXPECT_TRUE(device->present(t));
            gdi::Image shown = device->readWindow();
            ASSERT_EQ(shown.width, w);
            ASSERT_EQ(shown.height, h);
            size_t differing = 0, first = shown.data.size();
            for (size_t i = 0; i < shown.data.size() && i < src.data.size(); ++i)
                if (shown.data[i] != src.data[i]) ++differing, first = std::min(first, i);
            EXPECT_EQ(differing, 0u) << gdi::formatInfo(f).name << " " << w << "x" << h << ": first differing byte "
                                     << first << " (pixel " << first / 4 % w << "," << first / 4 / w << ")";
            device->destroy(t);
        }
    }
}

TEST_F(GlfwWindow, PresentRejectsDepthAndUnreadableTextures) {
    gdi::TextureHandle depth = device->createTexture(
        {.format = gdi::Format::D32F, .width = 8, .height = 8, .usage = gdi::TextureUsage::RenderTarget | gdi::TextureUsage::CopySrc});
    EXPECT_THROW(device->present(depth), gdi::Error);
    gdi::TextureHandle noCopy = device->createTexture({.width = 8, .height = 8, .usage = gdi::TextureUsage::Sampled});
    EXPECT_THROW(device->present(noCopy), gdi::Error);
    EXPECT_THROW(device->present(gdi::TextureHandle{}), gdi::Error);
}

// A whole frame of the scene renderer, shown in the window: what the window shows is the
// display pass's image.
TEST_F(GlfwWindow, SceneRendererFramesAppearInTheWindow) {
    assets::Scene scene = assets::loadScene("builtin:spheres", {}, {});
    render::RenderSettings s;
    s.width = 96, s.height = 64, s.technique = render::Technique::Deferred, s.displayImage = true;
    render::SceneRenderer renderer(*device, scene, s);
    for (int frame = 0; frame < 2; ++frame) {
        renderer.renderFrame();
        EXPECT_TRUE(device->present(renderer.displayTexture()));
    }
    gdi::Image shown = device->readWindow();
    gdi::Image display = renderer.readDisplay();
    ASSERT_EQ(shown.width, display.width);
    ASSERT_EQ(shown.height, display.height);
    EXPECT_EQ(shown.data, display.data);
}

// The conformance suite on the window's context, and its images against gl-egl's.
TEST_F(GlfwWindow, ConformanceSuitePassesAndMatchesHeadlessGl) {
    gdi::BackendProbe headless = gdi::probeBackend("gl-egl", true);
    if (!headless.available) headless = gdi::probeBackend("gl-osmesa", true);
    ASSERT_TRUE(headless.available) << headless.reason;
    int compared = 0;
    for (const conformance::Case& c : conformance::cases()) {
        conformance::CaseResult mine = conformance::runCase(*device, c);
        EXPECT_TRUE(mine.passed) << c.name << ": " << mine.message;
        conformance::CaseResult ref = conformance::runCase(*headless.device, c);
        ASSERT_EQ(mine.images.size(), ref.images.size()) << c.name;
        for (size_t i = 0; i < ref.images.size(); ++i) {
            gdi::ImageDiff d = gdi::compareImages(mine.images[i].image, ref.images[i].image, ref.images[i].absTolerance);
            EXPECT_LE(d.fractionOver(), ref.images[i].maxFractionOver) << c.name << "/" << ref.images[i].name;
            ++compared;
        }
    }
    EXPECT_GT(compared, 40);
}

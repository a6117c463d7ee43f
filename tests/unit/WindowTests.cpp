// The windowed backends, vulkan-glfw (a Vulkan surface and swap chain) and gl-glfw (a GL context),
// both in a GLFW window, and Device::present showing a texture in it. CTest runs this binary
// under xvfb-run (a virtual X server), so the window is real and readWindow reads what the X
// server shows; without a display the backends must say why they cannot start.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <optional>
#include <string>

#include "BackendTest.h"
#include "Conformance.h"
#include "fe/gdi/Backend.h"
#include "fe/gdi/Faults.h"
#include "assets/BuiltinScenes.h"
#include "integration/SceneRenderer.h"

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
            for (uint8_t v : {uint8_t(x * 255 / (w - 1)), uint8_t(y * 255 / (h - 1)),
                              uint8_t((x * 7 + y * 3) & 255), uint8_t(255)})
                img.data.push_back(v);
    return img;
}

// A windowed backend with validation on; without a display the test skips (CTest runs this
// binary under xvfb-run), with one the backend must start.
class WindowBackend : public ::testing::TestWithParam<std::string> {
protected:
    void SetUp() override {
        if (!haveDisplay()) GTEST_SKIP() << "no display: CTest runs this binary under xvfb-run";
        device = open(true);
    }
    void TearDown() override {
        if (device) {
            EXPECT_EQ(device->validationErrorCount(), 0u);
        }
    }
    std::unique_ptr<gdi::Device> open(bool vsync) {
        gdi::BackendProbe p = gdi::probeBackend(GetParam(), true, vsync);
        EXPECT_TRUE(p.available) << p.reason;
        return std::move(p.device);
    }
    bool isVulkan() const { return GetParam() == "vulkan-glfw"; }
    std::unique_ptr<gdi::Device> device;
};

// Uploads `src` into a new texture, presents it and expects the window to show exactly its bytes
// (in RGBA order: a BGRA8 texture's red byte is shown as red).
void expectPresentedExactly(gdi::Device& device, const gdi::Image& src, const std::string& what) {
    gdi::Image want = src;
    if (src.format == gdi::Format::BGRA8 || src.format == gdi::Format::BGRA8_SRGB)
        for (size_t i = 0; i + 3 < want.data.size(); i += 4)
            std::swap(want.data[i], want.data[i + 2]);
    gdi::TextureHandle t =
        device.createTexture({.format = src.format, .width = src.width, .height = src.height});
    device.writeTexture(t, {}, gdi::bytesOf(src.data));
    EXPECT_TRUE(device.present(t)) << what;
    gdi::Image shown = device.readWindow();
    device.destroy(t);
    ASSERT_EQ(shown.width, src.width) << what;
    ASSERT_EQ(shown.height, src.height) << what;
    size_t differing = 0, first = shown.data.size();
    for (size_t i = 0; i < shown.data.size() && i < want.data.size(); ++i)
        if (shown.data[i] != want.data[i]) ++differing, first = std::min(first, i);
    EXPECT_EQ(differing, 0u) << what << ": first differing byte " << first << " (pixel "
                             << first / 4 % src.width << "," << first / 4 / src.width << ")";
}

}  // namespace

INSTANTIATE_TEST_SUITE_P(Glfw, WindowBackend, ::testing::ValuesIn(gdi::windowBackendNames()),
                         fe::testing::backendTestName);

TEST_P(WindowBackend, WithoutADisplaySaysWhy) {
    ScopedUnsetEnv x("DISPLAY"), w("WAYLAND_DISPLAY");
    gdi::BackendProbe p = gdi::probeBackend(GetParam(), false);
    EXPECT_FALSE(p.available);
    EXPECT_NE(p.reason.find("no display"), std::string::npos) << p.reason;
    EXPECT_THROW(gdi::createDevice({.backend = GetParam(), .verbose = false}), gdi::Error);
}

TEST(HeadlessBackends, RefuseToPresent) {
    int tried = 0;
    for (const std::string& name : gdi::backendNames()) {
        gdi::BackendProbe p = gdi::probeBackend(name, true);
        if (!p.available) continue;
        EXPECT_FALSE(p.device->info().features.window) << name;
        EXPECT_TRUE(p.device->info().presentMode.empty()) << name;
        gdi::TextureHandle t = p.device->createTexture({.width = 4, .height = 4});
        const std::string e = fe::testing::errorOf([&] { p.device->present(t); });
        EXPECT_NE(e.find("no window"), std::string::npos) << name << ": " << e;
        EXPECT_THROW(p.device->readWindow(), gdi::Error) << name;
        ++tried;
    }
    EXPECT_GT(tried, 0);
}

TEST_P(WindowBackend, IsADeviceWithAWindow) {
    EXPECT_EQ(device->info().backend, GetParam());
    EXPECT_TRUE(device->info().features.window);
    const std::string api = isVulkan() ? "Vulkan 1." : "4.5";
    EXPECT_NE(device->info().apiVersion.find(api), std::string::npos) << device->info().apiVersion;
    EXPECT_EQ(device->info().presentMode,
              isVulkan() ? "FIFO (vsync on)" : "swap interval 1 (vsync on)");
}

// The window shows the texture's bytes unchanged (no sRGB re-encoding), upright, at its size.
// The sizes alternate, so the window grows and shrinks (Vulkan: the swap chain is recreated).
TEST_P(WindowBackend, PresentShowsTheTextureBytesUpright) {
    for (gdi::Format f :
         {gdi::Format::RGBA8, gdi::Format::RGBA8_SRGB, gdi::Format::BGRA8, gdi::Format::BGRA8_SRGB})
        for (auto [w, h] : {std::pair{64u, 48u}, std::pair{96u, 80u}})
            expectPresentedExactly(*device, pattern(w, h, f),
                                   std::string(gdi::formatInfo(f).name) + " " + std::to_string(w) +
                                       "x" + std::to_string(h));
}

// A device lost while presenting (Vulkan: the present's own submission; GL: a submission, whose
// reset status the next present sees) is a DeviceLostError, now and for every later present.
TEST_P(WindowBackend, DeviceLossWhilePresentingIsReported) {
    const gdi::Image img = pattern(32, 32, gdi::Format::RGBA8);
    gdi::TextureHandle t =
        device->createTexture({.format = img.format, .width = img.width, .height = img.height});
    device->writeTexture(t, {}, gdi::bytesOf(img.data));
    EXPECT_TRUE(device->present(t));
    gdi::fault::arm(gdi::fault::Site::Submission, 1);
    if (!isVulkan()) {
        auto cmd = device->createCommandList();
        EXPECT_THROW(device->submit(*cmd), gdi::DeviceLostError);
    }
    EXPECT_THROW(device->present(t), gdi::DeviceLostError);
    EXPECT_THROW(device->present(t), gdi::DeviceLostError);
    EXPECT_THROW(device->readWindow(), gdi::DeviceLostError);
    gdi::fault::arm(gdi::fault::Site::Submission, 0);
    device->destroy(t);  // objects are still released on a lost device
}

// Frames in a row at one size: the swap chain's images and semaphores are reused (Vulkan:
// more presents than images), each frame shown exactly.
TEST_P(WindowBackend, ManyFramesInARow) {
    for (uint32_t i = 0; i < 8; ++i) {
        gdi::Image img = pattern(48, 32, gdi::Format::RGBA8);
        for (size_t b = 2; b < img.data.size(); b += 4)
            img.data[b] = uint8_t(img.data[b] + 31 * i);  // differs per frame
        expectPresentedExactly(*device, img, "frame " + std::to_string(i));
    }
}

TEST_P(WindowBackend, PresentRejectsBadTextures) {
    using U = gdi::TextureUsage;
    gdi::TextureHandle depth = device->createTexture({.format = gdi::Format::D32F,
                                                      .width = 8,
                                                      .height = 8,
                                                      .usage = U::RenderTarget | U::CopySrc});
    EXPECT_NE(
        fe::testing::errorOf([&] { device->present(depth); }).find("format D32F cannot be shown"),
        std::string::npos);
    gdi::TextureHandle hdr =
        device->createTexture({.format = gdi::Format::RGBA32F, .width = 8, .height = 8});
    EXPECT_NE(fe::testing::errorOf([&] {
                  device->present(hdr);
              }).find("present RGBA8, RGBA8_SRGB, BGRA8 or BGRA8_SRGB"),
              std::string::npos);
    gdi::TextureHandle noCopy = device->createTexture(
        {.width = 8, .height = 8, .usage = U::Sampled, .debugName = "nocopy"});
    EXPECT_NE(fe::testing::errorOf([&] {
                  device->present(noCopy);
              }).find("texture 'nocopy': needs CopySrc usage"),
              std::string::npos);
    EXPECT_THROW(device->present(gdi::TextureHandle{}), gdi::Error);
    EXPECT_THROW(device->present(gdi::TextureHandle{12345}), gdi::Error);
    // Nothing half-done: the next good present still shows its bytes.
    expectPresentedExactly(*device, pattern(40, 24, gdi::Format::RGBA8), "after rejected presents");
}

TEST_P(WindowBackend, ReadWindowBeforeAnyPresentIsAnError) {
    EXPECT_NE(fe::testing::errorOf([&] { device->readWindow(); }).find("nothing presented yet"),
              std::string::npos);
}

// Vsync off: Vulkan picks IMMEDIATE or MAILBOX where the surface has one (lavapipe has both),
// GL swap interval 0; frames still appear exactly.
TEST_P(WindowBackend, VsyncOff) {
    device.reset();
    device = open(false);
    ASSERT_TRUE(device);
    const std::string mode = device->info().presentMode;
    if (isVulkan())
        EXPECT_TRUE(mode == "IMMEDIATE (vsync off)" || mode == "MAILBOX (vsync off)" ||
                    mode.find("neither IMMEDIATE nor MAILBOX") != std::string::npos)
            << mode;
    else
        EXPECT_EQ(mode, "swap interval 0 (vsync off)");
    for (auto [w, h] : {std::pair{64u, 48u}, std::pair{80u, 56u}})
        for (gdi::Format f : {gdi::Format::RGBA8, gdi::Format::RGBA8_SRGB})
            expectPresentedExactly(*device, pattern(w, h, f),
                                   std::string(gdi::formatInfo(f).name) + " vsync off");
}

// Whole frames of the scene renderer, shown in the window: what the window shows is the
// display pass's image.
TEST_P(WindowBackend, SceneRendererFramesAppearInTheWindow) {
    assets::Scene scene = assets::loadScene("builtin:spheres", {}, {});
    render::RenderSettings s;
    s.width = 96, s.height = 64, s.technique = "deferred", s.displayImage = true;
    render::SceneRenderer renderer(*device, scene, s);
    for (int frame = 0; frame < 3; ++frame) {
        renderer.renderFrame();
        EXPECT_TRUE(device->present(renderer.displayTexture()));
    }
    gdi::Image shown = device->readWindow();
    gdi::Image display = renderer.readDisplay();
    ASSERT_EQ(shown.width, display.width);
    ASSERT_EQ(shown.height, display.height);
    EXPECT_EQ(shown.data, display.data);
}

// The conformance suite on the windowed device, and its images against its headless twin's.
TEST_P(WindowBackend, ConformanceSuitePassesAndMatchesHeadlessTwin) {
    gdi::BackendProbe headless = gdi::probeBackend(isVulkan() ? "vulkan" : "gl-egl", true);
    if (!headless.available && !isVulkan()) headless = gdi::probeBackend("gl-osmesa", true);
    ASSERT_TRUE(headless.available) << headless.reason;
    int compared = 0;
    for (const conformance::Case& c : conformance::cases()) {
        conformance::CaseResult mine = conformance::runCase(*device, c);
        EXPECT_TRUE(mine.passed) << c.name << ": " << mine.message;
        conformance::CaseResult ref = conformance::runCase(*headless.device, c);
        ASSERT_EQ(mine.images.size(), ref.images.size()) << c.name;
        for (size_t i = 0; i < ref.images.size(); ++i) {
            gdi::ImageDiff d = gdi::compareImages(mine.images[i].image, ref.images[i].image,
                                                  ref.images[i].absTolerance);
            EXPECT_LE(d.fractionOver(), ref.images[i].maxFractionOver)
                << c.name << "/" << ref.images[i].name;
            ++compared;
        }
    }
    EXPECT_GT(compared, 40);
    EXPECT_EQ(headless.device->validationErrorCount(), 0u);
}

// DeviceCreateDesc::window: auto, vulkan and gl stand for their windowed backends; a
// headless-only backend is an error that says so.
TEST(WindowSelection, GenericNamesPickWindowedBackends) {
    EXPECT_EQ(gdi::windowCandidates("auto"), (std::vector<std::string>{"vulkan-glfw", "gl-glfw"}));
    EXPECT_EQ(gdi::windowCandidates("vulkan"), (std::vector<std::string>{"vulkan-glfw"}));
    EXPECT_EQ(gdi::windowCandidates("gl"), (std::vector<std::string>{"gl-glfw"}));
    EXPECT_EQ(gdi::windowCandidates("gl-glfw"), (std::vector<std::string>{"gl-glfw"}));
    EXPECT_TRUE(gdi::windowCandidates("gl-egl").empty());
    EXPECT_TRUE(gdi::windowCandidates("gl-osmesa").empty());
    EXPECT_THROW(gdi::windowCandidates("metal"), gdi::Error);
    const std::string e = fe::testing::errorOf(
        [] { gdi::createDevice({.backend = "gl-osmesa", .verbose = false, .window = true}); });
    EXPECT_NE(e.find("backend 'gl-osmesa' is headless"), std::string::npos) << e;
    // `auto` without a window never opens one.
    for (const std::string& name : gdi::backendNames())
        for (const std::string& w : gdi::windowBackendNames()) EXPECT_NE(name, w);
}

TEST(WindowSelection, CreateDeviceWithWindowPicksVulkanThenGl) {
    if (!haveDisplay()) GTEST_SKIP() << "no display: CTest runs this binary under xvfb-run";
    for (auto [name, expected] : {std::pair{"vulkan", "vulkan-glfw"}, std::pair{"gl", "gl-glfw"},
                                  std::pair{"auto", "vulkan-glfw"}}) {
        auto device = gdi::createDevice(
            {.backend = name, .validation = true, .verbose = false, .window = true});
        EXPECT_EQ(device->info().backend, expected) << name;
        EXPECT_TRUE(device->info().features.window) << name;
    }
}

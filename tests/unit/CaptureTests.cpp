// Capture and replay (Capture.h): programs captured on one backend replay on every backend.
//  - every technique: replayed on its own backend, the image is the live one exactly; on another
//    backend, it matches that backend's live render within the conformance tolerance;
//  - what the program wrote into mapped memory between submits reaches the replay;
//  - the whole conformance run (views, queries, constants, secondary lists, heaps, threads)
//    replays on every backend with the validation layer and GL debug output silent;
//  - damaged, truncated, future-version and hand-made files are refused with a CaptureError
//    naming the record or the offset, never a crash.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>

#include "BackendTest.h"
#include "Conformance.h"
#include "assets/BuiltinScenes.h"
#include "fe/gdi/Capture.h"
#include "fe/gdi/ShaderRegistry.h"
#include "integration/SceneRenderer.h"
#include "render/TechniqueRenderer.h"

using namespace fe;
namespace fs = std::filesystem;

namespace {

fs::path tempPath(const std::string& name) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string test = std::string(info->test_suite_name()) + "_" + info->name();
    for (char& c : test)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return fs::temp_directory_path() / ("fe_capture_" + test + "_" + name);
}

std::unique_ptr<gdi::Device> startOrNull(const std::string& backend) {
    gdi::BackendProbe p = gdi::probeBackend(backend, true);
    return p.available ? std::move(p.device) : nullptr;
}

// One display image per technique, in techniques() order, rendered on `device`.
std::vector<gdi::Image> renderEveryTechnique(gdi::Device& device, const assets::Scene& scene) {
    std::vector<gdi::Image> images;
    for (const render::TechniqueInfo& t : render::techniques()) {
        render::SceneRenderer r(
            device, scene, {.technique = t.name, .width = 48, .height = 32, .displayImage = true});
        r.renderFrame();
        images.push_back(r.readDisplay());
    }
    return images;
}

double fractionOver(const gdi::Image& a, const gdi::Image& b) {
    return gdi::compareImages(a, b, 5.0 / 255.0).fractionOver();
}

}  // namespace

// Capture on each backend, replay on each: 3 x 3 pairs, every technique in each capture.
TEST(CaptureReplay, EveryTechniqueOnEveryBackendPair) {
    const assets::Scene scene = assets::makeBuiltinScene("spheres", {.sphereGrid = 3});
    std::map<std::string, std::vector<gdi::Image>> live;
    std::map<std::string, fs::path> files;
    for (const std::string& b : gdi::backendNames()) {
        auto device = startOrNull(b);
        if (!device) continue;
        files[b] = tempPath(b + ".fecap");
        auto captured = gdi::makeCaptureDevice(std::move(device), {.path = files[b].string()});
        live[b] = renderEveryTechnique(*captured, scene);
        EXPECT_EQ(captured->validationErrorCount(), 0u) << b;
        gdi::finishCapture(*captured);
        EXPECT_EQ(gdi::captureStats(*captured)->frames, render::techniques().size()) << b;
    }
    if (live.empty()) GTEST_SKIP() << "no backend starts here";
    for (const auto& [from, file] : files) {
        for (const auto& [to, liveImages] : live) {
            auto device = startOrNull(to);
            ASSERT_TRUE(device);
            const gdi::ReplayResult r = gdi::replayCapture(file.string(), *device);
            EXPECT_EQ(r.capturedBackend, from);
            EXPECT_EQ(device->validationErrorCount(), 0u) << from << " on " << to;
            ASSERT_EQ(r.images.size(), liveImages.size()) << from << " on " << to;
            for (size_t i = 0; i < r.images.size(); ++i) {
                const std::string technique = render::techniques()[i].name;
                if (from == to) {
                    EXPECT_EQ(r.images[i].image.data, live[from][i].data)
                        << technique << " on " << to << " is not the live image";
                } else {
                    EXPECT_LE(fractionOver(r.images[i].image, liveImages[i]), 0.001)
                        << technique << ": captured on " << from << ", replayed on " << to;
                }
            }
        }
        fs::remove(file);
    }
}

// Bytes the program wrote into mapped Upload memory, different in each frame, reach the replay:
// each frame copies the buffer into a texture and reads it back.
class CaptureMappedMemory : public fe::testing::BackendTest {};
TEST_P(CaptureMappedMemory, EveryFramesBytesReplayOnEveryBackend) {
    const fs::path file = tempPath(GetParam() + ".fecap");
    const std::array<uint32_t, 3> colours = {0xff0000ffu, 0xff00ff00u, 0x80ff0000u};
    {
        auto d = gdi::makeCaptureDevice(std::move(device), {.path = file.string()});
        const auto upload = d->createBuffer({.size = 4 * 4 * 4,
                                             .usage = gdi::BufferUsage::CopySrc,
                                             .access = gdi::MemoryAccess::Upload});
        const auto texture =
            d->createTexture({.width = 4,
                              .height = 4,
                              .usage = gdi::TextureUsage::CopyDst | gdi::TextureUsage::CopySrc});
        auto* mapped = static_cast<uint32_t*>(d->map(upload));
        auto list = d->createCommandList();
        for (uint32_t colour : colours) {
            for (int i = 0; i < 16; ++i) mapped[i] = colour;
            // Only some bytes change between frames: the capture writes what changed.
            mapped[5] = colour ^ 0x00ffffffu;
            list->copyBufferToTexture(texture, {}, upload, 0);
            d->wait(d->submit(*list));
            const gdi::Image live = d->readTexture(texture);
            uint32_t texel;
            std::memcpy(&texel, live.data.data(), 4);
            ASSERT_EQ(texel, colour);
        }
        d->destroy(texture);
        d->destroy(upload);
        EXPECT_EQ(d->validationErrorCount(), 0u);
    }
    for (const std::string& to : gdi::backendNames()) {
        auto replay = startOrNull(to);
        if (!replay) continue;
        const gdi::ReplayResult r = gdi::replayCapture(file.string(), *replay);
        ASSERT_EQ(r.images.size(), colours.size()) << to;
        for (size_t f = 0; f < colours.size(); ++f) {
            std::vector<uint32_t> texels(16);
            std::memcpy(texels.data(), r.images[f].image.data.data(), 64);
            for (int i = 0; i < 16; ++i)
                EXPECT_EQ(texels[size_t(i)], i == 5 ? colours[f] ^ 0x00ffffffu : colours[f])
                    << "frame " << f << " texel " << i << " on " << to;
        }
        EXPECT_EQ(replay->validationErrorCount(), 0u) << to;
    }
    fs::remove(file);
}
FE_INSTANTIATE_FOR_EVERY_BACKEND(CaptureMappedMemory);

// The conformance cases use every part of the device: their capture must replay everywhere.
class CaptureConformanceRun : public fe::testing::BackendTest {};
TEST_P(CaptureConformanceRun, ReplaysOnEveryBackendWithValidationSilent) {
    const fs::path file = tempPath(GetParam() + ".fecap");
    {
        auto d = gdi::makeCaptureDevice(std::move(device), {.path = file.string()});
        for (const conformance::Case& c : conformance::cases()) {
            const conformance::CaseResult r = conformance::runCase(*d, c);
            EXPECT_TRUE(r.passed) << c.name << ": " << r.message;
        }
        EXPECT_EQ(d->validationErrorCount(), 0u);
        gdi::finishCapture(*d);
        EXPECT_GT(gdi::captureStats(*d)->dedupedBlobs, 0u)
            << "shaders made again should be written once";
    }
    const gdi::CaptureSummary summary = gdi::summarizeCapture(file.string());
    EXPECT_EQ(summary.backend, GetParam());
    for (const std::string& to : gdi::backendNames()) {
        auto replay = startOrNull(to);
        if (!replay) continue;
        const gdi::ReplayResult r = gdi::replayCapture(file.string(), *replay);
        EXPECT_EQ(r.submits, summary.submits) << to;
        EXPECT_GT(r.images.size(), 100u) << to;
        EXPECT_EQ(replay->validationErrorCount(), 0u) << to;
    }
    fs::remove(file);
}
FE_INSTANTIATE_FOR_EVERY_BACKEND(CaptureConformanceRun);

// A capture made where buffer offsets may be multiples of 16 or 64 must replay where GL asks for
// 256 (NVIDIA's Vulkan against its GL): the capture device tells the program the strictest.
class CaptureLimits : public fe::testing::BackendTest {};
TEST_P(CaptureLimits, OffsetAlignmentsSuitEveryBackend) {
    const gdi::DeviceLimits inner = device->info().limits;
    auto d = gdi::makeCaptureDevice(std::move(device),
                                    {.path = tempPath(GetParam() + "-limits.fecap").string()});
    const gdi::DeviceLimits& l = d->info().limits;
    EXPECT_EQ(l.uniformBufferOffsetAlignment % 256, 0u);
    EXPECT_EQ(l.storageBufferOffsetAlignment % 256, 0u);
    EXPECT_EQ(l.uniformBufferOffsetAlignment % inner.uniformBufferOffsetAlignment, 0u);
    EXPECT_EQ(l.storageBufferOffsetAlignment % inner.storageBufferOffsetAlignment, 0u);
    EXPECT_EQ(l.maxTextureSize2D, inner.maxTextureSize2D);  // the rest is the device's own
    d.reset();
    fs::remove(tempPath(GetParam() + "-limits.fecap"));
}
FE_INSTANTIATE_FOR_EVERY_BACKEND(CaptureLimits);

// ---------------------------------------------------------------------------------------------
// Hostile files, written byte by byte as docs/CAPTURE.md describes the format.
// ---------------------------------------------------------------------------------------------
namespace {

using nlohmann::json;

struct FileBuilder {
    std::vector<uint8_t> bytes;
    explicit FileBuilder(uint32_t version = gdi::kCaptureFormatVersion) {
        for (char c : std::string("FECAPTUR")) bytes.push_back(uint8_t(c));
        u32(version);
        u32(0);
    }
    void u32(uint32_t v) { put(&v, 4); }
    void u64(uint64_t v) { put(&v, 8); }
    void put(const void* p, size_t n) {
        for (size_t i = 0; i < n; ++i) bytes.push_back(static_cast<const uint8_t*>(p)[i]);
    }
    FileBuilder& chunk(uint32_t kind, const std::vector<uint8_t>& body) {
        u32(kind), u32(0), u64(body.size()), u64(body.size());
        bytes.insert(bytes.end(), body.begin(), body.end());
        return *this;
    }
    FileBuilder& record(const json& j) { return chunk(2, json::to_cbor(j)); }
    FileBuilder& blob(const std::vector<uint8_t>& b) { return chunk(1, b); }
    FileBuilder& end() { return chunk(3, {}); }
};

json deviceRecord(uint64_t commandSet) {
    return {{"op", "device"},
            {"backend", "vulkan"},
            {"device", "x"},
            {"commandSet", commandSet},
            {"window", false}};
}

class CaptureFileErrors : public fe::testing::BackendTest {
protected:
    void SetUp() override {
        BackendTest::SetUp();
        if (!device) return;
        // A real capture's first record gives the command-set fingerprint hand-made files need.
        const fs::path good = tempPath("good.fecap");
        {
            auto d = gdi::makeCaptureDevice(startOrNull(GetParam()),
                                            {.path = good.string(), .compress = false});
            const auto t = d->createTexture(
                {.width = 2,
                 .height = 2,
                 .usage = gdi::TextureUsage::CopyDst | gdi::TextureUsage::CopySrc});
            d->writeTexture(t, {}, gdi::bytesOf(std::vector<uint8_t>(16, 7)));
            d->readTexture(t);
            d->destroy(t);
        }
        std::ifstream in(good, std::ios::binary);
        valid.assign(std::istreambuf_iterator<char>(in), {});
        fs::remove(good);
        // The device record is the first chunk: 16 bytes of header, 24 of chunk header.
        uint64_t size;
        std::memcpy(&size, valid.data() + 16 + 8, 8);
        fingerprint = json::from_cbor(std::vector<uint8_t>(
            valid.begin() + 40, valid.begin() + 40 + long(size)))["commandSet"];
    }
    // Replays `bytes` and returns the CaptureError's message ("(replayed)" when accepted); any
    // other exception fails the test.
    std::string replayError(const std::vector<uint8_t>& bytes) {
        const fs::path file = tempPath("hostile.fecap");
        std::ofstream(file, std::ios::binary)
            .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
        std::string message = "(replayed)";
        try {
            gdi::replayCapture(file.string(), *device);
        } catch (const gdi::CaptureError& e) {
            message = e.what();
        } catch (const std::exception& e) {
            ADD_FAILURE() << "not a CaptureError: " << e.what();
        }
        fs::remove(file);
        return message;
    }
    FileBuilder started() {
        FileBuilder f;
        f.record(deviceRecord(fingerprint));
        return f;
    }
    std::vector<uint8_t> valid;
    uint64_t fingerprint = 0;
};

}  // namespace

TEST_P(CaptureFileErrors, TheValidFileReplays) { EXPECT_EQ(replayError(valid), "(replayed)"); }

TEST_P(CaptureFileErrors, NotACaptureOrAFutureVersion) {
    EXPECT_NE(replayError({'h', 'e', 'l', 'l', 'o'}).find("not a capture file"), std::string::npos);
    EXPECT_NE(replayError(FileBuilder(99).end().bytes)
                  .find("format version 99; this build reads version 1"),
              std::string::npos);
    EXPECT_NE(replayError(FileBuilder(0).end().bytes).find("format version 0"), std::string::npos);
}

TEST_P(CaptureFileErrors, EveryTruncationIsRefusedWithItsOffset) {
    for (size_t n = 0; n < valid.size(); n += 7) {
        const std::string e =
            replayError(std::vector<uint8_t>(valid.begin(), valid.begin() + long(n)));
        EXPECT_NE(e.find("offset"), std::string::npos) << "cut at " << n << ": " << e;
    }
}

TEST_P(CaptureFileErrors, DamagedBytesNeverCrash) {
    std::mt19937 random(27);
    for (int i = 0; i < 200; ++i) {
        std::vector<uint8_t> bytes = valid;
        for (int k = 0; k < 3; ++k)
            bytes[16 + random() % (bytes.size() - 16)] ^= uint8_t(1 + random() % 255);
        replayError(bytes);  // refused or replayed: only another exception or a crash fails
    }
}

TEST_P(CaptureFileErrors, ChunkSizesAreCheckedBeforeMemoryIsTaken) {
    FileBuilder past = started();
    past.u32(1), past.u32(0), past.u64(1000), past.u64(1000);
    EXPECT_NE(replayError(past.bytes).find("runs past the end of the file"), std::string::npos);
    FileBuilder huge = started();
    huge.u32(1), huge.u32(1), huge.u64(4), huge.u64(uint64_t(1) << 40), huge.u32(0);
    EXPECT_NE(replayError(huge.bytes).find("larger than a capture chunk may be"),
              std::string::npos);
    FileBuilder kind = started();
    kind.chunk(9, {}).end();
    EXPECT_NE(replayError(kind.bytes).find("unknown chunk kind 9"), std::string::npos);
    FileBuilder unended = started();
    EXPECT_NE(replayError(unended.bytes).find("truncated"), std::string::npos);
}

TEST_P(CaptureFileErrors, HandMadeRecordsNameTheRecordAndTheField) {
    auto error = [&](const json& record) {
        return replayError(started().record(record).end().bytes);
    };
    EXPECT_NE(error({{"op", "launchRockets"}}).find("record 1 (launchRockets) at offset"),
              std::string::npos);
    EXPECT_NE(error({{"op", "launchRockets"}}).find("unknown call"), std::string::npos);
    const json texture = {{"dimension", 0},
                          {"format", 250},
                          {"width", 4},
                          {"height", 4},
                          {"depthOrLayers", 1},
                          {"mips", 1},
                          {"samples", 1},
                          {"usage", 1},
                          {"heap", 0},
                          {"heapOffset", 0},
                          {"viewFormats", json::array()}};
    EXPECT_NE(error({{"op", "createTexture"}, {"id", 5}, {"desc", texture}})
                  .find("field 'format' has no such value (250)"),
              std::string::npos);
    json usage = texture;
    usage["format"] = 0, usage["usage"] = 1u << 20;
    EXPECT_NE(error({{"op", "createTexture"}, {"id", 5}, {"desc", usage}})
                  .find("field 'usage' has unknown bits"),
              std::string::npos);
    EXPECT_NE(error({{"op", "createBuffer"},
                     {"id", 1},
                     {"desc", {{"size", 16}, {"usage", 1}, {"access", 0}}},
                     {"data", 99}})
                  .find("data block 99 is not in the file before it"),
              std::string::npos);
    EXPECT_NE(error({{"op", "writeBuffer"}, {"id", 77}, {"offset", 0}, {"data", 0}})
                  .find("record 1 (writeBuffer)"),
              std::string::npos);
    EXPECT_NE(
        error({{"op", "createTimer"}, {"id", 0}}).find("object id 0 is null or already in use"),
        std::string::npos);
    EXPECT_NE(error({{"op", "submit"}, {"fence", 1}, {"lists", "no"}})
                  .find("field 'lists' is not an array"),
              std::string::npos);
    // The device's own checks stand behind the file's: a buffer of size 0 is the device's error.
    EXPECT_NE(error({{"op", "createBuffer"},
                     {"id", 1},
                     {"desc", {{"size", 0}, {"usage", 1}, {"access", 0}}},
                     {"data", 0}})
                  .find("record 1 (createBuffer)"),
              std::string::npos);
    // No SPIR-V at all (data block 0 is "no bytes"): the device refuses it, nothing copies from null.
    EXPECT_NE(error({{"op", "createShader"},
                     {"id", 1},
                     {"stage", 1},
                     {"name", "empty"},
                     {"entry", "main"},
                     {"vulkan", 0},
                     {"opengl", 0}})
                  .find("record 1 (createShader)"),
              std::string::npos);
    // Not CBOR at all.
    EXPECT_NE(replayError(started().chunk(2, {0xff, 0x00, 0x13}).end().bytes)
                  .find("record 1 (?) at offset"),
              std::string::npos);
    // A command list whose stream is damaged names the command-stream record inside it.
    EXPECT_NE(replayError(started()
                              .blob({1, 2, 3})
                              .record({{"op", "submit"}, {"fence", 1}, {"lists", {1}}})
                              .end()
                              .bytes)
                  .find("record 1 (submit)"),
              std::string::npos);
    // Another build's command set.
    EXPECT_NE(replayError(FileBuilder().record(deviceRecord(fingerprint + 1)).end().bytes)
                  .find("another build's command set"),
              std::string::npos);
}
FE_INSTANTIATE_FOR_EVERY_BACKEND(CaptureFileErrors);

// ---------------------------------------------------------------------------------------------
// Bisection: a frame captured on one backend, bisected against every backend. Unperturbed, no
// divergence; with one draw left out on one side, exactly that draw is named.
// ---------------------------------------------------------------------------------------------
class CaptureBisect : public fe::testing::BackendTest {};
TEST_P(CaptureBisect, FindsThePerturbedDrawAndNothingElse) {
    const fs::path file = tempPath(GetParam() + ".fecap");
    {
        auto d = gdi::makeCaptureDevice(std::move(device), {.path = file.string()});
        const assets::Scene scene = assets::makeBuiltinScene("spheres", {.sphereGrid = 3});
        render::SceneRenderer r(
            *d, scene, {.technique = "deferred", .width = 48, .height = 32, .displayImage = true});
        r.renderFrame();
        r.readDisplay();
    }
    auto self = startOrNull(GetParam());
    const uint64_t draws = gdi::replayCapture(file.string(), *self, {.snapshotPasses = true}).draws;
    ASSERT_GT(draws, 5u);
    for (const std::string& other : gdi::backendNames()) {
        auto b = startOrNull(other);
        if (!b) continue;
        const gdi::BisectResult same = gdi::bisectCapture(file.string(), *self, *b);
        EXPECT_FALSE(same.diverged) << GetParam() << " against " << other << ": "
                                    << (same.diffs.empty() ? "" : same.diffs[0].target);
        EXPECT_GT(same.passesCompared, 1u);
        // The first draw, one in the middle, the last (in the display pass).
        for (uint64_t perturbed : {uint64_t(0), draws / 2, draws - 1}) {
            const gdi::BisectResult r =
                gdi::bisectCapture(file.string(), *self, *b, {.perturb = {{1, perturbed}}});
            ASSERT_TRUE(r.diverged) << "draw " << perturbed << " on " << other;
            ASSERT_TRUE(r.draw) << "draw " << perturbed << " on " << other
                                << ": only the pass was found";
            EXPECT_EQ(r.draw->draw, perturbed) << other;
            EXPECT_FALSE(r.draw->pipeline.empty());
            EXPECT_FALSE(r.draw->shaders.empty());
            EXPECT_FALSE(r.diffs.empty());
            EXPECT_GT(r.diffs[0].diff.pixelsOverTolerance, 0u);
        }
        EXPECT_EQ(b->validationErrorCount(), 0u) << other;
    }
    EXPECT_EQ(self->validationErrorCount(), 0u);
    fs::remove(file);
}
FE_INSTANTIATE_FOR_EVERY_BACKEND(CaptureBisect);

// A frame range (fe capture --frame K): frames 2 and 3 start from the state frames 0 and 1 left: a texture
// filled in frame 0 and copied from in frame 2, a render target drawn in frame 0 and drawn over
// with LoadOp::Load in frame 2, a pipeline whose shaders were destroyed at start-up, mapped
// Upload memory. Replayed on every backend, the read-backs are the live ones exactly.
class CaptureFrameRange : public fe::testing::BackendTest {};
TEST_P(CaptureFrameRange, FramesFromTwoStartFromTheStateBeforeThem) {
    const fs::path file = tempPath(GetParam() + ".fecap");
    std::vector<std::vector<uint8_t>> scratchAt, targetAt;  // live read-backs, per frame
    {
        auto d = gdi::makeCaptureDevice(std::move(device),
                                        {.path = file.string(), .frames = 2, .firstFrame = 2});
        using namespace gdi;
        const auto upload = d->createBuffer(
            {.size = 64, .usage = BufferUsage::CopySrc, .access = MemoryAccess::Upload});
        const auto kept = d->createTexture(
            {.width = 4, .height = 4, .usage = TextureUsage::CopyDst | TextureUsage::CopySrc});
        const auto scratch = d->createTexture(
            {.width = 4, .height = 4, .usage = TextureUsage::CopyDst | TextureUsage::CopySrc});
        const auto target =
            d->createTexture({.width = 16,
                              .height = 16,
                              .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc});
        const auto vs = d->createShader({.stage = ShaderStage::Vertex,
                                         .binary = fe::shaders::find("conformance/triangle.vert")});
        const auto fs = d->createShader({.stage = ShaderStage::Fragment,
                                         .binary = fe::shaders::find("conformance/color.frag")});
        const auto triangle = d->createGraphicsPipeline(
            {.vertexShader = vs, .fragmentShader = fs, .colorFormats = {Format::RGBA8}});
        d->destroy(vs);
        d->destroy(fs);
        auto* mapped = static_cast<uint32_t*>(d->map(upload));
        auto list = d->createCommandList();
        for (uint32_t frame = 0; frame < 4; ++frame) {
            for (int i = 0; i < 16; ++i) mapped[i] = 0xff000000u | (frame * 0x40u + uint32_t(i));
            list->copyBufferToTexture(scratch, {}, upload, 0);
            if (frame == 0) {
                list->copyTexture(kept, scratch, 0);
                list->beginRenderPass({.colors = {{.texture = target, .clear = {1, 0, 0, 1}}}});
                list->setPipeline(triangle);
                list->setViewport({0, 0, 8, 8});
                list->draw(3);
                list->endRenderPass();
            }
            if (frame == 2) {
                list->copyTexture(scratch, kept, 0);  // frame 0's bytes, kept in `kept` since
                list->beginRenderPass({.colors = {{.texture = target, .load = LoadOp::Load}}});
                list->setPipeline(triangle);
                list->setViewport({8, 8, 8, 8});
                list->draw(3);
                list->endRenderPass();
            }
            d->wait(d->submit(*list));
            scratchAt.push_back(d->readTexture(scratch).data);  // ends the frame
            targetAt.push_back(d->readTexture(target).data);    // the next frame's first call
        }
        EXPECT_EQ(captureStats(*d)->frames, 2u);
        d->destroy(triangle);
        d->destroy(target);
        d->destroy(scratch);
        d->destroy(kept);
        d->destroy(upload);
        EXPECT_EQ(d->validationErrorCount(), 0u);
    }
    EXPECT_EQ(gdi::summarizeCapture(file.string()).firstFrame, 2u);
    for (const std::string& to : gdi::backendNames()) {
        auto replay = startOrNull(to);
        if (!replay) continue;
        const gdi::ReplayResult r = gdi::replayCapture(file.string(), *replay);
        // The range starts after frame 1's first read-back: its second (of the target drawn in
        // frame 0) is the capture's first; frame 3's second ends after the range.
        ASSERT_EQ(r.images.size(), 4u) << to;
        EXPECT_EQ(r.images[0].image.data, targetAt[1])
            << "the render target as frame 0 left it, on " << to;
        EXPECT_EQ(r.images[1].image.data, scratchAt[2])
            << "frame 2's copy from the texture kept since frame 0, on " << to;
        EXPECT_EQ(r.images[2].image.data, targetAt[2])
            << "frame 2's draw over the loaded target, on " << to;
        EXPECT_EQ(r.images[3].image.data, scratchAt[3])
            << "frame 3's upload through mapped memory, on " << to;
        EXPECT_NE(targetAt[1], targetAt[2]);
        EXPECT_EQ(r.frames, 2u) << to;
        EXPECT_EQ(r.unrestored, 0u) << to;
        EXPECT_EQ(replay->validationErrorCount(), 0u) << to;
    }
    fs::remove(file);
}
FE_INSTANTIATE_FOR_EVERY_BACKEND(CaptureFrameRange);

// A capture is a portable benchmark: replay times each render pass on the GPU (timestamps around
// it), named as the program named it, and the timing changes nothing in the images.
class CapturePassTimes : public fe::testing::BackendTest {};
TEST_P(CapturePassTimes, EveryPassIsTimedAndNamed) {
    if (!device->info().features.timestamps) GTEST_SKIP() << "no timestamps on " << GetParam();
    const fs::path file = tempPath(GetParam() + ".fecap");
    {
        auto d = gdi::makeCaptureDevice(std::move(device), {.path = file.string()});
        const assets::Scene scene = assets::makeBuiltinScene("spheres", {.sphereGrid = 2});
        render::SceneRenderer r(
            *d, scene, {.technique = "deferred", .width = 32, .height = 24, .displayImage = true});
        r.renderFrame();
        r.renderFrame();
        r.readDisplay();
    }
    auto replay = startOrNull(GetParam());
    const gdi::ReplayResult timed = gdi::replayCapture(file.string(), *replay, {.passTimes = true});
    const gdi::ReplayResult plain = gdi::replayCapture(file.string(), *replay);
    EXPECT_EQ(timed.passTimes.size(), timed.passes);
    EXPECT_TRUE(plain.passTimes.empty());
    std::set<std::string> names;
    for (const gdi::PassTime& t : timed.passTimes) {
        names.insert(t.name);
        EXPECT_GT(t.gpuMilliseconds, 0.0) << t.name;
    }
    EXPECT_TRUE(names.count("gbuffer") && names.count("lighting") && names.count("display"));
    EXPECT_EQ(timed.frames, 2u);
    ASSERT_EQ(timed.images.size(), plain.images.size());
    for (size_t i = 0; i < timed.images.size(); ++i)
        EXPECT_EQ(timed.images[i].image.data, plain.images[i].image.data);
    EXPECT_EQ(replay->validationErrorCount(), 0u);
    fs::remove(file);
}
FE_INSTANTIATE_FOR_EVERY_BACKEND(CapturePassTimes);

// A damaged count cannot make a replay run for hours: work per call is bounded (and the bound
// is the replay's option, so a capture of a really heavy frame can raise it).
TEST_P(CaptureFileErrors, DrawsBeyondTheWorkLimitAreRefused) {
    const fs::path file = tempPath("heavy.fecap");
    {
        auto d = gdi::makeCaptureDevice(startOrNull(GetParam()), {.path = file.string()});
        const auto target = d->createTexture(
            {.width = 4,
             .height = 4,
             .usage = gdi::TextureUsage::RenderTarget | gdi::TextureUsage::CopySrc});
        const auto vs = d->createShader({.stage = gdi::ShaderStage::Vertex,
                                         .binary = fe::shaders::find("conformance/triangle.vert")});
        const auto fs = d->createShader({.stage = gdi::ShaderStage::Fragment,
                                         .binary = fe::shaders::find("conformance/color.frag")});
        const auto p = d->createGraphicsPipeline(
            {.vertexShader = vs, .fragmentShader = fs, .colorFormats = {gdi::Format::RGBA8}});
        auto list = d->createCommandList();
        list->beginRenderPass({.colors = {{.texture = target}}});
        list->setPipeline(p);
        list->draw(3, 1000);
        list->endRenderPass();
        d->wait(d->submit(*list));
        d->readTexture(target);
    }
    std::string e = "(replayed)";
    try {
        gdi::replayCapture(file.string(), *device, {.maxDrawVertices = 2999});
    } catch (const gdi::CaptureError& x) {
        e = x.what();
    }
    EXPECT_NE(e.find("(submit)"), std::string::npos) << e;
    EXPECT_NE(e.find("draw 0 of 3000 vertices is beyond this replay's limit (2999"),
              std::string::npos)
        << e;
    EXPECT_NO_THROW(gdi::replayCapture(file.string(), *device, {.maxDrawVertices = 3000}));
    EXPECT_EQ(device->liveObjects(), gdi::LiveObjects{});
    fs::remove(file);
}

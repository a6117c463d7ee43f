// Pipelines that share native objects (gdi/PipelineSharing.h): the kept set's bookkeeping, and on
// every backend that an equal pipeline, made from other shader objects of the same code, takes
// the first one's objects, that each still draws what its description says after the other is
// destroyed, and that a pipeline differing in any field, its name included, gets its own.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <thread>
#include <vector>

#include "BackendTest.h"
#include "fe/gdi/DeviceObjects.h"
#include "fe/gdi/PipelineSharing.h"

using namespace fe;

TEST(SharedPipelines, KeepsUnusedObjectsUpToItsBoundLeastRecentlyUsedFirst) {
    gdi::SharedPipelines<int> shared(2);
    EXPECT_FALSE(shared.acquire("a"));
    shared.add("a", 1);
    shared.add("b", 2);
    shared.add("c", 3);
    ASSERT_EQ(shared.acquire("a"), 1);  // two users now
    EXPECT_EQ(shared.sharedCount(), 1u);
    EXPECT_TRUE(shared.release("a").empty());             // one left
    EXPECT_TRUE(shared.release("a").empty());             // none: kept
    EXPECT_TRUE(shared.release("b").empty());             // kept: two unused
    EXPECT_EQ(shared.release("c"), std::vector<int>{1});  // a, the least recently used, goes
    EXPECT_FALSE(shared.acquire("a"));
    ASSERT_EQ(shared.acquire("b"), 2);  // used again: no longer among the unused
    shared.add("d", 4);
    EXPECT_TRUE(shared.release("d").empty());
    EXPECT_TRUE(shared.release("x").empty());  // an unknown key is nothing to drop
    std::vector<int> all = shared.clear();
    std::sort(all.begin(), all.end());
    EXPECT_EQ(all, (std::vector<int>{2, 3, 4}));  // each once, used or not
    EXPECT_EQ(shared.sharedCount(), 2u);
}

namespace {

const char* kVertex = R"(#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_common.glsl"
void main() {
    vec2 p = vec2((FE_VERTEX_ID << 1) & 2, FE_VERTEX_ID & 2);
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";
const char* kFragment = R"(#version 450
layout(constant_id = 0) const float kRed = 1.0;
layout(location = 0) out vec4 outColor;
void main() { outColor = vec4(kRed, 0.5, 0.25, 1.0); }
)";

class PipelineSharing : public fe::testing::BackendTest {
protected:
    gdi::ShaderHandle shader(gdi::ShaderStage stage, const char* text) {
        return objects->add(device->createShader({.stage = stage, .source = {.text = text}}));
    }
    gdi::PipelineHandle pipeline(gdi::ShaderHandle fs, float red, const char* name = "tint") {
        return device->createGraphicsPipeline(
            {.vertexShader = vs,
             .fragmentShader = fs,
             .colorFormats = {gdi::Format::RGBA8},
             .specialization = {gdi::SpecializationConstant::of(0, red)},
             .debugName = name});
    }
    // The red channel `p` draws.
    float redOf(gdi::PipelineHandle p) {
        const gdi::TextureHandle target = objects->add(device->createTexture(
            {.width = 4,
             .height = 4,
             .usage = gdi::TextureUsage::RenderTarget | gdi::TextureUsage::CopySrc}));
        auto cmd = device->createCommandList();
        cmd->beginRenderPass({.colors = {{.texture = target}}});
        cmd->setPipeline(p);
        cmd->draw(3);
        cmd->endRenderPass();
        device->wait(device->submit(*cmd));
        return device->readTexture(target).texel(1, 1)[0];
    }
    uint32_t shared() { return device->pipelineCacheStats().shared; }

    void SetUp() override {
        BackendTest::SetUp();
        if (!device) return;
        objects = std::make_unique<gdi::DeviceObjects>(*device);
        vs = shader(gdi::ShaderStage::Vertex, kVertex);
    }
    void TearDown() override {
        objects.reset();
        BackendTest::TearDown();
    }
    std::unique_ptr<gdi::DeviceObjects> objects;
    gdi::ShaderHandle vs;
};

}  // namespace

TEST_P(PipelineSharing, EqualPipelinesShareTheirObjectsAndOutliveEachOther) {
    const gdi::ShaderHandle fs = shader(gdi::ShaderStage::Fragment, kFragment);
    // The same code from another shader object, as a second renderer makes it.
    const gdi::ShaderHandle sameCode = shader(gdi::ShaderStage::Fragment, kFragment);
    const uint32_t before = shared();
    const gdi::PipelineHandle first = pipeline(fs, 1.0f);
    const gdi::PipelineHandle equal = pipeline(sameCode, 1.0f);
    EXPECT_EQ(shared(), before + 1);
    // Any field apart: its own objects.
    const gdi::PipelineHandle half = objects->add(pipeline(fs, 0.5f));
    const gdi::PipelineHandle named = objects->add(pipeline(fs, 1.0f, "another name"));
    const gdi::ShaderHandle otherCode =
        shader(gdi::ShaderStage::Fragment,
               "#version 450\nlayout(constant_id = 0) const float kRed = 1.0;\n"
               "layout(location = 0) out vec4 c;\nvoid main() { c = vec4(kRed * 0.25); }\n");
    const gdi::PipelineHandle other = objects->add(pipeline(otherCode, 1.0f));
    EXPECT_EQ(shared(), before + 1);

    // Each draws its own, and the one left draws after its twin is destroyed.
    device->destroy(first);
    EXPECT_NEAR(redOf(equal), 1.0f, 0.01f);
    EXPECT_NEAR(redOf(half), 0.5f, 0.01f);
    EXPECT_NEAR(redOf(named), 1.0f, 0.01f);
    EXPECT_NEAR(redOf(other), 0.25f, 0.01f);
    // Both destroyed: the objects are kept, and the next equal pipeline takes them.
    device->destroy(equal);
    const gdi::PipelineHandle again = objects->add(pipeline(fs, 1.0f));
    EXPECT_EQ(shared(), before + 2);
    EXPECT_NEAR(redOf(again), 1.0f, 0.01f);
}

// Equal pipelines made on two threads at once: the first is compiled, every other one shares it
// (creation is serialised by the device), and each draws.
TEST_P(PipelineSharing, EqualPipelinesMadeOnTwoThreadsShareOneCompilation) {
    const gdi::ShaderHandle fs = shader(gdi::ShaderStage::Fragment, kFragment);
    const uint32_t before = shared();
    constexpr int kEach = 8;
    std::vector<gdi::PipelineHandle> made[2];
    std::thread other([&] {
        for (int i = 0; i < kEach; ++i) made[1].push_back(pipeline(fs, 0.75f));
    });
    for (int i = 0; i < kEach; ++i) made[0].push_back(pipeline(fs, 0.75f));
    other.join();
    EXPECT_EQ(shared(), before + 2 * kEach - 1);
    for (auto& list : made)
        for (gdi::PipelineHandle p : list) {
            EXPECT_NEAR(redOf(p), 0.75f, 0.01f);
            device->destroy(p);
        }
}

FE_INSTANTIATE_FOR_EVERY_BACKEND(PipelineSharing);

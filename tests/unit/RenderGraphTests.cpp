// The render graph: culling, lifetimes, memory plans that never overlap live textures (a
// randomized property test), barriers, errors, and real execution with aliased memory on every
// backend (validation layer on).
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "BackendTest.h"
#include "fe/gdi/Backend.h"
#include "fe/gdi/ShaderRegistry.h"
#include "graph/RenderGraph.h"

using namespace fe;
using gdi::Format;
using gdi::LoadOp;
using gdi::ResourceState;
using graph::RenderGraph;
using graph::TextureId;

namespace {
const gdi::TextureDesc kOutputDesc{
    .format = Format::RGBA8,
    .width = 64,
    .height = 64,
    .usage = gdi::TextureUsage::RenderTarget | gdi::TextureUsage::CopySrc};

// An imported output with a fake handle: planning never touches the device.
TextureId importFake(RenderGraph& g, const char* name = "output") {
    return g.importTexture(name, gdi::TextureHandle{1}, kOutputDesc);
}

bool culled(const RenderGraph& g, const std::string& name) {
    for (const auto& p : g.passes())
        if (p.name == name) return p.culled;
    ADD_FAILURE() << "no pass " << name;
    return false;
}
}  // namespace

TEST(RenderGraph, CullsPassesWhoseResultsNothingUses) {
    RenderGraph g;
    auto a = g.createTexture("a", {.width = 64, .height = 64});
    auto unused = g.createTexture("unused", {.width = 64, .height = 64});
    auto out = importFake(g);
    g.addPass("makeA", [&](auto& b) { b.colorTarget(a); }, {});
    g.addPass("makeUnused",
              [&](auto& b) {
                  b.sample(a);
                  b.colorTarget(unused);
              },
              {});
    g.addPass("final",
              [&](auto& b) {
                  b.sample(a);
                  b.colorTarget(out);
              },
              {});
    g.addPass("effect", [&](auto& b) { b.sideEffect(); }, {});
    g.markOutput(out);
    g.compile(graph::CompileOptions{});
    EXPECT_FALSE(culled(g, "makeA"));
    EXPECT_TRUE(culled(g, "makeUnused"));
    EXPECT_FALSE(culled(g, "final"));
    EXPECT_FALSE(culled(g, "effect"));
    EXPECT_FALSE(g.texture(unused).used());
    EXPECT_EQ(g.memory().transientTextures, 1u);  // only "a" needs memory
}

TEST(RenderGraph, CullsAWriteThatALaterClearHides) {
    RenderGraph g;
    auto a = g.createTexture("a", {.width = 8, .height = 8});
    auto out = importFake(g);
    g.addPass("first", [&](auto& b) { b.colorTarget(a); }, {});
    g.addPass("second", [&](auto& b) { b.colorTarget(a, LoadOp::Clear); }, {});
    g.addPass("accumulate", [&](auto& b) { b.colorTarget(a, LoadOp::Load); }, {});
    g.addPass("final",
              [&](auto& b) {
                  b.sample(a);
                  b.colorTarget(out);
              },
              {});
    g.markOutput(out);
    g.compile(graph::CompileOptions{});
    EXPECT_TRUE(culled(g, "first"));  // "second" clears what it wrote
    EXPECT_FALSE(culled(g, "second"));
    EXPECT_FALSE(culled(g, "accumulate"));
}

// A layered texture (shadow cascades, a cube's faces) is written one layer per pass: a later
// layer's clear hides nothing of the earlier layers, so every layer's pass survives; a layer
// that does not exist is an error, and a cube has 6 layers.
TEST(RenderGraph, PassesWritingDifferentLayersAllSurvive) {
    RenderGraph g;
    auto cascades = g.createTexture("cascades", {.format = Format::D32F,
                                                 .width = 16,
                                                 .height = 16,
                                                 .dimension = gdi::TextureDimension::Texture2DArray,
                                                 .layers = 3});
    auto out = importFake(g);
    for (uint32_t layer = 0; layer < 3; ++layer)
        g.addPass("layer " + std::to_string(layer),
                  [&](auto& b) { b.depthTarget(cascades, LoadOp::Clear, 1.0f, layer); }, {});
    g.addPass("final",
              [&](auto& b) {
                  b.sample(cascades);
                  b.colorTarget(out);
              },
              {});
    g.markOutput(out);
    g.compile(graph::CompileOptions{});
    for (const char* p : {"layer 0", "layer 1", "layer 2"}) EXPECT_FALSE(culled(g, p)) << p;
    EXPECT_EQ(g.texture(cascades).desc.depthOrLayers, 3u);
    EXPECT_EQ(g.texture(cascades).size, 16u * 16u * 4u * 3u);  // every layer's bytes

    RenderGraph bad;
    auto two = bad.createTexture("two", {.format = Format::D32F,
                                         .width = 8,
                                         .height = 8,
                                         .dimension = gdi::TextureDimension::Texture2DArray,
                                         .layers = 2});
    auto o = importFake(bad);
    bad.addPass("p",
                [&](auto& b) {
                    b.depthTarget(two, LoadOp::Clear, 1.0f, 2);
                    b.colorTarget(o);
                },
                {});
    try {
        bad.compile(graph::CompileOptions{});
        ADD_FAILURE() << "layer 2 of 2 accepted";
    } catch (const gdi::Error& e) {
        EXPECT_NE(std::string(e.what()).find("renders into layer 2 of 'two', which has 2"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_THROW(bad.createTexture("cube", {.width = 8,
                                            .height = 8,
                                            .dimension = gdi::TextureDimension::TextureCube,
                                            .layers = 4}),
                 gdi::Error);
}

TEST(RenderGraph, NothingMarkedOutputCullsEverything) {
    RenderGraph g;
    auto out = importFake(g);
    g.addPass("final", [&](auto& b) { b.colorTarget(out); }, {});
    g.compile(graph::CompileOptions{});
    EXPECT_TRUE(culled(g, "final"));
}

TEST(RenderGraph, LifetimesSpanFirstToLastUse) {
    RenderGraph g;
    auto a = g.createTexture("a", {.width = 8, .height = 8});
    auto b2 = g.createTexture("b", {.width = 8, .height = 8});
    auto out = importFake(g);
    g.addPass("p0", [&](auto& b) { b.colorTarget(a); }, {});
    g.addPass("p1",
              [&](auto& b) {
                  b.sample(a);
                  b.colorTarget(b2);
              },
              {});
    g.addPass("p2",
              [&](auto& b) {
                  b.sample(b2);
                  b.colorTarget(out);
              },
              {});
    g.addPass("p3", [&](auto& b) { b.colorTarget(out, LoadOp::Load); }, {});
    g.markOutput(out);
    g.compile(graph::CompileOptions{});
    EXPECT_EQ(g.texture(a).firstPass, 0);
    EXPECT_EQ(g.texture(a).lastPass, 1);
    EXPECT_EQ(g.texture(b2).firstPass, 1);
    EXPECT_EQ(g.texture(b2).lastPass, 2);
    EXPECT_EQ(g.texture(out).lastPass, 3);
    // Usage follows the accesses.
    EXPECT_TRUE(any(g.texture(a).desc.usage, gdi::TextureUsage::RenderTarget));
    EXPECT_TRUE(any(g.texture(a).desc.usage, gdi::TextureUsage::Sampled));
}

// Async compute: an async pass forks after the last pass sharing a resource with it and joins
// before the first later one that does; its textures stay alive over the window, so nothing
// beside it shares their memory. A window with no graphics pass in it, and an async pass
// rendering into a target, are refused (the first runs in order, the second is an Error).
TEST(RenderGraph, AsyncComputeForksAfterItsInputsAndJoinsBeforeItsReaders) {
    RenderGraph g;
    using A = gdi::BufferAccess;
    auto gb = g.createTexture("gbuffer", {.width = 64, .height = 64});
    auto shadow = g.createTexture("shadow", {.width = 64, .height = 64});
    auto lists = g.createTexture("lists", {.format = Format::R32U, .width = 64, .height = 64});
    auto lights = g.createBuffer("lights", {.size = 256});
    auto out = importFake(g);
    g.addPass("gbuffer", [&](auto& b) { b.colorTarget(gb); }, {});
    g.addPass("upload", [&](auto& b) { b.buffer(lights, A::StorageWrite); }, {});
    g.addPass("shadow", [&](auto& b) { b.colorTarget(shadow); }, {});
    g.addPass("assign",
              [&](auto& b) {
                  b.buffer(lights, A::StorageRead);
                  b.storage(lists);
                  b.asyncCompute();
              },
              {});
    g.addPass("light",
              [&](auto& b) {
                  b.sample(gb);
                  b.sample(shadow);
                  b.colorTarget(out);
              },
              {});
    g.addPass("shade",
              [&](auto& b) {
                  b.sample(lists);
                  b.colorTarget(out, LoadOp::Load);
              },
              {});
    g.markOutput(out);
    g.compile(graph::CompileOptions{});
    const graph::PassInfo& assign = g.passes()[3];
    EXPECT_EQ(assign.forkBefore, 2);  // after "upload", its input
    EXPECT_EQ(assign.joinBefore, 5);  // before "shade", its reader
    EXPECT_EQ(g.texture(lists).firstPass, 2);
    EXPECT_EQ(g.texture(lists).lastPass, 5);
    // "shadow" lives beside the async pass: their memory must not overlap.
    const graph::TextureInfo &l = g.texture(lists), &s = g.texture(shadow);
    EXPECT_TRUE(l.offset + l.size <= s.offset || s.offset + s.size <= l.offset)
        << "lists at " << l.offset << ", shadow at " << s.offset;
    for (const graph::PassInfo& p : g.passes())
        if (p.name != "assign") EXPECT_EQ(p.forkBefore, -1) << p.name;

    // Read right after it is written: no graphics pass beside it, so it runs in order.
    RenderGraph h;
    auto t = h.createTexture("t", {.width = 8, .height = 8});
    auto o = importFake(h);
    h.addPass("make", [&](auto& b) { b.storage(t), b.asyncCompute(); }, {});
    h.addPass("use",
              [&](auto& b) {
                  b.sample(t);
                  b.colorTarget(o);
              },
              {});
    h.markOutput(o);
    h.compile(graph::CompileOptions{});
    EXPECT_EQ(h.passes()[0].forkBefore, -1);

    RenderGraph bad;
    auto badOut = importFake(bad);
    bad.addPass("draw", [&](auto& b) { b.colorTarget(badOut), b.asyncCompute(); }, {});
    bad.markOutput(badOut);
    EXPECT_EQ(fe::testing::errorOf([&] { bad.compile(graph::CompileOptions{}); }),
              "render graph: pass 'draw' may run on the compute queue (asyncCompute) but renders "
              "into 'output'");
}

// A multisampled target a later pass samples (a G-buffer under --msaa, read per sample) is
// Sampled and lives past its pass (not Transient).
TEST(RenderGraph, SampledMultisampledTargetsAreSampled) {
    RenderGraph g;
    auto ms = g.createTexture("ms", {.width = 8, .height = 8, .sampleCount = 4});
    auto out = importFake(g);
    g.addPass("draw", [&](auto& b) { b.colorTarget(ms); }, {});
    g.addPass("read",
              [&](auto& b) {
                  b.sample(ms);
                  b.colorTarget(out);
              },
              {});
    g.markOutput(out);
    g.compile(graph::CompileOptions{});
    using U = gdi::TextureUsage;
    EXPECT_EQ(g.texture(ms).desc.usage, U::RenderTarget | U::Sampled);
    EXPECT_EQ(g.texture(ms).lastPass, 1);
}

// An attachment of one pass, cleared there and read by no later pass, is Transient; one that a
// later pass samples or loads, an output, or a texture loaded in its only pass is not. Object
// reuse never shares an object between a Transient texture and another.
TEST(RenderGraph, OnePassAttachmentsAreTransient) {
    RenderGraph g;
    const graph::TransientTextureDesc depthDesc{.format = Format::D32F, .width = 64, .height = 64};
    auto depth0 = g.createTexture("depth0", depthDesc);
    auto depth1 = g.createTexture("depth1", depthDesc);
    auto kept = g.createTexture("kept", {.width = 64, .height = 64});
    auto out = importFake(g);
    g.addPass("p0",
              [&](auto& b) {
                  b.colorTarget(out);
                  b.depthTarget(depth0);
                  b.colorTarget(kept);
              },
              {});
    g.addPass("p1",
              [&](auto& b) {
                  b.colorTarget(out, LoadOp::Load);
                  b.depthTarget(depth1);
                  b.sample(kept);
              },
              {});
    g.markOutput(out);
    using U = gdi::TextureUsage;
    for (auto mode : {graph::AliasingMode::Memory, graph::AliasingMode::ObjectReuse}) {
        g.compile(graph::CompileOptions{.aliasing = mode});
        EXPECT_EQ(g.texture(depth0).desc.usage, U::RenderTarget | U::Transient);
        EXPECT_EQ(g.texture(depth1).desc.usage, U::RenderTarget | U::Transient);
        EXPECT_FALSE(any(g.texture(kept).desc.usage, U::Transient));
        if (mode == graph::AliasingMode::ObjectReuse) {
            EXPECT_EQ(g.texture(depth1).physical, int(depth0.index));  // two transients share
            EXPECT_NE(g.texture(kept).physical, int(depth0.index));
        }
    }
    g.compile(graph::CompileOptions{.lazilyAllocated = true});
    EXPECT_TRUE(g.texture(depth0).ownMemory);  // lazily allocated, outside the heap
    EXPECT_FALSE(g.texture(kept).ownMemory);
}

TEST(RenderGraph, DisjointLifetimesShareMemoryOverlappingOnesDoNot) {
    RenderGraph g;
    auto a = g.createTexture("a", {.format = Format::RGBA16F, .width = 16, .height = 16});
    auto b2 = g.createTexture("b", {.format = Format::RGBA16F, .width = 16, .height = 16});
    auto c = g.createTexture("c", {.format = Format::RGBA16F, .width = 16, .height = 16});
    auto out = importFake(g);
    g.addPass("makeA", [&](auto& b) { b.colorTarget(a); }, {});
    g.addPass("aToB",
              [&](auto& b) {
                  b.sample(a);
                  b.colorTarget(b2);
              },
              {});
    g.addPass("makeC", [&](auto& b) { b.colorTarget(c); }, {});
    g.addPass("final",
              [&](auto& b) {
                  b.sample(b2);
                  b.sample(c);
                  b.colorTarget(out);
              },
              {});
    g.markOutput(out);

    g.compile({.aliasing = graph::AliasingMode::Memory});
    const uint64_t size = 16 * 16 * 8;
    EXPECT_EQ(g.memory().withoutAliasing, 3 * size);
    EXPECT_EQ(g.memory().withAliasing, 2 * size);
    EXPECT_EQ(g.texture(c).offset, g.texture(a).offset);
    EXPECT_NE(g.texture(b2).offset, g.texture(a).offset);

    g.compile({.aliasing = graph::AliasingMode::ObjectReuse});
    EXPECT_EQ(g.texture(c).physical, int(a.index));
    EXPECT_EQ(g.memory().allocations, 2u);
    EXPECT_EQ(g.memory().withAliasing, 2 * size);

    g.compile({.aliasing = graph::AliasingMode::None});
    EXPECT_EQ(g.memory().withAliasing, 3 * size);
}

TEST(RenderGraph, ObjectReuseNeedsTheSameFormatAndSize) {
    RenderGraph g;
    auto a = g.createTexture("a", {.format = Format::RGBA16F, .width = 16, .height = 16});
    auto c = g.createTexture("c", {.format = Format::RGBA8, .width = 16, .height = 16});
    auto out = importFake(g);
    g.addPass("makeA", [&](auto& b) { b.colorTarget(a); }, {});
    g.addPass("useA",
              [&](auto& b) {
                  b.sample(a);
                  b.colorTarget(out);
              },
              {});
    g.addPass("makeC", [&](auto& b) { b.colorTarget(c); }, {});
    g.addPass("useC",
              [&](auto& b) {
                  b.sample(c);
                  b.colorTarget(out, LoadOp::Load);
              },
              {});
    g.markOutput(out);
    g.compile({.aliasing = graph::AliasingMode::ObjectReuse});
    EXPECT_NE(g.texture(c).physical, g.texture(a).physical);
    g.compile({.aliasing = graph::AliasingMode::Memory});
    EXPECT_EQ(g.texture(c).offset, g.texture(a).offset);  // bytes can be shared across formats
}

// Property: over many random graphs, no two textures whose lifetimes overlap share a byte
// (Memory) or an object (ObjectReuse), offsets respect alignment, and aliasing never costs more.
TEST(RenderGraph, RandomGraphsNeverAliasLiveTextures) {
    std::mt19937 rng(1234);
    const Format formats[] = {Format::RGBA8, Format::RGBA16F, Format::RGBA32F, Format::R32F,
                              Format::D32F};
    int sharedSomewhere = 0;
    for (int iteration = 0; iteration < 300; ++iteration) {
        RenderGraph g;
        std::vector<TextureId> tex;
        const int textureCount = 2 + int(rng() % 10);
        const uint32_t w = 8 << (rng() % 3),
                       h = 8 << (rng() % 3);  // one size per graph: passes need equal targets
        for (int i = 0; i < textureCount; ++i)
            tex.push_back(g.createTexture("t" + std::to_string(i),
                                          {.format = formats[rng() % 5], .width = w, .height = h}));
        auto out = g.importTexture("out", gdi::TextureHandle{1},
                                   {.format = Format::RGBA8, .width = w, .height = h});
        std::vector<bool> written(textureCount, false);
        const int passCount = 2 + int(rng() % 12);
        for (int p = 0; p < passCount; ++p) {
            // Sample up to two written textures, write one colour (and maybe one depth) target.
            std::vector<int> reads;
            for (int k = 0; k < 2; ++k) {
                int r = int(rng() % textureCount);
                if (written[r] && std::find(reads.begin(), reads.end(), r) == reads.end())
                    reads.push_back(r);
            }
            int colour = -1, depth = -1;
            for (int tries = 0; tries < 8 && (colour < 0 || depth < 0); ++tries) {
                int t = int(rng() % textureCount);
                if (std::find(reads.begin(), reads.end(), t) != reads.end() || t == colour ||
                    t == depth)
                    continue;
                const bool isDepth = gdi::isDepthFormat(g.texture(tex[t]).desc.format);
                if (isDepth && depth < 0 && rng() % 2)
                    depth = t;
                else if (!isDepth && colour < 0)
                    colour = t;
            }
            const bool last = p == passCount - 1;
            g.addPass(
                "p" + std::to_string(p),
                [&](graph::PassBuilder& b) {
                    for (int r : reads) b.sample(tex[r]);
                    if (colour >= 0)
                        b.colorTarget(tex[colour],
                                      written[colour] && rng() % 2 ? LoadOp::Load : LoadOp::Clear);
                    if (depth >= 0)
                        b.depthTarget(tex[depth],
                                      written[depth] && rng() % 2 ? LoadOp::Load : LoadOp::Clear);
                    if (last || rng() % 4 == 0) b.colorTarget(out, LoadOp::Load);
                },
                {});
            if (colour >= 0) written[colour] = true;
            if (depth >= 0) written[depth] = true;
        }
        g.markOutput(out);
        for (auto mode : {graph::AliasingMode::Memory, graph::AliasingMode::ObjectReuse}) {
            graph::CompileOptions options{.aliasing = mode};
            // Unusual sizes and alignments, as real drivers report them.
            options.requirements = [](const gdi::TextureDesc& d) {
                const uint64_t bytes =
                    uint64_t(d.width) * d.height * gdi::formatInfo(d.format).bytesPerPixel;
                return gdi::MemoryRequirements{bytes + 96,
                                               gdi::isDepthFormat(d.format) ? 4096u : 512u};
            };
            g.compile(options);
            const auto& ts = g.textures();
            uint64_t heapEnd = 0;
            for (size_t i = 0; i < ts.size(); ++i) {
                if (ts[i].imported || !ts[i].used()) continue;
                heapEnd = std::max(heapEnd, ts[i].offset + ts[i].size);
                if (mode == graph::AliasingMode::Memory) {
                    EXPECT_EQ(ts[i].offset % ts[i].alignment, 0u);
                }
                for (size_t j = i + 1; j < ts.size(); ++j) {
                    if (ts[j].imported || !ts[j].used()) continue;
                    const bool shareBytes = ts[i].offset < ts[j].offset + ts[j].size &&
                                            ts[j].offset < ts[i].offset + ts[i].size;
                    const bool shareObject = ts[i].physical == ts[j].physical;
                    if (mode == graph::AliasingMode::Memory ? shareBytes : shareObject) {
                        ++sharedSomewhere;
                        ASSERT_FALSE(ts[i].overlaps(ts[j]))
                            << "iteration " << iteration << ": " << ts[i].name << " and "
                            << ts[j].name << " are both live in passes "
                            << std::max(ts[i].firstPass, ts[j].firstPass) << ".."
                            << std::min(ts[i].lastPass, ts[j].lastPass) << " yet share memory\n"
                            << g.toDot();
                        if (mode == graph::AliasingMode::ObjectReuse) {
                            EXPECT_EQ(ts[i].desc.format, ts[j].desc.format);
                            EXPECT_EQ(ts[i].desc.usage,
                                      ts[j].desc.usage);  // the shared object has every usage
                        }
                    }
                }
            }
            EXPECT_LE(g.memory().withAliasing, g.memory().withoutAliasing);
            if (mode == graph::AliasingMode::Memory) {
                EXPECT_EQ(g.memory().withAliasing, heapEnd);
            }
        }
    }
    EXPECT_GT(sharedSomewhere, 100);  // the property was exercised, not vacuously true
}

TEST(RenderGraph, BarriersFollowStateChanges) {
    RenderGraph g;
    auto gb = g.createTexture("gbuffer", {.width = 8, .height = 8});
    auto depth = g.createTexture("depth", {.format = Format::D32F, .width = 8, .height = 8});
    auto out = g.importTexture("out", gdi::TextureHandle{1},
                               {.format = Format::RGBA8, .width = 8, .height = 8});
    g.addPass("geometry",
              [&](auto& b) {
                  b.colorTarget(gb);
                  b.depthTarget(depth);
              },
              {});
    g.addPass("lighting",
              [&](auto& b) {
                  b.sample(gb);
                  b.sample(depth);
                  b.colorTarget(out);
              },
              {});
    g.addPass("transparent",
              [&](auto& b) {
                  b.colorTarget(out, LoadOp::Load);
                  b.depthTarget(depth, LoadOp::Load);
              },
              {});
    g.markOutput(out);
    g.compile(graph::CompileOptions{});
    auto has = [&](size_t pass, TextureId t, ResourceState before, ResourceState after) {
        for (const auto& b : g.passes()[pass].barriers)
            if (b.texture == t && b.before == before && b.after == after) return true;
        return false;
    };
    EXPECT_TRUE(has(0, gb, ResourceState::Undefined, ResourceState::RenderTarget));
    EXPECT_TRUE(has(0, depth, ResourceState::Undefined, ResourceState::DepthTarget));
    EXPECT_TRUE(has(1, gb, ResourceState::RenderTarget, ResourceState::ShaderRead));
    EXPECT_TRUE(has(1, depth, ResourceState::DepthTarget, ResourceState::ShaderRead));
    EXPECT_EQ(g.passes()[1].barriers.size(), 2u);  // the imported output's first use needs none
    EXPECT_TRUE(has(2, depth, ResourceState::ShaderRead, ResourceState::DepthTarget));
    EXPECT_TRUE(has(2, out, ResourceState::RenderTarget,
                    ResourceState::RenderTarget));  // write after write
    const std::string dot = g.toDot();
    EXPECT_NE(dot.find("digraph RenderGraph"), std::string::npos);
    EXPECT_NE(dot.find("1: lighting"), std::string::npos);
    EXPECT_NE(dot.find("depth: ShaderRead -> DepthTarget"), std::string::npos);
}

// Buffers: a read waits for the last write once per kind of read; a write waits for the last
// write and every read since; an imported buffer's first use waits for nothing.
TEST(RenderGraph, BufferBarriersOrderWritesAndReads) {
    using A = gdi::BufferAccess;
    RenderGraph g;
    auto out = importFake(g);
    auto args = g.importBuffer("args", gdi::BufferHandle{1}, 32);
    auto list = g.createBuffer("list", {.size = 256});
    g.addPass("reset", [&](auto& b) { b.buffer(args, A::CopyDst); }, {});
    g.addPass("simulate",
              [&](auto& b) {
                  b.buffer(args, A::StorageRead | A::StorageWrite);
                  b.buffer(list, A::StorageWrite);
              },
              {});
    auto sorted = g.createBuffer("sorted", {.size = 256});
    g.addPass("sort",
              [&](auto& b) {
                  b.buffer(list, A::StorageRead);
                  b.buffer(args, A::StorageRead);
                  b.buffer(sorted, A::StorageWrite);
              },
              {});
    g.addPass("draw",
              [&](auto& b) {
                  b.buffer(args, A::Indirect);
                  b.buffer(list, A::StorageRead);
                  b.buffer(sorted, A::StorageRead);
                  b.colorTarget(out);
              },
              {});
    g.addPass("rewrite",
              [&](auto& b) {
                  b.buffer(list, A::StorageWrite);
                  b.colorTarget(out, LoadOp::Load);
              },
              {});
    g.addPass("draw again",
              [&](auto& b) {
                  b.buffer(list, A::Vertex);
                  b.colorTarget(out, LoadOp::Load);
              },
              {});
    g.markOutput(out);
    g.compile(graph::CompileOptions{});
    using Planned = std::vector<std::tuple<uint32_t, A, A>>;
    auto planned = [&](size_t pass) {
        Planned v;
        for (const auto& b : g.passes()[pass].bufferBarriers)
            v.emplace_back(b.buffer.index, b.before, b.after);
        return v;
    };
    EXPECT_EQ(planned(0), Planned{});
    EXPECT_EQ(planned(1), (Planned{{args.index, A::CopyDst, A::StorageRead | A::StorageWrite}}));
    EXPECT_EQ(planned(2), (Planned{{list.index, A::StorageWrite, A::StorageRead},
                                   {args.index, A::StorageWrite, A::StorageRead}}));
    // The list is already visible to storage reads; the sorted list is not.
    EXPECT_EQ(planned(3), (Planned{{args.index, A::StorageWrite, A::Indirect},
                                   {sorted.index, A::StorageWrite, A::StorageRead}}));
    EXPECT_EQ(planned(4),
              (Planned{{list.index, A::StorageWrite | A::StorageRead, A::StorageWrite}}));
    EXPECT_EQ(planned(5), (Planned{{list.index, A::StorageWrite, A::Vertex}}));
    // A transient buffer gets the usages its passes need.
    EXPECT_EQ(g.buffer(list).usage, gdi::BufferUsage::Storage | gdi::BufferUsage::Vertex);
    EXPECT_EQ(g.buffer(list).firstPass, 1);
    EXPECT_EQ(g.buffer(list).lastPass, 5);
    const std::string dot = g.toDot();
    EXPECT_NE(dot.find("shape=cylinder, label=\"list\\nbuffer 256 B\""), std::string::npos) << dot;
}

// A pass that writes only a buffer survives when a surviving pass reads it or the buffer is an
// output (read after the frame), and is culled otherwise.
TEST(RenderGraph, BufferWritersSurviveOnlyWhenRead) {
    using A = gdi::BufferAccess;
    RenderGraph g;
    auto out = importFake(g);
    auto counts = g.importBuffer("counts", gdi::BufferHandle{1}, 16);
    auto lists = g.createBuffer("lists", {.size = 64});
    auto unread = g.createBuffer("unread", {.size = 64});
    g.addPass("count", [&](auto& b) { b.buffer(counts, A::StorageWrite); }, {});
    g.addPass("build lists", [&](auto& b) { b.buffer(lists, A::StorageWrite); }, {});
    g.addPass("write unread", [&](auto& b) { b.buffer(unread, A::StorageWrite); }, {});
    g.addPass("shade",
              [&](auto& b) {
                  b.buffer(lists, A::StorageRead);
                  b.colorTarget(out);
              },
              {});
    g.markOutput(out);
    g.compile(graph::CompileOptions{});
    EXPECT_TRUE(culled(g, "count"));
    EXPECT_FALSE(culled(g, "build lists"));
    EXPECT_TRUE(culled(g, "write unread"));
    EXPECT_FALSE(g.buffer(unread).used());
    g.markOutput(counts);
    g.compile(graph::CompileOptions{});
    EXPECT_FALSE(culled(g, "count"));
}

TEST(RenderGraph, MalformedGraphsAreClearErrors) {
    auto expectError = [](const std::function<void(RenderGraph&, TextureId, TextureId)>& build,
                          const std::string& message) {
        RenderGraph g;
        auto a = g.createTexture("a", {.width = 8, .height = 8});
        auto out = g.importTexture("out", gdi::TextureHandle{1},
                                   {.format = Format::RGBA8, .width = 8, .height = 8});
        build(g, a, out);
        g.markOutput(out);
        try {
            g.compile(graph::CompileOptions{});
            ADD_FAILURE() << "no error, expected: " << message;
        } catch (const gdi::Error& e) {
            EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
        }
    };
    expectError(
        [](auto& g, auto a, auto out) {
            g.addPass("p",
                      [&](auto& b) {
                          b.sample(a);
                          b.colorTarget(out);
                      },
                      {});
        },
        "reads transient texture 'a' before any pass writes it");
    expectError(
        [](auto& g, auto a, auto out) {
            g.addPass("w", [&](auto& b) { b.colorTarget(a); }, {});
            g.addPass("p",
                      [&](auto& b) {
                          b.sample(a);
                          b.colorTarget(a, LoadOp::Load);
                          b.colorTarget(out);
                      },
                      {});
        },
        "uses texture 'a' twice");
    expectError(
        [](auto& g, auto, auto out) {
            auto big = g.createTexture("big", {.width = 16, .height = 16});
            g.addPass("p",
                      [&](auto& b) {
                          b.colorTarget(out);
                          b.colorTarget(big);
                      },
                      {});
        },
        "target 'big' is 16x16, the others 8x8");
    expectError(
        [](auto& g, auto a, auto) { g.addPass("p", [&](auto& b) { b.depthTarget(a); }, {}); },
        "cannot be a depth target");
    expectError([](auto& g, auto,
                   auto) { g.addPass("p", [&](auto& b) { b.colorTarget(TextureId{99}); }, {}); },
                "invalid texture id");
    expectError(
        [](auto& g, auto a, auto out) {
            auto ms = g.createTexture("ms", {.width = 8, .height = 8, .sampleCount = 4});
            g.addPass("p",
                      [&](auto& b) {
                          b.colorTarget(out);
                          b.resolve(ms, a);
                      },
                      {});
        },
        "resolves 'ms' into 'a': the source is not a target of this pass");
    expectError(
        [](auto& g, auto a, auto out) {
            g.addPass("p",
                      [&](auto& b) {
                          b.colorTarget(out);
                          b.resolve(out, a);
                      },
                      {});
        },
        "the source is single-sample");
    expectError(
        [](auto& g, auto, auto out) {
            auto buf = g.createBuffer("buf", {.size = 16});
            g.addPass("p",
                      [&](auto& b) {
                          b.buffer(buf, gdi::BufferAccess::StorageRead);
                          b.buffer(buf, gdi::BufferAccess::Indirect);
                          b.colorTarget(out);
                      },
                      {});
        },
        "declares buffer 'buf' twice");
    expectError(
        [](auto& g, auto, auto out) {
            g.addPass("p",
                      [&](auto& b) {
                          b.buffer(graph::BufferId{7}, gdi::BufferAccess::StorageRead);
                          b.colorTarget(out);
                      },
                      {});
        },
        "invalid buffer id");
    expectError(
        [](auto& g, auto, auto out) {
            auto buf = g.createBuffer("buf", {.size = 16});
            g.addPass("p",
                      [&](auto& b) {
                          b.buffer(buf, gdi::BufferAccess::None);
                          b.colorTarget(out);
                      },
                      {});
        },
        "uses buffer 'buf' with no access");
    RenderGraph g;
    EXPECT_THROW(g.createBuffer("empty", {.size = 0}), gdi::Error);
    EXPECT_THROW(g.importBuffer("null", gdi::BufferHandle{}, 16), gdi::Error);
    EXPECT_THROW(g.createTexture("zero", {.width = 0, .height = 8}), gdi::Error);
    EXPECT_THROW(g.createTexture("three samples", {.width = 8, .height = 8, .sampleCount = 3}),
                 gdi::Error);
}

// ---- on every backend: real textures, aliased memory, explicit barriers --------------------------

class RenderGraphOnDevice : public fe::testing::BackendTest {};

// makeA (red) -> aToB (copy by sampling) -> makeC (blue, aliasing A's memory) -> final (B + C).
// If C's memory overlapped B's, B would turn blue before "final" and the sum would be wrong.
TEST_P(RenderGraphOnDevice, AliasedTexturesKeepTheirContents) {
    gdi::Device& d = *device;
    using namespace gdi;
    auto vs = d.createShader(
        {.stage = ShaderStage::Vertex, .binary = shaders::find("conformance/fullscreen_ubo.vert")});
    auto fs = d.createShader(
        {.stage = ShaderStage::Fragment, .binary = shaders::find("conformance/textured.frag")});
    const float params[8] = {0, 0, 0, 0, 0.5f, 0, 0, 0};
    auto ubo = d.createBuffer({.size = sizeof(params), .usage = BufferUsage::Uniform},
                              gdi::bytesOf(params));
    auto sampler = d.createSampler({.minFilter = Filter::Nearest, .magFilter = Filter::Nearest});
    const std::vector<BindingSlot> slots = {
        {0, BindingType::UniformBuffer, ShaderStage::Vertex},
        {1, BindingType::SampledTexture, ShaderStage::Fragment}};
    auto copy = d.createGraphicsPipeline({.vertexShader = vs,
                                          .fragmentShader = fs,
                                          .colorFormats = {Format::RGBA16F},
                                          .bindings = slots});
    auto add = d.createGraphicsPipeline({.vertexShader = vs,
                                         .fragmentShader = fs,
                                         .blend = {{.enable = true,
                                                    .srcColor = BlendFactor::One,
                                                    .dstColor = BlendFactor::One,
                                                    .srcAlpha = BlendFactor::One,
                                                    .dstAlpha = BlendFactor::Zero}},
                                         .colorFormats = {Format::RGBA8},
                                         .bindings = slots});
    auto output = d.createTexture(kOutputDesc);

    for (bool aliasing : {true, false}) {
        RenderGraph g;
        auto a = g.createTexture("a", {.format = Format::RGBA16F, .width = 64, .height = 64});
        auto b2 = g.createTexture("b", {.format = Format::RGBA16F, .width = 64, .height = 64});
        auto c = g.createTexture("c", {.format = Format::RGBA16F, .width = 64, .height = 64});
        auto unused =
            g.createTexture("unused", {.format = Format::RGBA16F, .width = 64, .height = 64});
        auto out = g.importTexture("out", output, kOutputDesc);
        bool unusedRan = false;
        auto draw = [&](graph::PassContext& ctx, PipelineHandle p,
                        std::initializer_list<TextureId> inputs) {
            ctx.cmd.setPipeline(p);
            ctx.cmd.setUniformBuffer(0, ubo);
            for (TextureId t : inputs) {
                ctx.cmd.setTexture(1, ctx.texture(t), sampler);
                ctx.cmd.draw(3);
            }
        };
        g.addPass(
            "makeA",
            [&](auto& b) {
                b.colorTarget(a, LoadOp::Clear, {1, 0, 0, 1});
            },
            [&](graph::PassContext& ctx) {
                ctx.beginRenderPass();
                ctx.cmd.endRenderPass();
            });
        g.addPass(
            "aToB",
            [&](auto& b) {
                b.sample(a);
                b.colorTarget(b2);
            },
            [&](graph::PassContext& ctx) {
                ctx.beginRenderPass();
                draw(ctx, copy, {a});
                ctx.cmd.endRenderPass();
            });
        g.addPass(
            "makeC",
            [&](auto& b) {
                b.colorTarget(c, LoadOp::Clear, {0, 0, 1, 0});
            },
            [&](graph::PassContext& ctx) {
                ctx.beginRenderPass();
                ctx.cmd.endRenderPass();
            });
        g.addPass(
            "makeUnused", [&](auto& b) { b.colorTarget(unused); },
            [&](graph::PassContext&) { unusedRan = true; });
        g.addPass(
            "final",
            [&](auto& b) {
                b.sample(b2);
                b.sample(c);
                b.colorTarget(out);
            },
            [&](graph::PassContext& ctx) {
                ctx.beginRenderPass();
                draw(ctx, add, {b2, c});
                ctx.cmd.endRenderPass();
            });
        g.markOutput(out);
        g.compile(d, aliasing);
        if (aliasing) {
            EXPECT_LT(g.memory().withAliasing, g.memory().withoutAliasing) << g.toDot();
            EXPECT_EQ(g.aliasing(), d.info().features.memoryAliasing
                                        ? graph::AliasingMode::Memory
                                        : graph::AliasingMode::ObjectReuse);
        }
        EXPECT_THROW(g.handle(unused), gdi::Error);
        for (int frame = 0; frame < 2; ++frame) {  // the second frame reuses the aliased memory
            auto cmd = d.createCommandList();
            g.execute(*cmd);
            d.wait(d.submit(*cmd));
        }
        EXPECT_FALSE(unusedRan);
        Image img = d.readTexture(output);
        int wrong = 0;
        for (uint32_t y = 0; y < img.height; ++y)
            for (uint32_t x = 0; x < img.width; ++x) {
                auto t = img.texel(x, y);
                wrong += std::abs(t[0] - 1) > 0.01f || std::abs(t[1]) > 0.01f ||
                         std::abs(t[2] - 1) > 0.01f;
            }
        EXPECT_EQ(wrong, 0) << "aliasing " << aliasing;
        if (d.info().features.timestamps) {
            auto timings = g.passTimings();
            ASSERT_EQ(timings.size(), 4u);  // the culled pass is not timed
            EXPECT_EQ(timings[0].name, "makeA");
        }
    }
    for (auto p : {copy, add}) d.destroy(p);
    d.destroy(output);
    d.destroy(sampler);
    d.destroy(ubo);
    d.destroy(vs);
    d.destroy(fs);
}

// Multisampled transients resolved at the end of their pass: "draw" renders a quad whose edge
// halves pixel column 31 into 4-sample colour and depth, resolves both; "show" samples the
// resolved colour into the output. The MS targets are transient, stored DontCare, and culled
// with their pass when nothing reads the resolve.
TEST_P(RenderGraphOnDevice, MultisampledTransientsAndResolves) {
    gdi::Device& d = *device;
    using namespace gdi;
    if (!(d.info().limits.colorSampleCounts & d.info().limits.depthSampleCounts & 4))
        GTEST_SKIP() << "no 4x MSAA";
    auto vsQuad = d.createShader({.stage = ShaderStage::Vertex,
                                  .binary = shaders::find("conformance/position3_color.vert")});
    auto fsColor = d.createShader(
        {.stage = ShaderStage::Fragment, .binary = shaders::find("conformance/color.frag")});
    auto vs = d.createShader(
        {.stage = ShaderStage::Vertex, .binary = shaders::find("conformance/fullscreen_ubo.vert")});
    auto fs = d.createShader(
        {.stage = ShaderStage::Fragment, .binary = shaders::find("conformance/textured.frag")});
    auto quadPipe = d.createGraphicsPipeline(
        {.vertexShader = vsQuad,
         .fragmentShader = fsColor,
         .vertexBuffers = {{.stride = 28,
                            .attributes = {{0, VertexFormat::Float3, 0},
                                           {1, VertexFormat::Float4, 12}}}},
         .multisample = {.sampleCount = 4},
         .depthStencil = {.depthTest = true, .depthWrite = true},
         .colorFormats = {Format::RGBA16F},
         .depthFormat = Format::D32F});
    const float e = 31.5f / 32.0f - 1.0f;
    const float quad[6][7] = {{-1, -1, 0.25f, 1, 1, 1, 1}, {e, -1, 0.25f, 1, 1, 1, 1},
                              {-1, 1, 0.25f, 1, 1, 1, 1},  {-1, 1, 0.25f, 1, 1, 1, 1},
                              {e, -1, 0.25f, 1, 1, 1, 1},  {e, 1, 0.25f, 1, 1, 1, 1}};
    auto vb = d.createBuffer({.size = sizeof quad, .usage = BufferUsage::Vertex}, bytesOf(quad));
    const float params[8] = {0, 0, 0, 0, 0.5f, 0, 0, 0};
    auto ubo =
        d.createBuffer({.size = sizeof(params), .usage = BufferUsage::Uniform}, bytesOf(params));
    auto sampler = d.createSampler({.minFilter = Filter::Nearest, .magFilter = Filter::Nearest});
    auto show = d.createGraphicsPipeline(
        {.vertexShader = vs,
         .fragmentShader = fs,
         .colorFormats = {Format::RGBA8},
         .bindings = {{0, BindingType::UniformBuffer, ShaderStage::Vertex},
                      {1, BindingType::SampledTexture, ShaderStage::Fragment}}});
    auto output = d.createTexture(kOutputDesc);
    RenderGraph g;
    auto msColor = g.createTexture(
        "ms colour", {.format = Format::RGBA16F, .width = 64, .height = 64, .sampleCount = 4});
    auto msDepth = g.createTexture(
        "ms depth", {.format = Format::D32F, .width = 64, .height = 64, .sampleCount = 4});
    auto color = g.createTexture("colour", {.format = Format::RGBA16F, .width = 64, .height = 64});
    auto depth = g.createTexture("depth", {.format = Format::D32F, .width = 64, .height = 64});
    auto out = g.importTexture("out", output, kOutputDesc);
    g.addPass(
        "draw",
        [&](auto& b) {
            b.colorTarget(msColor);
            b.depthTarget(msDepth);
            b.resolve(msColor, color);
            b.resolve(msDepth, depth);
        },
        [&](graph::PassContext& ctx) {
            ctx.beginRenderPass();
            ctx.cmd.setPipeline(quadPipe);
            ctx.cmd.setVertexBuffer(0, vb);
            ctx.cmd.draw(6);
            ctx.cmd.endRenderPass();
        });
    g.addPass(
        "show",
        [&](auto& b) {
            b.sample(color);
            b.colorTarget(out);
        },
        [&](graph::PassContext& ctx) {
            ctx.beginRenderPass();
            ctx.cmd.setPipeline(show);
            ctx.cmd.setUniformBuffer(0, ubo);
            ctx.cmd.setTexture(1, ctx.texture(color), sampler);
            ctx.cmd.draw(3);
            ctx.cmd.endRenderPass();
        });
    g.markOutput(out);
    g.compile(d, true);
    EXPECT_EQ(g.texture(msColor).desc.sampleCount, 4u);
    EXPECT_TRUE(g.texture(depth).used());  // written by the resolve even though nothing samples it
    // The multisampled targets live inside the pass (resolved, never stored): Transient; the
    // resolve targets and the sampled colour are not.
    using U = TextureUsage;
    EXPECT_EQ(g.texture(msColor).desc.usage, U::RenderTarget | U::Transient);
    EXPECT_EQ(g.texture(msDepth).desc.usage, U::RenderTarget | U::Transient);
    EXPECT_FALSE(any(g.texture(color).desc.usage, U::Transient));
    EXPECT_FALSE(any(g.texture(depth).desc.usage, U::Transient));
    auto cmd = d.createCommandList();
    g.execute(*cmd);
    d.wait(d.submit(*cmd));
    Image img = d.readTexture(output);
    for (uint32_t x : {0u, 30u, 31u, 32u, 63u}) {
        const float expected = x < 31 ? 1.0f : x == 31 ? 0.5f : 0.0f;
        EXPECT_NEAR(img.texel(x, 10)[0], expected, 1.0 / 255) << "column " << x;
    }
    for (auto p : {quadPipe, show}) d.destroy(p);
    for (auto s : {vsQuad, fsColor, vs, fs}) d.destroy(s);
    for (auto b : {vb, ubo}) d.destroy(b);
    d.destroy(sampler);
    d.destroy(output);
}

// A transient buffer between two copy passes, with the backend's automatic barriers off: the
// graph creates it with copy usages, orders the write before the read, and the bytes arrive.
namespace {
// The copy-chain tests' buffers: 64 known words in a source, and a result to copy them into.
struct CopyChain {
    explicit CopyChain(gdi::Device& device, uint32_t seed) : d(device), objects(device) {
        using gdi::BufferUsage;
        for (uint32_t i = 0; i < words.size(); ++i) words[i] = seed * (i + 1);
        src = objects.add(d.createBuffer(
            {.size = sizeof words, .usage = BufferUsage::CopySrc, .debugName = "source"},
            gdi::bytesOf(words)));
        dst = objects.add(d.createBuffer({.size = sizeof words,
                                          .usage = BufferUsage::CopyDst | BufferUsage::CopySrc,
                                          .debugName = "result"}));
    }
    // The pass copying the transient `mid` into the result (imported as `result`).
    void addDrain(RenderGraph& g, graph::BufferId mid, graph::BufferId result) const {
        g.addPass(
            "drain",
            [&](graph::PassBuilder& b) {
                b.buffer(mid, gdi::BufferAccess::CopySrc);
                b.buffer(result, gdi::BufferAccess::CopyDst);
            },
            [this, mid](graph::PassContext& pc) {
                pc.cmd.copyBuffer(dst, 0, pc.buffer(mid), 0, sizeof words);
            });
    }
    std::array<uint32_t, 64> result() const {
        const std::vector<uint8_t> bytes = d.readBuffer(dst, 0, sizeof words);
        std::array<uint32_t, 64> back{};
        std::memcpy(back.data(), bytes.data(), sizeof back);
        return back;
    }
    gdi::Device& d;
    gdi::DeviceObjects objects;
    std::array<uint32_t, 64> words{};
    gdi::BufferHandle src, dst;
};
}  // namespace

TEST_P(RenderGraphOnDevice, TransientBufferCarriesDataBetweenPasses) {
    using namespace gdi;
    using A = BufferAccess;
    Device& d = *device;
    CopyChain chain(d, 0x9e3779b9u);
    const auto& words = chain.words;
    const BufferHandle src = chain.src, dst = chain.dst;
    {
        RenderGraph g;
        auto in = g.importBuffer("source", src, sizeof words);
        auto mid = g.createBuffer("middle", {.size = sizeof words});
        auto result = g.importBuffer("result", dst, sizeof words);
        g.addPass(
            "fill",
            [&](auto& b) {
                b.buffer(in, A::CopySrc);
                b.buffer(mid, A::CopyDst);
            },
            [&](graph::PassContext& pc) {
                pc.cmd.copyBuffer(pc.buffer(mid), 0, src, 0, sizeof words);
            });
        chain.addDrain(g, mid, result);
        g.markOutput(result);
        g.compile(d);
        EXPECT_EQ(g.buffer(mid).usage, BufferUsage::CopySrc | BufferUsage::CopyDst);
        ASSERT_EQ(g.passes()[1].bufferBarriers.size(), 1u);
        auto cmd = d.createCommandList();
        g.execute(*cmd);
        d.wait(d.submit(*cmd));
    }
    EXPECT_EQ(chain.result(), words);
    EXPECT_EQ(d.validationErrorCount(), 0u);
}

// Async compute on a device: a copy chain on the compute queue (fill, then drain into the
// result after an unrelated graphics pass), recorded through CommandQueue: the frame is cut at
// the fork and the join, the graphics after the join waits for the compute list, and the bytes
// arrive with validation silent (on Vulkan the barriers of the compute list keep to its stages).
TEST_P(RenderGraphOnDevice, AsyncComputeRunsBesideGraphics) {
    using namespace gdi;
    using A = BufferAccess;
    Device& d = *device;
    CopyChain chain(d, 0x85ebca6bu);
    const auto& words = chain.words;
    const BufferHandle src = chain.src, dst = chain.dst;
    const TextureHandle target = chain.objects.add(
        d.createTexture({.width = 32,
                         .height = 32,
                         .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc,
                         .debugName = "beside"}));
    {
        render::CommandQueue queue(d, 2, 1024);
        RenderGraph g;
        auto in = g.importBuffer("source", src, sizeof words);
        auto mid = g.createBuffer("middle", {.size = sizeof words});
        auto result = g.importBuffer("result", dst, sizeof words);
        auto beside = g.importTexture("beside", target, d.desc(target));
        g.addPass(
            "fill",
            [&](auto& b) {
                b.buffer(in, A::CopySrc);
                b.buffer(mid, A::CopyDst);
                b.asyncCompute();
            },
            [&](graph::PassContext& pc) {
                EXPECT_EQ(pc.cmd.queue(), QueueKind::Compute);
                pc.cmd.copyBuffer(pc.buffer(mid), 0, src, 0, sizeof words);
            });
        g.addPass(
            "clear",
            [&](auto& b) {
                b.colorTarget(beside, LoadOp::Clear, {0, 1, 0, 1});
            },
            [&](graph::PassContext& pc) {
                EXPECT_EQ(pc.cmd.queue(), QueueKind::Graphics);
                pc.beginRenderPass();
                pc.cmd.endRenderPass();
            });
        chain.addDrain(g, mid, result);
        g.markOutput(result);
        g.markOutput(beside);
        g.compile(d);
        EXPECT_EQ(g.passes()[0].forkBefore, 0);
        EXPECT_EQ(g.passes()[0].joinBefore, 2);
        for (int frame = 0; frame < 3; ++frame) {  // the frame's lists are reused
            d.writeBuffer(dst, 0, bytesOf(std::array<uint32_t, 64>{}));
            queue.beginFrame();
            g.execute(queue);
            d.wait(queue.endFrame());
            EXPECT_EQ(chain.result(), words) << "frame " << frame;
            // The fork (before "fill": nothing before it), the compute list waiting for it, the
            // graphics beside it ("clear"), and the rest ("drain") waiting for the compute list.
            // A device with one queue runs them in order either way: these waits are what a
            // device with a compute family relies on.
            const auto& s = queue.submissions();
            ASSERT_EQ(s.size(), 4u) << "frame " << frame;
            EXPECT_EQ(s[0].queue, QueueKind::Graphics);
            EXPECT_EQ(s[1].queue, QueueKind::Compute);
            EXPECT_EQ(s[1].waitFor, s[0].fence);
            EXPECT_EQ(s[2].queue, QueueKind::Graphics);
            EXPECT_EQ(s[2].waitFor, 0u);
            EXPECT_EQ(s[3].queue, QueueKind::Graphics);
            EXPECT_EQ(s[3].waitFor, s[1].fence);
        }
        EXPECT_EQ(d.readTexture(target).texel(5, 5)[1], 1.0f);
    }
    EXPECT_EQ(d.validationErrorCount(), 0u);
}

FE_INSTANTIATE_FOR_EVERY_BACKEND(RenderGraphOnDevice);

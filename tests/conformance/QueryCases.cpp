// Conformance cases for queries: occlusion counts, pipeline statistics, timestamps in query
// sets, and the mistakes refused alike everywhere.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <unistd.h>

#include "CaseSupport.h"
#include "fe/gdi/CaptureStream.h"
#include "fe/gdi/CommandRecorder.h"
#include "fe/gdi/PipelineCacheFile.h"

namespace fe::conformance {

using namespace gdi;

namespace {

// Quads drawn with depth at one value: the viewport's depth range pins every fragment to it.
struct DepthQuads {
    DeviceObjects o;
    PipelineHandle pipeline;
    DepthQuads(Device& d, uint32_t samples) : o(d) {
        pipeline = o.add(d.createGraphicsPipeline(
            {.vertexShader =
                 registryShader(o, ShaderStage::Vertex, "conformance/constants_quad.vert"),
             .fragmentShader =
                 registryShader(o, ShaderStage::Fragment, "conformance/constants_quad.frag"),
             .topology = PrimitiveTopology::TriangleStrip,
             .multisample = {.sampleCount = samples},
             .depthStencil = {.depthTest = true,
                              .depthWrite = true,
                              .depthCompare = CompareOp::Less},
             .colorFormats = {Format::RGBA8},
             .depthFormat = Format::D32F,
             .debugName = "depth quads"}));
    }
    static void draw(CommandList& cmd, const QuadConstants& q, float depth) {
        cmd.setViewport({0, 0, float(kCaseSize), float(kCaseSize), depth, depth});
        cmd.setConstants(q);
        cmd.draw(4);
    }
};

// Occlusion queries count samples exactly: a visible 16x16 quad 256 x samples, a hidden one 0,
// one half behind an occluder 128 x samples; AnySamplesPassed gives 1 and 0. Results are read
// without blocking (not before the submission completes), resolved into a buffer on the GPU
// with the same values, and the queries are reused by a second submission.
std::vector<CaseImage> occlusionQuery(Device& d) {
    const uint32_t sampleCounts =
        d.info().limits.colorSampleCounts & d.info().limits.depthSampleCounts;
    for (uint32_t samples : {1u, 4u}) {
        if (!(sampleCounts & samples)) continue;
        DepthQuads quads(d, samples);
        DeviceObjects& o = quads.o;
        const TextureHandle color = o.add(d.createTexture({.width = kCaseSize,
                                                           .height = kCaseSize,
                                                           .sampleCount = samples,
                                                           .usage = TextureUsage::RenderTarget}));
        const TextureHandle depth = o.add(d.createTexture({.format = Format::D32F,
                                                           .width = kCaseSize,
                                                           .height = kCaseSize,
                                                           .sampleCount = samples,
                                                           .usage = TextureUsage::RenderTarget}));
        const QuerySetHandle occlusion = o.add(
            d.createQuerySet({.type = QueryType::Occlusion, .count = 3, .debugName = "occlusion"}));
        const QuerySetHandle any = o.add(d.createQuerySet(
            {.type = QueryType::AnySamplesPassed, .count = 2, .debugName = "any"}));
        const BufferHandle resolved = o.add(
            d.createBuffer({.size = 40, .usage = BufferUsage::CopyDst | BufferUsage::CopySrc}));
        const std::array<uint64_t, 3> expected = {256ull * samples, 0, 128ull * samples};
        for (int frame = 0; frame < 2; ++frame) {
            auto cmd = d.createCommandList();
            cmd->beginRenderPass({.colors = {{.texture = color}},
                                  .depth = {.texture = depth},
                                  .debugName = "occlusion"});
            cmd->setPipeline(quads.pipeline);
            DepthQuads::draw(*cmd, pixelQuad(32, 0, 64, 64),
                             0.2f);  // the occluder: the right half, near
            cmd->beginQuery(occlusion, 0);
            DepthQuads::draw(*cmd, pixelQuad(0, 0, 16, 16), 0.5f);  // in front of nothing
            cmd->endQuery(occlusion, 0);
            cmd->beginQuery(occlusion, 1);
            DepthQuads::draw(*cmd, pixelQuad(40, 40, 56, 56), 0.6f);  // wholly behind the occluder
            cmd->endQuery(occlusion, 1);
            cmd->beginQuery(any, 1);
            DepthQuads::draw(*cmd, pixelQuad(40, 40, 56, 56), 0.7f);
            cmd->endQuery(any, 1);
            cmd->beginQuery(occlusion, 2);
            DepthQuads::draw(*cmd, pixelQuad(24, 24, 40, 40),
                             0.5f);  // its right half behind the occluder
            cmd->endQuery(occlusion, 2);
            cmd->beginQuery(any, 0);
            DepthQuads::draw(*cmd, pixelQuad(24, 0, 40, 8), 0.5f);
            cmd->endQuery(any, 0);
            cmd->endRenderPass();
            cmd->resolveQueries(occlusion, 0, 3, resolved, 0);
            cmd->resolveQueries(any, 0, 2, resolved, 24);
            std::array<uint64_t, 3> counts{};
            const FenceValue fence = d.submit(*cmd);
            d.wait(fence);
            FE_CONFORMANCE_CHECK(d.queryResults(occlusion, 0, 3, counts),
                                 "results are available once the submission completed");
            for (size_t i = 0; i < 3; ++i)
                FE_CONFORMANCE_CHECK(counts[i] == expected[i],
                                     ("occlusion query " + std::to_string(i) + " counts " +
                                      std::to_string(counts[i]) + " samples, expected " +
                                      std::to_string(expected[i]))
                                         .c_str());
            std::array<uint64_t, 2> anyPassed{};
            FE_CONFORMANCE_CHECK(d.queryResults(any, 0, 2, anyPassed),
                                 "binary results are available");
            FE_CONFORMANCE_CHECK(anyPassed[0] == 1 && anyPassed[1] == 0,
                                 "AnySamplesPassed: 1 for a visible quad, 0 hidden");
            std::array<uint64_t, 5> gpu{};
            const std::vector<uint8_t> bytes = d.readBuffer(resolved, 0, 40);
            std::memcpy(gpu.data(), bytes.data(), 40);
            FE_CONFORMANCE_CHECK(gpu[0] == expected[0] && gpu[1] == 0 && gpu[2] == expected[2],
                                 "resolveQueries writes the same counts into the buffer");
            FE_CONFORMANCE_CHECK(gpu[3] != 0 && gpu[4] == 0,
                                 "resolved AnySamplesPassed: non-zero, then 0");
        }
    }
    return {};
}

// Pipeline statistics: a strip of 4 vertices is 2 primitives and at least 4 vertex shader runs
// (at most 4: no vertex is shaded twice here), a 16x16 quad at least 256 fragment shader runs
// (helper invocations may add a few); a dispatch of 3 groups of 8 is 24 compute invocations,
// and each query counts only its own stages.
std::vector<CaseImage> pipelineStatistics(Device& d) {
    if (!d.info().features.pipelineStatistics) {
        FE_CONFORMANCE_CHECK(
            throws([&] { d.destroy(d.createQuerySet({.type = QueryType::PipelineStatistics})); }),
            "without DeviceFeatures::pipelineStatistics the set is refused");
        return {};
    }
    DeviceObjects o(d);
    const PipelineHandle quad = o.add(d.createGraphicsPipeline(
        {.vertexShader = registryShader(o, ShaderStage::Vertex, "conformance/constants_quad.vert"),
         .fragmentShader =
             registryShader(o, ShaderStage::Fragment, "conformance/constants_quad.frag"),
         .topology = PrimitiveTopology::TriangleStrip,
         .colorFormats = {Format::RGBA8},
         .debugName = "statistics quad"}));
    const PipelineHandle copy = o.add(
        d.createComputePipeline({.computeShader = registryShader(o, ShaderStage::Compute,
                                                                 "conformance/constants_copy.comp"),
                                 .debugName = "statistics compute"}));
    const BufferHandle out =
        o.add(d.createBuffer({.size = 3 * kMaxConstantBytes, .usage = BufferUsage::Storage}));
    const BufferHandle resolved =
        o.add(d.createBuffer({.size = 64, .usage = BufferUsage::CopyDst | BufferUsage::CopySrc}));
    const QuerySetHandle stats = o.add(d.createQuerySet(
        {.type = QueryType::PipelineStatistics, .count = 2, .debugName = "stats"}));
    const TextureHandle target = caseTarget(o);
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = target}}});
    cmd->setPipeline(quad);
    cmd->beginQuery(stats, 0);
    cmd->setConstants(pixelQuad(8, 8, 24, 24));
    cmd->draw(4);
    cmd->endQuery(stats, 0);
    cmd->endRenderPass();
    cmd->beginQuery(stats, 1);
    cmd->setPipeline(copy);
    cmd->setStorageBuffer(0, out);
    cmd->dispatch(3);
    cmd->endQuery(stats, 1);
    cmd->resolveQueries(stats, 0, 2, resolved, 0);
    d.wait(d.submit(*cmd));
    std::array<PipelineStatistics, 2> s{};
    FE_CONFORMANCE_CHECK(d.queryResults(stats, 0, 2, std::span(&s[0].primitives, 8)),
                         "statistics are available");
    const std::string got = "primitives " + std::to_string(s[0].primitives) + ", vertex " +
                            std::to_string(s[0].vertexInvocations) + ", fragment " +
                            std::to_string(s[0].fragmentInvocations) + ", compute " +
                            std::to_string(s[0].computeInvocations) + " / " +
                            std::to_string(s[1].computeInvocations);
    FE_CONFORMANCE_CHECK(s[0].primitives == 2,
                         ("a strip of 4 vertices is 2 primitives: " + got).c_str());
    FE_CONFORMANCE_CHECK(s[0].vertexInvocations == 4,
                         ("4 vertex shader invocations: " + got).c_str());
    FE_CONFORMANCE_CHECK(s[0].fragmentInvocations >= 256 && s[0].fragmentInvocations <= 2 * 256,
                         ("256 pixels: 256 to 512 fragment invocations: " + got).c_str());
    FE_CONFORMANCE_CHECK(
        s[0].computeInvocations == 0 && s[1].computeInvocations == 24,
        ("compute invocations: 0 in the draw's query, 24 in the dispatch's: " + got).c_str());
    FE_CONFORMANCE_CHECK(
        s[1].primitives == 0 && s[1].vertexInvocations == 0 && s[1].fragmentInvocations == 0,
        ("the dispatch's query counts no graphics work: " + got).c_str());
    std::array<PipelineStatistics, 2> gpu{};
    const std::vector<uint8_t> bytes = d.readBuffer(resolved, 0, 64);
    std::memcpy(gpu.data(), bytes.data(), 64);
    FE_CONFORMANCE_CHECK(std::memcmp(gpu.data(), s.data(), 64) == 0,
                         "resolveQueries writes the same statistics");
    return {};
}

// Timestamps in a query set: increasing along the recording, in nanoseconds from queryResults
// and in timestampPeriodNs units from resolveQueries, never available before submission.
std::vector<CaseImage> timestampsInQuerySet(Device& d) {
    if (!d.info().features.timestamps) return {};
    DeviceObjects o(d);
    const QuerySetHandle times =
        o.add(d.createQuerySet({.type = QueryType::Timestamp, .count = 3, .debugName = "times"}));
    const BufferHandle resolved =
        o.add(d.createBuffer({.size = 24, .usage = BufferUsage::CopyDst | BufferUsage::CopySrc}));
    const PipelineHandle copy = o.add(
        d.createComputePipeline({.computeShader = registryShader(
                                     o, ShaderStage::Compute, "conformance/constants_copy.comp")}));
    const BufferHandle out =
        o.add(d.createBuffer({.size = kMaxConstantBytes, .usage = BufferUsage::Storage}));
    const TextureHandle target = caseTarget(o);
    std::array<uint64_t, 3> t{};
    FE_CONFORMANCE_CHECK(!d.queryResults(times, 0, 3, t),
                         "no results before the queries are submitted");
    auto cmd = d.createCommandList();
    cmd->writeTimestamp(times, 0);
    cmd->beginRenderPass({.colors = {{.texture = target}}});
    cmd->endRenderPass();
    cmd->writeTimestamp(times, 1);
    cmd->setPipeline(copy);
    cmd->setStorageBuffer(0, out);
    cmd->dispatch(1);
    cmd->writeTimestamp(times, 2);
    cmd->resolveQueries(times, 0, 3, resolved, 0);
    d.wait(d.submit(*cmd));
    FE_CONFORMANCE_CHECK(d.queryResults(times, 0, 3, t), "timestamps are available after the wait");
    FE_CONFORMANCE_CHECK(t[0] <= t[1] && t[1] <= t[2], "timestamps increase along the recording");
    FE_CONFORMANCE_CHECK(t[2] - t[0] < 10'000'000'000ull, "the three timestamps lie within 10 s");
    std::array<uint64_t, 3> raw{};
    const std::vector<uint8_t> bytes = d.readBuffer(resolved, 0, 24);
    std::memcpy(raw.data(), bytes.data(), 24);
    const double period = d.info().limits.timestampPeriodNs;
    for (size_t i = 0; i < 3; ++i)
        FE_CONFORMANCE_CHECK(
            std::abs(double(raw[i]) * period - double(t[i])) <= 1.0 + 1e-9 * double(t[i]),
            "resolved timestamps times timestampPeriodNs are queryResults' nanoseconds");
    return {};
}

// Results read in later lists and submissions: a query written in one submission and resolved
// in the next, one written by a list and resolved by a later list of the same submission, and
// one written again by a later submission (the resolve after it reads the new count). A resolve
// that would wait for a write that never comes, or that the submission's reset would erase, is
// an Error at submit (or at the write), the same on every backend.
std::vector<CaseImage> queriesAcrossLists(Device& d) {
    DepthQuads quads(d, 1);
    DeviceObjects& o = quads.o;
    const TextureHandle color = caseTarget(o);
    const TextureHandle depth = o.add(d.createTexture({.format = Format::D32F,
                                                       .width = kCaseSize,
                                                       .height = kCaseSize,
                                                       .usage = TextureUsage::RenderTarget}));
    const QuerySetHandle occlusion =
        o.add(d.createQuerySet({.type = QueryType::Occlusion, .count = 4, .debugName = "occ"}));
    const BufferHandle resolved =
        o.add(d.createBuffer({.size = 32, .usage = BufferUsage::CopyDst | BufferUsage::CopySrc}));
    auto counted = [&](uint32_t query, uint32_t w, uint32_t h) {
        auto cmd = d.createCommandList();
        cmd->beginRenderPass({.colors = {{.texture = color}}, .depth = {.texture = depth}});
        cmd->setPipeline(quads.pipeline);
        cmd->beginQuery(occlusion, query);
        DepthQuads::draw(*cmd, pixelQuad(0, 0, w, h), 0.5f);
        cmd->endQuery(occlusion, query);
        cmd->endRenderPass();
        return cmd;
    };
    auto resolving = [&](uint32_t query) {
        auto cmd = d.createCommandList();
        cmd->resolveQueries(occlusion, query, 1, resolved, 8 * query);
        return cmd;
    };
    auto values = [&] {
        std::array<uint64_t, 4> v{};
        std::memcpy(v.data(), d.readBuffer(resolved, 0, 32).data(), 32);
        return v;
    };
    d.wait(d.submit(*counted(0, 16, 16)));
    d.wait(d.submit(*resolving(0)));  // a later submission
    {
        auto writer = counted(1, 8, 4), reader = resolving(1);
        std::array<CommandList*, 2> lists = {writer.get(), reader.get()};
        d.wait(d.submit(lists));  // a later list of one submission
    }
    std::array<uint64_t, 4> v = values();
    FE_CONFORMANCE_CHECK(v[0] == 256, "a query written by an earlier submission resolves");
    FE_CONFORMANCE_CHECK(v[1] == 32, "a query written by an earlier list of the submission");
    {
        auto writer = counted(0, 4, 4), reader = resolving(0);
        std::array<CommandList*, 2> lists = {writer.get(), reader.get()};
        d.wait(d.submit(lists));
    }
    v = values();
    FE_CONFORMANCE_CHECK(v[0] == 16, "written again, the later resolve reads the new count");

    auto reader = resolving(2), writer = counted(2, 2, 2);
    std::array<CommandList*, 2> wrongOrder = {reader.get(), writer.get()};
    expectError([&] { d.submit(wrongOrder); },
                "list 0 resolves query 2 before a later list of this submission writes it");
    std::array<CommandList*, 2> rightOrder = {writer.get(), reader.get()};
    d.wait(d.submit(rightOrder));
    FE_CONFORMANCE_CHECK(values()[2] == 4, "the same lists in writing order");
    auto never = resolving(3);
    expectError([&] { d.submit(*never); },
                "list 0 resolves query 3 that no earlier list or submission has written");
    auto resolveThenWrite = resolving(0);
    resolveThenWrite->beginRenderPass({.colors = {{.texture = color}}});
    expectError([&] { resolveThenWrite->beginQuery(occlusion, 0); },
                "query 0 of set 'occ' was resolved earlier in this recording");
    resolveThenWrite->endRenderPass();
    d.wait(d.submit(*resolveThenWrite));
    FE_CONFORMANCE_CHECK(values()[0] == 16, "a resolve alone reads the last submitted count");
    return {};
}

// Mistakes with queries, refused while recording with the same message everywhere.
std::vector<CaseImage> queryErrors(Device& d) {
    DeviceObjects o(d);
    const QuerySetHandle occlusion =
        o.add(d.createQuerySet({.type = QueryType::Occlusion, .count = 2, .debugName = "occ"}));
    const TextureHandle target = caseTarget(o);
    const BufferHandle noCopy = o.add(d.createBuffer({.size = 64, .usage = BufferUsage::Storage}));
    expectError([&] { d.createQuerySet({.count = 0, .debugName = "none"}); },
                "count 0 is out of range (1..4096)");
    auto cmd = d.createCommandList();
    expectError([&] { cmd->beginQuery(occlusion, 0); },
                "Occlusion queries begin and end inside a render pass");
    cmd->beginRenderPass({.colors = {{.texture = target}}});
    expectError([&] { cmd->beginQuery(occlusion, 2); },
                "query 2 of set 'occ' is out of range (the set has 2)");
    cmd->beginQuery(occlusion, 0);
    expectError([&] { cmd->beginQuery(occlusion, 1); }, "a Occlusion query is already active (0)");
    expectError([&] { cmd->endQuery(occlusion, 1); }, "query 1 of set 'occ' is not active");
    expectError([&] { cmd->endRenderPass(); }, "query 0 begun in the pass is still active");
    cmd->endQuery(occlusion, 0);
    expectError([&] { cmd->beginQuery(occlusion, 0); },
                "query 0 of set 'occ' is already written in this recording");
    cmd->endRenderPass();
    expectError([&] { cmd->resolveQueries(occlusion, 0, 1, noCopy, 0); },
                "the buffer has no CopyDst usage");
    expectError([&] { cmd->writeTimestamp(occlusion, 1); }, "set 'occ' is not a Timestamp set");
    auto other = d.createCommandList();
    other->beginRenderPass({.colors = {{.texture = target}}});
    other->beginQuery(occlusion, 0);
    other->endQuery(occlusion, 0);
    other->endRenderPass();
    std::array<CommandList*, 2> both = {cmd.get(), other.get()};
    expectError([&] { d.submit(both); }, "is written by two lists of this submission");
    d.wait(d.submit(*cmd));
    d.wait(d.submit(*other));
    return {};
}

}  // namespace

std::vector<Case> queryCases() {
    return {
        {"occlusion_query", occlusionQuery},
        {"pipeline_statistics", pipelineStatistics},
        {"timestamps_in_query_set", timestampsInQuerySet},
        {"query_errors", queryErrors},
        {"queries_across_lists", queriesAcrossLists},
    };
}

}  // namespace fe::conformance

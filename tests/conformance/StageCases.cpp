// Conformance cases for the optional graphics stages (Device.h, ShaderStage): a geometry shader
// that turns points into squares, and tessellation control + evaluation shaders that cut a quad
// patch 4 x 4, each drawn the same on every backend. Then the mistakes a pipeline with these
// stages can make, each the same gdi::Error everywhere, before any native call.
#include <cmath>

#include "CaseSupport.h"
#include "fe/gdi/ShaderRegistry.h"

namespace fe::conformance {

using namespace gdi;

namespace {

struct ColoredPoint {
    float x, y;
    float r, g, b, a;
};

// Four points at the centres of the quadrants' 16x16 squares (pixel 16 or 48 on each axis); the
// geometry shader makes each a square [c - 8, c + 8) in its colour, blue = its index / 4.
std::vector<CaseImage> geometryStage(Device& d) {
    DeviceObjects o(d);
    if (!d.info().features.geometryShaders) {
        FE_CONFORMANCE_CHECK(
            throws([&] {
                o.add(d.createGraphicsPipeline(
                    {.vertexShader =
                         registryShader(o, ShaderStage::Vertex, "conformance/points_color.vert"),
                     .fragmentShader =
                         registryShader(o, ShaderStage::Fragment, "conformance/color.frag"),
                     .geometryShader =
                         registryShader(o, ShaderStage::Geometry, "conformance/point_quads.geom"),
                     .colorFormats = {Format::RGBA8}}));
            }),
            "without DeviceFeatures::geometryShaders a geometry shader is refused");
        return {};
    }
    const ShaderHandle vs = registryShader(o, ShaderStage::Vertex, "conformance/points_color.vert"),
                       gs =
                           registryShader(o, ShaderStage::Geometry, "conformance/point_quads.geom"),
                       fs = registryShader(o, ShaderStage::Fragment, "conformance/color.frag");
    const VertexBufferLayout layout{
        .stride = sizeof(ColoredPoint),
        .attributes = {{0, VertexFormat::Float2, 0}, {1, VertexFormat::Float4, 8}}};
    const PipelineHandle squares =
        o.add(d.createGraphicsPipeline({.vertexShader = vs,
                                        .fragmentShader = fs,
                                        .geometryShader = gs,
                                        .vertexBuffers = {layout},
                                        .topology = PrimitiveTopology::PointList,
                                        .colorFormats = {Format::RGBA8},
                                        .debugName = "point squares"}));
    const ColoredPoint points[4] = {{-0.5f, -0.5f, 1, 0, 0, 1},
                                    {0.5f, -0.5f, 0, 1, 0, 1},
                                    {-0.5f, 0.5f, 1, 1, 0, 1},
                                    {0.5f, 0.5f, 0, 1, 1, 1}};
    const BufferHandle vb = o.add(
        d.createBuffer({.size = sizeof points, .usage = BufferUsage::Vertex}, bytesOf(points)));
    const TextureHandle t = caseTarget(o);
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = t, .clear = {0, 0, 0, 1}}}});
    cmd->setPipeline(squares);
    cmd->setVertexBuffer(0, vb);
    cmd->draw(4);
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
    const Image expected = expectImage(Format::RGBA8, [&](uint32_t x, uint32_t y) -> Texel {
        const uint32_t qx = x / 32, qy = y / 32;  // the quadrant
        const uint32_t cx = 16 + 32 * qx, cy = 16 + 32 * qy;
        if (x < cx - 8 || x >= cx + 8 || y < cy - 8 || y >= cy + 8) return {0, 0, 0, 1};
        const ColoredPoint& p = points[qy * 2 + qx];
        return {p.r, p.g, 0.25f * float(qy * 2 + qx), 1};
    });
    std::vector<CaseImage> out;
    out.push_back(drawn8("points_become_squares", d.readTexture(t), expected));

    const std::string name = "stage errors";
    expectError(
        [&] {
            o.add(d.createGraphicsPipeline({.vertexShader = vs,
                                            .fragmentShader = fs,
                                            .geometryShader = vs,
                                            .vertexBuffers = {layout},
                                            .colorFormats = {Format::RGBA8},
                                            .debugName = name.c_str()}));
        },
        "pipeline 'stage errors': geometryShader is not a geometry shader (it is a vertex shader)");
    const ShaderHandle valueFs = registryShader(o, ShaderStage::Fragment, "conformance/value.frag");
    expectError(
        [&] {
            o.add(d.createGraphicsPipeline({.vertexShader = vs,
                                            .fragmentShader = valueFs,
                                            .geometryShader = gs,
                                            .vertexBuffers = {layout},
                                            .colorFormats = {Format::RGBA8},
                                            .debugName = name.c_str()}));
        },
        "pipeline 'stage errors': fragment shader input 'vValue' (location 0) is float x4, the "
        "geometry shader writes 'gColor' there as float x3");
    return out;
}

// Red u^2 interpolated linearly between the tessellated columns u = 0, 1/4, ... 1: the colour a
// pixel of the 4 x 4 cut quad over pixels [16, 48) shows at horizontal patch coordinate u.
float piecewiseSquare(float u) {
    const float k = std::min(std::floor(u * 4.0f), 3.0f) / 4.0f;  // the column's left edge
    const float left = k * k, right = (k + 0.25f) * (k + 0.25f);
    return left + (right - left) * (u - k) * 4.0f;
}

// A quad patch over pixels [16, 48) x [16, 48): the evaluation shader's colour (u^2, v, 0) shows
// the 4 x 4 cut (an uncut quad would show red u, up to 0.06 away); then the mistakes.
std::vector<CaseImage> tessellationStages(Device& d) {
    DeviceObjects o(d);
    const ShaderHandle vs = registryShader(o, ShaderStage::Vertex, "conformance/patch.vert"),
                       fs = registryShader(o, ShaderStage::Fragment, "conformance/color.frag");
    if (!d.info().features.tessellationShaders) {
        FE_CONFORMANCE_CHECK(
            throws([&] {
                o.add(d.createGraphicsPipeline(
                    {.vertexShader = vs,
                     .fragmentShader = fs,
                     .tessControlShader =
                         registryShader(o, ShaderStage::TessControl, "conformance/patch_quad.tesc"),
                     .tessEvaluationShader = registryShader(o, ShaderStage::TessEvaluation,
                                                            "conformance/patch_quad.tese"),
                     .patchControlPoints = 4,
                     .topology = PrimitiveTopology::PatchList,
                     .colorFormats = {Format::RGBA8}}));
            }),
            "without DeviceFeatures::tessellationShaders tessellation is refused");
        return {};
    }
    const ShaderHandle tcs = registryShader(o, ShaderStage::TessControl,
                                            "conformance/patch_quad.tesc"),
                       tes = registryShader(o, ShaderStage::TessEvaluation,
                                            "conformance/patch_quad.tese");
    const VertexBufferLayout layout{.stride = 8, .attributes = {{0, VertexFormat::Float2, 0}}};
    GraphicsPipelineDesc desc{.vertexShader = vs,
                              .fragmentShader = fs,
                              .tessControlShader = tcs,
                              .tessEvaluationShader = tes,
                              .patchControlPoints = 4,
                              .vertexBuffers = {layout},
                              .topology = PrimitiveTopology::PatchList,
                              .colorFormats = {Format::RGBA8},
                              .debugName = "tessellated quad"};
    const PipelineHandle quad = o.add(d.createGraphicsPipeline(desc));
    const float corners[8] = {-0.5f, -0.5f, 0.5f, -0.5f, -0.5f, 0.5f, 0.5f, 0.5f};
    const BufferHandle vb = o.add(
        d.createBuffer({.size = sizeof corners, .usage = BufferUsage::Vertex}, bytesOf(corners)));
    const TextureHandle t = caseTarget(o);
    auto cmd = d.createCommandList();
    cmd->beginRenderPass({.colors = {{.texture = t, .clear = {0, 0, 0, 1}}}});
    cmd->setPipeline(quad);
    cmd->setVertexBuffer(0, vb);
    cmd->draw(4);
    cmd->endRenderPass();
    d.wait(d.submit(*cmd));
    const Image expected = expectImage(Format::RGBA8, [](uint32_t x, uint32_t y) -> Texel {
        if (x < 16 || x >= 48 || y < 16 || y >= 48) return {0, 0, 0, 1};
        const float u = (float(x) + 0.5f - 16.0f) / 32.0f, v = (float(y) + 0.5f - 16.0f) / 32.0f;
        return {piecewiseSquare(u), v, 0, 1};
    });
    std::vector<CaseImage> out;
    // Two steps: the colour is interpolated across the cut's triangles, whose split differs by
    // API only in where a pixel centre on a diagonal falls (the value there is the same).
    out.push_back(drawn8("quad_patch_cut_4x4", d.readTexture(t), expected, 2.0));

    auto refused = [&](GraphicsPipelineDesc wrong, const std::string& why) {
        wrong.debugName = "tessellation errors";
        expectError([&] { o.add(d.createGraphicsPipeline(wrong)); },
                    "graphics pipeline 'tessellation errors': " + why);
    };
    GraphicsPipelineDesc noTes = desc;
    noTes.tessEvaluationShader = {};
    refused(noTes,
            "tessellation needs both a tessControlShader and a tessEvaluationShader (one is "
            "missing)");
    GraphicsPipelineDesc triangles = desc;
    triangles.topology = PrimitiveTopology::TriangleList;
    refused(triangles,
            "tessellation shaders draw patches: set topology PrimitiveTopology::PatchList");
    GraphicsPipelineDesc plain = desc;
    plain.tessControlShader = plain.tessEvaluationShader = {};
    refused(plain,
            "topology PatchList needs tessellation shaders (tessControlShader and "
            "tessEvaluationShader)");
    GraphicsPipelineDesc tooMany = desc;
    tooMany.patchControlPoints = d.info().limits.maxTessellationPatchSize + 1;
    refused(tooMany, "patchControlPoints " + std::to_string(tooMany.patchControlPoints) +
                         " is not 1 to " +
                         std::to_string(d.info().limits.maxTessellationPatchSize));
    GraphicsPipelineDesc swapped = desc;
    std::swap(swapped.tessControlShader, swapped.tessEvaluationShader);
    swapped.debugName = "tessellation errors";
    expectError([&] { o.add(d.createGraphicsPipeline(swapped)); },
                "pipeline 'tessellation errors': tessControlShader is not a tessellation control "
                "shader (it is a tessellation evaluation shader)");
    return out;
}

}  // namespace

std::vector<Case> stageCases() {
    return {
        {"geometry_stage", geometryStage},
        {"tessellation_stages", tessellationStages},
    };
}

}  // namespace fe::conformance

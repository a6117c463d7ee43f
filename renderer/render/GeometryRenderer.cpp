#include "render/GeometryRenderer.h"

#include <algorithm>

#include "fe/gdi/ShaderRegistry.h"
#include "render/ShaderSlots.h"

namespace fe::render {

std::vector<gdi::BindingSlot> meshPassBindings() {
    using gdi::BindingType;
    using gdi::ShaderStage;
    return {
        {kSlotFrame, BindingType::UniformBuffer, ShaderStage::AllGraphics},
        {kSlotObject, BindingType::UniformBuffer, ShaderStage::AllGraphics},
        {kSlotLights, BindingType::StorageBuffer, ShaderStage::Fragment},
        {kSlotBaseColor, BindingType::SampledTexture, ShaderStage::Fragment},
        {kSlotMetalRough, BindingType::SampledTexture, ShaderStage::Fragment},
        {kSlotNormalMap, BindingType::SampledTexture, ShaderStage::Fragment},
        {kSlotEmissive, BindingType::SampledTexture, ShaderStage::Fragment},
    };
}

GeometryRenderer::GeometryRenderer(gdi::Device& device, GpuScene& scene) : device_(device), scene_(scene) {
    vs_ = device.createShader({.stage = gdi::ShaderStage::Vertex, .binary = shaders::find("scene/mesh.vert")});
    forwardFs_ = device.createShader({.stage = gdi::ShaderStage::Fragment, .binary = shaders::find("scene/forward.frag")});
    gbufferFs_ = device.createShader({.stage = gdi::ShaderStage::Fragment, .binary = shaders::find("scene/gbuffer.frag")});
}

GeometryRenderer::~GeometryRenderer() {
    for (auto& [k, p] : pipelines_) device_.destroy(p);
    device_.destroy(vs_);
    device_.destroy(forwardFs_);
    device_.destroy(gbufferFs_);
}

gdi::PipelineHandle GeometryRenderer::pipeline(MeshPass pass, const MeshPassTargets& targets, gdi::CullMode cull,
                                               gdi::FrontFace face) {
    std::vector<uint32_t> key = {uint32_t(pass), uint32_t(cull), uint32_t(face), uint32_t(targets.depthFormat)};
    for (gdi::Format f : targets.colorFormats) key.push_back(uint32_t(f));
    if (auto it = pipelines_.find(key); it != pipelines_.end()) return it->second;

    using gdi::VertexFormat;
    gdi::GraphicsPipelineDesc d{
        .vertexShader = vs_,
        .fragmentShader = pass == MeshPass::GBuffer ? gbufferFs_ : forwardFs_,
        .vertexBuffers = {{.stride = GpuScene::kVertexStride,
                           .attributes = {{0, VertexFormat::Float3, 0},
                                          {1, VertexFormat::Float3, 12},
                                          {2, VertexFormat::Float4, 24},
                                          {3, VertexFormat::Float2, 40}}}},
        .raster = {.cullMode = cull, .frontFace = face},
        .depthStencil = {.depthTest = true, .depthWrite = pass != MeshPass::Transparent,
                         .depthCompare = gdi::CompareOp::LessOrEqual},
        .colorFormats = targets.colorFormats,
        .depthFormat = targets.depthFormat,
        .bindings = meshPassBindings(),
        .debugName = pass == MeshPass::GBuffer ? "gbuffer" : pass == MeshPass::Forward ? "forward" : "transparent",
    };
    if (pass == MeshPass::Transparent)
        d.blend = {{.enable = true,
                    .srcColor = gdi::BlendFactor::SrcAlpha,
                    .dstColor = gdi::BlendFactor::OneMinusSrcAlpha,
                    .srcAlpha = gdi::BlendFactor::One,
                    .dstAlpha = gdi::BlendFactor::OneMinusSrcAlpha}};
    gdi::PipelineHandle p = device_.createGraphicsPipeline(d);
    pipelines_[key] = p;
    return p;
}

uint32_t GeometryRenderer::drawCount(MeshPass pass) const {
    uint32_t n = 0;
    for (const DrawItem& d : scene_.draws())
        n += (pass == MeshPass::Transparent) == (d.alphaMode == assets::AlphaMode::Blend);
    return n;
}

void GeometryRenderer::draw(gdi::CommandList& cmd, CommandQueue& queue, MeshPass pass, const MeshPassTargets& targets,
                            const UploadAllocation& frame, const glm::vec3& eye) {
    std::vector<const DrawItem*> items;
    for (const DrawItem& d : scene_.draws())
        if ((pass == MeshPass::Transparent) == (d.alphaMode == assets::AlphaMode::Blend)) items.push_back(&d);
    if (pass == MeshPass::Transparent)  // back to front, so source-over blending composes correctly
        std::stable_sort(items.begin(), items.end(), [&](const DrawItem* a, const DrawItem* b) {
            return glm::distance(a->worldCenter, eye) > glm::distance(b->worldCenter, eye);
        });

    cmd.setVertexBuffer(0, scene_.vertexBuffer());
    cmd.setIndexBuffer(scene_.indexBuffer(), gdi::IndexType::U32);
    cmd.setUniformBuffer(kSlotFrame, frame.buffer, frame.offset, frame.size);
    cmd.setStorageBuffer(kSlotLights, scene_.lightBuffer());
    gdi::PipelineHandle current{};
    for (const DrawItem* d : items) {
        // glTF front faces are counter-clockwise; a mirroring transform turns them clockwise.
        gdi::CullMode cull = d->doubleSided ? gdi::CullMode::None : gdi::CullMode::Back;
        gdi::FrontFace face = d->mirrored ? gdi::FrontFace::Clockwise : gdi::FrontFace::CounterClockwise;
        gdi::PipelineHandle p = pipeline(pass, targets, cull, face);
        if (!(p == current)) {
            cmd.setPipeline(p);
            current = p;
        }
        ObjectConstants oc = scene_.objectConstants(*d);
        UploadAllocation o = queue.upload(oc);
        cmd.setUniformBuffer(kSlotObject, o.buffer, o.offset, o.size);
        const MaterialTextures& t = scene_.textures(d->material);
        cmd.setTexture(kSlotBaseColor, t.baseColor, t.baseColorSampler);
        cmd.setTexture(kSlotMetalRough, t.metallicRoughness, t.metallicRoughnessSampler);
        cmd.setTexture(kSlotNormalMap, t.normal, t.normalSampler);
        cmd.setTexture(kSlotEmissive, t.emissive, t.emissiveSampler);
        cmd.drawIndexed(d->indexCount, 1, d->firstIndex, d->baseVertex, 0);
    }
}

}  // namespace fe::render

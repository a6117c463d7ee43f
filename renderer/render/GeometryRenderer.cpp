#include "render/GeometryRenderer.h"

#include <algorithm>

#include "fe/gdi/ShaderRegistry.h"
#include "render/ShaderSlots.h"

namespace fe::render {

namespace {
bool isTransparent(MeshPass pass) {
    return pass == MeshPass::Transparent || pass == MeshPass::TransparentClustered;
}
// Which draws a pass takes: BLEND ones the transparent passes, transmissive ones the
// transmission pass, every other one the rest (opaque and MASK: shading, depth, shadow casting).
bool drawnBy(MeshPass pass, const DrawItem& d) {
    if (d.alphaMode == assets::AlphaMode::Blend) return isTransparent(pass);
    if (d.transmissive) return pass == MeshPass::Transmission;
    return !isTransparent(pass) && pass != MeshPass::Transmission;
}

// Shadow casters' depth bias (RasterState): 2 x the depth slope, plus 4 units of the format's
// resolution (for D32F a few ulps of the depth; the slope term does the work).
constexpr float kShadowSlopeBias = 2.0f;
constexpr float kShadowConstantBias = 4.0f;
}  // namespace

// The light count comes from the scene asset: the GpuScene's is set after this constructor
// (SceneRenderer::updateLights, which keeps it).
GeometryRenderer::GeometryRenderer(gdi::Device& device, GpuScene& scene)
    : objects_(device),
      device_(device),
      scene_(scene),
      uniformLights_(GpuScene::lightsFitUniformBlock(uint32_t(scene.scene().lights.size()),
                                                     device.info().limits)) {
    // The shaders are made at their first pipeline: a renderer uses a few of its passes, and
    // making (validating, reflecting) the others cost most of a small scene's set-up.
}

gdi::ShaderHandle GeometryRenderer::shader(gdi::ShaderHandle& made, gdi::ShaderStage stage,
                                           const std::string& path) {
    if (!made)
        made = objects_.add(device_.createShader({.stage = stage, .binary = shaders::find(path)}));
    return made;
}

gdi::ShaderHandle GeometryRenderer::fragment(gdi::ShaderHandle& made, const std::string& path) {
    return shader(made, gdi::ShaderStage::Fragment, path);
}

// The forward shaders read the lights from the uniform block when they fit it, else from the
// storage buffer (their FE_LIGHTS_IN_STORAGE variants; fe_forward_pass.glsl says why).
// With layered materials (GpuScene::hasLayeredMaterials), their FE_LAYERED variants; the parts in
// the order the shaders' fe-variant lines give them.
std::string GeometryRenderer::lightsVariant(const std::string& path, const char* variant) const {
    std::string v = variant ? variant : "";
    if (scene_.hasLayeredMaterials()) v += v.empty() ? "FE_LAYERED" : "+FE_LAYERED";
    if (!uniformLights_) v += v.empty() ? "FE_LIGHTS_IN_STORAGE" : "+FE_LIGHTS_IN_STORAGE";
    return v.empty() ? path : path + ":" + v;
}

void GeometryRenderer::setEnvironment(const EnvironmentLight& light) {
    if (!pipelines_.empty())
        throw gdi::Error("GeometryRenderer::setEnvironment after the first draw");
    environment_ = light;
    hasEnvironment_ = true;
}

gdi::PipelineHandle GeometryRenderer::pipeline(MeshPass pass, const MeshPassTargets& targets,
                                               gdi::CullMode cull, gdi::FrontFace face,
                                               uint32_t materialFeatures) {
    // Specialized for the scene's light types, the frame's BRDF (glTF's for the transmission
    // pass, whose lobe it is) and the draw's material (ShaderFeatures); the depth passes sample
    // only what the alpha test reads.
    const bool depthOnly = pass == MeshPass::DepthPrepass || pass == MeshPass::ShadowCaster ||
                           pass == MeshPass::Visibility;
    const ShaderFeatures features{
        .lightTypes = scene_.lightTypes(),
        .brdfModels = pass == MeshPass::Transmission ? ShaderFeatures::kGltf : brdfModels_,
        .material = depthOnly ? materialFeatures &
                                    (ShaderFeatures::kBaseTextures | ShaderFeatures::kAlphaMask)
                              : materialFeatures};
    std::vector<uint32_t> key = {uint32_t(pass),        uint32_t(cull),
                                 uint32_t(face),        uint32_t(targets.depthFormat),
                                 targets.samples,       features.lightTypes,
                                 features.brdfModels,   features.material,
                                 targets.displayTonemap};
    for (gdi::Format f : targets.colorFormats) key.push_back(uint32_t(f));
    if (auto it = pipelines_.find(key); it != pipelines_.end()) return it->second;

    // The state table of mesh passes.
    struct State {
        gdi::ShaderHandle fs;
        bool depthWrite;
        gdi::CompareOp compare;
        const char* name;
    };
    // The forward-shaded passes that add the environment's light (with the emissive term: not
    // multi-pass forward's additive passes).
    const bool ibl = hasEnvironment_ &&
                     (pass == MeshPass::Forward || pass == MeshPass::ForwardEqual ||
                      pass == MeshPass::Transparent || pass == MeshPass::LightPrepassMaterial);

    auto forward = [&] {
        return ibl ? fragment(forwardIblFs_,
                              lightsVariant(environment_.shader("scene/forward_ibl.frag")))
                   : fragment(forwardFs_, lightsVariant("scene/forward.frag"));
    };
    State st = [&]() -> State {
        switch (pass) {
            case MeshPass::GBuffer:
                // A fourth target: the occlusion (GBuffer::gb3), written by the shader's variant.
                if (targets.colorFormats.size() == 4)
                    return {
                        fragment(gbufferOcclusionFs_, "scene/gbuffer.frag:FE_GBUFFER_OCCLUSION"),
                        true, gdi::CompareOp::LessOrEqual, "gbuffer with occlusion"};
                return {fragment(gbufferFs_, "scene/gbuffer.frag"), true,
                        gdi::CompareOp::LessOrEqual, "gbuffer"};
            case MeshPass::Transparent:
                return {forward(), false, gdi::CompareOp::LessOrEqual, "transparent"};
            case MeshPass::DepthPrepass:
                return {fragment(depthFs_, "scene/depth_prepass.frag"), true,
                        gdi::CompareOp::LessOrEqual, "depth prepass"};
            case MeshPass::ForwardEqual:
                return {forward(), false, gdi::CompareOp::Equal, "forward equal"};
            case MeshPass::ForwardAdditive:
                return {forward(), false, gdi::CompareOp::Equal, "forward additive"};
            case MeshPass::NormalRoughness:
                return {fragment(lppNormalsFs_, "scene/lpp_normals.frag"), true,
                        gdi::CompareOp::LessOrEqual, "lpp normals"};
            case MeshPass::NormalRoughnessUnpacked:
                return {fragment(lppNormalsUnpackedFs_, "scene/lpp_normals_unpacked.frag"), true,
                        gdi::CompareOp::LessOrEqual, "lpp normals unpacked"};
            case MeshPass::LightPrepassMaterial:
                return {ibl ? fragment(lppMaterialIblFs_,
                                       environment_.shader("scene/lpp_material_ibl.frag"))
                            : fragment(lppMaterialFs_, "scene/lpp_material.frag"),
                        false, gdi::CompareOp::Equal, "lpp material"};
            case MeshPass::ShadowCaster:
                return {fragment(depthFs_, "scene/depth_prepass.frag"), true,
                        gdi::CompareOp::LessOrEqual, "shadow caster"};
            case MeshPass::ForwardShadowed:
                return {fragment(forwardShadowedFs_, lightsVariant("scene/forward_shadowed.frag")),
                        false, gdi::CompareOp::Equal, "forward shadowed"};
            case MeshPass::ForwardShadowedCube:
                return {fragment(forwardShadowedCubeFs_,
                                 lightsVariant("scene/forward_shadowed_cube.frag")),
                        false, gdi::CompareOp::Equal, "forward shadowed cube"};
            case MeshPass::ForwardTiled:
                // Multisampled: the variant whose fragments outside their tile's bounds walk their
                // cluster's list; with a second target, the one writing the display image too.
                if (targets.colorFormats.size() == 2)
                    return {listShader(forwardTiledDisplayFs_, "forward_plus", "FE_DISPLAY_OUT"),
                            false, gdi::CompareOp::Equal, "forward tiled to display"};
                return targets.samples > 1
                           ? State{listShader(forwardTiledMsaaFs_, "forward_plus",
                                              "FE_MULTISAMPLED"),
                                   false, gdi::CompareOp::Equal, "forward tiled multisampled"}
                           : State{listShader(forwardTiledFs_, "forward_plus"), false,
                                   gdi::CompareOp::Equal, "forward tiled"};
            case MeshPass::ForwardClustered:
                return {listShader(forwardClusteredFs_, "forward_clustered"), false,
                        gdi::CompareOp::Equal, "forward clustered"};
            case MeshPass::TransparentClustered:
                return {listShader(forwardClusteredFs_, "forward_clustered"), false,
                        gdi::CompareOp::LessOrEqual, "transparent clustered"};
            case MeshPass::Visibility:
                return {visibilityShaders(), true, gdi::CompareOp::LessOrEqual, "visibility"};
            case MeshPass::Transmission:
                return {transmissionShader(), true, gdi::CompareOp::LessOrEqual, "transmission"};
            default:
                return {forward(), true, gdi::CompareOp::LessOrEqual, "forward"};
        }
    }();
    using gdi::VertexFormat;
    gdi::GraphicsPipelineDesc d{
        .vertexShader = pass == MeshPass::Visibility
                            ? visibilityVs_
                            : shader(vs_, gdi::ShaderStage::Vertex, "scene/mesh.vert"),
        .fragmentShader = st.fs,
        .vertexBuffers = {{.stride = GpuScene::kVertexStride,
                           .attributes = {{0, VertexFormat::Float3, 0},
                                          {1, VertexFormat::Float3, 12},
                                          {2, VertexFormat::Float4, 24},
                                          {3, VertexFormat::Float2, 40},
                                          {4, VertexFormat::Float2, 48},
                                          {5, VertexFormat::Float4, 56}}}},
        .raster = {.cullMode = cull, .frontFace = face},
        .multisample = {.sampleCount = targets.samples},
        .depthStencil = {.depthTest = true,
                         .depthWrite = st.depthWrite,
                         .depthCompare = st.compare},
        .colorFormats = targets.colorFormats,
        .depthFormat = targets.depthFormat,
        .debugName = st.name,
    };
    d.specialization = features.constantsFor(device_, {d.vertexShader, d.fragmentShader});
    if (pass == MeshPass::ForwardTiled && targets.colorFormats.size() == 2)
        d.specialization.push_back(gdi::SpecializationConstant::of(
            ShaderFeatures::kDisplayTonemapId, targets.displayTonemap));
    if (pass == MeshPass::Visibility) {  // no vertex buffers: the vertex shader pulls its vertices
        d.vertexBuffers.clear();
    }
    if (isTransparent(pass))
        d.blend = {{.enable = true,
                    .srcColor = gdi::BlendFactor::SrcAlpha,
                    .dstColor = gdi::BlendFactor::OneMinusSrcAlpha,
                    .srcAlpha = gdi::BlendFactor::One,
                    .dstAlpha = gdi::BlendFactor::OneMinusSrcAlpha}};
    if (pass == MeshPass::ShadowCaster) {
        // Both sides cast (as in the reference's shadow rays); the slope-scaled bias keeps a
        // lit surface from shadowing itself where the light grazes it, the receiver's normal
        // offset (fe_shadow.glsl) does the rest.
        d.raster.cullMode = gdi::CullMode::None;
        d.raster.depthBiasSlope = kShadowSlopeBias;
        d.raster.depthBiasConstant = kShadowConstantBias;
    }
    if (pass == MeshPass::ForwardAdditive || pass == MeshPass::ForwardShadowed ||
        pass == MeshPass::ForwardShadowedCube)
        d.blend = {{.enable = true,
                    .srcColor = gdi::BlendFactor::One,
                    .dstColor = gdi::BlendFactor::One,
                    .srcAlpha = gdi::BlendFactor::One,
                    .dstAlpha = gdi::BlendFactor::Zero}};
    if (pass ==
        MeshPass::DepthPrepass)  // the colour targets stay attached (one pass layout), unwritten
        d.blend.assign(targets.colorFormats.size(), {.writeMask = gdi::ColorMask::None});
    gdi::PipelineHandle p = objects_.add(device_.createGraphicsPipeline(d));
    pipelines_[key] = p;
    return p;
}

// The forward shader walking a light list (scene/NAME.frag, its `variant` if given), with the
// environment's light when the renderer has one; made once, at its first pipeline.
gdi::ShaderHandle GeometryRenderer::listShader(gdi::ShaderHandle& made, const char* name,
                                               const char* variant) {
    if (made) return made;
    const std::string plain = std::string("scene/") + name + ".frag";
    return fragment(
        made, lightsVariant(hasEnvironment_
                                ? environment_.shader(std::string("scene/") + name + "_ibl.frag")
                                : plain,
                            variant));
}

// The transmission pass's forward shader (FE_TRANSMISSION), with the environment's light when
// the renderer has one; made at its first pipeline.
gdi::ShaderHandle GeometryRenderer::transmissionShader() {
    if (transmissionFs_) return transmissionFs_;
    const std::string path =
        hasEnvironment_ ? environment_.shader("scene/forward_ibl.frag") : "scene/forward.frag";
    return fragment(transmissionFs_, lightsVariant(path, "FE_TRANSMISSION"));
}

// The visibility pass's shaders (its fragment shader returned), made at its first pipeline.
gdi::ShaderHandle GeometryRenderer::visibilityShaders() {
    shader(visibilityVs_, gdi::ShaderStage::Vertex, "scene/visibility.vert");
    return fragment(visibilityFs_, "scene/visibility.frag");
}

uint32_t GeometryRenderer::drawCount(MeshPass pass) const {
    uint32_t n = 0;
    for (const DrawItem& d : scene_.draws()) n += drawnBy(pass, d);
    return n;
}

std::vector<const DrawItem*> GeometryRenderer::items(MeshPass pass, const glm::vec3& eye) const {
    std::vector<const DrawItem*> items;
    for (const DrawItem& d : scene_.draws())
        if (drawnBy(pass, d)) items.push_back(&d);
    auto distance = [&](const DrawItem* d) { return glm::distance(d->worldCenter, eye); };
    if (isTransparent(pass))  // back to front, so source-over blending composes correctly
        std::stable_sort(items.begin(), items.end(),
                         [&](auto* a, auto* b) { return distance(a) > distance(b); });
    if (pass == MeshPass::DepthPrepass || pass == MeshPass::ShadowCaster ||
        pass == MeshPass::Visibility ||
        pass == MeshPass::Transmission)  // front to back: hidden surfaces fail early
        std::stable_sort(items.begin(), items.end(),
                         [&](auto* a, auto* b) { return distance(a) < distance(b); });
    return items;
}

void GeometryRenderer::draw(gdi::CommandList& cmd, CommandQueue& queue, MeshPass pass,
                            const MeshPassTargets& targets, const UploadAllocation& frame,
                            const glm::vec3& eye, std::vector<UploadAllocation>* objects) {
    const std::vector<const DrawItem*> list = items(pass, eye);
    if (objects && objects->size() != scene_.draws().size())
        objects->assign(scene_.draws().size(), {});
    cmd.setVertexBuffer(0, scene_.vertexBuffer());
    cmd.setIndexBuffer(scene_.indexBuffer(), gdi::IndexType::U32);
    cmd.setUniformBuffer(kSlotFrame, frame.buffer, frame.offset, frame.size);
    scene_.bindLights(cmd, kSlotLights, uniformLights_);
    if (environment_) environment_.bind(cmd);
    if (pass == MeshPass::Visibility) {
        cmd.setStorageBuffer(kSlotVertices, scene_.vertexBuffer());
        cmd.setStorageBuffer(kSlotIndices, scene_.indexBuffer());
    }
    gdi::PipelineHandle current{};
    for (size_t i = 0; i < list.size(); ++i) {
        const DrawItem* d = list[i];
        // glTF front faces are counter-clockwise; a mirroring transform turns them clockwise.
        gdi::CullMode cull = d->doubleSided ? gdi::CullMode::None : gdi::CullMode::Back;
        gdi::FrontFace face =
            d->mirrored ? gdi::FrontFace::Clockwise : gdi::FrontFace::CounterClockwise;
        gdi::PipelineHandle p =
            pipeline(pass, targets, cull, face, scene_.materialFeatures(d->material));
        if (!(p == current)) {
            cmd.setPipeline(p);
            current = p;
        }
        UploadAllocation o;
        if (objects) {  // by the item's index in the scene, since passes order items differently
            UploadAllocation& cached = (*objects)[size_t(d - scene_.draws().data())];
            if (!cached.buffer) cached = queue.upload(scene_.objectConstants(*d));
            o = cached;
        } else {
            o = queue.upload(scene_.objectConstants(*d));
        }
        cmd.setUniformBuffer(kSlotObject, o.buffer, o.offset, o.size);
        scene_.textures(d->material).bind(cmd);
        if (pass == MeshPass::Visibility)
            cmd.draw(d->indexCount);  // unindexed: vertex id / 3 is the triangle
        else
            cmd.drawIndexed(d->indexCount, 1, d->firstIndex, d->baseVertex, 0);
    }
}

}  // namespace fe::render

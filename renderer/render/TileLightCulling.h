// Layer 7: the light-culling pass of the tiled techniques (deferred-tiled, redeferred-tiled).
// One compute pass reads the scene depth and writes, per 8x8-pixel tile, the list of lights
// whose range reaches the tile's slice of the view frustum (shaders/scene/tile_light_culling.comp:
// one invocation per 16x16 pixels, culling in two levels); the shading passes then read their
// pixel's list (fe_tile_culling.glsl with FE_TILE_LISTS). The lists are a transient R32U texture
// of the render graph: a block of 32 x H texels per list tile, a header of 3 (the count and the
// depth bounds culled for), then the lights. A tile with
// more lights than its block holds is marked to shade every light, so culling never drops one.
#pragma once
#include "render/TechniqueRenderer.h"

namespace fe::render {

class TileLightCulling {
public:
    // tile_light_culling.comp's FE_WIDEN_BOUNDS (specialization constant): widen the depth
    // bounds along the surface's slope (forward-plus under MSAA).
    static constexpr uint32_t kWidenBoundsId = 203;
    // `multisampledDepth`: the depth declare() reads is a multisampled G-buffer's, and the tiles
    // are bounded by every sample (the deferred techniques under --msaa; forward-plus culls for
    // its resolved depth, widened to the pixel centres its fragments shade at).
    explicit TileLightCulling(TechniqueContext& context, bool multisampledDepth = false);
    TileLightCulling(const TileLightCulling&) = delete;
    TileLightCulling& operator=(const TileLightCulling&) = delete;

    // Declares the list texture and the "light-culling" pass reading `depth`.
    graph::TextureId declare(graph::RenderGraph& g, graph::TextureId depth);
    // Binds the lists for a shading pass.
    void bindLists(gdi::CommandList& cmd, const graph::PassContext& pc,
                   graph::TextureId lists) const;

    // The passes that walk the lists (this one and the shading passes) read the lights from a
    // uniform block when the scene's lights fit one (GpuScene::kUniformLights) and the device
    // binds 64 KiB, else from the storage buffer with their FE_LIGHTS_IN_STORAGE variant.
    // Such a pass's shader (scene/NAME.comp), in the variant for this scene's lights.
    const gdi::ShaderBinary& shader(const std::string& name) const;
    // Binds the frame constants and the lights for such a pass's pipeline.
    void bindFrameAndLights(gdi::CommandList& cmd, gdi::PipelineHandle pipeline) const;
    // The same choice for any list pass (ClusterLightGrid's too): whether the lights fit the
    // uniform block, the shader variant, and the binding of the lights alone.
    static bool lightsFitUniformBlock(const TechniqueContext& c);
    // `layered`: the FE_LAYERED variant (GpuScene::hasLayeredMaterials: clearcoat and sheen lobes).
    // `multisampled`: the FE_MULTISAMPLED variant (a multisampled G-buffer or visibility buffer).
    static const gdi::ShaderBinary& listPassShader(const std::string& name, bool uniformLights,
                                                   bool layered = false, bool multisampled = false);
    static void bindLights(gdi::CommandList& cmd, const TechniqueContext& c, bool uniformLights);

    // The light-culling pass's VisibleLights block (tile_light_culling.comp), made each frame: a
    // header of four words (the first the count), then the indices below `count` of the lights not
    // wholly outside `seen`'s view (lightOutOfView), ascending; padded to the uniform block's
    // size (GpuScene::kUniformLights indices) when `uniformBlock`. The lists keep the lights'
    // own indices, so the passes that read them are unchanged.
    static std::vector<uint32_t> lightsInView(const std::vector<assets::Light>& lights,
                                              uint32_t count, const FrameConstants& seen,
                                              bool uniformBlock);

    // List tiles are finer than the shading passes' 16x16 work groups (FE_LIST_TILE in
    // fe_tile_culling.glsl): shorter lists, each invocation reading its own pixel's.
    static constexpr uint32_t kTileSize = 8;
    static constexpr uint32_t kBlockWidth = 32;  // texels per tile block row
    static constexpr uint32_t kListHeader = 3;   // count, depth min, depth max (FE_TILE_HEADER)
    static constexpr uint32_t kMaxListLength = 1021;  // lights per tile list at most

private:
    gdi::DeviceObjects objects_;
    TechniqueContext& ctx_;
    bool uniformLights_ = false;
    bool multisampledDepth_ = false;
    gdi::ShaderHandle cs_;
    gdi::PipelineHandle pipeline_;
};

}  // namespace fe::render

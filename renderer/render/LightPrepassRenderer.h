// Layer 7: the light pre-pass (Engel 2008; ../shared/seeds/004): pass 1 draws the scene into a
// small normal + roughness target and the depth buffer; pass 2 draws the lights as volumes
// into a light buffer of diffuse RGB and monochrome specular; pass 3 draws the scene again,
// each material combining its own albedo and F0 with the light buffer (depth EQUAL). Formats,
// packing and the specular-colour reconstruction: shaders/include/fe_light_prepass.glsl.
#pragma once
#include <memory>

#include "render/ShadowedLightVolumes.h"
#include <vector>

#include "render/LightVolumes.h"
#include "render/TechniqueRenderer.h"

namespace fe::render {

class LightPrepassRenderer final : public TechniqueRenderer {
public:
    // packed: RGBA8 view-space normal.xy (the deck's layout); otherwise RGBA16F world normal.
    LightPrepassRenderer(TechniqueContext& context, bool packed);
    ~LightPrepassRenderer() override;
    void declare(graph::RenderGraph& graph, graph::TextureId output,
                 graph::TextureId depth) override;
    LightLists lightLists() const override { return {LightLists::Kind::NotMeasured, {}}; }

    static constexpr gdi::Format kPackedNormals = gdi::Format::RGBA8,
                                 kUnpackedNormals = gdi::Format::RGBA16F;
    static constexpr gdi::Format kLightBuffer = gdi::Format::RGBA32F;

private:
    std::unique_ptr<ShadowedLightVolumes> shadowed_;  // with shadows: each shadowed light's pass
    bool packed_;
    std::unique_ptr<LightVolumes> volumes_;
    std::vector<UploadAllocation> objects_;  // object constants, shared by passes 1 and 3
};

}  // namespace fe::render

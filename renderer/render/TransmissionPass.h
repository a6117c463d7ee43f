// Layer 7: KHR_materials_transmission, drawn the same way after every technique. Transmissive
// surfaces (assets::Material::transmissive) are left out of the technique's passes, its depth and
// the shadow maps; after the background pass
//   "transmission-source" copies L_o (the opaque scene and its background) into a texture with a
//     mip chain and generates its mips (a 2x2 box filter per level);
//   "transmission" draws the transmissive surfaces with the forward shader's FE_TRANSMISSION
//     variant (every light, unshadowed, the environment's light when there is one) under the
//     glTF model whatever the technique's, depth test <= and depth write, each sampling that copy
//     where the refracted view ray leaves its volume at the mip level of its roughness
//     (docs/SHADING.md, "Transmission"), as the Khronos Sample Viewer and Filament do.
// A transmissive surface behind another is not seen through it (the copy holds the opaque scene
// only), and blended surfaces are drawn after, over both.
#pragma once
#include "fe/gdi/Device.h"
#include "fe/gdi/DeviceObjects.h"
#include "graph/RenderGraph.h"
#include "render/TechniqueRenderer.h"

namespace fe::render {

class TransmissionPass {
public:
    // Makes the copy (the size of `settings`' frame) and its sampler.
    explicit TransmissionPass(TechniqueContext& context);
    TransmissionPass(const TransmissionPass&) = delete;
    TransmissionPass& operator=(const TransmissionPass&) = delete;

    void declare(graph::RenderGraph& graph, graph::TextureId radiance, graph::TextureId depth);
    gdi::TextureHandle opaqueCopy() const { return copy_; }

private:
    gdi::DeviceObjects objects_;
    TechniqueContext& ctx_;
    gdi::TextureHandle copy_;
    gdi::SamplerHandle sampler_;
    uint32_t mips_ = 1;
};

}  // namespace fe::render

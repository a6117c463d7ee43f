// Layer 7 (Render): the shadowed lights of the techniques that light by volumes over screen
// data (deferred, deferred-tiled, light-prepass, redeferred): after each light's shadow map, one
// pass draws that light's volume with a shadowed variant of the technique's lighting shader,
// adding into the technique's targets (L_o, the light buffer or the I-buffer).
#pragma once
#include <functional>
#include <memory>

#include "render/LightVolumes.h"
#include "render/TechniqueRenderer.h"

namespace fe::render {

class ShadowedLightVolumes {
public:
    // `shader`: the variant for cascades and spot maps; `cubeShader`: for point lights' cubes.
    ShadowedLightVolumes(TechniqueContext& context, const std::string& shader,
                         const std::string& cubeShader, std::vector<gdi::Format> targets);
    ~ShadowedLightVolumes();
    // `setup` declares the pass's inputs and its targets (loaded: the light adds to them).
    // `bindInputs` binds what the shaders sample besides the shadow map. `frame`: the passes'
    // frame constants (default: the frame's own).
    void declare(graph::RenderGraph& g, const std::function<void(graph::PassBuilder&)>& setup,
                 std::function<void(graph::PassContext&)> bindInputs, FrameConstantsFn frame = {});

private:
    TechniqueContext& ctx_;
    std::unique_ptr<LightVolumes> volumes_, cubeVolumes_;
};

}  // namespace fe::render

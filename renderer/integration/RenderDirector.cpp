#include "integration/RenderDirector.h"

#include "render/TechniqueRenderer.h"

namespace fe::render {

SceneNeeds sceneNeeds(const assets::Scene& scene) {
    SceneNeeds n;
    n.lights = uint32_t(scene.lights.size());
    for (const assets::Light& l : scene.lights)
        n.boundedLights += l.type != assets::LightType::Directional && l.range > 0.0f;
    for (const assets::MeshInstance& i : scene.instances)
        for (const assets::Primitive& p : scene.meshes[i.meshIndex].primitives)
            n.blendPrimitives += scene.materials[p.material].alphaMode == assets::AlphaMode::Blend;
    return n;
}

DirectorChoice direct(const assets::Scene& scene, const RenderSettings& requested, const gdi::DeviceInfo& device) {
    DirectorChoice c{requested, {}};
    const SceneNeeds n = sceneNeeds(scene);
    RenderSettings& s = c.settings;
    if (s.technique != "auto") {
        c.reasons.push_back("technique " + s.technique + ": asked for");
    } else if (n.lights <= kForwardMaxLights) {
        s.technique = "forward";
        c.reasons.push_back("technique forward: " + std::to_string(n.lights) + " light(s), at most " +
                            std::to_string(kForwardMaxLights) + ": one pass shading every light is cheapest and exact, "
                            "and needs no G-buffer");
    } else if (device.features.computeShaders) {
        s.technique = "deferred-tiled";
        c.reasons.push_back("technique deferred-tiled: " + std::to_string(n.lights) + " lights (" +
                            std::to_string(n.boundedLights) + " with a range, culled per 16x16 tile): each pixel "
                            "shades only the lights that reach its tile, once");
    } else {
        s.technique = "deferred";
        c.reasons.push_back("technique deferred: " + std::to_string(n.lights) + " lights and no compute shaders on " +
                            device.backend + ": lights drawn as volumes");
    }
    if (!findTechnique(s.technique).illumScale && s.illumScale != 1) {
        c.reasons.push_back("illumination scale " + std::to_string(s.illumScale) + " ignored: " + s.technique +
                            " has no I-buffer");
        s.illumScale = 1;
    }
    c.reasons.push_back(n.blendPrimitives ? "transparent pass: " + std::to_string(n.blendPrimitives) + " BLEND primitive(s)"
                                          : "no transparent pass: no BLEND primitives");
    return c;
}

}  // namespace fe::render

#include "integration/FrameWarnings.h"

#include <array>

#include "reference/CameraMath.h"
#include "render/TechniqueRenderer.h"

namespace fe::render {

std::string outOfView(const assets::Scene& scene, const assets::Camera& camera, float aspect) {
    const assets::AABB& b = scene.bounds;
    if (b.empty()) return {};
    const glm::mat4 viewProj = viewProjection(camera, aspect);
    // A side of the frustum (clip space: -w <= x, y <= w, 0 <= z <= w) every corner lies beyond.
    static constexpr std::array<const char*, 6> kSides = {"left of the view",
                                                          "right of the view",
                                                          "below the view",
                                                          "above the view",
                                                          "behind the camera or nearer than znear",
                                                          "beyond zfar"};
    std::array<bool, 6> allBeyond;
    allBeyond.fill(true);
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 corner((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y,
                               (i & 4) ? b.max.z : b.min.z);
        const glm::vec4 c = viewProj * glm::vec4(corner, 1.0f);
        // The projection flips y for a top-left origin: +y in clip space is the bottom of the view.
        const std::array<bool, 6> beyond = {c.x<-c.w, c.x> c.w, c.y > c.w, c.y < -c.w,
                                            c.z < 0.0f || c.w <= 0.0f,
                                            !camera.infiniteFar() && c.z > c.w};
        for (int s = 0; s < 6; ++s) allBeyond[s] = allBeyond[s] && beyond[s];
    }
    // Behind the camera first: there the other sides' tests, divided by a negative w, mislead.
    for (int s : {4, 5, 0, 1, 2, 3})
        if (allBeyond[s]) return kSides[s];
    return {};
}

namespace {
// Why a frame came out black: the first cause that holds.
std::string blackCause(const assets::Scene& scene, const RenderSettings& settings) {
    bool anyLight = false;
    for (const assets::Light& l : scene.lights)
        anyLight = anyLight ||
                   (l.intensity > 0.0f && glm::any(glm::greaterThan(l.color, glm::vec3(0.0f))));
    bool emissive = false;
    for (const assets::Material& m : scene.materials)
        emissive =
            emissive || glm::any(glm::greaterThan(m.emissiveFactor, glm::vec3(0.0f))) || m.unlit;
    if (scene.lights.empty() && !settings.ibl() && !emissive)
        return "the scene has no lights, is not lit by an environment (--environment with --ibl-prefiltered) and emits nothing";
    if (!anyLight && !settings.ibl() && !emissive)
        return "every light of the scene has zero intensity or colour";
    return "no light reaches a visible surface brightly enough at exposure " +
           std::to_string(settings.exposure) +
           ": the lights may be out of range or behind the surfaces, or too faint for the exposure (--exposure)";
}
}  // namespace

std::vector<std::string> materialWarnings(const assets::Scene& scene,
                                          const RenderSettings& settings) {
    std::string names;
    size_t count = 0;
    for (const assets::Material& m : scene.materials)
        if (m.needsFullMaterial() && !m.unlit && count++ < 3)
            names += (names.empty() ? "'" : ", '") + m.name + "'";
    const TechniqueInfo& t = findTechnique(settings.technique);
    if (count == 0 || t.fullMaterial(resolveBrdf(settings))) return {};
    std::string capable;
    for (const TechniqueInfo& c : techniques())
        if (c.fullMaterial(shading::Brdf::Gltf))
            capable += (capable.empty() ? "" : ", ") + std::string(c.name);
    const std::string why =
        t.gbuffer ? "its G-buffer does not hold it" : "the separable BRDF has no such input";
    return {
        std::to_string(count) + " material(s) (" + names + (count > 3 ? ", ..." : "") +
        ") set the dielectric's Fresnel, a clearcoat or a sheen (KHR_materials_ior / specular / clearcoat / sheen): technique " +
        t.name + " shades them with F0 0.04, F90 1, no clearcoat and no sheen (" + why + "); " +
        capable + " evaluate them under the glTF BRDF"};
}

std::vector<std::string> frameWarnings(const assets::Scene& scene, const assets::Camera& camera,
                                       const RenderSettings& settings, const gdi::Image& display) {
    std::vector<std::string> warnings;
    const std::string side =
        outOfView(scene, camera, float(settings.width) / float(settings.height));
    if (!side.empty())
        warnings.push_back("nothing of the scene is in view: all of its bounds lie " + side +
                           " of camera '" + camera.name + "'");
    bool black = true, covered = false;
    for (uint32_t y = 0; y < display.height && black; ++y)
        for (uint32_t x = 0; x < display.width && black; ++x) {
            const std::array<float, 4> t = display.texel(x, y);
            if (t[3] == 0.0f) continue;  // a transparent background
            covered = true;
            black = t[0] <= 1.0f / 255.0f && t[1] <= 1.0f / 255.0f && t[2] <= 1.0f / 255.0f;
        }
    if (black && covered && side.empty())
        warnings.push_back("the image is black: " + blackCause(scene, settings));
    return warnings;
}

}  // namespace fe::render

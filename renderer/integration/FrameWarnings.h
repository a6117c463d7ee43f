// Layer 8: what is wrong with a frame that shows nothing, said in words (fe render prints these
// as warnings). A user's first render that comes out black, or shows none of the scene, exits 0
// like any other; these name the likely cause so the user need not guess.
#pragma once
#include <string>
#include <vector>

#include "assets/Scene.h"
#include "fe/gdi/Image.h"
#include "render/RenderSettings.h"

namespace fe::render {

// Nothing of the scene's bounds lies in `camera`'s view at `aspect` (width / height): the side of
// the view frustum all of it lies beyond ("behind the camera or nearer than znear", "beyond
// zfar", "left of the view", ...). Empty when some of it may be in view, or the scene is empty.
std::string outOfView(const assets::Scene& scene, const assets::Camera& camera, float aspect);

// Warnings about a rendered frame: nothing in view (outOfView), or a display image (RGBA8, as
// SceneRenderer::readDisplay returns it; alpha 0 marks a transparent background, not looked at)
// whose every pixel is black (no channel above 1/255), with the likely cause: no light and no
// image-based light, lights of zero intensity, or lights that reach no visible surface at this
// exposure.
// What the frame's technique and BRDF cannot show of the scene's materials, one line per kind
// naming the materials and the techniques that can: KHR_materials_ior / specular (a dielectric
// other than F0 0.04, F90 1) or KHR_materials_clearcoat on a G-buffer technique or under the
// separable BRDF.
std::vector<std::string> materialWarnings(const assets::Scene& scene,
                                          const RenderSettings& settings);

std::vector<std::string> frameWarnings(const assets::Scene& scene, const assets::Camera& camera,
                                       const RenderSettings& settings, const gdi::Image& display);

}  // namespace fe::render

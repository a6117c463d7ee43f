#version 450
#extension GL_GOOGLE_include_directive : require
// fe-variant: FE_MULTISAMPLED (--msaa: a fragment outside its tile's depth bounds walks its cluster's list)
// fe-variant: FE_LIGHTS_IN_STORAGE (more lights than the uniform block holds: fe_scene.glsl)
// fe-variant: FE_MULTISAMPLED+FE_LIGHTS_IN_STORAGE
// fe-variant: FE_LAYERED (a material with a clearcoat or a sheen: GpuScene::hasLayeredMaterials)
// fe-variant: FE_LAYERED+FE_LIGHTS_IN_STORAGE
// fe-variant: FE_MULTISAMPLED+FE_LAYERED
// fe-variant: FE_MULTISAMPLED+FE_LAYERED+FE_LIGHTS_IN_STORAGE
// fe-variant: FE_DISPLAY_OUT (the display image written too: SceneRenderer::displayInShading)
// fe-variant: FE_DISPLAY_OUT+FE_LIGHTS_IN_STORAGE
// fe-variant: FE_DISPLAY_OUT+FE_LAYERED
// fe-variant: FE_DISPLAY_OUT+FE_LAYERED+FE_LIGHTS_IN_STORAGE
// Forward+ shading (forward-plus): fe_forward_pass.glsl over the pixel's tile light list.
#define FE_TILE_LISTS
#include "fe_forward_pass.glsl"

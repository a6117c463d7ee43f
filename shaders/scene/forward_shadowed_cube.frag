#version 450
#extension GL_GOOGLE_include_directive : require
// fe-variant: FE_LIGHTS_IN_STORAGE (more lights than the uniform block holds: fe_scene.glsl)
// fe-variant: FE_LAYERED (a material with a clearcoat or a sheen: GpuScene::hasLayeredMaterials)
// fe-variant: FE_LAYERED+FE_LIGHTS_IN_STORAGE
// Forward shading of one point light with a shadow cube, added by a pass of its own.
#define FE_SHADOWED
#define FE_SHADOW_CUBE
#include "fe_forward_pass.glsl"

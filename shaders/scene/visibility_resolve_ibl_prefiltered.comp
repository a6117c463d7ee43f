#version 450
#extension GL_GOOGLE_include_directive : require
// fe-variant: FE_LIGHTS_IN_STORAGE (scenes with more lights than a uniform block holds)
// fe-variant: FE_LAYERED (a material with a clearcoat or a sheen: GpuScene::hasLayeredMaterials)
// fe-variant: FE_LAYERED+FE_LIGHTS_IN_STORAGE
// fe-variant: FE_MULTISAMPLED (--msaa: each triangle of a pixel shaded once, weighted by its samples)
// fe-variant: FE_MULTISAMPLED+FE_LIGHTS_IN_STORAGE
// fe-variant: FE_MULTISAMPLED+FE_LAYERED
// fe-variant: FE_MULTISAMPLED+FE_LAYERED+FE_LIGHTS_IN_STORAGE
// The visibility buffer's resolve (fe_visibility_resolve_pass.glsl), with the environment's light.
#define FE_IBL
#define FE_IBL_PREFILTERED
#include "fe_visibility_resolve_pass.glsl"

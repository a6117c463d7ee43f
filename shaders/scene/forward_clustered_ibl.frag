#version 450
#extension GL_GOOGLE_include_directive : require
// fe-variant: FE_LIGHTS_IN_STORAGE (more lights than the uniform block holds: fe_scene.glsl)
// fe-variant: FE_LAYERED (a material with a clearcoat or a sheen: GpuScene::hasLayeredMaterials)
// fe-variant: FE_LAYERED+FE_LIGHTS_IN_STORAGE
// Clustered forward shading (clustered-forward, and every technique's translucent pass):
// fe_forward_pass.glsl over the fragment's cluster light list.
#define FE_CLUSTER_LISTS
#define FE_IBL
#include "fe_forward_pass.glsl"

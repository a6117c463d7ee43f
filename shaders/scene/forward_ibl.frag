#version 450
#extension GL_GOOGLE_include_directive : require
// fe-variant: FE_LIGHTS_IN_STORAGE (more lights than the uniform block holds: fe_scene.glsl)
// fe-variant: FE_TRANSMISSION (the transmission pass: render/TransmissionPass.h)
// fe-variant: FE_TRANSMISSION+FE_LIGHTS_IN_STORAGE
// fe-variant: FE_LAYERED (a material with a clearcoat or a sheen: GpuScene::hasLayeredMaterials)
// fe-variant: FE_LAYERED+FE_LIGHTS_IN_STORAGE
// fe-variant: FE_TRANSMISSION+FE_LAYERED
// fe-variant: FE_TRANSMISSION+FE_LAYERED+FE_LIGHTS_IN_STORAGE
// Forward shading with image-based lighting (fe_forward_pass.glsl with FE_IBL): a shader of its
// own so that scenes without it pay nothing (on llvmpipe an untaken branch is not free).
#define FE_IBL
#include "fe_forward_pass.glsl"

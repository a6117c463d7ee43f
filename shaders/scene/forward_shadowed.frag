#version 450
#extension GL_GOOGLE_include_directive : require
// fe-variant: FE_LIGHTS_IN_STORAGE (more lights than the uniform block holds: fe_scene.glsl)
// Forward shading of one light with a shadow map, added by a pass of its own.
#define FE_SHADOWED
#include "fe_forward_pass.glsl"

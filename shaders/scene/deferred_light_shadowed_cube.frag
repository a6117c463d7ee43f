#version 450
#extension GL_GOOGLE_include_directive : require
// fe-variant: FE_MULTISAMPLED (--msaa: a multisampled G-buffer, edge pixels shaded per sample: fe_gbuffer.glsl)
// Deferred lighting of a point light with a shadow cube.
#define FE_SHADOWED
#define FE_SHADOW_CUBE
#include "fe_deferred_light_pass.glsl"

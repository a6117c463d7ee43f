#version 450
#extension GL_GOOGLE_include_directive : require
// Deferred lighting of a light with a shadow map: a cascade array or a spot map.
#define FE_SHADOWED
#include "fe_deferred_light_pass.glsl"

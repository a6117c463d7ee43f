#version 450
#extension GL_GOOGLE_include_directive : require
// Deferred lighting, one light per volume fragment (fe_deferred_light_pass.glsl).
#include "fe_deferred_light_pass.glsl"

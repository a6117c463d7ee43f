#version 450
#extension GL_GOOGLE_include_directive : require
// Redeferred material pass: full rate, w_o.n rebuilt from depth and normal (fe_material_pass.glsl).
#define FE_REBUILD_NOV
#include "fe_scene.glsl"
#include "fe_material_pass.glsl"

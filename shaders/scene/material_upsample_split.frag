#version 450
#extension GL_GOOGLE_include_directive : require
// Redeferred material pass: reduced rate, only L_dg upsampled (fe_material_pass.glsl).
#define FE_UPSAMPLE
#define FE_SPLIT
#include "fe_scene.glsl"
#include "fe_material_pass.glsl"

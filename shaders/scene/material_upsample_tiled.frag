#version 450
#extension GL_GOOGLE_include_directive : require
// Redeferred material pass: reduced rate, every sum upsampled, with the representative pixels'
// data from the tiled illumination pass's I-buffer alphas (fe_material_pass.glsl).
#define FE_UPSAMPLE
#define FE_REP_IN_IBUFFER
#include "fe_scene.glsl"
#include "fe_material_pass.glsl"

#version 450
#extension GL_GOOGLE_include_directive : require
// Redeferred material pass: full rate, w_o.n from the G-buffer (fe_material_pass.glsl).
#include "fe_scene.glsl"
#include "fe_material_pass.glsl"

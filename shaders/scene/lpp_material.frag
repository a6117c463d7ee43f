#version 450
#extension GL_GOOGLE_include_directive : require
// Light pre-pass, pass 3 (fe_lpp_material_pass.glsl).
#include "fe_lpp_material_pass.glsl"

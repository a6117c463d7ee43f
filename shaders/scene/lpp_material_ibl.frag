#version 450
#extension GL_GOOGLE_include_directive : require
// Light pre-pass, pass 3, with image-based lighting (fe_lpp_material_pass.glsl with FE_IBL).
#define FE_IBL
#include "fe_lpp_material_pass.glsl"

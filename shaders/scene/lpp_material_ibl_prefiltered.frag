#version 450
#extension GL_GOOGLE_include_directive : require
// Light pre-pass, pass 3, with image-based lighting, the fast path.
#define FE_IBL
#define FE_IBL_PREFILTERED
#include "fe_lpp_material_pass.glsl"

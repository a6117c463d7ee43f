#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_common.glsl"
// The quad's colour, scaled by a specialization constant (one SPIR-V pair, two pipelines).
FE_CONSTANTS(Quad) { vec4 rect; vec4 color; } quad;
layout(constant_id = 0) const float kBrightness = 1.0;
layout(location = 0) out vec4 outColor;
void main() { outColor = vec4(quad.color.rgb * kBrightness, 1.0); }

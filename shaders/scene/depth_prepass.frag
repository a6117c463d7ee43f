#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_material.glsl"
// Depth pre-pass: no colour, only MASK materials' alpha test, so the EQUAL-tested shading pass
// sees exactly the surfaces it will shade.
void main() {
    if (feMaterialUses(64u) && object.params.w == 1.0 && feCoverageAlpha(vUv, vColor) < object.params.z) discard;
}

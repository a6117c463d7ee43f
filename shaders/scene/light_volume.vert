#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_scene.glsl"
// Light volumes for deferred and redeferred lighting: a unit sphere scaled to a point light's
// range, a cone for a spot light, or a full-screen triangle (directional or unbounded lights).
layout(location = 0) in vec3 inPosition;  // unit sphere / unit cone (apex at 0, base at z=1) / NDC triangle
layout(location = 1) in uint inLightIndex; // per instance
layout(location = 2) in uint inShape;      // per instance: 0 full screen, 1 sphere, 2 cone
// The light itself, for the fragment shader (fe_deferred_light_pass.glsl, fe_illumination_pass.glsl,
// fe_lpp_light_pass.glsl): flat inputs are set up once a triangle, where a storage-buffer read in
// the fragment shader is a loop over the SIMD lanes on CPU rasterizers, for every fragment.
layout(location = 0) flat out vec4 vLightWords[4];
void main() {
    GpuLight L = feLight(inLightIndex);
    vLightWords[0] = L.positionRange;
    vLightWords[1] = L.colorIntensity;
    vLightWords[2] = L.directionType;
    vLightWords[3] = L.spotScaleOffset;
    if (inShape == 0u) {
        gl_Position = vec4(inPosition.xy, 0.0, 1.0);
        return;
    }
    vec3 world;  // relative to the light, then to the eye (camera-relative, as mesh.vert)
    if (inShape == 1u) {
        world = inPosition * L.positionRange.w;
    } else {
        vec3 d = normalize(L.directionType.xyz);
        vec3 up = abs(d.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
        vec3 t = normalize(cross(up, d));
        vec3 b = cross(d, t);
        // outer angle from the falloff constants: cos(outer) = -o / s
        float cosOuter = clamp(-L.spotScaleOffset.y / L.spotScaleOffset.x, 0.0, 1.0);
        float tanOuter = sqrt(max(1.0 - cosOuter * cosOuter, 0.0)) / max(cosOuter, 1e-3);
        float r = L.positionRange.w;
        world = (t * inPosition.x * tanOuter + b * inPosition.y * tanOuter + d * inPosition.z) * r;
    }
    gl_Position = frame.viewProjFromEye * vec4((L.positionRange.xyz - frame.cameraPosition.xyz) + world, 1.0);
}

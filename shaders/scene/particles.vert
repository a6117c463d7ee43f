#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_common.glsl"
#include "fe_scene.glsl"
#include "fe_particles.glsl"
// A camera-facing quad per particle (two triangles, six vertices, one instance per particle of
// the list the indirect draw counts).
layout(binding = FE_SLOT_PARTICLES_SORTED, std430) readonly buffer Particles { GpuParticle particles[]; };
layout(location = 0) out vec4 vColor;
layout(location = 1) out vec2 vCorner;
layout(location = 2) out vec3 vWorld;
layout(location = 3) out float vSoftness;
void main() {
    const vec2 corners[6] = vec2[](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1), vec2(-1, 1));
    GpuParticle p = particles[FE_INSTANCE_ID];
    vec2 c = corners[FE_VERTEX_ID];
    // The view's right and up axes in world space: rows of the rigid view matrix.
    vec3 right = vec3(frame.view[0][0], frame.view[1][0], frame.view[2][0]);
    vec3 up = vec3(frame.view[0][1], frame.view[1][1], frame.view[2][1]);
    vWorld = p.positionSize.xyz + (c.x * right + c.y * up) * p.positionSize.w;
    vColor = p.color;
    vCorner = c;
    vSoftness = p.depth.y;
    gl_Position = frame.viewProj * vec4(vWorld, 1.0);
}

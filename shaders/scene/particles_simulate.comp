#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_scene.glsl"
#include "fe_particles.glsl"
// One invocation per particle slot of every emitter. Motion is closed-form (exact for a constant
// acceleration), so the state at time t needs no previous frame: every backend computes the same
// particles at any frame rate. Slot i is born at i / rate and again every slots / rate seconds,
// each time in a new random direction within the emitter's cone; the living ones are lit (alpha
// particles, by every scene light at their centre) and appended to their blend mode's list,
// whose count is the instance count of that list's indirect draw.
layout(local_size_x = 64) in;
layout(binding = FE_SLOT_PARTICLE_EMITTERS, std430) readonly buffer Emitters { GpuEmitter emitters[]; };
layout(binding = FE_SLOT_PARTICLES_ADDITIVE, std430) writeonly buffer Additive { GpuParticle additive[]; };
layout(binding = FE_SLOT_PARTICLES_ALPHA, std430) writeonly buffer Alpha { GpuParticle alpha[]; };
layout(binding = FE_SLOT_PARTICLE_ARGS, std430) buffer Args { DrawArgs args[2]; };  // 0 additive, 1 alpha

uint feHash(uint x) {  // a 32-bit integer hash (Wang-style mixing)
    x ^= x >> 16; x *= 0x7feb352du; x ^= x >> 15; x *= 0x846ca68bu; x ^= x >> 16;
    return x;
}
float feUnit(uint x) { return float(feHash(x) >> 8) * (1.0 / 16777216.0); }

void main() {
    uint slot = gl_GlobalInvocationID.x;
    if (slot >= uint(sim.time.z)) return;
    uint e = 0;
    while (e + 1 < uint(sim.time.y) && slot >= emitters[e + 1].slots.x) ++e;
    GpuEmitter em = emitters[e];
    uint i = slot - em.slots.x;
    float rate = em.positionRate.w, lifetime = em.gravityLifetime.w;
    float since = sim.time.x - float(i) / rate;  // since this slot's first birth
    if (since < 0.0) return;
    float period = float(em.slots.y) / rate;
    float cycle = floor(since / period);
    float age = since - cycle * period;
    if (age >= lifetime) return;
    float t = age / lifetime;
    // A direction within the cone about the velocity, new for every birth of the slot.
    uint seed = feHash(slot * 747796405u + uint(cycle) * 2891336453u);
    float cosTheta = mix(1.0, cos(em.velocitySpread.w), feUnit(seed));
    float phi = 6.2831853 * feUnit(seed ^ 0x9e3779b9u);
    float speed = length(em.velocitySpread.xyz);
    vec3 axis = speed > 0.0 ? em.velocitySpread.xyz / speed : vec3(0.0, 1.0, 0.0);
    vec3 helper = abs(axis.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    vec3 u = normalize(cross(helper, axis)), v = cross(axis, u);
    float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
    vec3 dir = cosTheta * axis + sinTheta * (cos(phi) * u + sin(phi) * v);
    vec3 p = em.positionRate.xyz + dir * speed * age + 0.5 * em.gravityLifetime.xyz * age * age;

    GpuParticle q;
    q.positionSize = vec4(p, mix(em.sizeSoftness.x, em.sizeSoftness.y, t));
    vec4 c = mix(em.colorStart, em.colorEnd, t);
    q.depth = vec4(distance(p, frame.cameraPosition.xyz), em.sizeSoftness.z, 0.0, 0.0);
    if (em.sizeSoftness.w > 0.5) {
        // Lit like a diffuse card facing each light: albedo / pi x the irradiance at its centre.
        vec3 E = vec3(0.0);
        for (uint l = 0; l < frame.lightRange.y; ++l) E += feEvaluateLight(feLight(l), p).E;
        q.color = vec4(c.rgb * E / 3.14159265, c.a);
        uint k = atomicAdd(args[1].instanceCount, 1u);
        if (k < FE_MAX_SORTED_PARTICLES) alpha[k] = q;
    } else {
        q.color = vec4(c.rgb * c.a, 1.0);
        uint k = atomicAdd(args[0].instanceCount, 1u);
        additive[k] = q;
    }
}

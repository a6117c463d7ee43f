// The VFX renderer's particle data (render/VfxRenderer.h; the C++ structs there match these).
#ifndef FE_PARTICLES_GLSL
#define FE_PARTICLES_GLSL

#define FE_SLOT_PARTICLE_EMITTERS 28
#define FE_SLOT_PARTICLES_ADDITIVE 29
#define FE_SLOT_PARTICLES_ALPHA 30
#define FE_SLOT_PARTICLE_ARGS 31
#define FE_SLOT_PARTICLES_SORTED 32
#define FE_SLOT_PARTICLE_SIM 33

#define FE_MAX_SORTED_PARTICLES 1024  // alpha-blended particles are sorted in one work group

struct GpuEmitter {
    vec4 positionRate;       // xyz birth position, w particles per second
    vec4 velocitySpread;     // xyz initial velocity, w cone half-angle (radians)
    vec4 gravityLifetime;    // xyz acceleration, w lifetime (s)
    vec4 colorStart;
    vec4 colorEnd;
    vec4 sizeSoftness;       // x start half-width, y end half-width, z softness (m), w 1 = alpha-blended
    uvec4 slots;             // x first slot, y slot count (rate x lifetime, rounded up)
};

struct GpuParticle {
    vec4 positionSize;  // xyz world position, w billboard half-width
    vec4 color;         // additive: radiance x alpha; alpha-blended: lit colour and opacity
    vec4 depth;         // x distance from the eye (sorting), y softness
};

struct DrawArgs {
    uint vertexCount, instanceCount, firstVertex, firstInstance;
};

layout(binding = FE_SLOT_PARTICLE_SIM, std140) uniform ParticleSim {
    vec4 time;     // x seconds since the system started, y emitter count, z total slots
} sim;

#endif

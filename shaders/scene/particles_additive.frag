#version 450
#extension GL_GOOGLE_include_directive : require
// Particles, additive (emitted light added to L_o) (fe_particles_pass.glsl).
#define FE_PARTICLES_ALPHA 0
#include "fe_particles_pass.glsl"

#version 450
#extension GL_GOOGLE_include_directive : require
// Particles, alpha-blended (source-over, back to front) (fe_particles_pass.glsl).
#define FE_PARTICLES_ALPHA 1
#include "fe_particles_pass.glsl"

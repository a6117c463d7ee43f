#version 450
#extension GL_GOOGLE_include_directive : require
#include "fe_scene.glsl"
#include "fe_particles.glsl"
// The alpha-blended list sorted back to front (farthest first) for blending: a bitonic sort of
// (distance, index) pairs in shared memory by one work group, then a gather into the sorted list.
layout(local_size_x = FE_MAX_SORTED_PARTICLES / 2) in;
layout(binding = FE_SLOT_PARTICLES_ALPHA, std430) readonly buffer Alpha { GpuParticle alpha[]; };
layout(binding = FE_SLOT_PARTICLES_SORTED, std430) writeonly buffer Sorted { GpuParticle sorted[]; };
layout(binding = FE_SLOT_PARTICLE_ARGS, std430) buffer Args { DrawArgs args[2]; };

shared float keys[FE_MAX_SORTED_PARTICLES];
shared uint indices[FE_MAX_SORTED_PARTICLES];

void main() {
    uint n = min(args[1].instanceCount, uint(FE_MAX_SORTED_PARTICLES));
    for (uint k = gl_LocalInvocationID.x; k < FE_MAX_SORTED_PARTICLES; k += gl_WorkGroupSize.x) {
        keys[k] = k < n ? -alpha[k].depth.x : 3.0e38;  // ascending keys: farthest first, padding last
        indices[k] = k;
    }
    barrier();
    for (uint size = 2; size <= FE_MAX_SORTED_PARTICLES; size <<= 1) {
        for (uint stride = size >> 1; stride > 0; stride >>= 1) {
            uint t = gl_LocalInvocationID.x;
            uint a = 2 * t - (t & (stride - 1));  // the lower element of this invocation's pair
            uint b = a + stride;
            bool ascending = (a & size) == 0;
            if ((keys[a] > keys[b]) == ascending) {
                float kk = keys[a]; keys[a] = keys[b]; keys[b] = kk;
                uint ii = indices[a]; indices[a] = indices[b]; indices[b] = ii;
            }
            barrier();
        }
    }
    for (uint k = gl_LocalInvocationID.x; k < n; k += gl_WorkGroupSize.x) sorted[k] = alpha[indices[k]];
    if (gl_LocalInvocationID.x == 0) args[1].instanceCount = n;  // the list holds at most the maximum
}

#version 450
#extension GL_GOOGLE_include_directive : require
// The depths the opaque surfaces of each light cluster hold (ClusterLightGrid, "cluster-bounds"):
// a work group per tile column of the grid, an invocation per pixel column of the tile walking
// its rows. Each cluster's bounds are the least and greatest depth-buffer depth of the pixels
// filed under it, as bits (non-negative floats order like their bit patterns); min > max: it
// holds no surface. The light assignment then files first the lights that reach the box of
// those depths (Olsson, Billeter and Assarsson 2012's tight cluster bounds): a far slice is
// metres deep, the wall a tile sees in it a few centimetres, and lights of 2.5 m range reach
// the slice's box far more often than the wall's.
// A pixel within 0.05 % of a slice's boundary counts in both slices: a shading pass compiled
// apart may round its view depth across the boundary, and must still find its depth inside the
// bounds of the cluster it reads.
// Cost on lavapipe, builtin:atrium at 1280x720: 6.4-7.4 ms with 32 invocations a group, 8-10 with
// 256 (eight rows of invocations): with no pixel read at all the larger groups took 4.3 ms, their
// barriers' switches between lanes. The atomics are 2 ms of it; one logarithm for both roundings
// instead of feClusterSlice's two measured no faster. It saves clustered-deferred's lighting
// 10-18 ms there (docs/BENCHMARKS.md, bench/sweeps/cluster-bounds.json).
#define FE_CLUSTER_SLICING_ONLY
#include "fe_common.glsl"
#include "fe_scene.glsl"
#include "fe_clusters.glsl"
layout(local_size_x = FE_CLUSTER_TILE) in;
layout(binding = FE_SLOT_DEPTH) uniform sampler2D depthTexture;
// Per cluster in header order: (least, greatest) depth bits.
layout(binding = FE_SLOT_CLUSTER_BOUNDS, std430) writeonly buffer ClusterBounds {
    uint boundWords[];
};

shared uint sLeast[FE_CLUSTER_SLICES], sGreatest[FE_CLUSTER_SLICES];

void note(int slice, uint least, uint greatest) {
    if (slice >= FE_CLUSTER_SLICES) return;  // past the last slice: every light is shaded there
    atomicMin(sLeast[slice], least);
    atomicMax(sGreatest[slice], greatest);
}

void main() {
    const uint lane = gl_LocalInvocationIndex;
    if (lane < FE_CLUSTER_SLICES) {
        sLeast[lane] = 0xffffffffu;
        sGreatest[lane] = 0u;
    }
    barrier();
    const ivec2 tile = ivec2(gl_WorkGroupID.xy);
    const ivec2 size = ivec2(frame.viewport.xy);
    // Neighbouring pixels mostly fall in one slice: each run of rows notes its bounds once.
    int runSlice = FE_CLUSTER_SLICES;
    uint runLeast = 0xffffffffu, runGreatest = 0u;
    for (int row = 0; row < FE_CLUSTER_TILE; ++row) {
        const ivec2 p = tile * FE_CLUSTER_TILE + ivec2(gl_LocalInvocationID.x, row);
        if (any(greaterThanEqual(p, size))) break;
        const float depth = texelFetch(depthTexture, p, 0).r;
        if (depth >= 1.0) continue;  // no surface
        const float v = feViewDepth(depth);
        const int nearer = feClusterSlice(v * 0.9995), farther = feClusterSlice(v * 1.0005);
        const uint bits = floatBitsToUint(depth);
        if (nearer != farther) note(farther, bits, bits);  // at a boundary: both slices
        if (nearer != runSlice) {
            note(runSlice, runLeast, runGreatest);
            runSlice = nearer;
            runLeast = 0xffffffffu;
            runGreatest = 0u;
        }
        runLeast = min(runLeast, bits);
        runGreatest = max(runGreatest, bits);
    }
    note(runSlice, runLeast, runGreatest);
    barrier();
    if (lane < FE_CLUSTER_SLICES) {
        const uint c = feClusterIndex(tile, int(lane));
        boundWords[2u * c] = sLeast[lane];
        boundWords[2u * c + 1u] = sGreatest[lane];
    }
}

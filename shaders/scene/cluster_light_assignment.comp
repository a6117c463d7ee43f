#version 450
#extension GL_GOOGLE_include_directive : require
// fe-variant: FE_LIGHTS_IN_STORAGE (scenes with more lights than a uniform block holds)
#define FE_TILE_LISTS  // only for the shared helpers (feTileSliceBox, feLightTouchesBox)
#define FE_CLUSTER_ASSIGN
#include "fe_tile_culling.glsl"
#include "fe_clusters.glsl"
// The light assignment pass of the clustered techniques (ClusterLightGrid.h): one invocation per
// tile column of the grid. A light is tested against the box around the whole column, then
// against the boxes of the slices its range sphere spans in view depth only (two levels, as
// tile_light_culling.comp: one test per light and column, not one per light and cluster).
// Every light of the scene is assigned (frame.counts.w), shadowed ones too: the translucent
// pass lights with all of them, the opaque passes stop at their own range.
layout(local_size_x = 64) in;

// Depth-buffer depth of view depth v (the inverse of feViewDepth).
float feDepthOfViewDepth(float v) {
    const float a = frame.invViewProj[2][3], b = frame.invViewProj[3][3];
    const float s = sign(a * 0.5 + b);
    return clamp((s / v - b) / a, 0.0, 1.0);
}

void main() {
    const ivec2 tiles = feClusterTiles();
    const int t = int(gl_GlobalInvocationID.x);
    if (t >= tiles.x * tiles.y) return;
    const ivec2 tile = ivec2(t % tiles.x, t / tiles.x);
    const vec2 p0 = vec2(tile * FE_CLUSTER_TILE), p1 = min(p0 + float(FE_CLUSTER_TILE), frame.viewport.xy);
    // Slice bounds in depth-buffer depth, each widened by 0.1 % of its view depth: a fragment
    // rounded across a boundary still lies inside the box of the slice it is filed under.
    float z[FE_CLUSTER_SLICES + 1];
    for (int k = 0; k <= FE_CLUSTER_SLICES; ++k) z[k] = feClusterSliceStart(k);
    vec3 lo[FE_CLUSTER_SLICES], hi[FE_CLUSTER_SLICES];
    for (int k = 0; k < FE_CLUSTER_SLICES; ++k)
        feTileSliceBox(p0, p1, feDepthOfViewDepth(z[k] * 0.999), feDepthOfViewDepth(z[k + 1] * 1.001), lo[k], hi[k]);
    vec3 columnLo, columnHi;
    feTileSliceBox(p0, p1, feDepthOfViewDepth(z[0] * 0.999), feDepthOfViewDepth(z[FE_CLUSTER_SLICES] * 1.001), columnLo, columnHi);
    // Two walks over the lights: the first counts each slice's list, then each non-empty list
    // reserves its room in the shared index array (one atomic add), the second fills them.
    uint count[FE_CLUSTER_SLICES];
    for (int k = 0; k < FE_CLUSTER_SLICES; ++k) count[k] = 0u;
    for (int pass = 0; pass < 2; ++pass) {
        for (uint i = 0u; i < frame.counts.w; ++i) {
            const GpuLight L = feLight(i);
            if (!feLightTouchesBox(L, columnLo, columnHi)) continue;
            int first = 0, last = FE_CLUSTER_SLICES - 1;
            if (L.directionType.w != FE_LIGHT_DIRECTIONAL && L.positionRange.w > 0.0) {
                // The slices the sphere spans along the view axis, one more each side for rounding.
                const float v = -(frame.view * vec4(L.positionRange.xyz, 1.0)).z, r = L.positionRange.w;
                first = max(feClusterSlice(v - r) - 1, 0);
                last = min(feClusterSlice(v + r) + 1, FE_CLUSTER_SLICES - 1);
            }
            for (int k = first; k <= last; ++k) {
                if (!feLightTouchesBox(L, lo[k], hi[k])) continue;
                if (pass == 1) {
                    const uint header = feClusterHeader(tile, k);
                    if (clusterWords[header + 1u] != 0xffffffffu) clusterWords[clusterWords[header] + count[k]] = i;
                }
                ++count[k];
            }
        }
        if (pass == 1) break;
        const uint start = feClusterListsStart(), capacity = feClusterCapacity();
        for (int k = 0; k < FE_CLUSTER_SLICES; ++k) {
            const uint header = feClusterHeader(tile, k);
            const uint base = count[k] == 0u ? 0u : atomicAdd(clusterWords[0], count[k]);
            const bool fits = base + count[k] <= capacity && base + count[k] >= base;
            clusterWords[header] = start + base;
            clusterWords[header + 1u] = fits ? count[k] : 0xffffffffu;
            count[k] = 0u;  // the second walk counts again, as it writes
        }
    }
}

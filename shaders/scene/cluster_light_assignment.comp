#version 450
#extension GL_GOOGLE_include_directive : require
// fe-variant: FE_LIGHTS_IN_STORAGE (scenes with more lights than a uniform block holds)
#define FE_TILE_LISTS  // only for the shared helpers (feTileSliceBox, feLightTouchesBox)
#define FE_CLUSTER_ASSIGN
#include "fe_tile_culling.glsl"
#include "fe_clusters.glsl"
// The light assignment pass of the clustered techniques (ClusterLightGrid.h): one work group
// per tile column of the grid, its 64 invocations taking the lights 64 at a time. A light is
// tested against the box around the whole column, then against the boxes of the slices its
// range sphere spans in view depth only (two levels, as tile_light_culling.comp: one test per
// light and column, not one per light and cluster). Each invocation notes the slices its light
// reaches in a bit mask; per slice, the invocations' bits (a 64-bit ballot in shared memory)
// give each light its place in the slice's list, so lists stay in increasing light order with
// no serial walk. (One invocation per column walking every light, as this pass first did, kept
// 920 invocations busy for 1.4 ms on an H200 at 1024 lights: far too few to fill a GPU.)
// Every light of the scene is assigned (frame.counts.w), shadowed ones too: the translucent
// pass lights with all of them, the opaque passes stop at their own range.
#if FE_CLUSTER_SLICES > 32
#error "a light's slices are a 32-bit mask"
#endif
layout(local_size_x = 64) in;

// Depth-buffer depth of view depth v (the inverse of feViewDepth).
float feDepthOfViewDepth(float v) {
    const float a = frame.invViewProj[2][3], b = frame.invViewProj[3][3];
    const float s = sign(a * 0.5 + b);
    return clamp((s / v - b) / a, 0.0, 1.0);
}

shared vec3 sLo[FE_CLUSTER_SLICES + 1], sHi[FE_CLUSTER_SLICES + 1];  // the slices' boxes, then the column's
shared uint sBallot[2 * FE_CLUSTER_SLICES];  // per slice: which of the 64 invocations' lights reach it
shared uint sCount[FE_CLUSTER_SLICES];       // per slice: lights listed so far
shared uint sStart[FE_CLUSTER_SLICES];       // per slice: where its list begins (second walk)
shared bool sFits[FE_CLUSTER_SLICES];

// The slices the light reaches, as a bit mask.
uint feSlicesReached(uint i) {
    const GpuLight L = feLight(i);
    if (!feLightTouchesBox(L, sLo[FE_CLUSTER_SLICES], sHi[FE_CLUSTER_SLICES])) return 0u;
    int first = 0, last = FE_CLUSTER_SLICES - 1;
    if (L.directionType.w != FE_LIGHT_DIRECTIONAL && L.positionRange.w > 0.0) {
        // The slices the sphere spans along the view axis, one more each side for rounding.
        const float v = -(frame.view * vec4(L.positionRange.xyz, 1.0)).z, r = L.positionRange.w;
        first = max(feClusterSlice(v - r) - 1, 0);
        last = min(feClusterSlice(v + r) + 1, FE_CLUSTER_SLICES - 1);
    }
    uint mask = 0u;
    for (int k = first; k <= last; ++k)
        if (feLightTouchesBox(L, sLo[k], sHi[k])) mask |= 1u << k;
    return mask;
}

void main() {
    const ivec2 tiles = feClusterTiles();
    const int t = int(gl_WorkGroupID.x);
    const uint lane = gl_LocalInvocationIndex;
    const ivec2 tile = ivec2(t % tiles.x, t / tiles.x);
    const vec2 p0 = vec2(tile * FE_CLUSTER_TILE), p1 = min(p0 + float(FE_CLUSTER_TILE), frame.viewport.xy);
    // Slice bounds in depth-buffer depth, each widened by 0.1 % of its view depth: a fragment
    // rounded across a boundary still lies inside the box of the slice it is filed under.
    if (lane <= uint(FE_CLUSTER_SLICES)) {
        const int k = int(lane);
        const float z0 = k == FE_CLUSTER_SLICES ? feClusterSliceStart(0) : feClusterSliceStart(k);
        const float z1 = feClusterSliceStart(k == FE_CLUSTER_SLICES ? FE_CLUSTER_SLICES : k + 1);
        feTileSliceBox(p0, p1, feDepthOfViewDepth(z0 * 0.999), feDepthOfViewDepth(z1 * 1.001), sLo[k], sHi[k]);
    }
    if (lane < uint(FE_CLUSTER_SLICES)) sCount[lane] = 0u;
    if (lane < uint(2 * FE_CLUSTER_SLICES)) sBallot[lane] = 0u;
    barrier();
    const uint below = lane < 32u ? (1u << lane) - 1u : (lane == 32u ? 0u : (1u << (lane - 32u)) - 1u);
    // Two walks over the lights: the first counts each slice's list, then each non-empty list
    // reserves its room in the shared index array (one atomic add), the second fills them.
    for (int pass = 0; pass < 2; ++pass) {
        for (uint base = 0u; base < frame.counts.w; base += 64u) {
            const uint i = base + lane;
            const uint mask = i < frame.counts.w ? feSlicesReached(i) : 0u;
            for (uint m = mask; m != 0u; m &= m - 1u)
                atomicOr(sBallot[2 * findLSB(m) + (lane >> 5)], 1u << (lane & 31u));
            barrier();
            if (pass == 1) {
                for (uint m = mask; m != 0u; m &= m - 1u) {
                    const int k = findLSB(m);
                    if (!sFits[k]) continue;
                    const uint before = lane < 32u ? bitCount(sBallot[2 * k] & below)
                                                   : bitCount(sBallot[2 * k]) + bitCount(sBallot[2 * k + 1] & below);
                    clusterWords[sStart[k] + sCount[k] + before] = i;
                }
            }
            barrier();
            if (lane < uint(FE_CLUSTER_SLICES)) {
                sCount[lane] += bitCount(sBallot[2 * lane]) + bitCount(sBallot[2 * lane + 1]);
                sBallot[2 * lane] = sBallot[2 * lane + 1] = 0u;
            }
            barrier();
        }
        if (pass == 1) break;
        if (lane < uint(FE_CLUSTER_SLICES)) {
            const int k = int(lane);
            const uint count = sCount[k];
            const uint header = feClusterHeader(tile, k);
            const uint reserved = count == 0u ? 0u : atomicAdd(clusterWords[0], count);
            const bool fits = reserved + count <= feClusterCapacity() && reserved + count >= reserved;
            clusterWords[header] = feClusterListsStart() + reserved;
            clusterWords[header + 1u] = fits ? count : 0xffffffffu;
            sStart[k] = feClusterListsStart() + reserved;
            sFits[k] = fits;
            sCount[k] = 0u;  // the second walk counts again, as it writes
        }
        barrier();
    }
}

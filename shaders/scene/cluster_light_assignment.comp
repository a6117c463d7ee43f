#version 450
#extension GL_GOOGLE_include_directive : require
// fe-variant: FE_LIGHTS_IN_STORAGE (scenes with more lights than a uniform block holds)
#define FE_TILE_LISTS  // only for the shared helpers (feTileSliceBox, feLightTouchesBox)
#define FE_CLUSTER_ASSIGN
#include "fe_common.glsl"
#include "fe_tile_culling.glsl"
#include "fe_clusters.glsl"
// The light assignment pass of the clustered techniques (ClusterLightGrid.h), four dispatches
// chosen by assignment.phase.x, each a barrier apart:
//  0. Blocks: one work group per block of FE_ASSIGN_BLOCK x FE_ASSIGN_BLOCK tile columns marks,
//     in a bit mask of the lights, those that reach the block's part of the frustum (its box and
//     four side planes). The columns below walk only their block's marked lights: on lavapipe,
//     testing every light against every column twice took most of the pass.
//  1. Count: one work group per tile column of the grid, each of its 64 invocations taking a 64th
//     of the lights, in order. A light is tested against the box around the whole column and the
//     column's four side planes, then against the boxes of the slices its range sphere spans in
//     view depth only (two levels, as tile_light_culling.comp: one test per light and column, not
//     one per light and cluster).
//     Each cluster's length goes to its header.
//  2. Place: one work group turns the lengths, in header order, into each list's first word (an
//     exclusive prefix), so the layout is the same on every device and every run (a capture's
//     read-back compares byte by byte; atomic reservations land in the order threads happen to
//     run); a list past the shared index array's end is marked to shade every light.
//  3. Fill: as 1, each invocation's lights placed after those of the invocations before it (a
//     prefix over the shares), so lists stay in increasing light order.
// (One invocation per column walking every light, as this pass first did, left an H200 mostly
// idle: 920 invocations, 1.4 ms at 1024 lights.) Every light of the scene is assigned
// (frame.counts.w), shadowed ones too: the translucent pass lights with all of them, the opaque
// passes stop at their own range.
#if FE_CLUSTER_SLICES > 32
#error "a light's slices are a 32-bit mask"
#endif
#define FE_ASSIGN_LANES 64
layout(local_size_x = FE_ASSIGN_LANES) in;
#define FE_ASSIGN_BLOCK 4  // ClusterLightGrid::kBlockColumns
FE_CONSTANTS(AssignmentConstants) {
    uvec4 phase;  // x: 0 blocks, 1 count, 2 place, 3 fill
} assignment;
// Per block of columns (row-major), (frame.counts.w + 31) / 32 words: bit i of the lights that
// may reach the block (ClusterLightGrid's block masks).
layout(binding = FE_SLOT_CLUSTER_BLOCKS, std430) buffer ClusterBlocks {
    uint blockWords[];
};

// Depth-buffer depth of view depth v (the inverse of feViewDepth).
float feDepthOfViewDepth(float v) {
    const float a = frame.invViewProj[2][3], b = frame.invViewProj[3][3];
    const float s = sign(a * 0.5 + b);
    return clamp((s / v - b) / a, 0.0, 1.0);
}

shared vec3 sLo[FE_CLUSTER_SLICES + 1], sHi[FE_CLUSTER_SLICES + 1];  // the slices' boxes, then the column's
// The column's four side planes through the eye, as inward unit normals in eye space. A slice's
// box is loose where the column runs oblique to the world's axes (towards the screen's edges: a
// thin slab's box spans its depth times the slope); a sphere wholly outside a side plane misses
// every slice of the column, which the boxes alone do not see.
shared vec3 sSide[4];
shared uint sCount[FE_CLUSTER_SLICES][FE_ASSIGN_LANES];  // per slice and share: its lights, then its first word
shared uint sTotal[FE_ASSIGN_LANES];                     // phase 2: each invocation's run of lengths
shared bool sNoRoom[FE_CLUSTER_SLICES];                  // phase 3: the slice's list did not fit

// Whether the light's range sphere reaches the part of the frustum in sLo/sHi[FE_CLUSTER_SLICES]
// and inside sSide's planes; `margin` scales its range (rounding).
bool feReachesColumn(GpuLight L, float margin) {
    if (L.directionType.w == FE_LIGHT_DIRECTIONAL || L.positionRange.w <= 0.0) return true;
    if (!feLightTouchesBox(L, sLo[FE_CLUSTER_SLICES], sHi[FE_CLUSTER_SLICES])) return false;
    const vec3 eye = L.positionRange.xyz - frame.cameraPosition.xyz;
    const float reach = L.positionRange.w * margin + 1e-4;  // feLightTouchesBox's rounding margin
    for (int j = 0; j < 4; ++j)
        if (dot(sSide[j], eye) < -reach) return false;
    return true;
}

// The slices the light reaches, as a bit mask.
uint feSlicesReached(uint i) {
    const GpuLight L = feLight(i);
    if (!feReachesColumn(L, 1.0001)) return 0u;
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

// Phase 2: the lists' first words from their lengths, in header order.
void placeLists() {
    const ivec2 tiles = feClusterTiles();
    const uint clusters = uint(tiles.x * tiles.y * FE_CLUSTER_SLICES), lane = gl_LocalInvocationIndex;
    const uint run = (clusters + FE_ASSIGN_LANES - 1u) / FE_ASSIGN_LANES;
    const uint begin = min(lane * run, clusters), end = min(begin + run, clusters);
    uint sum = 0u;
    for (uint c = begin; c < end; ++c) sum += clusterWords[2u + 2u * c];
    sTotal[lane] = sum;
    barrier();
    uint place = 0u, total = 0u;
    for (uint j = 0u; j < FE_ASSIGN_LANES; ++j) {
        place += j < lane ? sTotal[j] : 0u;
        total += sTotal[j];
    }
    const uint start = feClusterListsStart(), capacity = feClusterCapacity();
    for (uint c = begin; c < end; ++c) {
        const uint count = clusterWords[2u + 2u * c];
        clusterWords[1u + 2u * c] = start + place;
        if (place + count > capacity) clusterWords[2u + 2u * c] = 0xffffffffu;  // no room: every light
        place += count;
    }
    if (lane == 0u) clusterWords[0] = total;  // the entries the lists asked for (statistics)
}

// The frustum part of the pixels [p0, p1): its box from the near plane to the far side of the
// slices in sLo/sHi[FE_CLUSTER_SLICES], with `slices` the boxes of the slices too, and its four
// side planes in sSide. Every invocation calls it; a barrier must follow.
void feSetUpFrustum(vec2 p0, vec2 p1, bool slices) {
    const uint lane = gl_LocalInvocationIndex;
    // Slice bounds in depth-buffer depth, each widened by 0.1 % of its view depth: a fragment
    // rounded across a boundary still lies inside the box of the slice it is filed under.
    if (lane <= uint(FE_CLUSTER_SLICES) && (slices || lane == uint(FE_CLUSTER_SLICES))) {
        const int k = int(lane);
        const float z0 = feClusterSliceStart(k == FE_CLUSTER_SLICES ? 0 : k);
        const float z1 = feClusterSliceStart(k == FE_CLUSTER_SLICES ? FE_CLUSTER_SLICES : k + 1);
        feTileSliceBox(p0, p1, feDepthOfViewDepth(z0 * 0.999), feDepthOfViewDepth(z1 * 1.001), sLo[k], sHi[k]);
        if (!slices) {  // a block's box holds its columns' boxes, whatever their corners' rounding
            const vec3 pad = (sHi[k] - sLo[k]) * 1e-4 + 1e-4;
            sLo[k] -= pad;
            sHi[k] += pad;
        }
    }
    if (lane < 4u) {
        // Two corner rays of the edge j (left, right, top, bottom), at the far end of the slices;
        // the normal points towards the centre ray.
        const float z = feDepthOfViewDepth(frame.clusters.z);
        const vec2 a = vec2(lane == 1u ? p1.x : p0.x, lane == 3u ? p1.y : p0.y);
        const vec2 b = lane < 2u ? vec2(a.x, p1.y) : vec2(p1.x, a.y);
        vec3 n = normalize(cross(feEyeFromDepth(a, z), feEyeFromDepth(b, z)));
        if (dot(n, feEyeFromDepth(0.5 * (p0 + p1), z)) < 0.0) n = -n;
        sSide[lane] = n;
    }
}

ivec2 feAssignBlocks() { return (feClusterTiles() + FE_ASSIGN_BLOCK - 1) / FE_ASSIGN_BLOCK; }
uint feMaskWords() { return (frame.counts.w + 31u) / 32u; }

// Phase 0: the lights that may reach the block of columns of this work group.
void markBlock() {
    const ivec2 blocks = feAssignBlocks();
    const int b = int(gl_WorkGroupID.x);
    const vec2 p0 = vec2(ivec2(b % blocks.x, b / blocks.x) * (FE_ASSIGN_BLOCK * FE_CLUSTER_TILE));
    feSetUpFrustum(p0, min(p0 + float(FE_ASSIGN_BLOCK * FE_CLUSTER_TILE), frame.viewport.xy), false);
    barrier();
    const uint words = feMaskWords(), base = uint(b) * words;
    for (uint w = gl_LocalInvocationIndex; w < words; w += FE_ASSIGN_LANES) {
        uint bits = 0u;
        for (uint j = 0u; j < 32u && w * 32u + j < frame.counts.w; ++j)
            if (feReachesColumn(feLight(w * 32u + j), 1.01)) bits |= 1u << j;  // a wider margin than a column's
        if (base + w < uint(blockWords.length())) blockWords[base + w] = bits;
    }
}

// Word w of the mask of the block at `base`, the bits of lights [begin, end) only (every bit
// where the buffer is short).
uint feBlockBits(uint base, uint w, uint begin, uint end) {
    uint bits = base + w < uint(blockWords.length()) ? blockWords[base + w] : 0xffffffffu;
    const uint first = w * 32u;
    if (begin > first) bits &= 0xffffffffu << (begin - first);
    if (end < first + 32u) bits &= (1u << (end - first)) - 1u;
    return bits;
}

void main() {
    if (assignment.phase.x == 0u) {
        markBlock();
        return;
    }
    if (assignment.phase.x == 2u) {
        placeLists();
        return;
    }
    const bool fill = assignment.phase.x == 3u;
    const ivec2 tiles = feClusterTiles();
    const int t = int(gl_WorkGroupID.x);
    const uint lane = gl_LocalInvocationIndex;
    const ivec2 tile = ivec2(t % tiles.x, t / tiles.x);
    const vec2 p0 = vec2(tile * FE_CLUSTER_TILE);
    feSetUpFrustum(p0, min(p0 + float(FE_CLUSTER_TILE), frame.viewport.xy), true);
    for (int k = 0; k < FE_CLUSTER_SLICES; ++k) sCount[k][lane] = 0u;
    barrier();
    // This invocation's share of the lights: [begin, end), in order; of those, its block's marked.
    const uint share = (frame.counts.w + FE_ASSIGN_LANES - 1u) / FE_ASSIGN_LANES;
    const uint begin = min(lane * share, frame.counts.w), end = min(begin + share, frame.counts.w);
    const ivec2 block = tile / FE_ASSIGN_BLOCK;
    const uint base = uint(block.y * feAssignBlocks().x + block.x) * feMaskWords();
    for (uint w = begin / 32u; w * 32u < end; ++w)
        for (uint b = feBlockBits(base, w, begin, end); b != 0u; b &= b - 1u)
            for (uint m = feSlicesReached(w * 32u + uint(findLSB(b))); m != 0u; m &= m - 1u) ++sCount[findLSB(m)][lane];
    barrier();
    if (lane < uint(FE_CLUSTER_SLICES)) {
        const int k = int(lane);
        uint count = 0u;
        for (int j = 0; j < FE_ASSIGN_LANES; ++j) {  // exclusive prefix: each share's place
            const uint c = sCount[k][j];
            sCount[k][j] = count;
            count += c;
        }
        const uint header = feClusterHeader(tile, k);
        if (!fill) {
            clusterWords[header + 1u] = count;
        } else {  // each share's first word, the list's place read once (measured 4-6 ms of 44-63 here)
            sNoRoom[k] = clusterWords[header + 1u] == 0xffffffffu;
            const uint first = sNoRoom[k] ? 0u : clusterWords[header];
            for (int j = 0; j < FE_ASSIGN_LANES; ++j) sCount[k][j] += first;
        }
    }
    if (!fill) return;
    barrier();
    for (uint w = begin / 32u; w * 32u < end; ++w)
        for (uint b = feBlockBits(base, w, begin, end); b != 0u; b &= b - 1u) {
            const uint i = w * 32u + uint(findLSB(b));
            for (uint m = feSlicesReached(i); m != 0u; m &= m - 1u) {
                const int k = findLSB(m);
                if (!sNoRoom[k]) clusterWords[sCount[k][lane]] = i;
                ++sCount[k][lane];
            }
        }
}

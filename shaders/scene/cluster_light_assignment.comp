#version 450
#extension GL_GOOGLE_include_directive : require
// fe-variant: FE_LIGHTS_IN_STORAGE (scenes with more lights than a uniform block holds)
#define FE_TILE_LISTS  // only for the shared helpers (feTileSliceBox, feLightTouchesBox)
#define FE_CLUSTER_ASSIGN
#include "fe_common.glsl"
#include "fe_tile_culling.glsl"
#include "fe_clusters.glsl"
// The light assignment pass of the clustered techniques (ClusterLightGrid.h), four dispatches
// chosen by assignment.phase.x, each a barrier apart, each (but 2) a work group per tile column
// of the grid:
//  0. Columns: the invocations take the lights 32 at a time and mark, in the column's bit mask
//     of the lights, those whose range reaches the column's part of the frustum (its box over
//     every slice and its four side planes).
//  1. Count: one invocation per slice. Every invocation walks the column's marked lights in
//     order, together (the same light in every lane: a broadcast load); a light that spans the
//     invocation's slice in view depth is tested against the slice's box, and where the grid has
//     the opaque depths' bounds (assignment.phase.y, cluster_bounds.comp) against the box of the
//     depths the cluster's surfaces hold. Each cluster's length, and its bounded part's, go to
//     its header; without blended readers (assignment.phase.z 0) a list holds only that part.
//  2. Place: one work group turns the lengths, in header order, into each list's first word (an
//     exclusive prefix), so the layout is the same on every device and every run (a capture's
//     read-back compares byte by byte; atomic reservations land in the order threads happen to
//     run); a list past the shared index array's end is marked to shade every light.
//  3. Fill: as 1, the bounded part first, then the rest, each in increasing light order.
// Each test has the lanes it suits: the column's test the lights, the slice's the slices; no
// shared memory and no barrier but in 2. The pass it replaces (64 invocations a column, each a
// 64th of the lights, counts per slice and share in shared memory, prefixes over the shares)
// took 77 ms with 8 lights and 146 ms with 1024 at 1280x720 on lavapipe, whose shared-memory
// loads at per-lane addresses are a loop over the SIMD lanes (docs/MEASUREMENT_LOG.md); one
// invocation per column walking every light, as this pass first did, left an H200 mostly idle
// (920 invocations, 1.4 ms at 1024 lights). Every light of the scene is assigned
// (frame.counts.w), shadowed ones too: the translucent pass lights with all of them, the opaque
// passes stop at their own range.
#define FE_ASSIGN_LANES FE_CLUSTER_SLICES
layout(local_size_x = FE_ASSIGN_LANES) in;
FE_CONSTANTS(AssignmentConstants) {
    uvec4 phase;  // x: 0 columns, 1 count, 2 place, 3 fill; y: bounded by the opaque depths; z: whole lists read
} assignment;
// Per tile column (row-major), (frame.counts.w + 31) / 32 words: bit i set where light i reaches
// the column (ClusterLightGrid's column masks).
layout(binding = FE_SLOT_CLUSTER_COLUMNS, std430) buffer ClusterColumns {
    uint columnWords[];
};
// Per cluster in header order: the least and greatest depth its opaque surfaces hold, as bits
// (cluster_bounds.comp); bound only where assignment.phase.y says so.
layout(binding = FE_SLOT_CLUSTER_BOUNDS, std430) readonly buffer ClusterBounds {
    uint boundWords[];
};

// Depth-buffer depth of view depth v (the inverse of feViewDepth).
float feDepthOfViewDepth(float v) {
    const float a = frame.invViewProj[2][3], b = frame.invViewProj[3][3];
    const float s = sign(a * 0.5 + b);
    return clamp((s / v - b) / a, 0.0, 1.0);
}

// A part of the frustum: the pixels [p0, p1) from the near plane to the far side of the slices:
// its box, and its four side planes through the eye as inward unit normals in eye space. A box
// is loose where the part runs oblique to the world's axes (towards the screen's edges: a thin
// slab's box spans its depth times the slope); a sphere wholly outside a side plane misses it,
// which the box alone does not see.
struct FrustumPart {
    vec3 lo, hi;
    vec3 side[4];
};

// The box of the depth-buffer depths [z0, z1) over the pixels [p0, p1), each bound widened by
// 0.1 % of its view depth: a fragment rounded across a slice boundary still lies inside the box
// of the slice it is filed under.
void feSliceBox(vec2 p0, vec2 p1, float v0, float v1, out vec3 lo, out vec3 hi) {
    feTileSliceBox(p0, p1, feDepthOfViewDepth(v0 * 0.999), feDepthOfViewDepth(v1 * 1.001), lo, hi);
}

FrustumPart feFrustumPart(vec2 p0, vec2 p1) {
    FrustumPart f;
    feSliceBox(p0, p1, feClusterSliceStart(0), feClusterSliceStart(FE_CLUSTER_SLICES), f.lo, f.hi);
    const float z = feDepthOfViewDepth(frame.clusters.z);
    const vec3 centre = feEyeFromDepth(0.5 * (p0 + p1), z);
    for (int j = 0; j < 4; ++j) {
        // Two corner rays of the edge j (left, right, top, bottom), at the far end of the slices;
        // the normal points towards the centre ray.
        const vec2 a = vec2(j == 1 ? p1.x : p0.x, j == 3 ? p1.y : p0.y);
        const vec2 b = j < 2 ? vec2(a.x, p1.y) : vec2(p1.x, a.y);
        vec3 n = normalize(cross(feEyeFromDepth(a, z), feEyeFromDepth(b, z)));
        f.side[j] = dot(n, centre) < 0.0 ? -n : n;
    }
    return f;
}

// Whether the light's range sphere reaches the frustum part; `margin` scales its range (rounding).
bool feReachesPart(GpuLight L, FrustumPart f, float margin) {
    if (L.directionType.w == FE_LIGHT_DIRECTIONAL || L.positionRange.w <= 0.0) return true;
    if (!feLightTouchesBox(L, f.lo, f.hi)) return false;
    const vec3 eye = L.positionRange.xyz - frame.cameraPosition.xyz;
    const float reach = L.positionRange.w * margin + 1e-4;  // feLightTouchesBox's rounding margin
    for (int j = 0; j < 4; ++j)
        if (dot(f.side[j], eye) < -reach) return false;
    return true;
}

// The view depths a light's range must overlap to reach slice k: those of the slices k - 1 to
// k + 1 (one more each side for rounding), unbounded past the first and last. Compared directly,
// not by the slice of each end (a logarithm per light and lane: 4x over in a column's 32 lanes
// on an 8-lane CPU).
vec2 feSliceReach(int k) {
    return vec2(k >= 1 ? feClusterSliceStart(k - 1) : -3.0e38, k + 2 <= FE_CLUSTER_SLICES ? feClusterSliceStart(k + 2) : 3.0e38);
}

// Whether the light reaches slice k, whose box is [lo, hi] and depths `reach` (feSliceReach),
// of a column it reaches.
bool feReachesSlice(GpuLight L, vec2 reach, vec3 lo, vec3 hi) {
    if (L.directionType.w != FE_LIGHT_DIRECTIONAL && L.positionRange.w > 0.0) {
        const float v = -(frame.view * vec4(L.positionRange.xyz, 1.0)).z, r = L.positionRange.w;
        if (v + r < reach.x || v - r >= reach.y) return false;
    }
    return feLightTouchesBox(L, lo, hi);
}

shared uint sTotal[FE_ASSIGN_LANES];  // phase 2: each invocation's run of lengths

// Phase 2: the lists' first words from their lengths, in header order.
void placeLists() {
    const ivec2 tiles = feClusterTiles();
    const uint clusters = uint(tiles.x * tiles.y * FE_CLUSTER_SLICES), lane = gl_LocalInvocationIndex;
    const uint run = (clusters + FE_ASSIGN_LANES - 1u) / FE_ASSIGN_LANES;
    const uint begin = min(lane * run, clusters), end = min(begin + run, clusters);
    uint sum = 0u;
    for (uint c = begin; c < end; ++c) sum += clusterWords[2u + FE_CLUSTER_HEADER * c];
    sTotal[lane] = sum;
    barrier();
    uint place = 0u, total = 0u;
    for (uint j = 0u; j < FE_ASSIGN_LANES; ++j) {
        place += j < lane ? sTotal[j] : 0u;
        total += sTotal[j];
    }
    const uint capacity = feClusterCapacity();
    for (uint c = begin; c < end; ++c) {
        const uint count = clusterWords[2u + FE_CLUSTER_HEADER * c];
        clusterWords[1u + FE_CLUSTER_HEADER * c] = place;
        if (place + count > capacity) clusterWords[2u + FE_CLUSTER_HEADER * c] = 0xffffffffu;  // no room: every light
        place += count;
    }
    if (lane == 0u) clusterWords[0] = total;  // the entries the lists asked for (statistics)
}

uint feMaskWords() { return (frame.counts.w + 31u) / 32u; }

// This work group's column: its tile and pixels [p0, p1).
ivec2 feColumnTile() { return ivec2(int(gl_WorkGroupID.x) % feClusterTiles().x, int(gl_WorkGroupID.x) / feClusterTiles().x); }
vec2 feColumnStart() { return vec2(feColumnTile() * FE_CLUSTER_TILE); }
vec2 feColumnEnd() { return min(feColumnStart() + float(FE_CLUSTER_TILE), frame.viewport.xy); }

// Phase 0: the lights that reach this work group's column.
void markColumn() {
    const FrustumPart column = feFrustumPart(feColumnStart(), feColumnEnd());
    const uint words = feMaskWords(), base = gl_WorkGroupID.x * words;
    for (uint w = gl_LocalInvocationIndex; w < words; w += FE_ASSIGN_LANES) {
        uint bits = 0u;
        for (uint j = 0u; j < 32u && w * 32u + j < frame.counts.w; ++j)
            if (feReachesPart(feLight(w * 32u + j), column, 1.0001)) bits |= 1u << j;
        if (base + w < uint(columnWords.length())) columnWords[base + w] = bits;
    }
}

// The box and view depths of the opaque surfaces cluster c holds, widened by 0.1 % of their view
// depth as the slices' are; false where it holds none.
bool feClusterSurfaceBox(uint c, out vec3 lo, out vec3 hi, out vec2 reach) {
    const uint least = boundWords[2u * c], greatest = boundWords[2u * c + 1u];
    if (least > greatest) return false;
    const float v0 = feViewDepth(uintBitsToFloat(least)), v1 = feViewDepth(uintBitsToFloat(greatest));
    reach = vec2(min(v0, v1) * 0.999, max(v0, v1) * 1.001);
    feSliceBox(feColumnStart(), feColumnEnd(), min(v0, v1), max(v0, v1), lo, hi);
    return true;
}

// Phases 1 and 3: this invocation's cluster (slice k of the work group's column).
void assignCluster(bool fill) {
    const int k = int(gl_LocalInvocationIndex);
    vec3 lo, hi;
    feSliceBox(feColumnStart(), feColumnEnd(), feClusterSliceStart(k), feClusterSliceStart(k + 1), lo, hi);
    const vec2 reach = feSliceReach(k);
    const uint header = feClusterHeader(feColumnTile(), k);
    const bool bounded = assignment.phase.y != 0u, whole = assignment.phase.z != 0u;
    vec3 surfaceLo = vec3(0.0), surfaceHi = vec3(0.0);
    vec2 surfaceReach = vec2(0.0);
    const bool surfaces = bounded && feClusterSurfaceBox(feClusterIndex(feColumnTile(), k), surfaceLo, surfaceHi, surfaceReach);
    const bool noRoom = fill && clusterWords[header + 1u] == 0xffffffffu;
    const uint first = fill && !noRoom ? clusterWords[header] : 0u;
    const uint boundedLength = fill ? clusterWords[header + 2u] : 0u;
    const uint words = feMaskWords(), base = gl_WorkGroupID.x * words;
    uint count = 0u, inBounds = 0u;
    for (uint w = 0u; w < words; ++w) {
        // Every light where the buffer is short (ClusterLightGrid sizes it for the scene's lights).
        uint bits = base + w < uint(columnWords.length()) ? columnWords[base + w] : 0xffffffffu;
        if (w == words - 1u && (frame.counts.w & 31u) != 0u) bits &= (1u << (frame.counts.w & 31u)) - 1u;
        for (; bits != 0u; bits &= bits - 1u) {
            const uint i = w * 32u + uint(findLSB(bits));
            const GpuLight L = feLight(i);
            if (!feReachesSlice(L, reach, lo, hi)) continue;
            const bool reachesSurfaces = !bounded || (surfaces && feReachesSlice(L, surfaceReach, surfaceLo, surfaceHi));
            if (!reachesSurfaces && !whole) continue;
            if (fill && !noRoom) {
                const uint e = reachesSurfaces ? inBounds : boundedLength + count - inBounds;
                imageStore(clusterIndicesOut, feClusterEntryTexel(first + e), uvec4(i));
            }
            ++count;
            inBounds += reachesSurfaces ? 1u : 0u;
        }
    }
    if (!fill) {
        clusterWords[header + 1u] = count;
        clusterWords[header + 2u] = inBounds;
    }
}

void main() {
    switch (assignment.phase.x) {
        case 0u: markColumn(); break;
        case 2u: placeLists(); break;
        default: assignCluster(assignment.phase.x == 3u); break;
    }
}

// Light culling for the tiled compute passes (tiled_deferred*.comp, tiled_illumination*.comp):
// lights whose range sphere touches a tile's slice of the view frustum, bounded by the tile's
// depths. Culling is exact by construction: the range window (SHADING.md) is 0 beyond a light's
// range, so a light whose sphere misses the slice contributes nothing to its pixels.
// Two forms:
//   FE_TILE_LISTS: the lists come from the light-culling pass (tile_light_culling.comp), one per
//     8x8 pixels; feUseTileList() picks the invocation's. Measured fastest (docs/MEASUREMENT_LOG.md).
//   otherwise: feCullTile() culls in each 16x16-pixel work group, in shared memory between
//     barriers (deferred-tiled --one-pass-culling). The slice is bounded by a world-space box,
//     each invocation computing it: on lavapipe that measured faster (89 ms at 1280x720, 512
//     lights) than six frustum planes (123 ms), both together (107 ms), the box made once per
//     tile in shared memory (96-144 ms), or depth bounds scanned per row (120-138 ms).
#ifndef FE_TILE_CULLING_GLSL
#define FE_TILE_CULLING_GLSL
#ifdef FE_TILE_LISTS
#define FE_LIGHTS_UNIFORM  // the list passes read the lights from a uniform block (fe_scene.glsl)
#endif
#include "fe_scene.glsl"

// World-space box around a tile's slice of the view frustum: its 8 corners at the tile's pixel
// edges and depth bounds z0..z1 (a frustum slice is the convex hull of its corners).
void feTileSliceBox(vec2 pixelMin, vec2 pixelMax, float z0, float z1, out vec3 lo, out vec3 hi) {
    lo = vec3(3.0e38);
    hi = vec3(-3.0e38);
    for (int c = 0; c < 8; ++c) {
        vec3 w = feWorldFromDepth(vec2((c & 1) != 0 ? pixelMax.x : pixelMin.x, (c & 2) != 0 ? pixelMax.y : pixelMin.y),
                                  (c & 4) != 0 ? z1 : z0);
        lo = min(lo, w);
        hi = max(hi, w);
    }
}

// Whether a light can reach point P: beyond its range its window (SHADING.md) is exactly 0.
bool feLightReaches(GpuLight L, vec3 P) {
    const vec3 d = L.positionRange.xyz - P;
    return L.directionType.w == FE_LIGHT_DIRECTIONAL || L.positionRange.w <= 0.0 ||
           dot(d, d) < L.positionRange.w * L.positionRange.w;
}

// Whether a light can reach the box: directional and unbounded lights always can.
bool feLightTouchesBox(GpuLight L, vec3 lo, vec3 hi) {
    const float range = L.positionRange.w;
    if (L.directionType.w == FE_LIGHT_DIRECTIONAL || range <= 0.0) return true;
    const vec3 d = L.positionRange.xyz - clamp(L.positionRange.xyz, lo, hi);
    const float r = range * 1.0001 + 1e-4;  // rounding of the corners must not cull
    return dot(d, d) <= r * r;
}

#ifdef FE_TILE_LISTS
// The lists come from the light-culling pass (tile_light_culling.comp, TileLightCulling.h): a
// block of 32 x H texels per tile in an R32U texture, texel 0 the count (all ones: the list
// overflowed, shade every light), texels 1 and 2 the depth bounds the tile was culled for (the
// bits of two floats; min > max: no surface), then the light indices in order.
layout(binding = FE_SLOT_TILE_LIGHTS) uniform usampler2D tileLightLists;
// List tiles are FE_LIST_TILE pixels wide (TileLightCulling::kListTileSize), finer than the
// shading passes' 16x16 work groups: each invocation reads the list of its own pixel's tile.
#define FE_LIST_TILE 8
uint feTileCount_;
ivec2 feTileBlock_;
void feUseTileList(ivec2 pixel) {
    const int tilesY = (int(frame.viewport.y) + FE_LIST_TILE - 1) / FE_LIST_TILE;
    const ivec2 tile = pixel / FE_LIST_TILE;
    // The block height by a float division, exact here (the height is tilesY blocks, both far
    // below 2^24): CPU rasterizers have no vector integer division and divide lane by lane.
    const int blockHeight = int(float(textureSize(tileLightLists, 0).y) / float(tilesY));
    feTileBlock_ = ivec2(tile.x * 32, tile.y * blockHeight);
    feTileCount_ = texelFetch(tileLightLists, feTileBlock_, 0).r;
}
#define FE_TILE_HEADER 3u  // count, depth min, depth max
// Whether the list of feUseTileList's tile holds for a fragment of depth `depth` (forward-plus):
// a list is only valid for points inside the slice it was culled for, and under MSAA a fragment
// may lie outside it (an edge pixel, whose tile was culled for sample 0's depths).
bool feTileListHolds(float depth) {
    const float lo = uintBitsToFloat(texelFetch(tileLightLists, feTileBlock_ + ivec2(1, 0), 0).r);
    const float hi = uintBitsToFloat(texelFetch(tileLightLists, feTileBlock_ + ivec2(2, 0), 0).r);
    return depth >= lo && depth <= hi;
}
uint feTileLightCount() { return feTileCount_ == 0xffffffffu ? frame.counts.x : feTileCount_; }
uint feTileLight(uint k) {
    if (feTileCount_ == 0xffffffffu) return k;
    const uint e = k + FE_TILE_HEADER;
    return texelFetch(tileLightLists, feTileBlock_ + ivec2(e % 32u, e / 32u), 0).r;
}
#else
// Invocations per work group, as the including shader's local size says (a macro: measured,
// striding by gl_WorkGroupSize.x * gl_WorkGroupSize.y made every invocation walk every light).
#ifndef FE_TILE_INVOCATIONS
#define FE_TILE_INVOCATIONS 256u
#endif
// A tile with more lights than this shades every light (still exact, only slower).
#define FE_TILE_MAX_LIGHTS 512u
shared uint tileMinDepth, tileMaxDepth, tileLightCount;
shared uint tileLights[FE_TILE_MAX_LIGHTS];

// Every invocation of the work group calls this (it has barriers). `depth` is the invocation's
// surface depth (1: none); the tile spans full-resolution pixels [pixelMin, pixelMax).
void feCullTile(float depth, vec2 pixelMin, vec2 pixelMax) {
    if (gl_LocalInvocationIndex == 0u) {
        tileMinDepth = 0xffffffffu;
        tileMaxDepth = 0u;
        tileLightCount = 0u;
    }
    barrier();
    // Non-negative floats order like their bit patterns.
    if (depth < 1.0) {
        atomicMin(tileMinDepth, floatBitsToUint(depth));
        atomicMax(tileMaxDepth, floatBitsToUint(depth));
    }
    barrier();
    if (tileMinDepth <= tileMaxDepth) {  // the tile has surfaces: cull
        vec3 lo, hi;
        feTileSliceBox(pixelMin, pixelMax, uintBitsToFloat(tileMinDepth), uintBitsToFloat(tileMaxDepth), lo, hi);
        for (uint i = gl_LocalInvocationIndex; i < frame.counts.x; i += FE_TILE_INVOCATIONS) {
            if (feLightTouchesBox(feLight(i), lo, hi)) {
                const uint slot = atomicAdd(tileLightCount, 1u);
                if (slot < FE_TILE_MAX_LIGHTS) tileLights[slot] = i;
            }
        }
    }
    barrier();
}

// The k-th light of the tile's list (every light when the list overflowed), and their count.
uint feTileLightCount() { return tileLightCount <= FE_TILE_MAX_LIGHTS ? tileLightCount : frame.counts.x; }
uint feTileLight(uint k) { return tileLightCount <= FE_TILE_MAX_LIGHTS ? tileLights[k] : k; }
#endif  // FE_TILE_LISTS

// The lights of this invocation's tile (every invocation of the work group calls it): its
// pixel's list, or its 16x16 work group's lights culled in shared memory. `depth`: the
// invocation's surface depth (1: none), used by the shared-memory form.
void feFindTileLights(ivec2 pixel, float depth) {
#ifdef FE_TILE_LISTS
    feUseTileList(pixel);
#else
    const vec2 tile = vec2(gl_WorkGroupID.xy * 16u);
    feCullTile(depth, tile, min(tile + 16.0, frame.viewport.xy));
#endif
}
#endif

#version 450
#extension GL_GOOGLE_include_directive : require
// fe-variant: FE_LIGHTS_IN_STORAGE (scenes with more lights than a uniform block holds)
// fe-variant: FE_MULTISAMPLED (a multisampled depth, deferred under --msaa: bounds over every sample)
// fe-variant: FE_MULTISAMPLED+FE_LIGHTS_IN_STORAGE
#define FE_TILE_LISTS  // only for the shared helpers: this pass writes the lists
#include "fe_common.glsl"
#include "fe_tile_culling.glsl"
// The light-culling pass of the tiled techniques (TileLightCulling.h): one invocation per tile of
// 16x16 pixels finds the depth bounds of its four FE_LIST_TILE^2 quarters, culls every light
// against the box around the tile's slice of the view frustum, then each light that passes
// against its quarters' boxes, and writes the quarters' lists, which the shading passes read
// (fe_tile_culling.glsl, FE_TILE_LISTS). Two levels: testing every light against every quarter
// directly cost 20 ms against 6 at 1280x720 with 512 lights. No shared memory and no barriers:
// on lavapipe a barrier splits a shader into resumable parts (docs/MEASUREMENT_LOG.md).
layout(local_size_x = 64) in;
#ifdef FE_MULTISAMPLED
layout(binding = FE_SLOT_DEPTH) uniform sampler2DMS depthTexture;
#else
layout(binding = FE_SLOT_DEPTH) uniform sampler2D depthTexture;
#endif
layout(binding = FE_SLOT_TILE_LIGHTS_OUT, r32ui) uniform writeonly uimage2D lists;
// Whether culling.widen may be set (TileLightCulling::kWidenBoundsId, on under MSAA): a
// constant, so that at one sample the slope's four fetches a pixel are not made at all.
layout(constant_id = 203) const bool FE_WIDEN_BOUNDS = true;
FE_CONSTANTS(CullingConstants) {
    // x: with MSAA, how far (in pixels of depth slope) a fragment's pixel-centre depth may lie from
    // the sample-0 depth culled for: 0.5 (every sample lies within half a pixel of the centre);
    // 0 at one sample, where the centre is the sample.
    vec4 widen;
} culling;

#ifndef FE_MULTISAMPLED
// Depth slope of the surface at pixel p in pixels, per axis: the smaller one-sided difference,
// so that an edge to another surface (or to the background) does not count.
float feDepthSlope(ivec2 p, float d, ivec2 axis, ivec2 viewport) {
    const float a = texelFetch(depthTexture, clamp(p - axis, ivec2(0), viewport - 1), 0).r;
    const float b = texelFetch(depthTexture, clamp(p + axis, ivec2(0), viewport - 1), 0).r;
    const float da = a < 1.0 ? abs(d - a) : 1.0, db = b < 1.0 ? abs(b - d) : 1.0;
    const float slope = min(da, db);
    return slope < 1.0 ? slope : 0.0;
}
#endif

void main() {
    const ivec2 viewport = ivec2(frame.viewport.xy);
    const int tilesX = (viewport.x + 15) / 16, tilesY = (viewport.y + 15) / 16;
    const int t = int(gl_GlobalInvocationID.x);
    if (t >= tilesX * tilesY) return;
    const ivec2 tile = ivec2(t % tilesX, t / tilesX);
    const int listTilesY = (viewport.y + FE_LIST_TILE - 1) / FE_LIST_TILE;
    const int blockHeight = imageSize(lists).y / listTilesY;
    const uint capacity = uint(32 * blockHeight) - FE_TILE_HEADER;
    // Depth bounds of the four quarters (a quarter outside the viewport stays empty).
    vec2 z[4] = vec2[4](vec2(1.0, 0.0), vec2(1.0, 0.0), vec2(1.0, 0.0), vec2(1.0, 0.0));
    const ivec2 p0 = tile * 16, p1 = min(p0 + 16, viewport);
    for (int y = p0.y; y < p1.y; ++y)
        for (int x = p0.x; x < p1.x; ++x) {
            const int k = (x - p0.x) / FE_LIST_TILE + 2 * ((y - p0.y) / FE_LIST_TILE);
#ifdef FE_MULTISAMPLED
            // The deferred passes shade an edge's samples at their own depths, and an inner
            // pixel at its samples' mean (fe_gbuffer.glsl): every sample's depth bounds it.
            for (int i = 0; i < textureSamples(depthTexture); ++i) {
                const float d = texelFetch(depthTexture, ivec2(x, y), i).r;
                if (d < 1.0) z[k] = vec2(min(z[k].x, d), max(z[k].y, d));
            }
#else
            const float d = texelFetch(depthTexture, ivec2(x, y), 0).r;
            if (!(d < 1.0)) continue;
            // With MSAA the fragments shading this pixel sit at its centre, the depth culled for at
            // sample 0: the bounds take in the centre's depth along the surface's slope.
            const float s = FE_WIDEN_BOUNDS && culling.widen.x > 0.0 ? culling.widen.x * (feDepthSlope(ivec2(x, y), d, ivec2(1, 0), viewport) +
                                                                        feDepthSlope(ivec2(x, y), d, ivec2(0, 1), viewport))
                                                  : 0.0;
            z[k] = vec2(min(z[k].x, max(d - s, 0.0)), max(z[k].y, min(d + s, 1.0)));
#endif
        }
    vec3 lo[4], hi[4];
    uint count[4] = uint[4](0u, 0u, 0u, 0u);
    vec2 zAll = vec2(1.0, 0.0);
    for (int k = 0; k < 4; ++k) {
        const ivec2 q0 = p0 + FE_LIST_TILE * ivec2(k & 1, k >> 1), q1 = min(q0 + FE_LIST_TILE, viewport);
        // Widened by 4 ulps: a forward-plus fragment's gl_FragCoord.z need not equal, bit for bit,
        // the depth the pre-pass stored (the EQUAL test passing does not promise it), and one
        // outside the bounds walks its cluster's list (fe_forward_pass.glsl, feTileListHolds).
        if (z[k].x <= z[k].y) z[k] = vec2(z[k].x * (1.0 - 4.8e-7), min(z[k].y * (1.0 + 4.8e-7), 1.0));
        if (z[k].x <= z[k].y) feTileSliceBox(vec2(q0), vec2(q1), z[k].x, z[k].y, lo[k], hi[k]);
        zAll = vec2(min(zAll.x, z[k].x), max(zAll.y, z[k].y));
    }
    if (zAll.x <= zAll.y) {  // the tile has surfaces
        vec3 tileLo, tileHi;
        feTileSliceBox(vec2(p0), vec2(p1), zAll.x, zAll.y, tileLo, tileHi);
        for (uint i = 0u; i < frame.counts.x; ++i) {
            const GpuLight L = feLight(i);
            if (!feLightTouchesBox(L, tileLo, tileHi)) continue;
            for (int k = 0; k < 4; ++k) {
                if (!(z[k].x <= z[k].y) || !feLightTouchesBox(L, lo[k], hi[k])) continue;
                const ivec2 block = ivec2((tile.x * 2 + (k & 1)) * 32, (tile.y * 2 + (k >> 1)) * blockHeight);
                const uint e = count[k]++ + FE_TILE_HEADER;
                if (count[k] <= capacity) imageStore(lists, block + ivec2(e % 32u, e / 32u), uvec4(i));
            }
        }
    }
    for (int k = 0; k < 4; ++k) {
        const ivec2 q = ivec2(tile.x * 2 + (k & 1), tile.y * 2 + (k >> 1));
        if (q.x * FE_LIST_TILE >= viewport.x || q.y * FE_LIST_TILE >= viewport.y) continue;
        const ivec2 block = ivec2(q.x * 32, q.y * blockHeight);
        imageStore(lists, block, uvec4(count[k] > capacity ? 0xffffffffu : count[k]));
        imageStore(lists, block + ivec2(1, 0), uvec4(floatBitsToUint(z[k].x)));
        imageStore(lists, block + ivec2(2, 0), uvec4(floatBitsToUint(z[k].y)));
    }
}

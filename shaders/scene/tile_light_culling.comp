#version 450
#extension GL_GOOGLE_include_directive : require
// fe-variant: FE_LIGHTS_IN_STORAGE (scenes with more lights than a uniform block holds)
// fe-variant: FE_MULTISAMPLED (a multisampled depth, deferred under --msaa: bounds over every sample)
// fe-variant: FE_MULTISAMPLED+FE_LIGHTS_IN_STORAGE
#define FE_TILE_LISTS  // only for the shared helpers: this pass writes the lists
#include "fe_common.glsl"
#include "fe_tile_culling.glsl"
// The light-culling pass of the tiled techniques (TileLightCulling.h): one invocation per block of
// 32x32 pixels, four tiles of 16x16, each of four FE_LIST_TILE^2 quarters. It finds the
// quarters' depth bounds, culls every light against the block's box (the union of its tiles'),
// each light that passes against the boxes around its tiles' slices of the view frustum, and
// each that passes one against that tile's quarters' boxes, and writes the quarters' lists, which
// the shading passes read (fe_tile_culling.glsl, FE_TILE_LISTS). The lists are those of the
// tile and quarter tests alone: a light touching a tile's box touches the union (the test is
// monotone in the box, in floating point too). Levels because a CPU rasterizer pays for every
// iteration of the light loop, whatever its body: testing every light against every quarter
// cost 20 ms against 6 for one invocation per tile at 1280x720 with 512 lights (on the AMD EPYC),
// and the block level took the pass from 10.1 to 6.6 ms on llvmpipe, 9.9 to 8.3 on lavapipe,
// on the Intel Xeon of the seventeenth session (docs/MEASUREMENT_LOG.md).
// No shared memory and no barriers: on lavapipe a barrier splits a shader into resumable parts.
layout(local_size_x = 64) in;
#ifdef FE_MULTISAMPLED
layout(binding = FE_SLOT_DEPTH) uniform sampler2DMS depthTexture;
#else
layout(binding = FE_SLOT_DEPTH) uniform sampler2D depthTexture;
#endif
layout(binding = FE_SLOT_TILE_LIGHTS_OUT, r32ui) uniform writeonly uimage2D lists;
// The lights the loop walks (TileLightCulling::lightsInView): the frame's lights less those wholly
// outside the view, ascending, their count in the header's x. A light outside the view lights no
// surface seen, yet its sphere may touch a tile's box (a box around a slice of the frustum reaches
// past it), and every light the loop walks costs each block an iteration: 107 of builtin:lights'
// 512 are out of its default view (docs/MEASUREMENT_LOG.md).
#define FE_SLOT_VISIBLE_LIGHTS 55
#ifdef FE_LIGHTS_IN_STORAGE
layout(binding = FE_SLOT_VISIBLE_LIGHTS, std430) readonly buffer VisibleLights {
    uvec4 visibleHeader;
    uint visibleIndices[];
};
uint feVisibleLight(uint k) { return visibleIndices[k]; }
#else
layout(binding = FE_SLOT_VISIBLE_LIGHTS, std140) uniform VisibleLights {
    uvec4 visibleHeader;
    uvec4 visibleWords[FE_UNIFORM_LIGHTS / 4];
};
uint feVisibleLight(uint k) { return visibleWords[k >> 2u][k & 3u]; }
#endif
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
    const int blocksX = (viewport.x + 31) / 32, blocksY = (viewport.y + 31) / 32;
    const int b = int(gl_GlobalInvocationID.x);
    if (b >= blocksX * blocksY) return;
    const ivec2 block = ivec2(b % blocksX, b / blocksX);
    const int listTilesY = (viewport.y + FE_LIST_TILE - 1) / FE_LIST_TILE;
    const int blockHeight = imageSize(lists).y / listTilesY;
    const uint capacity = uint(32 * blockHeight) - FE_TILE_HEADER;
    // Depth bounds of the sixteen quarters, q = 4 x tile + quarter (tile and quarter both in
    // reading order: x, then y); a quarter outside the viewport stays empty.
    vec2 z[16];
    for (int q = 0; q < 16; ++q) {
        const ivec2 q0 = block * 32 + 16 * ivec2((q >> 2) & 1, q >> 3) + FE_LIST_TILE * ivec2(q & 1, (q >> 1) & 1);
        const ivec2 q1 = min(q0 + FE_LIST_TILE, viewport);
        vec2 bounds = vec2(1.0, 0.0);
        for (int y = q0.y; y < q1.y; ++y)
            for (int x = q0.x; x < q1.x; ++x) {
#ifdef FE_MULTISAMPLED
                // The deferred passes shade an edge's samples at their own depths, and an inner
                // pixel at its samples' mean (fe_gbuffer.glsl): every sample's depth bounds it.
                for (int i = 0; i < textureSamples(depthTexture); ++i) {
                    const float d = texelFetch(depthTexture, ivec2(x, y), i).r;
                    if (d < 1.0) bounds = vec2(min(bounds.x, d), max(bounds.y, d));
                }
#else
                const float d = texelFetch(depthTexture, ivec2(x, y), 0).r;
                if (!(d < 1.0)) continue;
                // With MSAA the fragments shading this pixel sit at its centre, the depth culled
                // for at sample 0: the bounds take in the centre's depth along the surface's slope.
                const float s = FE_WIDEN_BOUNDS && culling.widen.x > 0.0 ? culling.widen.x * (feDepthSlope(ivec2(x, y), d, ivec2(1, 0), viewport) +
                                                                            feDepthSlope(ivec2(x, y), d, ivec2(0, 1), viewport))
                                                      : 0.0;
                bounds = vec2(min(bounds.x, max(d - s, 0.0)), max(bounds.y, min(d + s, 1.0)));
#endif
            }
        // Widened by 4 ulps: a forward-plus fragment's gl_FragCoord.z need not equal, bit for bit,
        // the depth the pre-pass stored (the EQUAL test passing does not promise it), and one
        // outside the bounds walks its cluster's list (fe_forward_pass.glsl, feTileListHolds).
        if (bounds.x <= bounds.y) bounds = vec2(bounds.x * (1.0 - 4.8e-7), min(bounds.y * (1.0 + 4.8e-7), 1.0));
        z[q] = bounds;
    }
    // The boxes: each quarter's, each tile's (over its quarters' depths, as one tile was culled
    // before the block level), and the block's, the union of its tiles'.
    vec3 lo[16], hi[16], tileLo[4], tileHi[4];
    vec2 zTile[4];
    vec3 blockLo = vec3(3.0e38), blockHi = vec3(-3.0e38);
    for (int t = 0; t < 4; ++t) {
        const ivec2 p0 = block * 32 + 16 * ivec2(t & 1, t >> 1), p1 = min(p0 + 16, viewport);
        zTile[t] = vec2(1.0, 0.0);
        for (int k = 0; k < 4; ++k) {
            const int q = 4 * t + k;
            const ivec2 q0 = p0 + FE_LIST_TILE * ivec2(k & 1, k >> 1), q1 = min(q0 + FE_LIST_TILE, viewport);
            if (z[q].x <= z[q].y) feTileSliceBox(vec2(q0), vec2(q1), z[q].x, z[q].y, lo[q], hi[q]);
            zTile[t] = vec2(min(zTile[t].x, z[q].x), max(zTile[t].y, z[q].y));
        }
        if (zTile[t].x <= zTile[t].y) {
            feTileSliceBox(vec2(p0), vec2(p1), zTile[t].x, zTile[t].y, tileLo[t], tileHi[t]);
            blockLo = min(blockLo, tileLo[t]);
            blockHi = max(blockHi, tileHi[t]);
        }
    }
    uint count[16];
    for (int q = 0; q < 16; ++q) count[q] = 0u;
    if (blockLo.x <= blockHi.x) {  // the block has surfaces
        // The bound is not the uniform alone: lavapipe (Mesa 22.3) inlines a uniform that ends a
        // loop, compiling a variant of the shader for each value it sees (each light count in
        // view), and under LeakSanitizer those variants outlived the device.
        // gl_WorkGroupID.y is 0 (one row of groups), which the driver cannot know.
        for (uint v = 0u; v < visibleHeader.x + gl_WorkGroupID.y; ++v) {
            const uint i = feVisibleLight(v);
            const GpuLight L = feLight(i);
            if (!feLightTouchesBox(L, blockLo, blockHi)) continue;
            for (int t = 0; t < 4; ++t) {
                if (!(zTile[t].x <= zTile[t].y) || !feLightTouchesBox(L, tileLo[t], tileHi[t])) continue;
                for (int k = 0; k < 4; ++k) {
                    const int q = 4 * t + k;
                    if (!(z[q].x <= z[q].y) || !feLightTouchesBox(L, lo[q], hi[q])) continue;
                    const ivec2 list = block * 4 + 2 * ivec2(t & 1, t >> 1) + ivec2(k & 1, k >> 1);
                    const uint e = count[q]++ + FE_TILE_HEADER;
                    if (count[q] <= capacity) imageStore(lists, ivec2(list.x * 32, list.y * blockHeight) + ivec2(e % 32u, e / 32u), uvec4(i));
                }
            }
        }
    }
    for (int q = 0; q < 16; ++q) {
        const int t = q >> 2, k = q & 3;
        const ivec2 list = block * 4 + 2 * ivec2(t & 1, t >> 1) + ivec2(k & 1, k >> 1);
        if (list.x * FE_LIST_TILE >= viewport.x || list.y * FE_LIST_TILE >= viewport.y) continue;
        const ivec2 origin = ivec2(list.x * 32, list.y * blockHeight);
        imageStore(lists, origin, uvec4(count[q] > capacity ? 0xffffffffu : count[q]));
        imageStore(lists, origin + ivec2(1, 0), uvec4(floatBitsToUint(z[q].x)));
        imageStore(lists, origin + ivec2(2, 0), uvec4(floatBitsToUint(z[q].y)));
    }
}

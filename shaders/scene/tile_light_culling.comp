#version 450
#extension GL_GOOGLE_include_directive : require
#define FE_TILE_LISTS  // only for the shared helpers: this pass writes the lists
#include "fe_tile_culling.glsl"
// The light-culling pass of the tiled techniques (TileLightCulling.h): one invocation per tile of
// 16x16 pixels finds the tile's depth bounds, culls every light against the tile's slice of the
// view frustum, and writes the list the shading passes read (fe_tile_culling.glsl, FE_TILE_LISTS).
// No shared memory and no barriers: on lavapipe a barrier splits a shader into resumable parts,
// which measured as costly as the shading itself (docs/BENCHMARKS.md).
layout(local_size_x = 64) in;
layout(binding = FE_SLOT_DEPTH) uniform sampler2D depthTexture;
layout(binding = FE_SLOT_TILE_LIGHTS_OUT, r32ui) uniform writeonly uimage2D lists;

void main() {
    const ivec2 viewport = ivec2(frame.viewport.xy);
    const int tilesX = (viewport.x + 15) / 16, tilesY = (viewport.y + 15) / 16;
    const int t = int(gl_GlobalInvocationID.x);
    if (t >= tilesX * tilesY) return;
    const ivec2 tile = ivec2(t % tilesX, t / tilesX);
    const int blockHeight = imageSize(lists).y / tilesY;
    const uint capacity = uint(32 * blockHeight - 1);
    const ivec2 block = ivec2(tile.x * 32, tile.y * blockHeight);
    const ivec2 p0 = tile * 16, p1 = min(p0 + 16, viewport);
    float z0 = 1.0, z1 = 0.0;
    for (int y = p0.y; y < p1.y; ++y)
        for (int x = p0.x; x < p1.x; ++x) {
            const float d = texelFetch(depthTexture, ivec2(x, y), 0).r;
            if (d < 1.0) {
                z0 = min(z0, d);
                z1 = max(z1, d);
            }
        }
    uint count = 0u;
    if (z0 <= z1) {  // the tile has surfaces
        vec3 lo, hi;
        feTileSliceBox(vec2(p0), vec2(p1), z0, z1, lo, hi);
        for (uint i = 0u; i < frame.counts.x; ++i)
            if (feLightTouchesBox(lights[i], lo, hi)) {
                ++count;
                if (count <= capacity) imageStore(lists, block + ivec2(count % 32u, count / 32u), uvec4(i));
            }
    }
    imageStore(lists, block, uvec4(count > capacity ? 0xffffffffu : count));
}

// Clustered light lists (Olsson, Billeter and Assarsson 2012; ClusterLightGrid.h): the view
// frustum cut into FE_CLUSTER_TILE x FE_CLUSTER_TILE-pixel tiles and FE_CLUSTER_SLICES slices
// of view depth (slice 0 up to the near split frame.clusters.w, the others spaced exponentially
// from there to frame.clusters.z, the far side of the scene), each holding the lights whose
// range reaches it. The grid does not depend on the opaque depth, so translucent surfaces read
// it as opaque ones do.
// The lists: a storage buffer of uints, word 0 counting the index entries the lists asked for
// this frame, then per cluster (slice-major, then rows, then columns) its list's first entry and
// its length (all ones: no room was left, shade every light); and the entries, compact, each list
// in increasing light order, in an R32U texture of FE_CLUSTER_INDEX_WIDTH texels a row (entry e
// at (e % width, e / width)). A texture because the shading loops read an entry per light, and
// llvmpipe loads a storage buffer lane by lane through the stack, a texel fetch as one gather: one
// more storage-buffer read per light made clustered-deferred's lighting of builtin:atrium (1280x720,
// 1024 lights) 60-80 ms slower, of 250. A fragment beyond the last slice shades every light too,
// so no light is ever dropped.
#ifndef FE_CLUSTERS_GLSL
#define FE_CLUSTERS_GLSL
#include "fe_scene.glsl"

#define FE_CLUSTER_TILE 32
#define FE_CLUSTER_SLICES 32
#define FE_SLOT_CLUSTER_LIGHTS 35
#define FE_SLOT_CLUSTER_COLUMNS 40  // the assignment's scratch: the lights reaching each column
#define FE_SLOT_CLUSTER_INDICES 41      // the lists' entries, sampled by the shading passes
#define FE_SLOT_CLUSTER_INDICES_OUT 42  // ... and written by the assignment
#define FE_CLUSTER_INDEX_WIDTH 4096u    // ClusterLightGrid::kIndexWidth

#ifdef FE_CLUSTER_ASSIGN
layout(binding = FE_SLOT_CLUSTER_LIGHTS, std430) buffer ClusterLights {
#else
layout(binding = FE_SLOT_CLUSTER_LIGHTS, std430) readonly buffer ClusterLights {
#endif
    uint clusterWords[];
};
#ifdef FE_CLUSTER_ASSIGN
layout(binding = FE_SLOT_CLUSTER_INDICES_OUT, r32ui) uniform writeonly uimage2D clusterIndicesOut;
#else
layout(binding = FE_SLOT_CLUSTER_INDICES) uniform usampler2D clusterIndices;
#endif
ivec2 feClusterEntryTexel(uint e) { return ivec2(e % FE_CLUSTER_INDEX_WIDTH, e / FE_CLUSTER_INDEX_WIDTH); }

ivec2 feClusterTiles() {
    return (ivec2(frame.viewport.xy) + FE_CLUSTER_TILE - 1) / FE_CLUSTER_TILE;
}

// View depth where slice k begins (k = FE_CLUSTER_SLICES: where the last one ends). Slice 0 is
// the near one, from the near plane to frame.clusters.w; the others are spaced exponentially
// from there to frame.clusters.z.
float feClusterSliceStart(int k) {
    return k == 0 ? frame.clusters.x : frame.clusters.w * exp(float(k - 1) / frame.clusters.y);
}

// The slice holding view depth v: 0 before the near split, FE_CLUSTER_SLICES beyond the last.
int feClusterSlice(float v) {
    if (v >= frame.clusters.z) return FE_CLUSTER_SLICES;
    if (v < frame.clusters.w) return 0;
    return clamp(1 + int(floor(log(v / frame.clusters.w) * frame.clusters.y)), 1, FE_CLUSTER_SLICES - 1);
}

#ifdef FE_CLUSTER_ASSIGN
// The index entries the lists have room for together.
uint feClusterCapacity() {
    const ivec2 size = imageSize(clusterIndicesOut);
    return uint(size.x) * uint(size.y);
}
#endif

// The cluster's (first word, length) pair.
uint feClusterHeader(ivec2 tile, int slice) {
    const ivec2 tiles = feClusterTiles();
    return 1u + 2u * uint((slice * tiles.y + tile.y) * tiles.x + tile.x);
}

#ifndef FE_CLUSTER_ASSIGN
uint feClusterBase_, feClusterCount_;
// The list of the cluster holding the fragment at `pixel` of depth `depth` (the depth buffer's).
void feUseClusterList(ivec2 pixel, float depth) {
    const int slice = feClusterSlice(feViewDepth(depth));
    feClusterCount_ = 0xffffffffu;
    if (slice >= FE_CLUSTER_SLICES) return;
    const uint header = feClusterHeader(pixel / FE_CLUSTER_TILE, slice);
    feClusterBase_ = clusterWords[header];
    feClusterCount_ = clusterWords[header + 1u];
}
// Lights below `end` (the list is ordered): the caller's range, all of them when overflowed.
uint feClusterLightCount(uint end) { return feClusterCount_ == 0xffffffffu ? end : feClusterCount_; }
uint feClusterLight(uint k) {
    return feClusterCount_ == 0xffffffffu ? k : texelFetch(clusterIndices, feClusterEntryTexel(feClusterBase_ + k), 0).r;
}
#endif
#endif

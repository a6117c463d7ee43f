// Clustered light lists (Olsson, Billeter and Assarsson 2012; ClusterLightGrid.h): the view
// frustum cut into FE_CLUSTER_TILE x FE_CLUSTER_TILE-pixel tiles and FE_CLUSTER_SLICES slices
// of view depth (slice 0 up to the near split frame.clusters.w, the others spaced exponentially
// from there to frame.clusters.z, the far side of the scene), each holding the lights whose
// range reaches it.
// The lists: a storage buffer of uints, word 0 counting the index entries the lists asked for
// this frame, then per cluster (slice-major, then rows, then columns) three words: its list's
// first entry, its length (all ones: no room was left, shade every light), and the length of its
// bounded part. Where the grid is given the opaque depth (cluster_bounds.comp), the list begins
// with the lights that reach the box of the depths the opaque surfaces of the cluster hold (the
// bounded part, what an opaque pixel walks), then the others the slice's box reaches (what a
// blended fragment in front of them walks), each part in increasing light order; without it the
// bounded part is the whole list. The entries, compact, in an R32U texture of
// FE_CLUSTER_INDEX_WIDTH texels a row (entry e at (e % width, e / width)). A texture because the
// shading loops read an entry per light, and llvmpipe loads a storage buffer lane by lane
// through the stack, a texel fetch as one gather: one more storage-buffer read per light made
// clustered-deferred's lighting of builtin:atrium (1280x720, 1024 lights) 60-80 ms slower, of
// 250. A fragment beyond the last slice shades every light too, so no light is ever dropped.
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
#define FE_SLOT_CLUSTER_BOUNDS 43       // the opaque depths each cluster holds (cluster_bounds.comp)
#define FE_CLUSTER_HEADER 3u            // words per cluster: first entry, length, bounded length

#ifndef FE_CLUSTER_SLICING_ONLY  // cluster_bounds.comp: the slicing, no lists
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

// The cluster's index in header order (slice-major, then rows, then columns).
uint feClusterIndex(ivec2 tile, int slice) {
    const ivec2 tiles = feClusterTiles();
    return uint((slice * tiles.y + tile.y) * tiles.x + tile.x);
}
// The cluster's first header word (first entry, length, bounded length).
uint feClusterHeader(ivec2 tile, int slice) { return 1u + FE_CLUSTER_HEADER * feClusterIndex(tile, slice); }

#if !defined(FE_CLUSTER_ASSIGN) && !defined(FE_CLUSTER_SLICING_ONLY)
uint feClusterBase_, feClusterCount_, feClusterBounded_;
// The list of the cluster holding the fragment at `pixel` of depth `depth` (the depth buffer's).
void feUseClusterList(ivec2 pixel, float depth) {
    const int slice = feClusterSlice(feViewDepth(depth));
    feClusterCount_ = 0xffffffffu;
    if (slice >= FE_CLUSTER_SLICES) return;
    const uint header = feClusterHeader(pixel / FE_CLUSTER_TILE, slice);
    feClusterBase_ = clusterWords[header];
    feClusterCount_ = clusterWords[header + 1u];
    feClusterBounded_ = clusterWords[header + 2u];
}
// The whole list's length (blended fragments, multisampled ones): its two parts are each in
// light order, so a caller walking a range of lights skips the others rather than stopping. All
// of them (`end`) when overflowed.
uint feClusterLightCount(uint end) { return feClusterCount_ == 0xffffffffu ? end : feClusterCount_; }
// The bounded part's length: what an opaque pixel of the depth the grid was bounded by walks
// (the whole list where it was not). In light order: a caller may stop at the first light past
// its range.
uint feClusterBoundedLightCount(uint end) { return feClusterCount_ == 0xffffffffu ? end : feClusterBounded_; }
uint feClusterLight(uint k) {
    return feClusterCount_ == 0xffffffffu ? k : texelFetch(clusterIndices, feClusterEntryTexel(feClusterBase_ + k), 0).r;
}
#endif
#endif

// Layer 7: the light cluster grid of the clustered techniques and of every technique's
// translucent pass (Olsson, Billeter and Assarsson 2012, "Clustered Deferred and Forward
// Shading"). The view frustum is cut into kTilePixels x kTilePixels-pixel tiles and kSlices
// slices of view depth: slice 0 from the near plane to a near split, the others spaced
// exponentially from there to the far side of the scene (FrameConstants::clusters; Doom 2016
// and Olsson's paper use about as many). In builtin:atrium at 1280x720 with 1024 lights, 32
// slices after the split walk 15.8 lights a pixel where 24 from the near plane walked 23.0 (9.0
// reach each pixel; 16-pixel tiles walk 14.4 at 3.4x the assignment's cost), 15.4 with each
// column's side planes tested too, and 13.3 bounded by the opaque depth (below; 16-pixel tiles
// then walk 11.4, the assignment taking 171 ms against 38) (lavapipe). One compute pass
// ("light-assignment", shaders/scene/cluster_light_assignment.comp) files every light whose
// range reaches a cluster's box into its list (headers in a storage buffer, the entries in an R32U
// texture: a texel fetch, not a storage-buffer load, per light the shading passes walk) they read
// (shaders/include/fe_clusters.glsl). It first marks, per tile column, the lights that reach the
// column (the invocations taking the lights), then an invocation per cluster tests those against
// its slice (all lanes on the same light): builtin:atrium, 1280x720, 1024 lights, lavapipe, on
// one day: 189-201 -> 80-98 ms, where 64 invocations a column sharing the lights counted in
// shared memory; the lists and images are unchanged, bit for bit.
// Bounded by the opaque depth (declareBounded: clustered-deferred, the visibility buffer,
// clustered-forward at one sample): a pass ("cluster-bounds", shaders/scene/cluster_bounds.comp)
// first finds the depths the opaque surfaces of each cluster hold, and each list begins with
// the lights that reach the box of those depths (Olsson et al.'s tight cluster bounds), which
// is all an opaque pixel walks; blended fragments, which lie in front of the opaque depth, walk
// the whole list (the slice's box). Without it (declare) every reader walks the whole list, so
// the grid serves techniques with no depth yet and multisampled ones. The lists are compact:
// the pass counts each cluster's
// lights, places the lists one after another in one shared index array (a prefix over the
// clusters in order, so the layout is the same on every device and run), then fills them; a
// crowded far cluster takes what near empty ones leave; the array holds kMeanListCapacity
// lights per cluster on average, and grows when a frame asks for more (beginFrame). A cluster
// past its end is marked to shade every light and counted (Statistics), so a light is never
// dropped, and the lists hold it again a few frames later.
#pragma once
#include <cstdint>
#include <vector>

#include "fe/gdi/DeviceObjects.h"
#include "render/TechniqueRenderer.h"

namespace fe::render {

class ClusterLightGrid {
public:
    static constexpr uint32_t kTilePixels = 32;  // FE_CLUSTER_TILE
    static constexpr uint32_t kSlices = 32;      // FE_CLUSTER_SLICES
    static constexpr float kNearSplit =
        1.0f / 32;  // slice 0 ends at this share of the far depth (at least)
    static constexpr uint32_t kMeanListCapacity =
        64;  // index entries per cluster (at most the scene's lights)
    static constexpr uint32_t kIndexWidth =
        4096;  // FE_CLUSTER_INDEX_WIDTH: texels a row of the entries
    static constexpr uint32_t kHeaderWords =
        3;  // FE_CLUSTER_HEADER: first entry, length, bounded length

    explicit ClusterLightGrid(TechniqueContext& context);
    ClusterLightGrid(const ClusterLightGrid&) = delete;
    ClusterLightGrid& operator=(const ClusterLightGrid&) = delete;

    // The lists as a graph holds them: the headers (a storage buffer) and the entries (an R32U
    // texture of kIndexWidth texels a row).
    struct Lists {
        graph::BufferId headers;
        graph::TextureId entries;
    };
    // The lists and the pass that fills them: declared once per graph, later calls return the
    // same (the clustered technique and the translucent pass share them). declare: for a reader
    // that walks whole lists (blended or multisampled fragments: feClusterLightCount).
    // declareBounded: for one that shades the opaque surfaces whose one-sample depth `opaqueDepth`
    // holds and walks the bounded parts (feClusterBoundedLightCount); the first call of a graph
    // that names a depth adds the bounds pass, which the lists then depend on. A graph whose
    // readers are all bounded keeps only the bounded parts.
    Lists declare(graph::RenderGraph& g);
    Lists declareBounded(graph::RenderGraph& g, graph::TextureId opaqueDepth);
    // A shading pass's reads of the lists (its setup declares them), and their bindings
    // (kSlotClusterLights, kSlotClusterIndices).
    static void read(graph::PassBuilder& b, const Lists& lists);
    void bindLists(gdi::CommandList& cmd) const;
    // Before each frame is recorded (after CommandQueue::beginFrame): when the frame
    // framesInFlight ago asked for more entries than the lists hold, they grow to a quarter more
    // than it asked (at most what one 2D texture of the device holds) from this frame on. Each
    // frame copies the count it asked into a readback ring; the queue has waited for that frame,
    // so nothing here waits. Until then the clusters past the end shade every light (counted):
    // growth changes the speed, never the picture.
    void beginFrame();

    // The frame's slicing (FrameConstants::clusters): the near plane to the farthest corner of
    // the scene's bounds along the view axis.
    static glm::vec4 slicing(const assets::Camera& camera, const assets::Bounds& sceneBounds);

    uint32_t clusterCount() const { return tiles_.x * tiles_.y * kSlices; }
    uint32_t listCapacity() const { return capacity_; }  // light indices all lists together hold

    // What the last frame's lists hold (read back: after the frame completes).
    struct Statistics {
        uint32_t clusters = 0;
        uint32_t nonEmpty = 0;  // clusters with at least one light
        double meanLights = 0;  // per non-empty cluster
        uint32_t maxLights = 0;
        uint32_t overflowed =
            0;                 // clusters that shade every light (no room left in the index array)
        uint32_t entries = 0;  // light indices the lists asked for (overflowed ones included)
        double meanBoundedLights =
            0;                 // per non-empty cluster: the part that reaches its opaque surfaces
        bool bounded = false;  // the lists were bounded by the opaque depth
    };
    Statistics statistics() const;

private:
    gdi::DeviceObjects objects_;
    TechniqueContext& ctx_;
    bool uniformLights_ = false;
    glm::uvec2 tiles_{0};
    // The entries texture, (re)made with `rows` rows of kIndexWidth.
    void createEntries(uint32_t rows);

    uint32_t capacity_ = 0, maxRows_ = 1;
    uint64_t mostEntries_ = 0;  // every light in every cluster: more is never asked
    gdi::BufferHandle lists_;
    gdi::TextureHandle indices_;
    std::vector<gdi::BufferHandle> asked_;  // per frame in flight: the entries that frame asked for
    std::vector<bool> askedWritten_;
    gdi::BufferHandle columnMasks_;  // the assignment's: the lights that reach each tile column
    gdi::BufferHandle bounds_;       // per cluster: the least and greatest opaque depth it holds
    gdi::ShaderHandle cs_, boundsCs_;
    gdi::PipelineHandle pipeline_, boundsPipeline_;
    graph::RenderGraph* declaredIn_ = nullptr;
    Lists declared_{};
    bool bounded_ = false, wholeListsRead_ = false;  // of the graph declaredIn_
    Lists declareLists(graph::RenderGraph& g, graph::TextureId opaqueDepth);
    graph::BufferId declareBounds(graph::RenderGraph& g,
                                  graph::TextureId opaqueDepth);  // the cluster-bounds pass
    void recordAssignment(gdi::CommandList& cmd);  // the light-assignment pass's commands
};

}  // namespace fe::render

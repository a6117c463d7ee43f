// Layer 8 (Integration): the bench (`fe bench`): every case of a sweep (scene x technique x
// options) on every backend asked for, timed over frames and compared with an exact image.
//
// Per case and backend: CPU frame time and each pass's GPU time (median, min, max over the
// timed frames, after warm-up frames); the render graph's transient memory with and without
// aliasing and each transient texture's bytes per pixel; and the error of the image against the
// CPU double-precision reference of the same scene and camera (renderer/reference), by every
// measure of ImageMetrics.h. The reference evaluates everything the bench's scenes use
// (punctual lights, shadow rays, image-based lighting by the sampled estimator at 4096 samples,
// the converged integral), so every error is against an exact image.
//
// The results are one JSON document (schema "fe-results/1", shared in spirit with the
// conformance report: engine, date, device summaries, then one record per measurement) and a
// CSV of the same records; compareResults() says what changed between two of them.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "fe/gdi/InfoJson.h"
#include "render/RenderSettings.h"

namespace fe::render {

struct BenchCase {
    std::string scene = "builtin:spheres";  // builtin:NAME or a glTF path
    std::string environment;                // "", "builtin:sky" or an .hdr path
    uint32_t lights = 0;                    // builtin:lights: its light count (0: its default)
    uint32_t sphereGrid = 5;                // builtin:spheres: spheres per row
    uint32_t crowd = 0;                     // builtin:crowd: its reed count (0: its default)
    // An animation of the scene (index or name; empty: none) played from `time` seconds, each
    // frame 1/30 s later (looping): every frame then poses the scene and deforms its meshes.
    std::string animation;
    double time = 0.0;
    RenderSettings settings;  // technique, size and every option
    // "spheres/redeferred/scale2", unique within a sweep: the key compareResults() matches on.
    std::string key() const;
};

struct BenchOptions {
    uint32_t warmupFrames = 2;
    // On hardware (not on software rasterizers, which have no clocks to raise) the warm-up also
    // lasts at least this long, so that the GPU's clocks have risen before the timed frames.
    double warmupSeconds = 1.0;
    uint32_t frames = 5;
    uint32_t referenceIblSamples =
        4096;  // the converged integral (EnvironmentTests: 8192 changes it by < 1 %)
    // The Khronos validation layer / GL debug output on (tests); each backend's record then
    // counts its validation errors. Off for measuring: the layer's cost is not the engine's.
    bool validation = false;
    // When set, each measurement's image, its reference and FLIP's error map as a heat map are
    // written there as PNG (images/BACKEND/KEY.png, KEY.flip.png, reference/...) and named in
    // the record, for the report's matrix of thumbnails.
    std::string imageDir;
    // The cases' timed frames in alternation (frame 1 of every case, then frame 2, ...), every
    // case's renderer alive throughout: a burst of interference from elsewhere on the machine
    // then lands on all cases alike instead of on the one running, which steadies the ratios
    // between them. Off by default: it holds every case's renderer in memory at once.
    bool interleave = false;
    // Called before each frame a case renders, warm-up frames included (frame counts from 0).
    std::function<void(const std::string& key, uint32_t frame)> onFrame;
    // Called with the document so far after each measurement, so that a run stopped part way
    // (a time limit on a lent GPU) still leaves what it measured.
    std::function<void(const gdi::Json& partial)> onResult;
};

struct BenchProgress {
    size_t index = 0, count = 0;  // measurement index (from 1) of count
    double elapsedSeconds = 0, remainingSeconds = 0;
    std::string what;  // backend and case key
};

// The quick sweep a developer runs before a change lands: every technique on builtin:spheres
// (redeferred at every illumination scale, the forward techniques and light-prepass also with
// 4x MSAA), and every technique on builtin:shadows with shadows on, lit by builtin:sky at 16, 64
// and 256 samples and by the fast path, and on builtin:lights with 16, 64 and 256 lights; 96x72.
std::vector<BenchCase> quickSweep();
// A sweep file: {"cases": [{"scene": ..., "technique": ..., "size": "WxH", "illumScale": 2,
// "msaa": 4, "shadows": true, "shadowMapSize": 512, "environment": "builtin:sky",
// "iblSamples": 64, "iblPrefiltered": false, "temporal": false, "illumSplit": false,
// "precomputedNoV": true, "tileCullingPass": true, "clusterDepthBounds": true,
// "asyncCompute": true, "brdf": "auto"
// (or "gltf", "separable": fe render --brdf), "lights": 64,
// "sphereGrid": 5}, ...],
// "description": "..."}; unknown keys are errors (a typo must not silently bench the default).
// A value given as an array, or "technique": "all", makes the case a matrix: one case per
// combination, skipping options its technique does not take (MSAA on the deferred techniques,
// an illumination scale without an I-buffer). bench/sweeps/ holds the documented sweeps.
std::vector<BenchCase> sweepFromJson(const gdi::Json& sweep);

gdi::Json runBench(const std::vector<BenchCase>& cases, const std::vector<std::string>& backends,
                   const BenchOptions& options,
                   const std::function<void(const BenchProgress&)>& progress = {});
std::string resultsCsv(const gdi::Json& results);

// The stability suite (StabilitySuite.h) on the backends: one record per backend, case and
// technique with its outcome (the percentage of pixels beyond 5/255 of the reference, the
// refusal, or non-finite pixels) and the case's bound; fe bench adds them to its results as
// "stability", and the report shows them as a technique x case table. `caseNames`: only the
// cases named by one of its comma-separated parts (stabilityCases(names)); empty: every case.
gdi::Json runStability(const std::vector<std::string>& backends, uint32_t width = 48,
                       uint32_t height = 36,
                       const std::function<void(const BenchProgress&)>& progress = {},
                       const std::string& caseNames = {});

struct BenchComparison {
    std::string report;  // one line per matched measurement that changed, then a summary
    bool regression = false;
};
// B against A, matched by backend and case key: CPU frame-time ratio B/A beyond `timeRatio` or
// an error increase (percentage of pixels over 5/255) beyond `errorPoints` is a regression.
BenchComparison compareResults(const gdi::Json& a, const gdi::Json& b, double timeRatio = 1.25,
                               double errorPoints = 0.5);

}  // namespace fe::render

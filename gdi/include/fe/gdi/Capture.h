// Layer 2 (GDI abstraction, device-independent): capture and replay of whole programs at the device interface
// (docs/CAPTURE.md). A capturing device wraps any device: every call reaches the wrapped device
// first (so its checks and errors are the same), then is written to a file with its data, object
// descriptions, both SPIR-V targets of every shader, uploads, what the program wrote into mapped
// memory, each submitted command list (CommandSet.inc records), waits, read-backs and presents.
// replayCapture runs such a file on any device, so a frame captured on Vulkan replays on GL and
// the other way round.
//
//   auto device = gdi::createDevice({.backend = "vulkan", .capture = "frame.fecap"});
//   ... the program as it is ...                       // or FE_CAPTURE=frame.fecap, no change at all
//   device.reset();                                    // the file is complete once the device goes
//   auto gl = gdi::createDevice({.backend = "gl-egl"});
//   gdi::ReplayResult r = gdi::replayCapture("frame.fecap", *gl, {.outDir = "replayed"});
//   // r.images: every texture the program read back and every frame it presented, as replayed.
#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fe/gdi/CaptureStream.h"
#include "fe/gdi/Device.h"
#include "fe/gdi/Image.h"

namespace fe::gdi {

// The capture file format this build writes (and the newest it reads).
inline constexpr uint32_t kCaptureFormatVersion = 1;

struct CaptureDesc {
    std::string path;      // the file written (created or replaced)
    bool compress = true;  // zstd on every chunk it shrinks
    // Frames captured: 0 for all of them, until the device is destroyed; N: the first N, after
    // which the file is finished and the device goes on uncaptured. A frame ends at
    // markFrameEnd (the renderer's CommandQueue calls it after each frame's submit), at
    // present(), or at the first readTexture; each only when something was submitted since the
    // last frame ended.
    uint32_t frames = 0;
    // The first frame captured (0: from the start). Before it nothing is written; when it starts,
    // every live object is written in the state it has then: its description, and its contents
    // read back from the device (buffers; single-sample uncompressed 2D, array and cube
    // textures), or for textures that cannot be read back (compressed, 3D) what the program
    // wrote into them. Multisampled textures start undefined, as after their creation.
    uint32_t firstFrame = 0;
};

// Wraps `inner` in a capturing device. Throws Error when the file cannot be created. Its info()
// is inner's except that both buffer offset alignments are multiples of 256 (the most Vulkan
// allows; GL drivers ask up to that, NVIDIA's 256 where its Vulkan asks 64), and command lists
// are held to them: a program that aligns as info() says records a capture every backend replays.
std::unique_ptr<Device> makeCaptureDevice(std::unique_ptr<Device> inner, const CaptureDesc& desc);

struct CaptureStats {
    uint32_t frames = 0;        // frames ended so far
    uint64_t records = 0;       // calls written
    uint64_t blobs = 0;         // distinct data blocks written
    uint64_t dedupedBlobs = 0;  // data blocks that repeated one already written
    uint64_t rawBytes = 0;      // records and blobs before compression
    uint64_t fileBytes = 0;     // written to the file so far
    bool finished = false;      // the file is complete
};
// Ends the current frame of a capturing device (headless programs, which never present, mark
// their frames so); does nothing for other devices.
void markFrameEnd(Device& device);
// A capturing device's statistics; nullopt for any other device.
std::optional<CaptureStats> captureStats(Device& device);
// Completes a capturing device's file now (it goes on uncaptured); throws Error when writing
// failed. Does nothing for other devices.
void finishCapture(Device& device);

// What a capture file holds, read through without a device (every chunk checked as replay
// does, the calls themselves not). Throws CaptureError as replayCapture does.
struct CaptureSummary {
    uint32_t formatVersion = 0;
    std::string backend, device;  // where it was captured
    uint32_t frames = 0;
    uint32_t firstFrame = 0;  // the program's frame the capture starts at
    uint64_t records = 0, submits = 0, blobs = 0;
    uint64_t fileBytes = 0, rawBytes = 0;  // on disk; records and blobs uncompressed
};
CaptureSummary summarizeCapture(const std::string& path);

struct ReplayOptions {
    // When set, every read-back and presented image is written there as PNG, named
    // frame<F>_<N>_<texture name>.png (N counts the images of the whole replay).
    std::string outDir;
    // On a device with a window, present what the program presented (else read it back).
    bool present = false;
    // Probes (fe replay --pass/--draw, fe bisect). Draws are counted over the whole capture in
    // submission order from 0: draw, drawIndexed and the indirect draws (a secondary list a pass
    // executes counts as one). Render passes likewise. While probing, attachments are stored
    // (StoreOp::DontCare becomes Store) and render targets get CopySrc usage, so they can be read.
    bool snapshotPasses = false;               // every render pass's attachments, read at its end
    std::optional<uint64_t> stopAfterDraw;     // end the replay after this draw, reading its pass
    std::optional<std::string> stopAfterPass;  // end after the first render pass of this name
    std::optional<uint64_t> skipDraw;          // leave this draw out (fe bisect --perturb)
    // GPU time of every render pass (timestamps before and after it, where the device has
    // DeviceFeatures::timestamps): ReplayResult::passTimes. Changes nothing else.
    bool passTimes = false;
    // Work one recorded call may ask for (vertices x instances of a draw, work groups of a
    // dispatch): beyond it the replay stops with a CaptureError instead of running for hours on
    // a damaged count. Indirect arguments are the GPU's and are not checked.
    uint64_t maxDrawVertices = uint64_t(1) << 28;
    uint64_t maxDispatchGroups = uint64_t(1) << 24;
};
struct PassTime {
    uint32_t frame = 0;
    uint64_t pass = 0;  // over the capture
    std::string name;   // the pass's debug name, else the innermost debug group's
    double gpuMilliseconds = 0;
};
struct ReplayImage {
    uint32_t frame = 0;
    std::string name;  // the texture's debug name, else "texture <id>"
    bool presented = false;
    Image image;
};
struct ReplayBuffer {
    uint32_t frame = 0;
    std::string name;  // the buffer's debug name, else "buffer <id>"
    std::vector<uint8_t> bytes;
};
// Where a draw is in the capture, and what it used.
struct DrawContext {
    uint64_t draw = 0;        // over the capture
    uint64_t pass = 0;        // its render pass, over the capture
    uint64_t drawInPass = 0;  // within that pass
    std::string passName;
    std::vector<std::string> groups;   // debug groups open at the draw, outermost first
    std::string command;               // Draw, DrawIndexed, ...
    std::string pipeline;              // its debug name
    std::vector<std::string> shaders;  // the pipeline's shaders, by name
    std::vector<std::string>
        resources;  // what was bound: "vertex buffer 0: NAME", "texture 2: NAME", ...
};
// A render pass's attachments as its last draw left them (ReplayImage::name: "colour N: TEXTURE"
// or "depth: TEXTURE"); attachments that cannot be read (views, multisampled without a resolve
// target) are left out.
struct PassSnapshot {
    uint64_t pass = 0;
    std::string name;
    uint64_t firstDraw = 0, draws = 0;
    std::vector<ReplayImage> targets;
};
struct ReplayResult {
    std::string capturedBackend;  // the device the capture was made on
    uint32_t formatVersion = 0;
    uint32_t frames = 0;
    uint64_t records = 0, submits = 0, commandLists = 0;
    std::vector<double> frameMilliseconds;  // wall time of each replayed frame (CPU and GPU)
    std::vector<ReplayImage> images;
    std::vector<ReplayBuffer> buffers;  // every readBuffer, as replayed
    std::vector<PassTime> passTimes;    // ReplayOptions::passTimes
    uint32_t unrestored = 0;            // object contents of a trimmed capture this device refused
    uint64_t draws = 0, passes = 0;     // replayed (up to the stop)
    std::vector<PassSnapshot> passSnapshots;  // snapshotPasses
    std::optional<DrawContext> stoppedAt;     // stopAfterDraw: the draw, when it was reached
    std::optional<PassSnapshot> stopTargets;  // stopAfterDraw / stopAfterPass: the targets there
};
// Replays the capture at `path` on `device`. Throws CaptureError naming the record and the byte
// offset for a damaged, truncated or future-version file, and for a call `device` refuses.
ReplayResult replayCapture(const std::string& path, Device& device,
                           const ReplayOptions& options = {});

// fe bisect: where two devices first disagree on a capture. Both replay it, reading every render
// pass's attachments; the first pass whose targets differ beyond the tolerance is then replayed
// draw by draw on both (each replay stopping after one draw) until a draw's targets differ.
struct BisectOptions {
    double absTolerance = 5.0 / 255.0;  // per channel, as the conformance suite
    double maxFractionOver = 0.001;     // of a target's pixels beyond absTolerance
    // A test switch: leave draw N out on device A or B (Device index 0 or 1), so the bisection
    // has a known answer.
    std::optional<std::pair<int, uint64_t>> perturb;
};
struct TargetDiff {
    std::string target;  // "colour 0: NAME", "depth: NAME", or a read-back's name
    ImageDiff diff;
    Image a, b, heat;  // heat: per pixel, how far apart (compareImages' diff image)
};
struct BisectResult {
    bool diverged = false;
    std::optional<PassSnapshot>
        pass;  // the first pass that differs (targets: as device A made them)
    std::optional<DrawContext> draw;  // the first draw in it whose targets differ
    std::vector<TargetDiff> diffs;    // the targets that differ there (at the draw, else the pass)
    uint64_t passesCompared = 0, drawsCompared = 0;
    uint32_t replays = 0;
};
BisectResult bisectCapture(const std::string& path, Device& a, Device& b,
                           const BisectOptions& options = {});

}  // namespace fe::gdi

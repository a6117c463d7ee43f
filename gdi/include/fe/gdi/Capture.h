// Layer 3 (device-independent): capture and replay of whole programs at the device interface
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
    std::string path;       // the file written (created or replaced)
    bool compress = true;   // zstd on every chunk it shrinks
    // Frames captured: 0 for all of them, until the device is destroyed; N: the first N, after
    // which the file is finished and the device goes on uncaptured. A frame ends at present(),
    // or, for headless programs, at the first readTexture after a submit.
    uint32_t frames = 0;
};

// Wraps `inner` in a capturing device. Throws Error when the file cannot be created.
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
};
struct ReplayImage {
    uint32_t frame = 0;
    std::string name;  // the texture's debug name, else "texture <id>"
    bool presented = false;
    Image image;
};
struct ReplayResult {
    std::string capturedBackend;  // the device the capture was made on
    uint32_t formatVersion = 0;
    uint32_t frames = 0;
    uint64_t records = 0, submits = 0, commandLists = 0;
    std::vector<double> frameMilliseconds;  // wall time of each replayed frame (CPU and GPU)
    std::vector<ReplayImage> images;
};
// Replays the capture at `path` on `device`. Throws CaptureError naming the record and the byte
// offset for a damaged, truncated or future-version file, and for a call `device` refuses.
ReplayResult replayCapture(const std::string& path, Device& device, const ReplayOptions& options = {});

}  // namespace fe::gdi

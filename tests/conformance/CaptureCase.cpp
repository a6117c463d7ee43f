// A capture file as a conformance case (fe conformance --capture): replayed on each backend, its
// read-back and presented images are the case's images, compared across backends with the
// suite's 8-bit rule like any case's.
#include <filesystem>

#include "Conformance.h"
#include "fe/gdi/Capture.h"

namespace fe::conformance {

Case captureCase(const std::string& path) {
    const std::string name = "capture:" + std::filesystem::path(path).filename().string();
    return {
        name, [path](gdi::Device& device) {
            const gdi::ReplayResult r = gdi::replayCapture(path, device);
            FE_CONFORMANCE_CHECK(
                !r.images.empty() || !r.buffers.empty(),
                "the capture reads nothing back and presents nothing: nothing to compare");
            std::vector<CaseImage> images;
            for (size_t i = 0; i < r.images.size(); ++i) {
                // Named by frame and order: texture names differ where GL reuses textures.
                CaseImage ci{
                    .name = "frame" + std::to_string(r.images[i].frame) + "_" + std::to_string(i),
                    .image = r.images[i].image};
                ci.toleranceReason =
                    "a capture's read-back: 0.1% of pixels may differ by more than 5/255";
                images.push_back(std::move(ci));
            }
            // Buffers read back compare byte by byte, as one row of RGBA8 texels (zero-padded).
            for (size_t i = 0; i < r.buffers.size(); ++i) {
                std::vector<uint8_t> b = r.buffers[i].bytes;
                b.resize((b.size() + 3) / 4 * 4);
                CaseImage ci{.name = "frame" + std::to_string(r.buffers[i].frame) + "_buffer" +
                                     std::to_string(i),
                             .image = {uint32_t(b.size() / 4), 1, gdi::Format::RGBA8, b}};
                ci.toleranceReason =
                    "a capture's buffer read-back, byte by byte: 0.1% may differ by more than 5";
                images.push_back(std::move(ci));
            }
            return images;
        }};
}

}  // namespace fe::conformance

// libFuzzer harness: the command-stream part of capture files (CaptureStream.h). Any bytes either
// decode into a stream that re-encodes and decodes again to the same bytes, or are refused with
// a CaptureError; never a crash, a hang or an allocation beyond what the input holds.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <span>
#include <vector>

#include "FuzzSupport.h"
#include "fe/gdi/CaptureStream.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::span<const std::byte> bytes(reinterpret_cast<const std::byte*>(data), size);
    try {
        const auto stream = fe::gdi::decodeCommandStream(bytes);
        const std::vector<std::byte> again = fe::gdi::encodeCommandStream(*stream);
        FUZZ_CHECK(fe::gdi::encodeCommandStream(*fe::gdi::decodeCommandStream(again)) == again,
                   "an accepted stream does not re-encode to the same bytes",
                   std::to_string(again.size()) + " bytes");
    } catch (const fe::gdi::CaptureError&) {}
    return 0;
}

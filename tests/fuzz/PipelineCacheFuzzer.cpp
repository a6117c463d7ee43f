// libFuzzer harness: the pipeline cache file (PipelineCacheFile.h). Any bytes must parse into
// "accepted" or "ignored, because ..." and never read outside the input: the header, the
// identity, the stated sizes, the checksum, and (for accepted data, as the GL backend does)
// the program binary entries. The first input byte picks whether the identity matches, so the
// fuzzer reaches the payload checks without having to guess the identity string.
#include <cstdint>
#include <map>
#include <span>
#include <string>

#include "FuzzSupport.h"
#include "fe/gdi/PipelineCacheFile.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size == 0) return 0;
    const std::string identity = "fuzz|device|api|driver";
    std::span<const uint8_t> rest(data + 1, size - 1);
    std::vector<uint8_t> file;
    if (data[0] & 1) {  // a well-formed header around the rest: exercises the payload decoder
        file = fe::gdi::encodePipelineCache(identity, rest);
        if (data[0] & 2 && !file.empty()) file[file.size() / 2] ^= 0x5a;   // damaged
        if (data[0] & 4 && file.size() > 4) file.resize(file.size() - 3);  // truncated
    } else {
        file.assign(rest.begin(), rest.end());
    }
    const fe::gdi::PipelineCacheLoad load = fe::gdi::parsePipelineCache(file, identity);
    FUZZ_CHECK(load.payload.empty() || load.warning.empty(), "a file both loaded and ignored",
               load.warning);
    if (data[0] & 1 && !(data[0] & 6))  // an intact file made here must load
        FUZZ_CHECK(load.payload.size() == rest.size() && load.warning.empty(),
                   "an intact file was ignored", load.warning);
    if (!load.payload.empty()) {
        std::map<uint64_t, fe::gdi::ProgramBinary> programs;
        std::string why;
        if (fe::gdi::decodeProgramBinaries(load.payload, programs, why)) {
            std::map<uint64_t, fe::gdi::ProgramBinary> again;
            FUZZ_CHECK(fe::gdi::decodeProgramBinaries(fe::gdi::encodeProgramBinaries(programs),
                                                      again, why) &&
                           again.size() == programs.size(),
                       "accepted programs do not round-trip", why);
        }
    }
    return 0;
}

// Layer 2 (GDI abstraction): a recorded command list as bytes, for capture files.
// The records are written exactly as CommandStream holds them (CommandSet.inc defines them;
// payload offsets are relative to each record), followed by the secondary streams the list
// executed. Reading checks every record before it becomes a CommandStream again, so a damaged or
// hand-made file is refused with an error naming the record and its byte offset, and nothing is
// allocated beyond the sizes the bytes actually hold.
//
//   stream := u32 records | u32 children | u64 record bytes | records | children x (u64 bytes | stream)
//   record := u16 op | u16 0 | u32 size (a multiple of 8) | the record | its payloads
#pragma once
#include <cstddef>
#include <memory>
#include <span>
#include <stdexcept>
#include <vector>

#include "fe/gdi/CommandStream.h"

namespace fe::gdi {

// A refused capture: what is wrong, with the record index and the byte offset in the input.
struct CaptureError : Error {
    using Error::Error;
};

std::vector<std::byte> encodeCommandStream(const cmd::CommandStream& stream);
// `baseOffset`: where `bytes` starts in the file, for messages. Throws CaptureError.
std::unique_ptr<cmd::CommandStream> decodeCommandStream(std::span<const std::byte> bytes,
                                                        uint64_t baseOffset = 0);

}  // namespace fe::gdi

// Per-draw constants on GL, which has no push constants (CommandList::setConstants): each draw
// whose constants changed reads a fresh slice of one persistently mapped uniform buffer, bound
// at the binding the engine include reserves (kConstantsGlBinding). Slices are never rewritten
// while the GPU may read them: the ring is split in quarters, a fence follows the last use of
// each, and a quarter is waited for only when the GPU is a whole ring behind. Context thread only.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>

#include "gl/GlFunctions.h"

namespace fe::gl {

class GlConstantsRing {
public:
    // Copies `bytes` of `data` into the ring and binds them (made on first use).
    void bind(const GlFunctions& gl, const void* data, uint32_t bytes, uint32_t alignment);
    void release(const GlFunctions& gl);

private:
    static constexpr uint32_t kSize = 1u << 20;
    static constexpr uint32_t kQuarter = kSize / 4;
    void enterQuarter(const GlFunctions& gl, uint32_t quarter);
    GLuint buffer_ = 0;
    std::byte* mapped_ = nullptr;
    uint32_t head_ = 0;               // next free byte
    uint32_t quarter_ = 0;            // the quarter head_ is in
    std::array<GLsync, 4> fences_{};  // after the last use of each quarter, until it is reused
};

}  // namespace fe::gl

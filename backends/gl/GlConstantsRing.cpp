#include "gl/GlConstantsRing.h"

#include <cstring>

#include "fe/gdi/ShaderReflection.h"

namespace fe::gl {

void GlConstantsRing::bind(const GlFunctions& gl, const void* data, uint32_t bytes,
                           uint32_t alignment) {
    if (!buffer_) {
        const GLbitfield flags = GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
        gl.CreateBuffers(1, &buffer_);
        gl.NamedBufferStorage(buffer_, kSize, nullptr, flags);
        mapped_ = static_cast<std::byte*>(gl.MapNamedBufferRange(buffer_, 0, kSize, flags));
        gl.ObjectLabel(GL_BUFFER, buffer_, -1, "fe per-draw constants");
    }
    const uint32_t align = alignment ? alignment : 256;
    uint32_t at = (head_ + align - 1) / align * align;
    if (at / kQuarter != (at + bytes - 1) / kQuarter)
        at = (at / kQuarter + 1) * kQuarter;  // never straddle
    if (at + bytes > kSize) at = 0;
    if (at / kQuarter != quarter_) enterQuarter(gl, at / kQuarter);
    std::memcpy(mapped_ + at, data, bytes);
    head_ = at + bytes;
    gl.BindBufferRange(GL_UNIFORM_BUFFER, gdi::kConstantsGlBinding, buffer_, GLintptr(at),
                       GLsizeiptr(bytes));
}

// Fences the quarter being left, then waits for the GPU to be done with the one entered.
void GlConstantsRing::enterQuarter(const GlFunctions& gl, uint32_t quarter) {
    fences_[quarter_] = gl.FenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    if (GLsync f = fences_[quarter]) {
        while (gl.ClientWaitSync(f, GL_SYNC_FLUSH_COMMANDS_BIT, 1'000'000'000) ==
               GL_TIMEOUT_EXPIRED) {}
        gl.DeleteSync(f);
        fences_[quarter] = nullptr;
    }
    quarter_ = quarter;
}

void GlConstantsRing::release(const GlFunctions& gl) {
    for (GLsync& f : fences_)
        if (f) gl.DeleteSync(f), f = nullptr;
    if (buffer_) gl.DeleteBuffers(1, &buffer_);
    buffer_ = 0;
    mapped_ = nullptr;
}

}  // namespace fe::gl

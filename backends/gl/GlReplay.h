// Replays a recorded command stream as GL calls, on the context thread, at submit. The
// stream was validated while it was recorded, so replay only translates: one overload per
// command of CommandSet.inc (the compiler rejects a command without one).
#pragma once
#include <array>
#include <atomic>
#include <functional>
#include <utility>
#include <vector>

#include "fe/gdi/CommandStream.h"
#include "gl/GlDevice.h"

namespace fe::gl {

class GlReplay {
public:
    explicit GlReplay(GlDevice& d) : dev_(d), gl_(d.gl()) {}
    // `serve` runs between two commands whenever `waiting` is set: the device serves urgent
    // calls there (creation, fence waits) one command after they arrive, not after the stream.
    void run(const gdi::cmd::CommandStream& stream, const std::atomic<bool>* waiting = nullptr,
             const std::function<void()>& serve = {});

    void operator()(const gdi::cmd::BeginRenderPass& r);
    void operator()(const gdi::cmd::InsertDebugLabel& r);
    void operator()(const gdi::cmd::ClearBuffer& r);
    void operator()(const gdi::cmd::ExecuteSecondary& r);
    void operator()(const gdi::cmd::EndRenderPass&);
    void operator()(const gdi::cmd::SetPipeline& r);
    void operator()(const gdi::cmd::SetConstants& r);
    void operator()(const gdi::cmd::SetViewport& r);
    void operator()(const gdi::cmd::SetScissor& r);
    void operator()(const gdi::cmd::SetBlendConstant& r);
    void operator()(const gdi::cmd::SetStencilReference& r);
    void operator()(const gdi::cmd::SetDepthBias& r);
    void operator()(const gdi::cmd::SetVertexBuffer& r);
    void operator()(const gdi::cmd::SetIndexBuffer& r);
    void operator()(const gdi::cmd::SetUniformBuffer& r);
    void operator()(const gdi::cmd::SetStorageBuffer& r);
    void operator()(const gdi::cmd::SetTexture& r);
    void operator()(const gdi::cmd::SetStorageTexture& r);
    void operator()(const gdi::cmd::Draw& r);
    void operator()(const gdi::cmd::DrawOneInstance& r);
    void operator()(const gdi::cmd::SetUniformOffset& r);
    void operator()(const gdi::cmd::DrawIndexed& r);
    void operator()(const gdi::cmd::Dispatch& r);
    void operator()(const gdi::cmd::DrawIndirect& r);
    void operator()(const gdi::cmd::DrawIndexedIndirect& r);
    void operator()(const gdi::cmd::DrawIndirectCount& r);
    void operator()(const gdi::cmd::DrawIndexedIndirectCount& r);
    void operator()(const gdi::cmd::DispatchIndirect& r);
    void operator()(const gdi::cmd::GenerateMips& r);
    void operator()(const gdi::cmd::CopyBuffer& r);
    void operator()(const gdi::cmd::CopyTexture& r);
    void operator()(const gdi::cmd::CopyBufferToTexture& r);
    void operator()(const gdi::cmd::CopyTextureToBuffer& r);
    void operator()(const gdi::cmd::CopyBufferToTextureRegion& r);
    void operator()(const gdi::cmd::CopyTextureToBufferRegion& r);
    void operator()(const gdi::cmd::ResolveTextureRegion& r);
    void operator()(const gdi::cmd::CopyTextureRegion& r);
    void operator()(const gdi::cmd::BeginTimer& r);
    void operator()(const gdi::cmd::EndTimer& r);
    void operator()(const gdi::cmd::BeginQuery& r);
    void operator()(const gdi::cmd::EndQuery& r);
    void operator()(const gdi::cmd::WriteTimestamp& r);
    void operator()(const gdi::cmd::ResolveQueries& r);
    void operator()(const gdi::cmd::PushDebugGroup& r);
    void operator()(const gdi::cmd::PopDebugGroup&);
    void operator()(const gdi::cmd::DiscardTexture&) {
    }  // GL reuses whole objects; contents are simply overwritten
    void operator()(const gdi::cmd::SetAutomaticBarriers& r);
    void operator()(const gdi::cmd::TextureBarriers& r);
    void operator()(const gdi::cmd::BufferBarriers& r);

private:
    void replayRecords(const gdi::cmd::CommandStream& stream);
    const gdi::cmd::CommandStream* stream_ = nullptr;  // being replayed (a secondary's, inside one)
    const std::atomic<bool>* waiting_ = nullptr;
    const std::function<void()>* serve_ = nullptr;
    void applyPipelineState(const Pipeline& p);
    void applyStencil(uint8_t reference);
    void applyDepthBias(float constant, float slope, float clamp);
    void resolve();
    void bindVertexBuffers();
    void bindIndexBuffer();
    bool drainSoftwareRasterizer();
    GLenum indexType() const {
        return indexType_ == gdi::IndexType::U16 ? GL_UNSIGNED_SHORT : GL_UNSIGNED_INT;
    }

    GlDevice& dev_;
    const GlFunctions& gl_;
    bool automatic_ = true;  // setAutomaticBarriers
    bool labelled_ = false;  // the open pass pushed a debug group
    // Dynamic state the pass has set (setBlendConstant, ...): setPipeline leaves it (Device.h).
    static constexpr uint8_t kBlendConstantSet = 1, kStencilReferenceSet = 2, kDepthBiasSet = 4;
    uint8_t dynamicSet_ = 0;
    uint8_t stencilReference_ = 0;  // the pass's, when kStencilReferenceSet
    gdi::Rect area_;
    GLuint fbo_ = 0;  // the open pass's framebuffer
    std::vector<std::pair<GLenum, FboAttachment>>
        resolves_;  // attachment point -> resolve target, at EndRenderPass
    const Pipeline* pipeline_ = nullptr;
    GLenum topology_ = GL_TRIANGLES;
    std::array<std::pair<GLuint, uint64_t>, 16> vertexBuffers_{};
    bool vertexDirty_ = true, indexDirty_ = true;
    // setConstants' bytes, uploaded to the device's ring at the next draw or dispatch.
    std::array<std::byte, gdi::kMaxConstantBytes> constants_{};
    bool constantsDirty_ = true;
    void flushConstants();
    // setStorageTexture's textures by slot, bound to the pipeline's image units (Pipeline::
    // imageSlots) at the next draw or dispatch: the unit of a slot depends on the pipeline.
    struct ImageBinding {
        GLuint texture = 0;
        GLint mipLevel = 0;
        GLboolean layered = GL_FALSE;
        GLenum format = 0;
    };
    std::array<ImageBinding, 64> images_{};
    bool imagesDirty_ = true;
    void bindImages();
    // What every draw and dispatch needs first: the constants and the storage textures.
    void flushBindings() {
        if (constantsDirty_) flushConstants();
        if (imagesDirty_) bindImages();
    }
    // The stream's last SetUniformBuffer, which a SetUniformOffset binds at another offset.
    struct LastUniform {
        GLuint slot = 0, name = 0;
        GLsizeiptr size = 0;
    };
    LastUniform lastUniform_;
    GLuint indexBuffer_ = 0;
    uint64_t indexOffset_ = 0;
    gdi::IndexType indexType_ = gdi::IndexType::U32;
};

}  // namespace fe::gl

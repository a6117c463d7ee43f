// Command recording for GL: validates like the Vulkan list, then issues GL calls directly.
#include <algorithm>
#include <array>
#include <bit>

#include "fe/gdi/Validation.h"
#include "gl/GlDevice.h"

namespace fe::gl {

namespace {
GLenum compare(gdi::CompareOp c) { return GLenum(GL_NEVER + int(c)); }  // same order as GL_NEVER..GL_ALWAYS
GLenum stencilOp(gdi::StencilOp o) {
    switch (o) {
        case gdi::StencilOp::Zero: return GL_ZERO;
        case gdi::StencilOp::Replace: return GL_REPLACE;
        case gdi::StencilOp::IncrementClamp: return GL_INCR;
        case gdi::StencilOp::DecrementClamp: return GL_DECR;
        case gdi::StencilOp::Invert: return GL_INVERT;
        case gdi::StencilOp::IncrementWrap: return GL_INCR_WRAP;
        case gdi::StencilOp::DecrementWrap: return GL_DECR_WRAP;
        default: return GL_KEEP;
    }
}
GLenum blendFactor(gdi::BlendFactor f) {
    static const GLenum t[] = {GL_ZERO, GL_ONE, GL_SRC_COLOR, GL_ONE_MINUS_SRC_COLOR, GL_DST_COLOR, GL_ONE_MINUS_DST_COLOR,
                               GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_DST_ALPHA, GL_ONE_MINUS_DST_ALPHA,
                               GL_CONSTANT_COLOR, GL_ONE_MINUS_CONSTANT_COLOR};
    return t[int(f)];
}
GLenum blendOp(gdi::BlendOp o) {
    static const GLenum t[] = {GL_FUNC_ADD, GL_FUNC_SUBTRACT, GL_FUNC_REVERSE_SUBTRACT, GL_MIN, GL_MAX};
    return t[int(o)];
}
GLenum topology(gdi::PrimitiveTopology p) {
    static const GLenum t[] = {GL_TRIANGLES, GL_TRIANGLE_STRIP, GL_LINES, GL_LINE_STRIP, GL_POINTS};
    return t[int(p)];
}
}  // namespace

class GlCommandList final : public gdi::CommandList {
public:
    explicit GlCommandList(GlDevice& d) : dev_(d), gl_(d.gl()) {}

    void beginRenderPass(const gdi::RenderPassDesc& desc) override {
        if (inPass_) throw gdi::Error("beginRenderPass is not allowed inside a render pass");
        std::vector<gdi::validate::AttachmentInfo> infos;
        std::vector<std::pair<GLuint, uint32_t>> colors;
        for (const auto& c : desc.colors) {
            Texture& t = dev_.texture(c.texture);
            if (c.mipLevel >= t.desc.mipLevels) throw gdi::Error("beginRenderPass: attachment mip level out of range");
            infos.push_back({t.desc.format, std::max(1u, t.desc.width >> c.mipLevel), std::max(1u, t.desc.height >> c.mipLevel),
                             t.desc.usage});
            colors.push_back({t.name, c.mipLevel});
        }
        Texture* depth = desc.depth.texture ? &dev_.texture(desc.depth.texture) : nullptr;
        gdi::validate::AttachmentInfo di{};
        if (depth) di = {depth->desc.format, depth->desc.width, depth->desc.height, depth->desc.usage};
        area_ = gdi::validate::renderPass(desc, infos, depth ? &di : nullptr, dev_.info().limits);
        const bool stencil = depth && gdi::formatInfo(depth->desc.format).hasStencil;
        GLuint fbo = dev_.framebuffer(colors, depth ? depth->name : 0, stencil);
        if (desc.debugName) pushDebugGroup(desc.debugName);
        labelled_ = desc.debugName != nullptr;
        if (automatic_) gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
        gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
        // Clears must not be masked by the previous pipeline's write masks.
        gl_.Scissor(0, 0, GLsizei(area_.width), GLsizei(area_.height));
        for (size_t i = 0; i < desc.colors.size(); ++i) {
            gl_.ColorMaski(GLuint(i), GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
            if (desc.colors[i].load != gdi::LoadOp::Clear) continue;
            if (gdi::formatInfo(infos[i].format).isInteger) {
                GLuint v[4];
                for (int k = 0; k < 4; ++k) v[k] = GLuint(desc.colors[i].clear[k]);
                gl_.ClearNamedFramebufferuiv(fbo, GL_COLOR, GLint(i), v);
            } else {
                gl_.ClearNamedFramebufferfv(fbo, GL_COLOR, GLint(i), desc.colors[i].clear);
            }
        }
        if (depth && desc.depth.load == gdi::LoadOp::Clear) {
            gl_.DepthMask(GL_TRUE);
            gl_.StencilMask(0xff);
            if (stencil) gl_.ClearNamedFramebufferfi(fbo, GL_DEPTH_STENCIL, 0, desc.depth.clearDepth, desc.depth.clearStencil);
            else gl_.ClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &desc.depth.clearDepth);
        }
        inPass_ = true;
        pipeline_ = nullptr;  // a render pass starts with no pipeline (the clears above changed its state)
        readyToDraw_ = false;
        vertexDirty_ = indexDirty_ = true;
        setViewport({0, 0, float(area_.width), float(area_.height), 0, 1});
        setScissor(area_);
    }

    void endRenderPass() override {
        if (!inPass_) throw gdi::Error("endRenderPass without beginRenderPass");
        inPass_ = false;
        readyToDraw_ = false;
        if (automatic_) gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
        if (labelled_) popDebugGroup();
    }

    void setPipeline(gdi::PipelineHandle h) override {
        Pipeline& p = dev_.pipeline(h);
        if (pipeline_ != &p) {
            vertexDirty_ = indexDirty_ = true;  // another VAO
            unchecked_ = ~uint64_t(0);          // other slots, other kinds
        }
        pipeline_ = &p;
        requiredSlots_ = p.requiredSlots;
        readyToDraw_ = inPass_ && !p.compute;
        gl_.UseProgram(p.program);
        if (p.compute) return;
        topology_ = topology(p.desc.topology);
        const auto& d = p.desc;
        gl_.BindVertexArray(p.vao);
        if (d.raster.cullMode == gdi::CullMode::None) {
            gl_.Disable(GL_CULL_FACE);
        } else {
            gl_.Enable(GL_CULL_FACE);
            gl_.CullFace(d.raster.cullMode == gdi::CullMode::Back ? GL_BACK : GL_FRONT);
        }
        // gdi's winding is Vulkan's: its area formula is negated with respect to GL's over the
        // same (row-index) coordinates, so the GL enum is the opposite one.
        gl_.FrontFace(d.raster.frontFace == gdi::FrontFace::CounterClockwise ? GL_CW : GL_CCW);
        const auto& ds = d.depthStencil;
        if (ds.depthTest || ds.depthWrite) {
            gl_.Enable(GL_DEPTH_TEST);
            gl_.DepthFunc(ds.depthTest ? compare(ds.depthCompare) : GL_ALWAYS);
        } else {
            gl_.Disable(GL_DEPTH_TEST);
        }
        gl_.DepthMask(ds.depthWrite ? GL_TRUE : GL_FALSE);
        if (ds.stencilTest) {
            gl_.Enable(GL_STENCIL_TEST);
            for (auto [face, s] : {std::pair{GL_FRONT, ds.front}, std::pair{GL_BACK, ds.back}}) {
                gl_.StencilFuncSeparate(face, compare(s.compare), ds.stencilReference, ds.stencilReadMask);
                gl_.StencilOpSeparate(face, stencilOp(s.failOp), stencilOp(s.depthFailOp), stencilOp(s.passOp));
            }
            gl_.StencilMask(ds.stencilWriteMask);
        } else {
            gl_.Disable(GL_STENCIL_TEST);
        }
        for (size_t i = 0; i < d.colorFormats.size(); ++i) {
            gdi::BlendTargetState b = i < d.blend.size() ? d.blend[i] : gdi::BlendTargetState{};
            if (b.enable) {
                gl_.Enablei(GL_BLEND, GLuint(i));
                gl_.BlendFuncSeparatei(GLuint(i), blendFactor(b.srcColor), blendFactor(b.dstColor), blendFactor(b.srcAlpha),
                                       blendFactor(b.dstAlpha));
                gl_.BlendEquationSeparatei(GLuint(i), blendOp(b.colorOp), blendOp(b.alphaOp));
            } else {
                gl_.Disablei(GL_BLEND, GLuint(i));
            }
            const auto m = uint8_t(b.writeMask);
            gl_.ColorMaski(GLuint(i), m & 1, (m >> 1) & 1, (m >> 2) & 1, (m >> 3) & 1);
        }
        gl_.BlendColor(d.blendConstant[0], d.blendConstant[1], d.blendConstant[2], d.blendConstant[3]);
    }

    void setViewport(const gdi::Viewport& v) override {
        gl_.Viewport(GLint(v.x), GLint(v.y), GLsizei(v.width), GLsizei(v.height));
        gl_.DepthRangef(v.minDepth, v.maxDepth);
    }
    void setScissor(const gdi::Rect& r) override { gl_.Scissor(r.x, r.y, GLsizei(r.width), GLsizei(r.height)); }

    void setVertexBuffer(uint32_t index, gdi::BufferHandle h, uint64_t offset) override {
        if (index >= vertexBuffers_.size()) throw gdi::Error("setVertexBuffer: index out of range");
        Buffer& b = dev_.buffer(h);
        if (offset >= b.desc.size) gdi::validate::bufferRange(b.desc, offset, 1, "setVertexBuffer");
        if (vertexBuffers_[index] != std::pair<GLuint, uint64_t>{b.name, offset}) vertexDirty_ = true;
        vertexBuffers_[index] = {b.name, offset};
    }
    void setIndexBuffer(gdi::BufferHandle h, gdi::IndexType type, uint64_t offset) override {
        Buffer& b = dev_.buffer(h);
        if (offset >= b.desc.size) gdi::validate::bufferRange(b.desc, offset, 1, "setIndexBuffer");
        if (indexBuffer_ != b.name) indexDirty_ = true;
        indexBuffer_ = b.name;
        indexOffset_ = offset;
        indexType_ = type;
    }

    // Per-object path: plainly valid arguments go straight to GL; anything else (size 0 = "the
    // rest", errors) takes the checked path, which owns the messages.
    void setUniformBuffer(uint32_t slot, gdi::BufferHandle h, uint64_t offset, uint64_t size) override {
        setBuffer<gdi::BindingType::UniformBuffer>(slot, h, offset, size);
    }
    void setStorageBuffer(uint32_t slot, gdi::BufferHandle h, uint64_t offset, uint64_t size) override {
        setBuffer<gdi::BindingType::StorageBuffer>(slot, h, offset, size);
    }
    void setTexture(uint32_t slot, gdi::TextureHandle th, gdi::SamplerHandle sh) override {
        checkSlot(slot, "setTexture");
        Texture& t = dev_.texture(th);
        if (!any(t.desc.usage, gdi::TextureUsage::Sampled))
            throw gdi::Error("setTexture: texture '" + t.label + "' lacks Sampled usage");
        gl_.BindTextureUnit(slot, t.name);
        gl_.BindSampler(slot, dev_.sampler(sh).name);
        bound(slot, gdi::BindingType::SampledTexture);
    }
    void setStorageTexture(uint32_t slot, gdi::TextureHandle th, uint32_t mip) override {
        checkSlot(slot, "setStorageTexture");
        Texture& t = dev_.texture(th);
        if (!any(t.desc.usage, gdi::TextureUsage::Storage))
            throw gdi::Error("setStorageTexture: texture '" + t.label + "' lacks Storage usage");
        gl_.BindImageTexture(slot, t.name, GLint(mip), GL_FALSE, 0, GL_READ_WRITE, toGlFormat(t.desc.format).internal);
        bound(slot, gdi::BindingType::StorageTexture);
    }

    void draw(uint32_t vertexCount, uint32_t instanceCount, uint32_t firstVertex, uint32_t firstInstance) override {
        prepareDraw("draw");
        gl_.DrawArraysInstancedBaseInstance(topology_, GLint(firstVertex), GLsizei(vertexCount), GLsizei(instanceCount),
                                            firstInstance);
    }
    void drawIndexed(uint32_t indexCount, uint32_t instanceCount, uint32_t firstIndex, int32_t baseVertex,
                     uint32_t firstInstance) override {
        prepareDraw("drawIndexed");
        if (!indexBuffer_) throw gdi::Error("drawIndexed without an index buffer");
        if (indexDirty_) gl_.VertexArrayElementBuffer(pipeline_->vao, indexBuffer_);
        indexDirty_ = false;
        const uint32_t size = indexType_ == gdi::IndexType::U16 ? 2 : 4;
        gl_.DrawElementsInstancedBaseVertexBaseInstance(
            topology_, GLsizei(indexCount),
            indexType_ == gdi::IndexType::U16 ? GL_UNSIGNED_SHORT : GL_UNSIGNED_INT,
            reinterpret_cast<const void*>(uintptr_t(indexOffset_ + uint64_t(firstIndex) * size)), GLsizei(instanceCount),
            baseVertex, firstInstance);
    }
    void dispatch(uint32_t x, uint32_t y, uint32_t z) override {
        if (inPass_) throw gdi::Error("dispatch is not allowed inside a render pass");
        if (!pipeline_) throw gdi::Error("draw/dispatch without a pipeline (call setPipeline first)");
        if (!pipeline_->compute) throw gdi::Error("dispatch with graphics pipeline '" + pipeline_->label + "'");
        checkBindings();
        gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
        gl_.DispatchCompute(x, y, z);
        gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
    }

    void copyBuffer(gdi::BufferHandle dst, uint64_t dstOffset, gdi::BufferHandle src, uint64_t srcOffset, uint64_t size) override {
        outside("copyBuffer");
        Buffer& d = dev_.buffer(dst);
        Buffer& s = dev_.buffer(src);
        gdi::validate::bufferRange(d.desc, dstOffset, size, "copyBuffer destination");
        gdi::validate::bufferRange(s.desc, srcOffset, size, "copyBuffer source");
        if (size) gl_.CopyNamedBufferSubData(s.name, d.name, GLintptr(srcOffset), GLintptr(dstOffset), GLsizeiptr(size));
        gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
    }
    void copyTexture(gdi::TextureHandle dst, gdi::TextureHandle src, uint32_t mip) override {
        outside("copyTexture");
        Texture& d = dev_.texture(dst);
        Texture& s = dev_.texture(src);
        if (d.desc.format != s.desc.format || d.desc.width != s.desc.width || d.desc.height != s.desc.height)
            throw gdi::Error("copyTexture: '" + s.label + "' and '" + d.label + "' differ in format or size");
        if (mip >= d.desc.mipLevels || mip >= s.desc.mipLevels) throw gdi::Error("copyTexture: mip level out of range");
        gl_.CopyImageSubData(s.name, GL_TEXTURE_2D, GLint(mip), 0, 0, 0, d.name, GL_TEXTURE_2D, GLint(mip), 0, 0, 0,
                             GLsizei(std::max(1u, d.desc.width >> mip)), GLsizei(std::max(1u, d.desc.height >> mip)), 1);
        gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
    }
    void copyBufferToTexture(gdi::TextureHandle dst, uint32_t mip, gdi::BufferHandle src, uint64_t srcOffset) override {
        outside("copyBufferToTexture");
        Texture& t = dev_.texture(dst);
        Buffer& b = dev_.buffer(src);
        if (mip >= t.desc.mipLevels) throw gdi::Error("copyBufferToTexture: mip level out of range");
        if (gdi::isDepthFormat(t.desc.format)) throw gdi::Error("copyBufferToTexture: depth formats are not supported");
        const uint32_t w = std::max(1u, t.desc.width >> mip), h = std::max(1u, t.desc.height >> mip);
        gdi::validate::bufferRange(b.desc, srcOffset, uint64_t(w) * h * gdi::formatInfo(t.desc.format).bytesPerPixel,
                                   "copyBufferToTexture source");
        GlFormat f = toGlFormat(t.desc.format);
        gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
        gl_.BindBuffer(GL_PIXEL_UNPACK_BUFFER, b.name);
        gl_.TextureSubImage2D(t.name, GLint(mip), 0, 0, GLsizei(w), GLsizei(h), f.format, f.type,
                              reinterpret_cast<const void*>(uintptr_t(srcOffset)));
        gl_.BindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    }
    void copyTextureToBuffer(gdi::BufferHandle dst, uint64_t dstOffset, gdi::TextureHandle src, uint32_t mip) override {
        outside("copyTextureToBuffer");
        Texture& t = dev_.texture(src);
        Buffer& b = dev_.buffer(dst);
        if (mip >= t.desc.mipLevels) throw gdi::Error("copyTextureToBuffer: mip level out of range");
        if (gdi::isDepthFormat(t.desc.format)) throw gdi::Error("copyTextureToBuffer: depth formats are not supported");
        const uint32_t w = std::max(1u, t.desc.width >> mip), h = std::max(1u, t.desc.height >> mip);
        const uint64_t bytes = uint64_t(w) * h * gdi::formatInfo(t.desc.format).bytesPerPixel;
        gdi::validate::bufferRange(b.desc, dstOffset, bytes, "copyTextureToBuffer destination");
        GlFormat f = toGlFormat(t.desc.format);
        gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
        gl_.BindBuffer(GL_PIXEL_PACK_BUFFER, b.name);
        gl_.GetTextureImage(t.name, GLint(mip), f.format, f.type, GLsizei(bytes), reinterpret_cast<void*>(uintptr_t(dstOffset)));
        gl_.BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    }

    void beginTimer(gdi::TimerHandle h) override {
        outside("beginTimer");
        Timer& t = dev_.timer(h);
        if (drainSoftwareRasterizer()) t.begin = std::chrono::steady_clock::now();
        gl_.QueryCounter(t.queries[0], GL_TIMESTAMP);
    }
    void endTimer(gdi::TimerHandle h) override {
        Timer& t = dev_.timer(h);
        if (drainSoftwareRasterizer()) t.end = std::chrono::steady_clock::now();
        gl_.QueryCounter(t.queries[1], GL_TIMESTAMP);
        t.used = true;
    }
    // llvmpipe's GL_TIMESTAMP does not wait for the binned rendering before it (measured: a
    // 3 s forward pass timed as 9 ms, even after glFinish). On software rasterizers a timed
    // section is therefore the wall-clock time between two glFinish calls: GL executes as it
    // records, so that is the pass's whole cost. Hardware drivers keep GL_TIMESTAMP.
    bool drainSoftwareRasterizer() {
        if (!dev_.info().softwareRasterizer) return false;
        gl_.Finish();
        return true;
    }
    void pushDebugGroup(const char* name) override {
        ++depth_;
        gl_.PushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, name ? name : "");
    }
    void popDebugGroup() override {
        if (depth_ == 0) throw gdi::Error("popDebugGroup without pushDebugGroup");
        --depth_;
        gl_.PopDebugGroup();
    }
    void discardTexture(gdi::TextureHandle h) override {
        outside("discardTexture");
        (void)dev_.texture(h);  // GL reuses whole objects; contents are simply overwritten
    }
    // GL orders framebuffer writes, copies and texture fetches itself; only image stores
    // (Storage) need glMemoryBarrier, and Undefined lets the driver drop old contents.
    void setAutomaticBarriers(bool enabled) override {
        outside("setAutomaticBarriers");
        if (enabled != automatic_) gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
        automatic_ = enabled;
    }
    void barrier(const gdi::TextureBarrier* barriers, uint32_t count) override {
        outside("barrier");
        bool storage = false;
        for (uint32_t i = 0; i < count; ++i) {
            if (barriers[i].after == gdi::ResourceState::Undefined)
                throw gdi::Error("barrier: a texture cannot go to Undefined");
            Texture& t = dev_.texture(barriers[i].texture);
            if (barriers[i].before == gdi::ResourceState::Undefined)
                for (uint32_t m = 0; m < t.desc.mipLevels; ++m) gl_.InvalidateTexImage(t.name, GLint(m));
            storage = storage || barriers[i].before == gdi::ResourceState::Storage;
        }
        if (storage) gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
    }
    uint64_t nativeCommandBuffer() override {
        if (inPass_) throw gdi::Error("submit: render pass still open (missing endRenderPass)");
        if (depth_) throw gdi::Error("submit: debug group(s) not popped");
        kinds_ = {};  // a new recording starts after submit
        unchecked_ = ~uint64_t(0);
        if (!automatic_) gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
        automatic_ = true;
        return 0;
    }

private:
    void checkSlot(uint32_t slot, const char* what) {
        if (slot >= 64) throw gdi::Error(std::string(what) + ": slot " + std::to_string(slot) + " out of range");
    }
    void outside(const char* what) {
        if (inPass_) throw gdi::Error(std::string(what) + " is not allowed inside a render pass");
    }
    template <gdi::BindingType kKind>
    static constexpr GLenum kTarget = kKind == gdi::BindingType::UniformBuffer ? GL_UNIFORM_BUFFER : GL_SHADER_STORAGE_BUFFER;
    template <gdi::BindingType kKind>
    void setBuffer(uint32_t slot, gdi::BufferHandle h, uint64_t offset, uint64_t size) {
        const Buffer* b = dev_.findBuffer(h);
        const uint64_t bindSize = b ? gdi::validate::plainBindingSize(slot, b->desc.size, offset, size) : 0;
        if (!bindSize) [[unlikely]]
            return setBufferChecked<kKind>(slot, h, offset, size);
        bound(slot, kKind);
        gl_.BindBufferRange(kTarget<kKind>, slot, b->name, GLintptr(offset), GLsizeiptr(bindSize));
    }
    template <gdi::BindingType kKind>
    [[gnu::noinline]] void setBufferChecked(uint32_t slot, gdi::BufferHandle h, uint64_t offset, uint64_t size) {
        const char* what = kKind == gdi::BindingType::UniformBuffer ? "setUniformBuffer" : "setStorageBuffer";
        checkSlot(slot, what);
        Buffer& b = dev_.buffer(h);
        if (size == 0) size = b.desc.size - std::min(offset, b.desc.size);
        gdi::validate::bindingRange(b.desc, offset, size, what);
        gl_.BindBufferRange(kTarget<kKind>, slot, b.name, GLintptr(offset), GLsizeiptr(size));
        bound(slot, kKind);
    }
    void bound(uint32_t slot, gdi::BindingType kind) {
        kinds_[slot] = uint8_t(1 + uint8_t(kind));
        unchecked_ |= uint64_t(1) << slot;
    }
    // Every slot the pipeline uses must be bound with the kind it declares (GL would otherwise
    // read whatever the other binding namespace holds). Only slots changed since the last check
    // with this pipeline are looked at; an unbound slot (kind 0) fails the same comparison.
    void checkBindings() {
        const uint64_t check = unchecked_ & requiredSlots_;
        if (!check) return;
        if (!(check & (check - 1))) [[likely]] {  // the per-object case: one slot changed
            const uint32_t slot = uint32_t(std::countr_zero(check));
            if (kinds_[slot] != pipeline_->slotKinds[slot]) [[unlikely]]
                checkEachSlot(check);
            unchecked_ &= ~check;
            return;
        }
        checkEachSlot(check);
        unchecked_ &= ~check;
    }
    [[gnu::noinline]] void checkEachSlot(uint64_t check) const {  // throws for the first problem
        uint64_t missing = 0;
        for (uint64_t m = check; m; m &= m - 1)
            if (!kinds_[std::countr_zero(m)]) missing |= m & -m;
        gdi::validate::missingBindings(missing, 0, pipeline_->label.c_str());
        for (uint64_t m = check; m; m &= m - 1) {
            const uint32_t slot = uint32_t(std::countr_zero(m));
            if (kinds_[slot] != pipeline_->slotKinds[slot]) [[unlikely]]
                gdi::validate::wrongBindingKindFailed(slot, gdi::BindingType(pipeline_->slotKinds[slot] - 1),
                                                      gdi::BindingType(kinds_[slot] - 1), pipeline_->label.c_str());
        }
    }
    [[noreturn, gnu::cold, gnu::noinline]] void notReadyToDraw(const char* what) const {
        if (!inPass_) throw gdi::Error(std::string(what) + " outside a render pass");
        if (!pipeline_) throw gdi::Error(std::string(what) + " without a pipeline (call setPipeline first)");
        throw gdi::Error(std::string(what) + " with compute pipeline '" + pipeline_->label + "'");
    }
    void prepareDraw(const char* what) {
        if (!readyToDraw_) [[unlikely]]
            notReadyToDraw(what);
        checkBindings();
        if (vertexDirty_) [[unlikely]]  // re-binding unchanged buffers per draw is measurable CPU cost
            bindVertexBuffers();
    }
    void bindVertexBuffers() {
        for (size_t i = 0; i < pipeline_->strides.size(); ++i)
            gl_.VertexArrayVertexBuffer(pipeline_->vao, GLuint(i), vertexBuffers_[i].first, GLintptr(vertexBuffers_[i].second),
                                        GLsizei(pipeline_->strides[i]));
        vertexDirty_ = false;
    }

    GlDevice& dev_;
    const GlFunctions& gl_;
    bool inPass_ = false, labelled_ = false;
    bool automatic_ = true;  // setAutomaticBarriers
    int depth_ = 0;
    gdi::Rect area_;
    Pipeline* pipeline_ = nullptr;
    bool readyToDraw_ = false;    // in a render pass with a graphics pipeline
    uint64_t requiredSlots_ = 0;  // pipeline_->requiredSlots
    GLenum topology_ = GL_TRIANGLES;
    std::array<uint8_t, 64> kinds_{};      // per slot: 1 + BindingType bound, 0 = unbound
    uint64_t unchecked_ = ~uint64_t(0);  // slots to check at the next draw/dispatch
    std::array<std::pair<GLuint, uint64_t>, 16> vertexBuffers_{};
    bool vertexDirty_ = true, indexDirty_ = true;
    GLuint indexBuffer_ = 0;
    uint64_t indexOffset_ = 0;
    gdi::IndexType indexType_ = gdi::IndexType::U32;
};

std::unique_ptr<gdi::CommandList> GlDevice::createCommandList() {
    loss_.check("createCommandList");
    return std::make_unique<GlCommandList>(*this);
}

}  // namespace fe::gl

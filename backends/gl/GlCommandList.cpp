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
        using gdi::validate::attachment;
        std::vector<gdi::validate::AttachmentInfo> infos, resolveInfos(desc.colors.size());
        std::vector<FboAttachment> colors;
        resolves_.clear();
        for (size_t i = 0; i < desc.colors.size(); ++i) {
            const auto& c = desc.colors[i];
            Texture& t = dev_.texture(c.texture);
            infos.push_back(attachment(t.desc, c.mipLevel, c.layer, "beginRenderPass", t.label));
            colors.push_back(dev_.fboAttachment(t, c.mipLevel, c.layer));
            if (c.resolveTexture) {
                Texture& r = dev_.texture(c.resolveTexture);
                const gdi::Subresource at = c.resolveSubresource;
                resolveInfos[i] = attachment(r.desc, at.mipLevel, at.layer, "beginRenderPass resolve", r.label);
                resolves_.push_back({GLenum(GL_COLOR_ATTACHMENT0 + i), dev_.fboAttachment(r, at.mipLevel, at.layer)});
            }
        }
        Texture* depth = desc.depth.texture ? &dev_.texture(desc.depth.texture) : nullptr;
        gdi::validate::AttachmentInfo di{}, dri{};
        if (depth) di = attachment(depth->desc, desc.depth.mipLevel, desc.depth.layer, "beginRenderPass", depth->label);
        Texture* depthResolve = desc.depth.resolveTexture ? &dev_.texture(desc.depth.resolveTexture) : nullptr;
        if (depthResolve) {
            if (!depth) throw gdi::Error("beginRenderPass: a depth resolve target without a depth attachment");
            const gdi::Subresource at = desc.depth.resolveSubresource;
            dri = attachment(depthResolve->desc, at.mipLevel, at.layer, "beginRenderPass resolve", depthResolve->label);
        }
        area_ = gdi::validate::renderPass(desc, infos, resolveInfos, depth ? &di : nullptr, depthResolve ? &dri : nullptr,
                                          dev_.info().limits);
        passSamples_ = infos.empty() ? di.samples : infos[0].samples;
        const bool stencil = depth && gdi::formatInfo(depth->desc.format).hasStencil;
        GLuint fbo = dev_.framebuffer(colors, depth ? dev_.fboAttachment(*depth, desc.depth.mipLevel, desc.depth.layer) : FboAttachment{},
                                      stencil);
        fbo_ = fbo;
        if (depthResolve)
            resolves_.push_back({GLenum(stencil ? GL_DEPTH_STENCIL_ATTACHMENT : GL_DEPTH_ATTACHMENT),
                                 dev_.fboAttachment(*depthResolve, desc.depth.resolveSubresource.mipLevel,
                                                    desc.depth.resolveSubresource.layer)});
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
        if (!resolves_.empty()) resolve();
        inPass_ = false;
        readyToDraw_ = false;
        if (automatic_) gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
        if (labelled_) popDebugGroup();
    }

    void setPipeline(gdi::PipelineHandle h) override {
        Pipeline& p = dev_.pipeline(h);
        if (inPass_ && !p.compute) gdi::validate::pipelineSamples(p.desc.multisample.sampleCount, passSamples_, p.label.c_str());
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
        // Depth bias: glPolygonOffset(factor, units) is Vulkan's (slope, constant) with the same formula.
        if (d.raster.depthBiasConstant != 0 || d.raster.depthBiasSlope != 0) {
            gl_.Enable(GL_POLYGON_OFFSET_FILL);
            if (gl_.PolygonOffsetClamp)
                gl_.PolygonOffsetClamp(d.raster.depthBiasSlope, d.raster.depthBiasConstant, d.raster.depthBiasClamp);
            else
                gl_.PolygonOffset(d.raster.depthBiasSlope, d.raster.depthBiasConstant);
        } else {
            gl_.Disable(GL_POLYGON_OFFSET_FILL);
        }
        if (d.raster.depthClamp) gl_.Enable(GL_DEPTH_CLAMP);
        else gl_.Disable(GL_DEPTH_CLAMP);
        if (d.multisample.alphaToCoverage) gl_.Enable(GL_SAMPLE_ALPHA_TO_COVERAGE);
        else gl_.Disable(GL_SAMPLE_ALPHA_TO_COVERAGE);
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
        if (mip >= t.desc.mipLevels) throw gdi::Error("setStorageTexture: mip level out of range");
        // Every layer (arrays, cubes, 3D slices) of the mip, as Vulkan's storage view binds it.
        const GLboolean layered = t.target == GL_TEXTURE_2D ? GL_FALSE : GL_TRUE;
        gl_.BindImageTexture(slot, t.name, GLint(mip), layered, 0, GL_READ_WRITE, toGlFormat(t.desc.format).internal);
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
        prepareIndexed("drawIndexed", false);
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
        if (d.desc.format != s.desc.format || d.desc.width != s.desc.width || d.desc.height != s.desc.height ||
            d.desc.dimension != s.desc.dimension || d.desc.depthOrLayers != s.desc.depthOrLayers ||
            d.desc.sampleCount != s.desc.sampleCount)
            throw gdi::Error("copyTexture: '" + s.label + "' and '" + d.label + "' differ in format, kind, size or samples");
        if (mip >= d.desc.mipLevels || mip >= s.desc.mipLevels) throw gdi::Error("copyTexture: mip level out of range");
        const gdi::validate::Extent3 e = gdi::validate::mipExtent(d.desc, mip);
        gl_.CopyImageSubData(s.name, s.target, GLint(mip), 0, 0, 0, d.name, d.target, GLint(mip), 0, 0, 0, GLsizei(e.width),
                             GLsizei(e.height), GLsizei(e.depthOrLayers));
        gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
    }
    // One subresource through a pixel buffer; checks shared by both directions.
    uint64_t bufferTextureBytes(const Texture& t, gdi::Subresource at, const Buffer& b, uint64_t offset, const char* what) {
        outside(what);
        gdi::validate::subresource(t.desc, at, what, t.label);
        if (gdi::isDepthFormat(t.desc.format)) throw gdi::Error(std::string(what) + ": depth formats are not supported");
        if (t.desc.sampleCount > 1) throw gdi::Error(std::string(what) + ": multisampled textures are not supported");
        const gdi::validate::Extent3 e = gdi::validate::mipExtent(t.desc, at.mipLevel);
        const uint64_t bytes = gdi::imageByteSize(t.desc.format, e.width, e.height);
        gdi::validate::bufferRange(b.desc, offset, bytes, what);
        if (offset % 4) throw gdi::Error(std::string(what) + ": buffer offset must be a multiple of 4");
        return bytes;
    }
    void copyBufferToTexture(gdi::TextureHandle dst, gdi::Subresource at, gdi::BufferHandle src, uint64_t srcOffset) override {
        Texture& t = dev_.texture(dst);
        Buffer& b = dev_.buffer(src);
        const uint64_t bytes = bufferTextureBytes(t, at, b, srcOffset, "copyBufferToTexture");
        gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
        gl_.BindBuffer(GL_PIXEL_UNPACK_BUFFER, b.name);
        dev_.uploadSubresource(t, at, reinterpret_cast<const void*>(uintptr_t(srcOffset)), bytes);
        gl_.BindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    }
    void copyTextureToBuffer(gdi::BufferHandle dst, uint64_t dstOffset, gdi::TextureHandle src, gdi::Subresource at) override {
        Texture& t = dev_.texture(src);
        Buffer& b = dev_.buffer(dst);
        const uint64_t bytes = bufferTextureBytes(t, at, b, dstOffset, "copyTextureToBuffer");
        gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
        gl_.BindBuffer(GL_PIXEL_PACK_BUFFER, b.name);
        dev_.readSubresource(t, at, reinterpret_cast<void*>(uintptr_t(dstOffset)), bytes);
        gl_.BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    }
    void generateMips(gdi::TextureHandle h) override {
        outside("generateMips");
        Texture& t = dev_.texture(h);
        gdi::validate::mipGeneration(t.desc, t.label);
        gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
        gl_.GenerateTextureMipmap(t.name);
    }

    // Indirect work. GL reads indexed records relative to the element buffer's start, so the
    // index buffer must be bound at offset 0 (checked on every backend, so both behave alike).
    void drawIndirect(gdi::BufferHandle args, uint64_t offset, uint32_t drawCount, uint32_t stride) override {
        indirectArgs(args, offset, drawCount, stride, sizeof(gdi::DrawIndirectArgs), "drawIndirect");
        gl_.MultiDrawArraysIndirect(topology_, reinterpret_cast<const void*>(uintptr_t(offset)), GLsizei(drawCount), GLsizei(stride));
    }
    void drawIndexedIndirect(gdi::BufferHandle args, uint64_t offset, uint32_t drawCount, uint32_t stride) override {
        indirectArgs(args, offset, drawCount, stride, sizeof(gdi::DrawIndexedIndirectArgs), "drawIndexedIndirect");
        gl_.MultiDrawElementsIndirect(topology_, indexType(), reinterpret_cast<const void*>(uintptr_t(offset)), GLsizei(drawCount),
                                      GLsizei(stride));
    }
    void drawIndirectCount(gdi::BufferHandle args, uint64_t offset, gdi::BufferHandle count, uint64_t countOffset,
                           uint32_t maxDrawCount, uint32_t stride) override {
        countBuffer(count, countOffset, "drawIndirectCount");
        indirectArgs(args, offset, maxDrawCount, stride, sizeof(gdi::DrawIndirectArgs), "drawIndirectCount");
        gl_.MultiDrawArraysIndirectCount(topology_, reinterpret_cast<const void*>(uintptr_t(offset)), GLintptr(countOffset),
                                         GLsizei(maxDrawCount), GLsizei(stride));
    }
    void drawIndexedIndirectCount(gdi::BufferHandle args, uint64_t offset, gdi::BufferHandle count, uint64_t countOffset,
                                  uint32_t maxDrawCount, uint32_t stride) override {
        countBuffer(count, countOffset, "drawIndexedIndirectCount");
        indirectArgs(args, offset, maxDrawCount, stride, sizeof(gdi::DrawIndexedIndirectArgs), "drawIndexedIndirectCount");
        gl_.MultiDrawElementsIndirectCount(topology_, indexType(), reinterpret_cast<const void*>(uintptr_t(offset)),
                                           GLintptr(countOffset), GLsizei(maxDrawCount), GLsizei(stride));
    }
    void dispatchIndirect(gdi::BufferHandle args, uint64_t offset) override {
        if (inPass_) throw gdi::Error("dispatchIndirect is not allowed inside a render pass");
        if (!pipeline_) throw gdi::Error("dispatchIndirect without a pipeline (call setPipeline first)");
        if (!pipeline_->compute) throw gdi::Error("dispatchIndirect with graphics pipeline '" + pipeline_->label + "'");
        const Buffer& b = dev_.buffer(args);
        gdi::validate::indirect(b.desc, b.label, offset, 1, sizeof(gdi::DispatchIndirectArgs), sizeof(gdi::DispatchIndirectArgs),
                                dev_.info().features, "dispatchIndirect");
        checkBindings();
        gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
        gl_.BindBuffer(GL_DISPATCH_INDIRECT_BUFFER, b.name);
        gl_.DispatchComputeIndirect(GLintptr(offset));
        gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
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
    GLenum indexType() const { return indexType_ == gdi::IndexType::U16 ? GL_UNSIGNED_SHORT : GL_UNSIGNED_INT; }
    void indirectArgs(gdi::BufferHandle h, uint64_t offset, uint32_t drawCount, uint32_t stride, uint32_t recordSize,
                      const char* what) {
        // Same order of checks as Vulkan: draw state, index buffer, then the arguments.
        prepareDraw(what);
        if (recordSize == sizeof(gdi::DrawIndexedIndirectArgs)) prepareIndexed(what, true);
        const Buffer& b = dev_.buffer(h);
        gdi::validate::indirect(b.desc, b.label, offset, drawCount, stride, recordSize, dev_.info().features, what);
        gl_.BindBuffer(GL_DRAW_INDIRECT_BUFFER, b.name);
    }
    void countBuffer(gdi::BufferHandle h, uint64_t offset, const char* what) {
        if (!dev_.info().features.drawIndirectCount)
            throw gdi::Error(std::string(what) + ": not supported on this device (DeviceFeatures::drawIndirectCount)");
        const Buffer& b = dev_.buffer(h);
        gdi::validate::indirect(b.desc, b.label, offset, 1, 4, 4, dev_.info().features, what);
        gl_.BindBuffer(GL_PARAMETER_BUFFER, b.name);
    }
    // Writes every resolve target from the pass's multisampled attachments. A blit from a
    // multisampled framebuffer resolves; colour averages the samples. Depth: GL leaves the
    // choice to the implementation; Mesa takes sample 0, which is what Vulkan's SAMPLE_ZERO
    // gives (conformance case msaa_resolve checks both against the same expectation).
    void resolve() {
        gl_.Disable(GL_SCISSOR_TEST);  // blits honour the scissor
        // GL_FRAMEBUFFER_SRGB stays on: sRGB samples are averaged as linear values and encoded
        // again, as Vulkan's AVERAGE resolve does (msaa_resolve's colour_srgb image checks it).
        for (const auto& [point, target] : resolves_) {
            const bool color = point >= GL_COLOR_ATTACHMENT0 && point < GL_COLOR_ATTACHMENT0 + 16;
            std::vector<FboAttachment> colors;
            FboAttachment depth{};
            if (color) colors.push_back(target);
            else depth = target;
            const GLuint dst = dev_.framebuffer(colors, depth, point == GL_DEPTH_STENCIL_ATTACHMENT);
            if (color) gl_.NamedFramebufferReadBuffer(fbo_, point);
            gl_.BlitNamedFramebuffer(fbo_, dst, 0, 0, GLint(area_.width), GLint(area_.height), 0, 0, GLint(area_.width),
                                     GLint(area_.height), color ? GL_COLOR_BUFFER_BIT : GL_DEPTH_BUFFER_BIT, GL_NEAREST);
        }
        gl_.Enable(GL_SCISSOR_TEST);
        resolves_.clear();
    }
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
    void prepareIndexed(const char* what, bool indirect) {
        if (!indexBuffer_) throw gdi::Error(std::string(what) + " without an index buffer");
        if (indirect && indexOffset_ != 0)
            throw gdi::Error(std::string(what) + ": the index buffer must be bound at offset 0 (records hold firstIndex)");
        if (indexDirty_) gl_.VertexArrayElementBuffer(pipeline_->vao, indexBuffer_);
        indexDirty_ = false;
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
    uint32_t passSamples_ = 1;  // sample count of the open pass's attachments
    GLuint fbo_ = 0;            // the open pass's framebuffer
    std::vector<std::pair<GLenum, FboAttachment>> resolves_;  // attachment point -> resolve target, at endRenderPass
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

// Replay of a recorded stream as GL calls (the context thread runs it at submit).
#include "gl/GlReplay.h"

#include <chrono>
#include <cstring>

#include "fe/gdi/Validation.h"

namespace fe::gl {

namespace cmd = gdi::cmd;

namespace {
GLenum compare(gdi::CompareOp c) {
    return GLenum(GL_NEVER + int(c));
}  // same order as GL_NEVER..GL_ALWAYS
GLenum stencilOp(gdi::StencilOp o) {
    switch (o) {
        case gdi::StencilOp::Zero:
            return GL_ZERO;
        case gdi::StencilOp::Replace:
            return GL_REPLACE;
        case gdi::StencilOp::IncrementClamp:
            return GL_INCR;
        case gdi::StencilOp::DecrementClamp:
            return GL_DECR;
        case gdi::StencilOp::Invert:
            return GL_INVERT;
        case gdi::StencilOp::IncrementWrap:
            return GL_INCR_WRAP;
        case gdi::StencilOp::DecrementWrap:
            return GL_DECR_WRAP;
        default:
            return GL_KEEP;
    }
}
GLenum blendFactor(gdi::BlendFactor f) {
    static const GLenum t[] = {GL_ZERO,           GL_ONE,
                               GL_SRC_COLOR,      GL_ONE_MINUS_SRC_COLOR,
                               GL_DST_COLOR,      GL_ONE_MINUS_DST_COLOR,
                               GL_SRC_ALPHA,      GL_ONE_MINUS_SRC_ALPHA,
                               GL_DST_ALPHA,      GL_ONE_MINUS_DST_ALPHA,
                               GL_CONSTANT_COLOR, GL_ONE_MINUS_CONSTANT_COLOR};
    return t[int(f)];
}
GLenum blendOp(gdi::BlendOp o) {
    static const GLenum t[] = {GL_FUNC_ADD, GL_FUNC_SUBTRACT, GL_FUNC_REVERSE_SUBTRACT, GL_MIN,
                               GL_MAX};
    return t[int(o)];
}
GLenum topology(gdi::PrimitiveTopology p) {
    static const GLenum t[] = {GL_TRIANGLES,  GL_TRIANGLE_STRIP, GL_LINES,
                               GL_LINE_STRIP, GL_POINTS,         GL_PATCHES};
    return t[int(p)];
}
}  // namespace

void GlReplay::run(const cmd::CommandStream& stream, const std::atomic<bool>* waiting,
                   const std::function<void()>& serve) {
    stream_ = &stream;
    waiting_ = waiting;
    serve_ = &serve;
    constants_ = {};  // each recording starts with zero constants
    constantsDirty_ = true;
    replayRecords(stream);
    // A recording ends with automatic barriers on again; anything it left unordered is ordered
    // before later submissions and readback.
    if (!automatic_) gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
    automatic_ = true;
}

// Locals, not members, on the per-command path: a member would be reloaded and stored around
// every record's call (measured: about 30 instructions per draw).
void GlReplay::replayRecords(const cmd::CommandStream& stream) {
    static const std::atomic<bool> never{false};
    const std::atomic<bool>& waiting = waiting_ ? *waiting_ : never;
    const std::function<void()>& serve = *serve_;
    stream.forEach([&](const auto& record) {
        (*this)(record);
        // One load a command (the flag's writer takes the queue's lock, which orders the task).
        if (waiting.load(std::memory_order_relaxed)) [[unlikely]]
            serve();
    });
}

// A secondary list's records, in place (it sets its own viewport, scissor, pipeline and bindings).
void GlReplay::operator()(const cmd::ExecuteSecondary& r) {
    const cmd::CommandStream* primary = stream_;
    const auto primaryConstants =
        constants_;  // a secondary starts from zeros and leaves the primary's alone
    constants_ = {};
    constantsDirty_ = true;
    dynamicSet_ = 0;  // and from its pipelines' state
    stream_ = &primary->child(r.child);
    replayRecords(*stream_);
    stream_ = primary;
    constants_ = primaryConstants;
    constantsDirty_ = true;
    // The primary's draws after it take blend constant, stencil reference and depth bias from
    // their pipelines again (Vulkan leaves that state undefined after vkCmdExecuteCommands).
    dynamicSet_ = 0;
}

void GlReplay::operator()(const cmd::SetConstants& r) {
    const auto data = cmd::view(r, r.data);
    std::memcpy(constants_.data() + r.offset, data.data(), data.size());
    constantsDirty_ = true;
}
void GlReplay::flushConstants() {
    constantsDirty_ = false;
    if (pipeline_->constantBytes)
        dev_.constantsRing().bind(gl_, constants_.data(), pipeline_->constantBytes,
                                  dev_.info().limits.uniformBufferOffsetAlignment);
}

void GlReplay::operator()(const cmd::BeginRenderPass& r) {
    dynamicSet_ = 0;  // each pass starts from its pipelines' values
    gl_.Disable(
        GL_RASTERIZER_DISCARD);  // a pipeline's empty sample mask must not discard the clears
    const auto colorsIn = cmd::view(r, r.colors);
    std::vector<FboAttachment> colors;
    resolves_.clear();
    for (size_t i = 0; i < colorsIn.size(); ++i) {
        const auto& c = colorsIn[i];
        colors.push_back(dev_.fboAttachment(dev_.textureAt(c.texture), c.mipLevel, c.layer));
        if (c.resolveTexture)
            resolves_.push_back(
                {GLenum(GL_COLOR_ATTACHMENT0 + i),
                 dev_.fboAttachment(dev_.textureAt(c.resolveTexture), c.resolveSubresource.mipLevel,
                                    c.resolveSubresource.layer)});
    }
    const gdi::DepthAttachment& d = r.depth;
    const Texture* depth = d.texture ? &dev_.textureAt(d.texture) : nullptr;
    const GLenum depthPoint = depth ? depthAttachmentPoint(depth->desc.format) : GL_NONE;
    const GLuint fbo = dev_.framebuffer(
        colors, depth ? dev_.fboAttachment(*depth, d.mipLevel, d.layer) : FboAttachment{},
        depthPoint);
    fbo_ = fbo;
    if (d.resolveTexture)
        resolves_.push_back({depthPoint, dev_.fboAttachment(dev_.textureAt(d.resolveTexture),
                                                            d.resolveSubresource.mipLevel,
                                                            d.resolveSubresource.layer)});
    // The render area: the attachments' common size (validated when recorded).
    const Texture& first = colorsIn.empty() ? *depth : dev_.textureAt(colorsIn[0].texture);
    const uint32_t mip = colorsIn.empty() ? d.mipLevel : colorsIn[0].mipLevel;
    const gdi::validate::Extent3 e = gdi::validate::mipExtent(first.desc, mip);
    area_ = {0, 0, e.width, e.height};
    const char* name = cmd::view(r, r.debugName);
    labelled_ = name != nullptr;
    if (labelled_) gl_.PushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, name);
    if (automatic_) gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
    gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    // Clears must not be masked by the previous pipeline's write masks.
    gl_.Scissor(0, 0, GLsizei(area_.width), GLsizei(area_.height));
    for (size_t i = 0; i < colorsIn.size(); ++i) {
        gl_.ColorMaski(GLuint(i), GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        if (colorsIn[i].load != gdi::LoadOp::Clear) continue;
        if (gdi::formatInfo(dev_.textureAt(colorsIn[i].texture).desc.format).isInteger) {
            GLuint v[4];
            for (int k = 0; k < 4; ++k) v[k] = GLuint(colorsIn[i].clear[k]);
            gl_.ClearNamedFramebufferuiv(fbo, GL_COLOR, GLint(i), v);
        } else {
            gl_.ClearNamedFramebufferfv(fbo, GL_COLOR, GLint(i), colorsIn[i].clear);
        }
    }
    if (depth && d.load == gdi::LoadOp::Clear) {
        gl_.DepthMask(GL_TRUE);
        gl_.StencilMask(0xff);
        if (depthPoint == GL_DEPTH_STENCIL_ATTACHMENT) {
            gl_.ClearNamedFramebufferfi(fbo, GL_DEPTH_STENCIL, 0, d.clearDepth, d.clearStencil);
        } else if (depthPoint == GL_DEPTH_ATTACHMENT) {
            gl_.ClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &d.clearDepth);
        } else {
            const GLint s = d.clearStencil;
            gl_.ClearNamedFramebufferiv(fbo, GL_STENCIL, 0, &s);
        }
    }
    pipeline_ =
        nullptr;  // a render pass starts with no pipeline (the clears above changed its state)
    vertexDirty_ = indexDirty_ = true;
    (*this)(cmd::SetViewport{{0, 0, float(area_.width), float(area_.height), 0, 1}});
    (*this)(cmd::SetScissor{area_});
}

void GlReplay::operator()(const cmd::EndRenderPass&) {
    gl_.Disable(GL_RASTERIZER_DISCARD);
    if (!resolves_.empty()) resolve();
    if (automatic_) gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
    if (labelled_) gl_.PopDebugGroup();
    labelled_ = false;
}

void GlReplay::operator()(const cmd::SetPipeline& r) {
    const Pipeline& p = dev_.pipelineAt(r.pipeline);
    if (pipeline_ != &p)
        vertexDirty_ = indexDirty_ = constantsDirty_ = imagesDirty_ =
            true;  // another VAO, block size, units
    pipeline_ = &p;
    gl_.UseProgram(p.program);
    if (p.compute) return;
    topology_ = topology(p.desc.topology);
    if (p.desc.patchControlPoints)
        gl_.PatchParameteri(GL_PATCH_VERTICES, GLint(p.desc.patchControlPoints));
    applyPipelineState(p);
}

void GlReplay::applyPipelineState(const Pipeline& p) {
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
    if (!(dynamicSet_ & kDepthBiasSet))  // the pipeline's, unless set in the pass
        applyDepthBias(d.raster.depthBiasConstant, d.raster.depthBiasSlope,
                       d.raster.depthBiasClamp);
    if (d.raster.depthClamp)
        gl_.Enable(GL_DEPTH_CLAMP);
    else
        gl_.Disable(GL_DEPTH_CLAMP);
    if (d.multisample.alphaToCoverage)
        gl_.Enable(GL_SAMPLE_ALPHA_TO_COVERAGE);
    else
        gl_.Disable(GL_SAMPLE_ALPHA_TO_COVERAGE);
    if (d.multisample.sampleMask != ~0u) {
        gl_.Enable(GL_SAMPLE_MASK);
        gl_.SampleMaski(0, d.multisample.sampleMask);
    } else {
        gl_.Disable(GL_SAMPLE_MASK);
    }
    // GL ignores the sample mask without sample buffers; Vulkan applies bit 0 to single-sample
    // targets, where a clear bit writes nothing at all. Discarding every primitive does the same.
    // (Clears are discarded too, so BeginRenderPass and EndRenderPass turn it off again.)
    if (d.multisample.sampleCount == 1 && !(d.multisample.sampleMask & 1))
        gl_.Enable(GL_RASTERIZER_DISCARD);
    else
        gl_.Disable(GL_RASTERIZER_DISCARD);
    if (d.primitiveRestart)
        gl_.Enable(GL_PRIMITIVE_RESTART_FIXED_INDEX);  // 0xFFFF / 0xFFFFFFFF, as on Vulkan
    else
        gl_.Disable(GL_PRIMITIVE_RESTART_FIXED_INDEX);
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
        for (auto [face, s] : {std::pair{GL_FRONT, ds.front}, std::pair{GL_BACK, ds.back}})
            gl_.StencilOpSeparate(face, stencilOp(s.failOp), stencilOp(s.depthFailOp),
                                  stencilOp(s.passOp));
        applyStencil(dynamicSet_ & kStencilReferenceSet ? stencilReference_ : ds.stencilReference);
        gl_.StencilMask(ds.stencilWriteMask);
    } else {
        gl_.Disable(GL_STENCIL_TEST);
    }
    for (size_t i = 0; i < d.colorFormats.size(); ++i) {
        gdi::BlendTargetState b = i < d.blend.size() ? d.blend[i] : gdi::BlendTargetState{};
        if (b.enable) {
            gl_.Enablei(GL_BLEND, GLuint(i));
            gl_.BlendFuncSeparatei(GLuint(i), blendFactor(b.srcColor), blendFactor(b.dstColor),
                                   blendFactor(b.srcAlpha), blendFactor(b.dstAlpha));
            gl_.BlendEquationSeparatei(GLuint(i), blendOp(b.colorOp), blendOp(b.alphaOp));
        } else {
            gl_.Disablei(GL_BLEND, GLuint(i));
        }
        const auto m = uint8_t(b.writeMask);
        gl_.ColorMaski(GLuint(i), m & 1, (m >> 1) & 1, (m >> 2) & 1, (m >> 3) & 1);
    }
    if (!(dynamicSet_ & kBlendConstantSet))
        gl_.BlendColor(d.blendConstant[0], d.blendConstant[1], d.blendConstant[2],
                       d.blendConstant[3]);
}

// The reference goes with the compare function and mask in GL; they are the pipeline's.
void GlReplay::applyStencil(uint8_t reference) {
    const auto& ds = pipeline_->desc.depthStencil;
    for (auto [face, s] : {std::pair{GL_FRONT, ds.front}, std::pair{GL_BACK, ds.back}})
        gl_.StencilFuncSeparate(face, compare(s.compare), reference, ds.stencilReadMask);
}

// glPolygonOffset(factor, units) is Vulkan's (slope, constant) with the same formula. Always
// enabled, as Vulkan's depth bias is (0 and 0 is no bias), so setDepthBias works with any pipeline.
void GlReplay::applyDepthBias(float constant, float slope, float clamp) {
    gl_.Enable(GL_POLYGON_OFFSET_FILL);
    if (gl_.PolygonOffsetClamp)
        gl_.PolygonOffsetClamp(slope, constant, clamp);
    else
        gl_.PolygonOffset(slope, constant);
}

void GlReplay::operator()(const cmd::SetBlendConstant& r) {
    gl_.BlendColor(r.rgba[0], r.rgba[1], r.rgba[2], r.rgba[3]);
    dynamicSet_ |= kBlendConstantSet;
}
// GL keeps the reference with the stencil function, which is the pipeline's: without a stencil
// test it is kept here, and the next setPipeline applies it.
void GlReplay::operator()(const cmd::SetStencilReference& r) {
    stencilReference_ = r.reference;
    dynamicSet_ |= kStencilReferenceSet;
    if (pipeline_ && !pipeline_->compute && pipeline_->desc.depthStencil.stencilTest)
        applyStencil(r.reference);
}
void GlReplay::operator()(const cmd::SetDepthBias& r) {
    applyDepthBias(r.constant, r.slope, r.clamp);
    dynamicSet_ |= kDepthBiasSet;
}

void GlReplay::operator()(const cmd::SetViewport& r) {
    const gdi::Viewport& v = r.viewport;
    gl_.ViewportIndexedf(0, v.x, v.y, v.width,
                         v.height);  // fractional, as Vulkan's (glViewport rounds)
    gl_.DepthRangef(v.minDepth, v.maxDepth);
}
void GlReplay::operator()(const cmd::SetScissor& r) {
    gl_.Scissor(r.rect.x, r.rect.y, GLsizei(r.rect.width), GLsizei(r.rect.height));
}
void GlReplay::operator()(const cmd::SetVertexBuffer& r) {
    const std::pair<GLuint, uint64_t> binding{dev_.bufferAt(r.buffer).name, r.offset};
    if (vertexBuffers_[r.index] != binding) vertexDirty_ = true;
    vertexBuffers_[r.index] = binding;
}
void GlReplay::operator()(const cmd::SetIndexBuffer& r) {
    const GLuint name = dev_.bufferAt(r.buffer).name;
    if (indexBuffer_ != name) indexDirty_ = true;
    indexBuffer_ = name;
    indexOffset_ = r.offset;
    indexType_ = r.type;
}
void GlReplay::operator()(const cmd::SetUniformBuffer& r) {
    lastUniform_ = {
        .slot = r.slot, .name = dev_.bufferAt(r.buffer).name, .size = GLsizeiptr(r.size)};
    gl_.BindBufferRange(GL_UNIFORM_BUFFER, r.slot, lastUniform_.name, GLintptr(r.offset),
                        lastUniform_.size);
}
void GlReplay::operator()(const cmd::SetUniformOffset& r) {
    gl_.BindBufferRange(GL_UNIFORM_BUFFER, lastUniform_.slot, lastUniform_.name, GLintptr(r.offset),
                        lastUniform_.size);
}
void GlReplay::operator()(const cmd::SetStorageBuffer& r) {
    gl_.BindBufferRange(GL_SHADER_STORAGE_BUFFER, r.slot, dev_.bufferAt(r.buffer).name,
                        GLintptr(r.offset), GLsizeiptr(r.size));
}
void GlReplay::operator()(const cmd::SetTexture& r) {
    gl_.BindTextureUnit(r.slot, dev_.textureAt(r.texture).name);
    gl_.BindSampler(r.slot, dev_.samplerAt(r.sampler).name);
}
void GlReplay::operator()(const cmd::SetStorageTexture& r) {
    const Texture& t = dev_.textureAt(r.texture);
    // Every layer (arrays, cubes, 3D slices) of the mip, as Vulkan's storage view binds it.
    const GLboolean layered = t.target == GL_TEXTURE_2D ? GL_FALSE : GL_TRUE;
    images_[r.slot] = {t.name, GLint(r.mipLevel), layered, toGlFormat(t.desc.format).internal};
    imagesDirty_ = true;
}
void GlReplay::bindImages() {
    imagesDirty_ = false;
    if (!pipeline_) return;
    for (size_t unit = 0; unit < pipeline_->imageSlots.size(); ++unit) {
        const ImageBinding& b = images_[pipeline_->imageSlots[unit]];
        if (b.texture)
            gl_.BindImageTexture(GLuint(unit), b.texture, b.mipLevel, b.layered, 0, GL_READ_WRITE,
                                 b.format);
    }
}

void GlReplay::bindVertexBuffers() {
    flushBindings();
    if (!vertexDirty_) return;  // re-binding unchanged buffers per draw is measurable CPU cost
    for (size_t i = 0; i < pipeline_->strides.size(); ++i)
        gl_.VertexArrayVertexBuffer(pipeline_->vao, GLuint(i), vertexBuffers_[i].first,
                                    GLintptr(vertexBuffers_[i].second),
                                    GLsizei(pipeline_->strides[i]));
    vertexDirty_ = false;
}
void GlReplay::bindIndexBuffer() {
    if (indexDirty_) gl_.VertexArrayElementBuffer(pipeline_->vao, indexBuffer_);
    indexDirty_ = false;
}
// A single instance at base 0 (most draws) takes the plain entry point: the instanced one is the
// same draw (gl_InstanceID 0, base instance 0) but costs more in some drivers' call path.
void GlReplay::operator()(const cmd::Draw& r) {
    if (constantsDirty_ | imagesDirty_ | vertexDirty_) [[unlikely]]  // no call per object
        bindVertexBuffers();
    if (r.instanceCount == 1 && r.firstInstance == 0) [[likely]]
        return gl_.DrawArrays(topology_, GLint(r.firstVertex), GLsizei(r.vertexCount));
    gl_.DrawArraysInstancedBaseInstance(topology_, GLint(r.firstVertex), GLsizei(r.vertexCount),
                                        GLsizei(r.instanceCount), r.firstInstance);
}
void GlReplay::operator()(const cmd::DrawOneInstance& r) {
    if (constantsDirty_ | imagesDirty_ | vertexDirty_) [[unlikely]]
        bindVertexBuffers();
    gl_.DrawArrays(topology_, GLint(r.firstVertex), GLsizei(r.vertexCount));
}
void GlReplay::operator()(const cmd::DrawIndexed& r) {
    if (constantsDirty_ | imagesDirty_ | vertexDirty_) [[unlikely]]
        bindVertexBuffers();
    if (indexDirty_) [[unlikely]]
        bindIndexBuffer();
    const uint32_t size = indexType_ == gdi::IndexType::U16 ? 2 : 4;
    const auto* first =
        reinterpret_cast<const void*>(uintptr_t(indexOffset_ + uint64_t(r.firstIndex) * size));
    if (r.instanceCount == 1 && r.firstInstance == 0) [[likely]]
        return gl_.DrawElementsBaseVertex(topology_, GLsizei(r.indexCount), indexType(), first,
                                          r.baseVertex);
    gl_.DrawElementsInstancedBaseVertexBaseInstance(topology_, GLsizei(r.indexCount), indexType(),
                                                    first, GLsizei(r.instanceCount), r.baseVertex,
                                                    r.firstInstance);
}
// Dispatches and copies keep full barriers even with automatic barriers off: glMemoryBarrier
// is cheap next to them, and GL has no finer ordering to gain.
void GlReplay::operator()(const cmd::Dispatch& r) {
    flushBindings();
    gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
    gl_.DispatchCompute(r.groupsX, r.groupsY, r.groupsZ);
    gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
}

// Indirect work (argument buffers validated when recorded).
void GlReplay::operator()(const cmd::DrawIndirect& r) {
    bindVertexBuffers();
    gl_.BindBuffer(GL_DRAW_INDIRECT_BUFFER, dev_.bufferAt(r.args).name);
    gl_.MultiDrawArraysIndirect(topology_, reinterpret_cast<const void*>(uintptr_t(r.offset)),
                                GLsizei(r.drawCount), GLsizei(r.stride));
}
void GlReplay::operator()(const cmd::DrawIndexedIndirect& r) {
    bindVertexBuffers();
    bindIndexBuffer();
    gl_.BindBuffer(GL_DRAW_INDIRECT_BUFFER, dev_.bufferAt(r.args).name);
    gl_.MultiDrawElementsIndirect(topology_, indexType(),
                                  reinterpret_cast<const void*>(uintptr_t(r.offset)),
                                  GLsizei(r.drawCount), GLsizei(r.stride));
}
void GlReplay::operator()(const cmd::DrawIndirectCount& r) {
    bindVertexBuffers();
    gl_.BindBuffer(GL_PARAMETER_BUFFER, dev_.bufferAt(r.countBuffer).name);
    gl_.BindBuffer(GL_DRAW_INDIRECT_BUFFER, dev_.bufferAt(r.args).name);
    gl_.MultiDrawArraysIndirectCount(topology_, reinterpret_cast<const void*>(uintptr_t(r.offset)),
                                     GLintptr(r.countOffset), GLsizei(r.maxDrawCount),
                                     GLsizei(r.stride));
}
void GlReplay::operator()(const cmd::DrawIndexedIndirectCount& r) {
    bindVertexBuffers();
    bindIndexBuffer();
    gl_.BindBuffer(GL_PARAMETER_BUFFER, dev_.bufferAt(r.countBuffer).name);
    gl_.BindBuffer(GL_DRAW_INDIRECT_BUFFER, dev_.bufferAt(r.args).name);
    gl_.MultiDrawElementsIndirectCount(
        topology_, indexType(), reinterpret_cast<const void*>(uintptr_t(r.offset)),
        GLintptr(r.countOffset), GLsizei(r.maxDrawCount), GLsizei(r.stride));
}
void GlReplay::operator()(const cmd::DispatchIndirect& r) {
    flushBindings();
    gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
    gl_.BindBuffer(GL_DISPATCH_INDIRECT_BUFFER, dev_.bufferAt(r.args).name);
    gl_.DispatchComputeIndirect(GLintptr(r.offset));
    gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
}

void GlReplay::operator()(const cmd::GenerateMips& r) {
    gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
    gl_.GenerateTextureMipmap(dev_.textureAt(r.texture).name);
}
// A marker message: frame debuggers (RenderDoc, apitrace) show GL_DEBUG_TYPE_MARKER messages
// among the calls.
void GlReplay::operator()(const cmd::InsertDebugLabel& r) {
    const char* name = cmd::view(r, r.name);
    gl_.DebugMessageInsert(GL_DEBUG_SOURCE_APPLICATION, GL_DEBUG_TYPE_MARKER, 0,
                           GL_DEBUG_SEVERITY_NOTIFICATION, -1, name ? name : "");
}
void GlReplay::operator()(const cmd::ClearBuffer& r) {
    if (r.size)
        gl_.ClearNamedBufferSubData(dev_.bufferAt(r.buffer).name, GL_R32UI, GLintptr(r.offset),
                                    GLsizeiptr(r.size), GL_RED_INTEGER, GL_UNSIGNED_INT, &r.value);
    gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
}
void GlReplay::operator()(const cmd::CopyBuffer& r) {
    if (r.size)
        gl_.CopyNamedBufferSubData(dev_.bufferAt(r.src).name, dev_.bufferAt(r.dst).name,
                                   GLintptr(r.srcOffset), GLintptr(r.dstOffset),
                                   GLsizeiptr(r.size));
    gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
}
void GlReplay::operator()(const cmd::CopyTexture& r) {
    const Texture& d = dev_.textureAt(r.dst);
    const Texture& s = dev_.textureAt(r.src);
    const gdi::validate::Extent3 e = gdi::validate::mipExtent(d.desc, r.mipLevel);
    gl_.CopyImageSubData(s.name, s.target, GLint(r.mipLevel), 0, 0, 0, d.name, d.target,
                         GLint(r.mipLevel), 0, 0, 0, GLsizei(e.width), GLsizei(e.height),
                         GLsizei(e.depthOrLayers));
    gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
}
void GlReplay::operator()(const cmd::CopyBufferToTexture& r) {
    const Texture& t = dev_.textureAt(r.dst);
    const gdi::validate::Extent3 e = gdi::validate::mipExtent(t.desc, r.at.mipLevel);
    gl_.MemoryBarrier(
        GL_ALL_BARRIER_BITS);  // buffer writes by shaders become visible to the unpack
    gl_.BindBuffer(GL_PIXEL_UNPACK_BUFFER, dev_.bufferAt(r.src).name);
    dev_.uploadSubresource(t, r.at, reinterpret_cast<const void*>(uintptr_t(r.srcOffset)),
                           gdi::imageByteSize(t.desc.format, e.width, e.height));
    gl_.BindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
}
void GlReplay::operator()(const cmd::CopyTextureToBuffer& r) {
    const Texture& t = dev_.textureAt(r.src);
    const gdi::validate::Extent3 e = gdi::validate::mipExtent(t.desc, r.at.mipLevel);
    gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
    gl_.BindBuffer(GL_PIXEL_PACK_BUFFER, dev_.bufferAt(r.dst).name);
    dev_.readSubresource(t, r.at, reinterpret_cast<void*>(uintptr_t(r.dstOffset)),
                         gdi::imageByteSize(t.desc.format, e.width, e.height));
    gl_.BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
}

// The end offset of a resolved layout's span, from validate::texelLayout's formula.
static uint64_t spanBytes(gdi::Format f, const gdi::TextureRegion& r, const gdi::TexelLayout& l) {
    return gdi::validate::texelLayout(f, r, l, "replay").end - l.offset;
}
void GlReplay::operator()(const cmd::CopyBufferToTextureRegion& r) {
    const Texture& t = dev_.textureAt(r.dst);
    gl_.MemoryBarrier(
        GL_ALL_BARRIER_BITS);  // buffer writes by shaders become visible to the unpack
    if (gdi::hasTwoAspects(t.desc.format)) {  // one aspect: merged on the CPU (uploadAspect)
        std::vector<uint8_t> bytes(spanBytes(t.desc.format, r.region, r.layout));
        gl_.GetNamedBufferSubData(dev_.bufferAt(r.src).name, GLintptr(r.layout.offset),
                                  GLsizeiptr(bytes.size()), bytes.data());
        dev_.uploadAspect(t, r.region, r.layout, bytes.data());
        return;
    }
    gl_.BindBuffer(GL_PIXEL_UNPACK_BUFFER, dev_.bufferAt(r.src).name);
    dev_.uploadRegion(t, r.region, r.layout,
                      reinterpret_cast<const void*>(uintptr_t(r.layout.offset)),
                      spanBytes(t.desc.format, r.region, r.layout));
    gl_.BindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
}
void GlReplay::operator()(const cmd::CopyTextureToBufferRegion& r) {
    const Texture& t = dev_.textureAt(r.src);
    gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
    if (gdi::hasTwoAspects(t.desc.format)) {  // one aspect, taken out on the CPU (readAspect);
        // the span is read first so that the bytes between rows keep their contents
        const GLuint buffer = dev_.bufferAt(r.dst).name;
        std::vector<uint8_t> bytes(spanBytes(t.desc.format, r.region, r.layout));
        gl_.GetNamedBufferSubData(buffer, GLintptr(r.layout.offset), GLsizeiptr(bytes.size()),
                                  bytes.data());
        dev_.readAspect(t, r.region, r.layout, bytes.data());
        gl_.NamedBufferSubData(buffer, GLintptr(r.layout.offset), GLsizeiptr(bytes.size()),
                               bytes.data());
        return;
    }
    gl_.BindBuffer(GL_PIXEL_PACK_BUFFER, dev_.bufferAt(r.dst).name);
    dev_.readRegion(t, r.region, r.layout, reinterpret_cast<void*>(uintptr_t(r.layout.offset)),
                    spanBytes(t.desc.format, r.region, r.layout));
    gl_.BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
}
void GlReplay::operator()(const cmd::CopyTextureRegion& r) {
    const Texture& d = dev_.textureAt(r.dst);
    const Texture& s = dev_.textureAt(r.src);
    const auto& a = r.srcRegion;
    const auto& b = r.dstAt;
    gl_.CopyImageSubData(s.name, s.target, GLint(a.mipLevel), GLint(a.x), GLint(a.y), GLint(a.z),
                         d.name, d.target, GLint(b.mipLevel), GLint(b.x), GLint(b.y), GLint(b.z),
                         GLsizei(a.width), GLsizei(a.height), GLsizei(a.depth));
    gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
}

// A blit from the multisampled texture's framebuffer resolves it (averaging, sRGB as linear
// values: the render pass's resolve above, by region).
void GlReplay::operator()(const cmd::ResolveTextureRegion& r) {
    const Texture& d = dev_.textureAt(r.dst);
    const Texture& s = dev_.textureAt(r.src);
    const GLuint from = dev_.framebuffer({dev_.fboAttachment(s, 0, r.srcRegion.z)}, {}, GL_NONE);
    const GLuint to =
        dev_.framebuffer({dev_.fboAttachment(d, r.dstAt.mipLevel, r.dstAt.z)}, {}, GL_NONE);
    const auto& a = r.srcRegion;
    const auto& b = r.dstAt;
    gl_.Disable(GL_SCISSOR_TEST);  // blits honour the scissor
    gl_.BlitNamedFramebuffer(from, to, GLint(a.x), GLint(a.y), GLint(a.x + a.width),
                             GLint(a.y + a.height), GLint(b.x), GLint(b.y), GLint(b.x + a.width),
                             GLint(b.y + a.height), GL_COLOR_BUFFER_BIT, GL_NEAREST);
    gl_.Enable(GL_SCISSOR_TEST);
    gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
}

// llvmpipe's GL_TIMESTAMP does not wait for the binned rendering before it (measured: a 3 s
// forward pass timed as 9 ms, even after glFinish). On software rasterizers a timed section is
// therefore the wall-clock time between two glFinish calls during replay, which is the
// section's whole cost. Hardware drivers keep GL_TIMESTAMP.
bool GlReplay::drainSoftwareRasterizer() {
    if (!dev_.info().softwareRasterizer) return false;
    gl_.Finish();
    return true;
}
void GlReplay::operator()(const cmd::BeginTimer& r) {
    Timer& t = dev_.timerAt(r.timer);
    if (drainSoftwareRasterizer()) t.begin = std::chrono::steady_clock::now();
    gl_.QueryCounter(t.queries[0], GL_TIMESTAMP);
}
void GlReplay::operator()(const cmd::EndTimer& r) {
    Timer& t = dev_.timerAt(r.timer);
    if (drainSoftwareRasterizer()) t.end = std::chrono::steady_clock::now();
    gl_.QueryCounter(t.queries[1], GL_TIMESTAMP);
    t.used = true;
}
// Queries: a statistics query is four GL queries, one per counter, begun and ended together.
void GlReplay::operator()(const cmd::BeginQuery& r) {
    const QuerySet& q = dev_.querySetAt(r.set);
    const auto targets = queryTargets(q.desc.type);
    for (size_t k = 0; k < targets.size(); ++k)
        gl_.BeginQuery(targets[k], q.names[r.index * targets.size() + k]);
}
void GlReplay::operator()(const cmd::EndQuery& r) {
    for (GLenum target : queryTargets(dev_.querySetAt(r.set).desc.type)) gl_.EndQuery(target);
}
void GlReplay::operator()(const cmd::WriteTimestamp& r) {
    gl_.QueryCounter(dev_.querySetAt(r.set).names[r.index], GL_TIMESTAMP);
}
void GlReplay::operator()(const cmd::ResolveQueries& r) {
    const QuerySet& q = dev_.querySetAt(r.set);
    const GLuint buffer = dev_.bufferAt(r.dst).name;
    const size_t values = queryTargets(q.desc.type).size();
    for (size_t i = 0; i < r.count * values; ++i)  // the GPU waits for each result, not this thread
        gl_.GetQueryBufferObjectui64v(q.names[r.first * values + i], buffer, GL_QUERY_RESULT,
                                      GLintptr(r.dstOffset + 8 * i));
}

void GlReplay::operator()(const cmd::PushDebugGroup& r) {
    const char* name = cmd::view(r, r.name);
    gl_.PushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, name ? name : "");
}
void GlReplay::operator()(const cmd::PopDebugGroup&) { gl_.PopDebugGroup(); }

// GL orders framebuffer writes, copies and texture fetches itself; shader stores (images and
// storage buffers) need glMemoryBarrier, and Undefined lets the driver drop old contents.
void GlReplay::operator()(const cmd::SetAutomaticBarriers& r) {
    if (r.enabled != automatic_) gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
    automatic_ = r.enabled;
}
void GlReplay::operator()(const cmd::TextureBarriers& r) {
    bool storage = false;
    for (const gdi::TextureBarrier& b : cmd::view(r, r.barriers)) {
        const Texture& t = dev_.textureAt(b.texture);
        if (b.before == gdi::ResourceState::Undefined) {
            const auto range = gdi::validate::textureBarrier(t.desc, b, t.label);
            for (uint32_t m = range.baseMip; m < range.baseMip + range.mipCount; ++m) {
                if (range.whole || t.target == GL_TEXTURE_2D ||
                    t.target == GL_TEXTURE_2D_MULTISAMPLE) {
                    gl_.InvalidateTexImage(t.name, GLint(m));
                } else {
                    const gdi::validate::Extent3 e = gdi::validate::mipExtent(t.desc, m);
                    gl_.InvalidateTexSubImage(t.name, GLint(m), 0, 0, GLint(range.baseLayer),
                                              GLsizei(e.width), GLsizei(e.height),
                                              GLsizei(range.layerCount));
                }
            }
        }
        storage = storage || b.before == gdi::ResourceState::Storage;
    }
    if (storage) gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
}
// Only shader stores need ordering on GL; the bits say which later reads wait for them.
void GlReplay::operator()(const cmd::BufferBarriers& r) {
    using A = gdi::BufferAccess;
    GLbitfield bits = 0;
    for (const gdi::BufferBarrier& b : cmd::view(r, r.barriers)) {
        if (!any(b.before, A::StorageWrite)) continue;
        if (any(b.after, A::Vertex)) bits |= GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT;
        if (any(b.after, A::Index)) bits |= GL_ELEMENT_ARRAY_BARRIER_BIT;
        if (any(b.after, A::Indirect)) bits |= GL_COMMAND_BARRIER_BIT;
        if (any(b.after, A::Uniform)) bits |= GL_UNIFORM_BARRIER_BIT;
        if (any(b.after, A::StorageRead | A::StorageWrite)) bits |= GL_SHADER_STORAGE_BARRIER_BIT;
        if (any(b.after, A::CopySrc | A::CopyDst))
            bits |= GL_BUFFER_UPDATE_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT;
    }
    if (bits) gl_.MemoryBarrier(bits);
}

// Writes every resolve target from the pass's multisampled attachments. A blit from a
// multisampled framebuffer resolves; colour averages the samples. Depth: GL leaves the
// choice to the implementation; Mesa takes sample 0, which is what Vulkan's SAMPLE_ZERO
// gives (conformance case msaa_resolve checks both against the same expectation).
void GlReplay::resolve() {
    gl_.Disable(GL_SCISSOR_TEST);  // blits honour the scissor
    // GL_FRAMEBUFFER_SRGB stays on: sRGB samples are averaged as linear values and encoded
    // again, as Vulkan's AVERAGE resolve does (msaa_resolve's colour_srgb image checks it).
    for (const auto& [point, target] : resolves_) {
        const bool color = point >= GL_COLOR_ATTACHMENT0 && point < GL_COLOR_ATTACHMENT0 + 16;
        const GLenum depthPoint = color ? GLenum(GL_NONE) : point;
        std::vector<FboAttachment> colors;
        FboAttachment depth{};
        if (color)
            colors.push_back(target);
        else
            depth = target;
        const GLuint dst = dev_.framebuffer(colors, depth, depthPoint);
        if (color) gl_.NamedFramebufferReadBuffer(fbo_, point);
        // Depth-stencil resolves carry stencil too, as Vulkan's (SAMPLE_ZERO for both aspects).
        const GLbitfield mask = color ? GL_COLOR_BUFFER_BIT
                                : point == GL_DEPTH_STENCIL_ATTACHMENT
                                    ? GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT
                                : point == GL_DEPTH_ATTACHMENT ? GL_DEPTH_BUFFER_BIT
                                                               : GL_STENCIL_BUFFER_BIT;
        gl_.BlitNamedFramebuffer(fbo_, dst, 0, 0, GLint(area_.width), GLint(area_.height), 0, 0,
                                 GLint(area_.width), GLint(area_.height), mask, GL_NEAREST);
    }
    gl_.Enable(GL_SCISSOR_TEST);
    resolves_.clear();
}

}  // namespace fe::gl

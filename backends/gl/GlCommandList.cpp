// Recording for GL: the checks of every call (the same as Vulkan's, in the same order), then
// one record in the stream. The GL work is GlReplay's, at submit.
#include "gl/GlCommandList.h"

#include <algorithm>
#include <bit>

#include "fe/gdi/ExclusiveUse.h"
#include "fe/gdi/Validation.h"

namespace fe::gl {

namespace cmd = gdi::cmd;

GlCommandList::GlCommandList(GlDevice& d, gdi::QueueKind queue)
    : dev_(d),
      queue_(queue),
      validating_(d.info().features.validation),
      uniformLimits_(gdi::validate::uniformBindingLimits(d.info().limits)),
      storageLimits_(gdi::validate::storageBindingLimits(d.info().limits)),
      viewportLimits_(gdi::validate::viewportLimits(d.info().limits)),
      stream_(d.takeStream()) {
    restart();
    dev_.liveLists().add(this);
}
GlCommandList::~GlCommandList() {
    if (orphaned_) return;  // the device is gone: the stream is freed with the list
    dev_.returnStream(std::move(stream_));
    dev_.liveLists().remove(this);
}
// Dynamic state and per-draw constants: checked, then one record each.
void GlCommandList::setViewport(const gdi::Viewport& v) {
    checkUnrestricted("setViewport");
    if (!inPass_) [[unlikely]]
        gdi::validate::stateOutsidePass("setViewport");
    gdi::validate::viewport(v, viewportLimits_);
    stream_->push(cmd::SetViewport{v});
}
void GlCommandList::setScissor(const gdi::Rect& r) {
    checkUnrestricted("setScissor");
    if (!inPass_) [[unlikely]]
        gdi::validate::stateOutsidePass("setScissor");
    stream_->push(cmd::SetScissor{gdi::validate::scissor(r)});
}
void GlCommandList::setConstants(uint32_t offset, gdi::ByteSpan data) {
    gdi::validate::constantsRange(offset, data.size());
    checkUnrestricted("setConstants");
    auto* r =
        stream_->push(cmd::SetConstants{offset}, cmd::CommandStream::payloadSize(data.size()));
    r->data = stream_->payload(*r, data);
}
void GlCommandList::setBlendConstant(const std::array<float, 4>& rgba) {
    checkUnrestricted("setBlendConstant");
    if (!inPass_) [[unlikely]]
        gdi::validate::stateOutsidePass("setBlendConstant");
    gdi::validate::blendConstant(rgba.data(), "setBlendConstant");
    stream_->push(cmd::SetBlendConstant{rgba});
}
void GlCommandList::setStencilReference(uint8_t reference) {
    checkUnrestricted("setStencilReference");
    if (!inPass_) [[unlikely]]
        gdi::validate::stateOutsidePass("setStencilReference");
    stream_->push(cmd::SetStencilReference{reference});
}
void GlCommandList::setDepthBias(float constant, float slope, float clamp) {
    checkUnrestricted("setDepthBias");
    if (!inPass_) [[unlikely]]
        gdi::validate::stateOutsidePass("setDepthBias");
    gdi::validate::depthBias(constant, slope, clamp, dev_.info().features);
    stream_->push(cmd::SetDepthBias{constant, slope, clamp});
}

// The device is being destroyed before this list (LiveLists.h): every later call throws.
// Clearing the bind cache sends every bind to the checked path, which throws before the
// fast path could read the destroyed device.
void GlCommandList::orphan() {
    orphaned_ = restricted_ = true, readyToDraw_ = inPass_ = false;
    lastBound_ = {};
}

void GlCommandList::restart() {
    feedback_.clear();
    unbindAll();
    queries_.clear();
    destroyEpoch_ = dev_.destroyEpoch();
}

void GlCommandList::unbindAll() {
    kinds_ = {};
    lastBound_ = {};
    lastUniform_ = {};
    unchecked_ = ~uint64_t(0);
    pipeline_ = nullptr;
    readyToDraw_ = false;
    vertexInputs_.clear();
    vertexInputs_.setPipeline(nullptr, nullptr);
}

void GlCommandList::checkSubmittable() const {
    if (secondary_) gdi::validate::submittedSecondary();
    if (inPass_) throw gdi::Error("submit: render pass still open (missing endRenderPass)");
    if (depth_)
        throw gdi::Error("submit: " + std::to_string(depth_) + " debug group(s) not popped");
    queries_.finish();
    if (dev_.destroyEpoch() != destroyEpoch_)
        dev_.checkAlive(*stream_);  // only when something was destroyed
}

std::unique_ptr<cmd::CommandStream> GlCommandList::finish() {
    auto recorded = std::exchange(stream_, dev_.takeStream());
    restart();
    return recorded;
}

// The pass's attachments, validated (the same checks and messages as Vulkan's).
gdi::validate::PassSignature GlCommandList::checkPass(const gdi::RenderPassDesc& desc) const {
    using gdi::validate::attachment;
    std::vector<gdi::validate::AttachmentInfo> infos, resolveInfos(desc.colors.size());
    for (size_t i = 0; i < desc.colors.size(); ++i) {
        const auto& c = desc.colors[i];
        const Texture& t = dev_.texture(c.texture);
        infos.push_back(attachment(t.desc, c.mipLevel, c.layer, "beginRenderPass", t.label));
        if (c.resolveTexture) {
            const Texture& r = dev_.texture(c.resolveTexture);
            const gdi::Subresource at = c.resolveSubresource;
            resolveInfos[i] =
                attachment(r.desc, at.mipLevel, at.layer, "beginRenderPass resolve", r.label);
        }
    }
    const Texture* depth = desc.depth.texture ? &dev_.texture(desc.depth.texture) : nullptr;
    gdi::validate::AttachmentInfo di{}, dri{};
    if (depth)
        di = attachment(depth->desc, desc.depth.mipLevel, desc.depth.layer, "beginRenderPass",
                        depth->label);
    if (desc.depth.resolveTexture) {
        const Texture& r = dev_.texture(desc.depth.resolveTexture);
        if (!depth)
            throw gdi::Error("beginRenderPass: a depth resolve target without a depth attachment");
        const gdi::Subresource at = desc.depth.resolveSubresource;
        dri = attachment(r.desc, at.mipLevel, at.layer, "beginRenderPass resolve", r.label);
    }
    const gdi::Rect area =
        gdi::validate::renderPass(desc, infos, resolveInfos, depth ? &di : nullptr,
                                  desc.depth.resolveTexture ? &dri : nullptr, dev_.info().limits);
    return gdi::validate::passSignature(infos, depth ? &di : nullptr, area);
}

void GlCommandList::beginRenderPass(const gdi::RenderPassDesc& desc) {
    gdi::validate::queueAllows(queue_, gdi::QueueKind::Graphics, "beginRenderPass");
    checkDevice("beginRenderPass");
    if (secondary_) gdi::validate::notInSecondary("beginRenderPass");
    if (inPass_) gdi::validate::insidePass("beginRenderPass");
    signature_ = checkPass(desc);
    beginPassFeedback(desc);
    passSamples_ = signature_.samples;
    const std::span<const gdi::ColorAttachment> colors(desc.colors);
    auto* r = stream_->push(
        cmd::BeginRenderPass{.depth = desc.depth, .secondaryLists = desc.secondaryLists},
        cmd::CommandStream::payloadSize(colors.size_bytes()) +
            cmd::CommandStream::payloadSize(desc.debugName));
    r->colors = stream_->payload(*r, colors);
    r->debugName = stream_->payload(*r, desc.debugName);
    inPass_ = true;
    pipeline_ = nullptr;  // a render pass starts with no pipeline
    readyToDraw_ = false;
    secondaryPass_ = desc.secondaryLists;  // the primary may draw between executed lists
}

void GlCommandList::endRenderPass() {
    checkDevice("endRenderPass");
    if (secondary_) gdi::validate::notInSecondary("endRenderPass");
    if (!inPass_) throw gdi::Error("endRenderPass without beginRenderPass");
    queries_.endPass();
    inPass_ = false;
    readyToDraw_ = false;
    endPassFeedback();
    if (secondaryPass_) {  // as on Vulkan, where vkCmdExecuteCommands leaves the state undefined
        secondaryPass_ = false;
        unbindAll();
    }
    stream_->push(cmd::EndRenderPass{});
}

void GlCommandList::restrictedCall(const char* what) const {
    if (orphaned_) gdi::validate::listOfDestroyedDevice(what);
    gdi::validate::afterEndSecondary(what);  // restricted_: an ended secondary list
}

void GlCommandList::beginSecondary(const gdi::RenderPassDesc& desc) {
    gdi::validate::queueAllows(queue_, gdi::QueueKind::Graphics, "beginSecondary");
    checkDevice("beginSecondary");
    if (ended_) {  // recorded anew: primaries that executed the old recording keep it
        recorded_.reset();
        secondary_ = ended_ = restricted_ = inPass_ = false;
        depth_ = 0;
        restart();
    }
    if (!stream_->empty() || secondary_ || inPass_) gdi::validate::secondaryNotEmpty();
    signature_ = checkPass(desc);
    restart();
    beginPassFeedback(desc);  // no texture is bound yet: checks the attachments
    secondary_ = inPass_ = true;
    passSamples_ = signature_.samples;
    const gdi::Rect area = gdi::validate::renderArea(signature_);
    stream_->push(cmd::SetViewport{{0, 0, float(area.width), float(area.height), 0, 1}});
    stream_->push(cmd::SetScissor{area});
}

void GlCommandList::reset() {
    checkDevice("reset");
    recorded_.reset();
    dev_.returnStream(std::exchange(stream_, dev_.takeStream()));
    secondary_ = ended_ = restricted_ = inPass_ = secondaryPass_ = false;
    depth_ = 0;
    restart();
}

void GlCommandList::endSecondary() {
    checkDevice("endSecondary");
    if (!secondary_ || ended_) throw gdi::Error("endSecondary without beginSecondary");
    if (depth_)
        throw gdi::Error("endSecondary: " + std::to_string(depth_) + " debug group(s) not popped");
    ended_ = restricted_ = true;
    readyToDraw_ = false;
    endPassFeedback();
    recorded_ =
        std::shared_ptr<const gdi::cmd::CommandStream>(std::exchange(stream_, dev_.takeStream()));
}

void GlCommandList::executeSecondary(std::span<gdi::CommandList* const> lists) {
    checkDevice("executeSecondary");
    const auto parts =
        gdi::validate::executedLists(lists, this, [&](const GlCommandList& l, size_t i) {
            if (&l.dev_ != &dev_) gdi::validate::secondaryOfAnotherDevice(i);
            gdi::validate::executedSecondary(inPass_ && secondaryPass_, l.secondary_, l.ended_,
                                             l.signature_, signature_, i);
        });
    // Each recording is shared, uncopied, with this list's stream: the secondary list keeps it
    // for the next pass or frame that executes it.
    for (GlCommandList* l : parts) {
        destroyEpoch_ = std::min(destroyEpoch_, l->destroyEpoch_);
        stream_->push(cmd::ExecuteSecondary{stream_->adopt(l->recorded_)});
    }
    // As on Vulkan after vkCmdExecuteCommands: the primary's pipeline and bindings are unset,
    // its viewport and scissor the render area again.
    unbindAll();
    pipeline_ = nullptr;
    readyToDraw_ = false;
    const gdi::Rect area = gdi::validate::renderArea(signature_);
    stream_->push(cmd::SetViewport{{0, 0, float(area.width), float(area.height), 0, 1}});
    stream_->push(cmd::SetScissor{area});
}

void GlCommandList::setPipeline(gdi::PipelineHandle h) {
    checkUnrestricted("setPipeline");
    const Pipeline& p = dev_.pipeline(h);
    if (inPass_ && !p.compute)
        gdi::validate::pipelineFitsPass(p.signature, signature_, p.label.c_str());
    if (pipeline_ != &p) unchecked_ = ~uint64_t(0);  // other slots, other kinds
    unchecked_ |= feedback_.reaching();  // checked again against this pipeline's depth writes
    pipeline_ = &p;
    requiredSlots_ = p.requiredSlots;
    vertexInputs_.setPipeline(p.compute ? nullptr : &p.vertexBindings, &p.label);
    readyToDraw_ = inPass_ && !p.compute && vertexInputs_.ready();
    stream_->push(cmd::SetPipeline{h});
}

void GlCommandList::setVertexBuffer(uint32_t index, gdi::BufferHandle h, uint64_t offset) {
    checkUnrestricted("setVertexBuffer");
    const Buffer& b = dev_.buffer(h);
    vertexInputs_.setVertexBuffer(index, b.desc, b.label, offset);
    readyToDraw_ = inPass_ && pipeline_ && !pipeline_->compute && vertexInputs_.ready();
    stream_->push(cmd::SetVertexBuffer{index, h, offset});
}
void GlCommandList::setIndexBuffer(gdi::BufferHandle h, gdi::IndexType type, uint64_t offset) {
    checkUnrestricted("setIndexBuffer");
    const Buffer& b = dev_.buffer(h);
    vertexInputs_.setIndexBuffer(b.desc, b.label, type, offset);
    stream_->push(cmd::SetIndexBuffer{h, type, offset});
}

// Per-object path: plainly valid arguments are recorded at once; anything else (size 0 = "the
// rest", errors) takes the checked path, which owns the messages. Size 0 is resolved here so
// replay binds exactly what was validated. The per-object case binds one buffer at many offsets:
// the buffer the checked path bound last, with nothing destroyed since, is still alive and of the
// usage checked then, so the fast path checks only the range and that a buffer of this kind is
// in the slot already (no handle lookup, no saved registers); orphan() clears the cache. While
// validating, each bind's range is noted for the next draw's check against the block.
template <gdi::BindingType kKind>
inline void GlCommandList::setBuffer(uint32_t slot, gdi::BufferHandle h, uint64_t offset,
                                     uint64_t size) {
    using Record = std::conditional_t<kKind == gdi::BindingType::UniformBuffer,
                                      cmd::SetUniformBuffer, cmd::SetStorageBuffer>;
    constexpr size_t kind = kKind == gdi::BindingType::UniformBuffer ? 0 : 1;
    const BoundBuffer& last = lastBound_[kind];
    const uint64_t bindSize = gdi::validate::plainBindingSize(
        slot, last.size, offset, size, kind == 0 ? uniformLimits_ : storageLimits_);
    if (h.id != last.id || !bindSize || last.destroyEpoch != dev_.destroyEpoch() ||
        kinds_[slot] != uint8_t(1 + uint8_t(kKind)) || !stream_->fits<Record>()) [[unlikely]]
        return setBufferChecked<kKind>(slot, h, offset, size);
    if (validating_) [[unlikely]]
        noteRange(slot, bindSize);
    if constexpr (kind == 0) {
        if (slot == lastUniform_.slot && h.id == lastUniform_.id && bindSize == lastUniform_.size)
            return stream_->pushFitting(cmd::SetUniformOffset{offset});
        lastUniform_ = {.slot = slot, .id = h.id, .size = bindSize};
    }
    stream_->pushFitting(Record{slot, h, offset, bindSize});
}
template <gdi::BindingType kKind>
void GlCommandList::setBufferChecked(uint32_t slot, gdi::BufferHandle h, uint64_t offset,
                                     uint64_t size) {
    using Record = std::conditional_t<kKind == gdi::BindingType::UniformBuffer,
                                      cmd::SetUniformBuffer, cmd::SetStorageBuffer>;
    constexpr size_t kind = kKind == gdi::BindingType::UniformBuffer ? 0 : 1;
    const char* what = kind == 0 ? "setUniformBuffer" : "setStorageBuffer";
    checkDevice(what);
    checkSlot(slot, what);
    const uint64_t epoch = dev_.destroyEpoch();  // before the lookup: a destroy after it counts
    const Buffer& checked = dev_.buffer(h);
    gdi::validate::bufferUsage(checked.desc,
                               kind == 0 ? gdi::BufferUsage::Uniform : gdi::BufferUsage::Storage,
                               checked.label, what);
    const gdi::validate::BindingLimits& limits = kind == 0 ? uniformLimits_ : storageLimits_;
    const uint64_t bindSize =
        size == 0
            ? std::min(checked.desc.size - std::min(offset, checked.desc.size), limits.maxRange)
            : size;
    gdi::validate::bindingRange(checked.desc, offset, bindSize, what);
    gdi::validate::bindingLimits(offset, bindSize, limits, what);
    boundBuffer(slot, kKind);
    if (validating_) noteRange(slot, bindSize);
    lastBound_[kind] = {.id = h.id, .destroyEpoch = epoch, .size = checked.desc.size};
    if constexpr (kind == 0) lastUniform_ = {.slot = slot, .id = h.id, .size = bindSize};
    stream_->push(Record{slot, h, offset, bindSize});
}
void GlCommandList::setUniformBuffer(uint32_t slot, gdi::BufferHandle h, uint64_t offset,
                                     uint64_t size) {
    setBuffer<gdi::BindingType::UniformBuffer>(slot, h, offset, size);
}
void GlCommandList::setStorageBuffer(uint32_t slot, gdi::BufferHandle h, uint64_t offset,
                                     uint64_t size) {
    setBuffer<gdi::BindingType::StorageBuffer>(slot, h, offset, size);
}
void GlCommandList::setTexture(uint32_t slot, gdi::TextureHandle th, gdi::SamplerHandle sh) {
    checkDevice("setTexture");
    checkSlot(slot, "setTexture");
    const Texture& t = dev_.texture(th);
    if (!any(t.desc.usage, gdi::TextureUsage::Sampled))
        throw gdi::Error("setTexture: texture '" + t.label + "' lacks Sampled usage");
    const Sampler& s = dev_.sampler(sh);
    if (s.filtersLinearly && !t.linearFilter)
        gdi::validate::notFilterable(t.label, t.desc.format, s.label);
    bound(slot, gdi::BindingType::SampledTexture,
          t.desc.sampleCount > 1 ? gdi::kTexture2DMultisampleKind
                                 : uint8_t(1 + uint8_t(t.desc.dimension)));
    const auto span = gdi::validate::bindingSpanOf(th.id, t, t.label,
                                                   s.readsMips ? std::nullopt : std::optional(0u));
    if (feedback_.bind(slot, span, false)) kinds_[slot] |= kFeedback;
    stream_->push(cmd::SetTexture{slot, th, sh});
}
void GlCommandList::setStorageTexture(uint32_t slot, gdi::TextureHandle th, uint32_t mip) {
    checkDevice("setStorageTexture");
    checkSlot(slot, "setStorageTexture");
    const Texture& t = dev_.texture(th);
    if (!any(t.desc.usage, gdi::TextureUsage::Storage))
        throw gdi::Error("setStorageTexture: texture '" + t.label + "' lacks Storage usage");
    if (mip >= t.desc.mipLevels) throw gdi::Error("setStorageTexture: mip level out of range");
    bound(slot, gdi::BindingType::StorageTexture, uint8_t(1 + uint8_t(t.desc.dimension)));
    if (feedback_.bind(slot, gdi::validate::bindingSpanOf(th.id, t, t.label, mip), true))
        kinds_[slot] |= kFeedback;
    stream_->push(cmd::SetStorageTexture{slot, th, mip});
}

// The per-object path is a leaf: one test covers the draw state, changed slots, the vertex and
// instance ranges and the stream's room; anything else goes to drawChecked (errors, the bindings'
// check, a new block).
void GlCommandList::draw(uint32_t vertexCount, uint32_t instanceCount, uint32_t firstVertex,
                         uint32_t firstInstance) {
    if (!readyToDraw_ || (unchecked_ & requiredSlots_) ||
        uint64_t(firstVertex) + vertexCount > vertexInputs_.vertexCapacity() ||
        uint64_t(firstInstance) + instanceCount > vertexInputs_.instanceCapacity() ||
        !stream_->fits<cmd::Draw>()) [[unlikely]]
        return drawChecked(vertexCount, instanceCount, firstVertex, firstInstance);
    if (instanceCount == 1 && firstInstance == 0) [[likely]]
        return stream_->pushFitting(cmd::DrawOneInstance{vertexCount, firstVertex});
    stream_->pushFitting(cmd::Draw{vertexCount, instanceCount, firstVertex, firstInstance});
}
void GlCommandList::drawChecked(uint32_t vertexCount, uint32_t instanceCount, uint32_t firstVertex,
                                uint32_t firstInstance) {
    prepareDraw("draw");
    vertexInputs_.draw(vertexCount, instanceCount, firstVertex, firstInstance);
    stream_->push(cmd::Draw{vertexCount, instanceCount, firstVertex, firstInstance});
}
void GlCommandList::drawIndexed(uint32_t indexCount, uint32_t instanceCount, uint32_t firstIndex,
                                int32_t baseVertex, uint32_t firstInstance) {
    prepareDraw("drawIndexed");
    vertexInputs_.drawIndexed(indexCount, instanceCount, firstIndex, firstInstance);
    stream_->push(
        cmd::DrawIndexed{indexCount, instanceCount, firstIndex, baseVertex, firstInstance});
}
void GlCommandList::prepareCompute(const char* what) {
    checkDevice(what);
    if (inPass_) gdi::validate::insidePass(what);
    if (!pipeline_)
        throw gdi::Error(std::string(what) + " without a pipeline (call setPipeline first)");
    if (!pipeline_->compute)
        throw gdi::Error(std::string(what) + " with graphics pipeline '" + pipeline_->label + "'");
}
void GlCommandList::dispatch(uint32_t x, uint32_t y, uint32_t z) {
    gdi::validate::queueAllows(queue_, gdi::QueueKind::Compute, "dispatch");
    prepareCompute("dispatch");
    gdi::validate::dispatchSize(x, y, z, dev_.info().limits);
    checkBindings();
    stream_->push(cmd::Dispatch{x, y, z});
}

void GlCommandList::copyBuffer(gdi::BufferHandle dst, uint64_t dstOffset, gdi::BufferHandle src,
                               uint64_t srcOffset, uint64_t size) {
    outsidePass("copyBuffer");
    const Buffer& d = dev_.buffer(dst);
    const Buffer& s = dev_.buffer(src);
    gdi::validate::bufferCopy(d.desc, d.label, dstOffset, s.desc, s.label, srcOffset, size,
                              &d == &s);
    stream_->push(cmd::CopyBuffer{dst, dstOffset, src, srcOffset, size});
}
void GlCommandList::copyTexture(gdi::TextureHandle dst, gdi::TextureHandle src, uint32_t mip) {
    outsidePass("copyTexture");
    const Texture& d = copied(dst);
    const Texture& s = copied(src);
    gdi::validate::wholeTextureCopy(d.desc, d.label, s.desc, s.label, mip);
    stream_->push(cmd::CopyTexture{dst, src, mip});
}
void GlCommandList::copyBufferToTexture(gdi::TextureHandle dst, gdi::Subresource at,
                                        gdi::BufferHandle src, uint64_t srcOffset) {
    outsidePass("copyBufferToTexture");
    const Texture& t = copied(dst);
    const Buffer& b = dev_.buffer(src);
    gdi::validate::subresourceBufferCopy(t.desc, t.label, at, b.desc, b.label, srcOffset, true,
                                         "copyBufferToTexture");
    stream_->push(cmd::CopyBufferToTexture{dst, at, src, srcOffset});
}
void GlCommandList::copyTextureToBuffer(gdi::BufferHandle dst, uint64_t dstOffset,
                                        gdi::TextureHandle src, gdi::Subresource at) {
    outsidePass("copyTextureToBuffer");
    const Texture& t = copied(src);
    const Buffer& b = dev_.buffer(dst);
    gdi::validate::subresourceBufferCopy(t.desc, t.label, at, b.desc, b.label, dstOffset, false,
                                         "copyTextureToBuffer");
    stream_->push(cmd::CopyTextureToBuffer{dst, dstOffset, src, at});
}
// Regions: the shared rules resolve them, and the records carry the resolved values.
void GlCommandList::copyBufferToTexture(gdi::TextureHandle dst, const gdi::TextureRegion& region,
                                        gdi::BufferHandle src, const gdi::TexelLayout& layout) {
    outsidePass("copyBufferToTexture");
    const Texture& t = copied(dst);
    const Buffer& b = dev_.buffer(src);
    const auto [r, l] = gdi::validate::bufferTextureRegion(t.desc, t.label, b.desc, b.label, region,
                                                           layout, true, "copyBufferToTexture");
    stream_->push(cmd::CopyBufferToTextureRegion{dst, r, src, l});
}
void GlCommandList::copyTextureToBuffer(gdi::BufferHandle dst, const gdi::TexelLayout& layout,
                                        gdi::TextureHandle src, const gdi::TextureRegion& region) {
    outsidePass("copyTextureToBuffer");
    const Texture& t = copied(src);
    const Buffer& b = dev_.buffer(dst);
    const auto [r, l] = gdi::validate::bufferTextureRegion(t.desc, t.label, b.desc, b.label, region,
                                                           layout, false, "copyTextureToBuffer");
    stream_->push(cmd::CopyTextureToBufferRegion{dst, l, src, r});
}
void GlCommandList::copyTexture(gdi::TextureHandle dst, const gdi::TextureRegion& dstAt,
                                gdi::TextureHandle src, const gdi::TextureRegion& srcRegion) {
    outsidePass("copyTexture");
    const Texture& d = copied(dst);
    const Texture& s = copied(src);
    const auto [dr, sr] =
        gdi::validate::textureCopy(d.desc, d.label, dstAt, dst == src, s.desc, s.label, srcRegion);
    stream_->push(cmd::CopyTextureRegion{dst, dr, src, sr});
}

void GlCommandList::resolveTexture(gdi::TextureHandle dst, const gdi::TextureRegion& dstAt,
                                   gdi::TextureHandle src, const gdi::TextureRegion& srcRegion) {
    gdi::validate::queueAllows(queue_, gdi::QueueKind::Graphics, "resolveTexture");
    outsidePass("resolveTexture");
    const Texture& d = copied(dst);
    const Texture& s = copied(src);
    const auto [dr, sr] =
        gdi::validate::textureResolve(d.desc, d.label, dstAt, s.desc, s.label, srcRegion);
    stream_->push(cmd::ResolveTextureRegion{dst, dr, src, sr});
}

void GlCommandList::generateMips(gdi::TextureHandle h) {
    gdi::validate::queueAllows(queue_, gdi::QueueKind::Graphics, "generateMips");
    outsidePass("generateMips");
    const Texture& t = copied(h);
    gdi::validate::mipGeneration(t.desc, t.label);
    stream_->push(cmd::GenerateMips{h});
}

// Indirect work. GL reads indexed records relative to the element buffer's start, so the
// index buffer must be bound at offset 0 (checked on every backend, so both behave alike).
void GlCommandList::indirectArgs(gdi::BufferHandle h, uint64_t offset, uint32_t drawCount,
                                 uint32_t stride, uint32_t recordSize, const char* what) {
    // Same order of checks as Vulkan: draw state, index buffer, then the arguments.
    prepareDraw(what);
    if (recordSize == sizeof(gdi::DrawIndexedIndirectArgs)) vertexInputs_.indexedIndirect(what);
    const Buffer& b = dev_.buffer(h);
    gdi::validate::indirect(b.desc, b.label, offset, drawCount, stride, recordSize,
                            dev_.info().features, what);
}
void GlCommandList::countBuffer(gdi::BufferHandle h, uint64_t offset, const char* what) const {
    checkDevice(what);
    if (!dev_.info().features.drawIndirectCount)
        throw gdi::Error(std::string(what) +
                         ": not supported on this device (DeviceFeatures::drawIndirectCount)");
    const Buffer& b = dev_.buffer(h);
    gdi::validate::indirect(b.desc, b.label, offset, 1, 4, 4, dev_.info().features, what);
}
void GlCommandList::drawIndirect(gdi::BufferHandle args, uint64_t offset, uint32_t drawCount,
                                 uint32_t stride) {
    indirectArgs(args, offset, drawCount, stride, sizeof(gdi::DrawIndirectArgs), "drawIndirect");
    stream_->push(cmd::DrawIndirect{args, offset, drawCount, stride});
}
void GlCommandList::drawIndexedIndirect(gdi::BufferHandle args, uint64_t offset, uint32_t drawCount,
                                        uint32_t stride) {
    indirectArgs(args, offset, drawCount, stride, sizeof(gdi::DrawIndexedIndirectArgs),
                 "drawIndexedIndirect");
    stream_->push(cmd::DrawIndexedIndirect{args, offset, drawCount, stride});
}
void GlCommandList::drawIndirectCount(gdi::BufferHandle args, uint64_t offset,
                                      gdi::BufferHandle count, uint64_t countOffset,
                                      uint32_t maxDrawCount, uint32_t stride) {
    countBuffer(count, countOffset, "drawIndirectCount");
    indirectArgs(args, offset, maxDrawCount, stride, sizeof(gdi::DrawIndirectArgs),
                 "drawIndirectCount");
    stream_->push(cmd::DrawIndirectCount{args, offset, count, countOffset, maxDrawCount, stride});
}
void GlCommandList::drawIndexedIndirectCount(gdi::BufferHandle args, uint64_t offset,
                                             gdi::BufferHandle count, uint64_t countOffset,
                                             uint32_t maxDrawCount, uint32_t stride) {
    countBuffer(count, countOffset, "drawIndexedIndirectCount");
    indirectArgs(args, offset, maxDrawCount, stride, sizeof(gdi::DrawIndexedIndirectArgs),
                 "drawIndexedIndirectCount");
    stream_->push(
        cmd::DrawIndexedIndirectCount{args, offset, count, countOffset, maxDrawCount, stride});
}
void GlCommandList::dispatchIndirect(gdi::BufferHandle args, uint64_t offset) {
    gdi::validate::queueAllows(queue_, gdi::QueueKind::Compute, "dispatchIndirect");
    prepareCompute("dispatchIndirect");
    const Buffer& b = dev_.buffer(args);
    gdi::validate::indirect(b.desc, b.label, offset, 1, sizeof(gdi::DispatchIndirectArgs),
                            sizeof(gdi::DispatchIndirectArgs), dev_.info().features,
                            "dispatchIndirect");
    checkBindings();
    stream_->push(cmd::DispatchIndirect{args, offset});
}

void GlCommandList::beginTimer(gdi::TimerHandle h) {
    gdi::validate::queueAllows(queue_, gdi::QueueKind::Compute, "beginTimer");
    outsidePass("beginTimer");
    (void)dev_.timer(h);
    queries_.beginTimer(h.id);
    stream_->push(cmd::BeginTimer{h});
}
void GlCommandList::endTimer(gdi::TimerHandle h) {
    gdi::validate::queueAllows(queue_, gdi::QueueKind::Compute, "endTimer");
    checkUnrestricted("endTimer");
    if (secondary_) gdi::validate::notInSecondary("endTimer");
    (void)dev_.timer(h);
    queries_.endTimer(h.id);
    stream_->push(cmd::EndTimer{h});
}
QuerySet& GlCommandList::usedQuerySet(gdi::QuerySetHandle h, const char* what) {
    checkUnrestricted(what);
    if (secondary_) gdi::validate::notInSecondary(what);
    return dev_.querySet(h);
}
void GlCommandList::beginQuery(gdi::QuerySetHandle h, uint32_t index) {
    gdi::validate::queueAllows(queue_, gdi::QueueKind::Compute, "beginQuery");
    const QuerySet& q = usedQuerySet(h, "beginQuery");
    queries_.begin(q.desc, q.label, h.id, index, inPass_);
    stream_->push(cmd::BeginQuery{h, index});
}
void GlCommandList::endQuery(gdi::QuerySetHandle h, uint32_t index) {
    const QuerySet& q = usedQuerySet(h, "endQuery");
    queries_.end(q.desc, q.label, h.id, index, inPass_);
    stream_->push(cmd::EndQuery{h, index});
}
void GlCommandList::writeTimestamp(gdi::QuerySetHandle h, uint32_t index) {
    gdi::validate::queueAllows(queue_, gdi::QueueKind::Compute, "writeTimestamp");
    const QuerySet& q = usedQuerySet(h, "writeTimestamp");
    queries_.timestamp(q.desc, q.label, h.id, index, inPass_);
    stream_->push(cmd::WriteTimestamp{h, index});
}
void GlCommandList::resolveQueries(gdi::QuerySetHandle h, uint32_t first, uint32_t count,
                                   gdi::BufferHandle dst, uint64_t dstOffset) {
    gdi::validate::queueAllows(queue_, gdi::QueueKind::Compute, "resolveQueries");
    outsidePass("resolveQueries");
    const QuerySet& q = usedQuerySet(h, "resolveQueries");
    const Buffer& b = dev_.buffer(dst);
    gdi::validate::queryDestination(b.desc, b.label, dstOffset,
                                    8ull * gdi::validate::queryValues(q.desc.type) * count);
    queries_.resolve(q.desc, q.label, h.id, first, count);  // last: it keeps what it resolves
    stream_->push(cmd::ResolveQueries{h, first, count, dst, dstOffset});
}

void GlCommandList::pushDebugGroup(const char* name) {
    checkUnrestricted("pushDebugGroup");
    ++depth_;
    auto* r =
        stream_->push(cmd::PushDebugGroup{}, cmd::CommandStream::payloadSize(name ? name : ""));
    r->name = stream_->payload(*r, name ? name : "");
}
void GlCommandList::popDebugGroup() {
    checkUnrestricted("popDebugGroup");
    if (depth_ == 0) throw gdi::Error("popDebugGroup without pushDebugGroup");
    --depth_;
    stream_->push(cmd::PopDebugGroup{});
}
void GlCommandList::insertDebugLabel(const char* name) {
    checkUnrestricted("insertDebugLabel");
    auto* r =
        stream_->push(cmd::InsertDebugLabel{}, cmd::CommandStream::payloadSize(name ? name : ""));
    r->name = stream_->payload(*r, name ? name : "");
}
void GlCommandList::clearBuffer(gdi::BufferHandle h, uint64_t offset, uint64_t size,
                                uint32_t value) {
    outsidePass("clearBuffer");
    const Buffer& b = dev_.buffer(h);
    const uint64_t bytes = gdi::validate::clearRange(b.desc, b.label, offset, size);
    stream_->push(cmd::ClearBuffer{h, offset, bytes, value});
}
void GlCommandList::discardTexture(gdi::TextureHandle h) {
    outsidePass("discardTexture");
    (void)copied(h);
    stream_->push(cmd::DiscardTexture{h});
}
void GlCommandList::setAutomaticBarriers(bool enabled) {
    outsidePass("setAutomaticBarriers");
    stream_->push(cmd::SetAutomaticBarriers{enabled});
}
void GlCommandList::barrier(const gdi::TextureBarrier* barriers, uint32_t count) {
    outsidePass("barrier");
    gdi::validate::barrierArray(barriers, count);
    for (const gdi::TextureBarrier& b : std::span(barriers, count)) {
        const Texture& t = copied(b.texture);
        gdi::validate::textureBarrier(t.desc, b, t.label);
    }
    pushArray<cmd::TextureBarriers>(std::span(barriers, count));
}
void GlCommandList::barrier(const gdi::BufferBarrier* barriers, uint32_t count) {
    outsidePass("barrier");
    gdi::validate::barrierArray(barriers, count);
    for (const gdi::BufferBarrier& b : std::span(barriers, count)) {
        const Buffer& buffer = dev_.buffer(b.buffer);
        gdi::validate::bufferBarrier(buffer.desc, b, buffer.label);
    }
    pushArray<cmd::BufferBarriers>(std::span(barriers, count));
}

void GlCommandList::beginPassFeedback(const gdi::RenderPassDesc& desc) {
    uint64_t textures = 0;
    for (uint32_t slot = 0; slot < 64; ++slot) {
        const uint8_t kind = kinds_[slot] & ~kFeedback;
        if (kind == 1 + uint8_t(gdi::BindingType::SampledTexture) ||
            kind == 1 + uint8_t(gdi::BindingType::StorageTexture))
            textures |= uint64_t(1) << slot;
    }
    const uint64_t reach = feedback_.beginPass(
        desc,
        [&](gdi::TextureHandle h) {
            const Texture& t = dev_.texture(h);
            return gdi::validate::bindingSpanOf(h.id, t, t.label);
        },
        textures);
    for (uint64_t m = reach; m; m &= m - 1) kinds_[std::countr_zero(m)] |= kFeedback;
    unchecked_ |= reach;
}

void GlCommandList::endPassFeedback() {
    for (uint64_t m = feedback_.endPass(); m; m &= m - 1) kinds_[std::countr_zero(m)] &= ~kFeedback;
}

void GlCommandList::checkSlot(uint32_t slot, const char* what) const {
    if (slot >= 64)
        throw gdi::Error(std::string(what) + ": slot " + std::to_string(slot) + " out of range");
}
void GlCommandList::outsidePass(const char* what) const {
    if (orphaned_) gdi::validate::listOfDestroyedDevice(what);
    if (inPass_) gdi::validate::insidePass(what);
}
// Every slot the pipeline uses must be bound with the kind it declares (GL would otherwise
// read whatever the other binding namespace holds). Only slots changed since the last check
// with this pipeline are looked at; an unbound slot (kind 0) fails the same comparison.
void GlCommandList::checkBindings() {
    const uint64_t check = unchecked_ & requiredSlots_;
    if (!check) return;
    if (validating_) [[unlikely]]  // each buffer covers the block declared at its slot
        for (uint64_t m = check; m; m &= m - 1) {
            const uint32_t slot = uint32_t(std::countr_zero(m));
            const uint8_t kind = kinds_[slot] & ~kFeedback;
            if (kind == 1 + uint8_t(gdi::BindingType::UniformBuffer) ||
                kind == 1 + uint8_t(gdi::BindingType::StorageBuffer))
                gdi::validate::rangeCoversBlock(slot, boundBytes_[slot],
                                                pipeline_->slotBlockBytes[slot], pipeline_->label);
        }
    if (!(check & (check - 1))) [[likely]] {  // the per-object case: one slot changed
        const uint32_t slot = uint32_t(std::countr_zero(check));
        if (!slotMatches(slot)) [[unlikely]]
            checkEachSlot(check);
        unchecked_ &= ~check;
        return;
    }
    checkEachSlot(check);
    unchecked_ &= ~check;
}
void GlCommandList::checkEachSlot(uint64_t check) const {  // throws for the first problem
    uint64_t missing = 0;
    for (uint64_t m = check; m; m &= m - 1)
        if (!kinds_[std::countr_zero(m)]) missing |= m & -m;
    gdi::validate::missingBindings(missing, 0, pipeline_->label.c_str());
    for (uint64_t m = check; m; m &= m - 1) {
        const uint32_t slot = uint32_t(std::countr_zero(m));
        const uint8_t kind = kinds_[slot] & ~kFeedback;
        if (kinds_[slot] & kFeedback) [[unlikely]]
            feedback_.check(slot, pipeline_->writesDepthStencil, pipeline_->label.c_str());
        if (kind != pipeline_->slotKinds[slot]) [[unlikely]]
            gdi::validate::wrongBindingKindFailed(
                slot, gdi::BindingType(pipeline_->slotKinds[slot] - 1), gdi::BindingType(kind - 1),
                pipeline_->label.c_str());
        if (pipeline_->slotDimensions[slot] && dims_[slot] != pipeline_->slotDimensions[slot])
            [[unlikely]]
            gdi::validate::wrongTextureDimensionFailed(slot, pipeline_->slotDimensions[slot],
                                                       dims_[slot], pipeline_->label.c_str());
    }
}
void GlCommandList::notReadyToDraw(const char* what) const {
    checkUnrestricted(what);
    if (!inPass_) throw gdi::Error(std::string(what) + " outside a render pass");
    if (!pipeline_)
        throw gdi::Error(std::string(what) + " without a pipeline (call setPipeline first)");
    if (pipeline_->compute)
        throw gdi::Error(std::string(what) + " with compute pipeline '" + pipeline_->label + "'");
    vertexInputs_.notReady(what);
}

std::unique_ptr<gdi::CommandList> GlDevice::createCommandList(const gdi::CommandListDesc& desc) {
    loss_.check("createCommandList");
    auto list = std::make_unique<GlCommandList>(*this, desc.queue);
    return info_.features.validation ? gdi::exclusiveUse(std::move(list)) : std::move(list);
}

}  // namespace fe::gl

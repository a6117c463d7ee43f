#include "VulkanCommandList.h"
#include "VulkanFaults.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <string>

#include "fe/gdi/Validation.h"

namespace fe::vk {

namespace {
// Error paths of the per-draw functions, kept out of line so the hot paths stay small.
[[noreturn, gnu::cold, gnu::noinline]] void fail(const char* message) { throw gdi::Error(message); }
[[noreturn, gnu::cold, gnu::noinline]] void slotOutOfRange(const char* what, uint32_t slot) {
    throw gdi::Error(std::string(what) + ": slot " + std::to_string(slot) + " out of range");
}
[[noreturn, gnu::cold, gnu::noinline]] void wrongPipelineKind(const char* what,
                                                              const std::string& pipeline) {
    throw gdi::Error(std::string(what) + " pipeline '" + pipeline + "'");
}
gdi::BindingType kindOf(VkDescriptorType t) {
    switch (t) {
        case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER:
            return gdi::BindingType::StorageBuffer;
        case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER:
            return gdi::BindingType::SampledTexture;
        case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE:
            return gdi::BindingType::StorageTexture;
        default:
            return gdi::BindingType::UniformBuffer;
    }
}

VkAttachmentLoadOp toLoad(gdi::LoadOp op) {
    switch (op) {
        case gdi::LoadOp::Load:
            return VK_ATTACHMENT_LOAD_OP_LOAD;
        case gdi::LoadOp::DontCare:
            return VK_ATTACHMENT_LOAD_OP_DONT_CARE;
        default:
            return VK_ATTACHMENT_LOAD_OP_CLEAR;
    }
}
VkAttachmentStoreOp toStore(gdi::StoreOp op) {
    return op == gdi::StoreOp::DontCare ? VK_ATTACHMENT_STORE_OP_DONT_CARE
                                        : VK_ATTACHMENT_STORE_OP_STORE;
}
}  // namespace

VulkanCommandList::VulkanCommandList(VulkanDevice& device, gdi::QueueKind queue)
    : dev_(device),
      queue_(queue),
      validating_(device.info().features.validation),
      uniformLimits_(gdi::validate::uniformBindingLimits(device.info().limits)),
      storageLimits_(gdi::validate::storageBindingLimits(device.info().limits)),
      viewportLimits_(gdi::validate::viewportLimits(device.info().limits)) {
    addRecordingBuffer();
    pushDescriptorSet_ = dev_.cmdPushDescriptorSet;
    destroyEpoch_ = dev_.destroyEpoch();
    dev_.liveLists().add(this);
}

// One command pool and buffer per recording still in flight: recording the next frame does not
// wait for the previous one's execution.
void VulkanCommandList::addRecordingBuffer() {
    RecordingBuffer b;
    VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pci.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
    pci.queueFamilyIndex = dev_.queueFamily(queue_);
    check(nativeAllocation(
              "vkCreateCommandPool",
              [&] { return vkCreateCommandPool(dev_.vkDevice(), &pci, nullptr, &b.pool); }),
          "vkCreateCommandPool");
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = b.pool;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    if (VkResult r =
            nativeAllocation("vkAllocateCommandBuffers",
                             [&] { return vkAllocateCommandBuffers(dev_.vkDevice(), &ai, &b.cb); });
        r != VK_SUCCESS) {
        vkDestroyCommandPool(dev_.vkDevice(), b.pool,
                             nullptr);  // not yet in buffers_: nothing else frees it
        check(r, "vkAllocateCommandBuffers");
    }
    buffers_.push_back(b);
    current_ = buffers_.size() - 1;
    cb_ = b.cb;
}

VulkanCommandList::~VulkanCommandList() {
    if (orphaned_) return;  // the device is gone; what the list held went with orphan()
    releaseNative();
    closeRecording();  // what was destroyed while it recorded is released now
    dev_.liveLists().remove(this);
}

// The device holds back the native release of objects destroyed while a recording is open
// (VulkanDevice::openRecording): from the first native command until submit, execution by a
// primary, or the list's end; and from the first object bound, where that comes first.
void VulkanCommandList::openRecording() {
    if (openSince_ != kNotOpen) return;
    dev_.openRecording(destroyEpoch_);
    openSince_ = destroyEpoch_;
}

void VulkanCommandList::closeRecording() {
    if (openSince_ == kNotOpen) return;
    dev_.closeRecording(std::exchange(openSince_, kNotOpen));
}

VulkanCommandList::SharedSecondary::~SharedSecondary() {
    dev.releaseSecondary(std::span(&recording, 1), lastFence.load());
}

void VulkanCommandList::releaseNative() {
    // Secondary recordings go back once no list holds them (after the last submission that ran
    // them: their fence).
    executed_.clear();
    lease_.reset();
    if (lastSubmit_) dev_.settle(lastSubmit_);  // not wait(): a lost device must not throw here
    for (const RecordingBuffer& b : buffers_)
        vkDestroyCommandPool(dev_.vkDevice(), b.pool, nullptr);
    buffers_.clear();
}

// The device is being destroyed before this list (LiveLists.h): every later call throws.
void VulkanCommandList::orphan() {
    releaseNative();
    orphaned_ = restricted_ = true;
    recording_ = inPass_ = false;
    lastBound_[0].id = lastBound_[1].id =
        ~0u;                // no device makes it: the setters take the checked path, which throws
    openSince_ = kNotOpen;  // the device releases everything as it goes
    setNotReady();
    cb_ = VK_NULL_HANDLE;
}

void VulkanCommandList::fullBarrier(VkCommandBuffer cb) {
    VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    mb.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
    mb.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                         0, 1, &mb, 0, nullptr, 0, nullptr);
}

void VulkanCommandList::toGeneral(VkCommandBuffer cb, VkImage image, gdi::Format format) {
    VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    b.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;  // whatever last wrote these bytes (aliasing)
    b.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
    b.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    b.newLayout = VK_IMAGE_LAYOUT_GENERAL;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {aspectOf(format), 0, VK_REMAINING_MIP_LEVELS, 0,
                          VK_REMAINING_ARRAY_LAYERS};
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                         0, 0, nullptr, 0, nullptr, 1, &b);
}

void VulkanCommandList::discardTexture(gdi::TextureHandle h) {
    outsidePass("discardTexture");
    Texture& t = copiedTexture(h);
    toGeneral(cb_, t.image, t.desc.format);
}

namespace {
// Stages and accesses of each state; every texture stays in GENERAL, so a barrier only
// orders and makes memory visible (plus UNDEFINED -> GENERAL for contents not needed).
struct StateScope {
    VkPipelineStageFlags stages;
    VkAccessFlags access;
};
StateScope scopeOf(gdi::ResourceState s) {
    constexpr VkPipelineStageFlags shaders = VK_PIPELINE_STAGE_VERTEX_SHADER_BIT |
                                             VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT |
                                             VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
    switch (s) {
        case gdi::ResourceState::RenderTarget:
            return {VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT};
        case gdi::ResourceState::DepthTarget:
            return {VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                        VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                    VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                        VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT};
        case gdi::ResourceState::ShaderRead:
            return {shaders, VK_ACCESS_SHADER_READ_BIT};
        case gdi::ResourceState::Storage:
            return {shaders, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT};
        case gdi::ResourceState::CopySrc:
            return {VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT};
        case gdi::ResourceState::CopyDst:
            return {VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT};
        case gdi::ResourceState::Undefined:
            break;
    }
    // Undefined: whatever last used these bytes (another texture aliasing the memory).
    return {VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT};
}

// A barrier's scope as a list of `queue` may state it: the stages and accesses that queue's
// family supports. The rest happened, or will happen, on another queue, which the submissions'
// waits order (a render graph's async compute pass after a G-buffer pass).
StateScope onQueue(StateScope s, gdi::QueueKind queue, bool source) {
    if (queue == gdi::QueueKind::Graphics) return s;
    constexpr VkPipelineStageFlags kAnyQueue =
        VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT | VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT |
        VK_PIPELINE_STAGE_ALL_COMMANDS_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
    constexpr VkAccessFlags kTransfer = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT |
                                        VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
    const bool compute = queue == gdi::QueueKind::Compute;
    s.stages &=
        kAnyQueue |
        (compute ? VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT : 0u);
    s.access &=
        kTransfer | (compute ? VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                                   VK_ACCESS_UNIFORM_READ_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT
                             : 0u);
    if (s.stages == 0)
        s = {source ? VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT : VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0};
    return s;
}
}  // namespace

void VulkanCommandList::setAutomaticBarriers(bool enabled) {
    outsidePass("setAutomaticBarriers");
    if (enabled == automaticBarriers_) return;
    if (!enabled) barrierIfWritten();  // order what came before before the explicit section
    automaticBarriers_ = enabled;
    written_ = enabled;  // and the explicit section before whatever follows it (lazily)
}

void VulkanCommandList::barrier(const gdi::TextureBarrier* barriers, uint32_t count) {
    outsidePass("barrier");
    gdi::validate::barrierArray(barriers, count);
    if (count == 0) return;
    std::vector<VkImageMemoryBarrier> bs(count);
    VkPipelineStageFlags src = 0, dst = 0;
    for (uint32_t i = 0; i < count; ++i) {
        const gdi::TextureBarrier& in = barriers[i];
        Texture& t = copiedTexture(in.texture);
        const auto range = gdi::validate::textureBarrier(t.desc, in, t.name);
        const StateScope before = onQueue(scopeOf(in.before), queue_, true),
                         after = onQueue(scopeOf(in.after), queue_, false);
        VkImageMemoryBarrier& b = bs[i];
        b = {VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
        b.srcAccessMask = before.access;
        b.dstAccessMask = after.access;
        b.oldLayout = in.before == gdi::ResourceState::Undefined ? VK_IMAGE_LAYOUT_UNDEFINED
                                                                 : VK_IMAGE_LAYOUT_GENERAL;
        b.newLayout = VK_IMAGE_LAYOUT_GENERAL;
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.image = t.image;
        b.subresourceRange = {aspectOf(t.desc.format), range.baseMip, range.mipCount,
                              range.baseLayer, range.layerCount};
        if (t.desc.dimension == gdi::TextureDimension::Texture3D) b.subresourceRange.layerCount = 1;
        src |= before.stages;
        dst |= after.stages;
    }
    vkCmdPipelineBarrier(cb_, src, dst, 0, 0, nullptr, 0, nullptr, count, bs.data());
}

namespace {
// Where and how a buffer access happens, for a buffer memory barrier.
StateScope bufferScope(gdi::BufferAccess a) {
    using A = gdi::BufferAccess;
    StateScope s{0, 0};
    auto add = [&](A bit, VkPipelineStageFlags stages, VkAccessFlags access) {
        if (any(a, bit)) s.stages |= stages, s.access |= access;
    };
    constexpr VkPipelineStageFlags kShaders = VK_PIPELINE_STAGE_VERTEX_SHADER_BIT |
                                              VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT |
                                              VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
    add(A::Vertex, VK_PIPELINE_STAGE_VERTEX_INPUT_BIT, VK_ACCESS_VERTEX_ATTRIBUTE_READ_BIT);
    add(A::Index, VK_PIPELINE_STAGE_VERTEX_INPUT_BIT, VK_ACCESS_INDEX_READ_BIT);
    add(A::Indirect, VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT, VK_ACCESS_INDIRECT_COMMAND_READ_BIT);
    add(A::Uniform, kShaders, VK_ACCESS_UNIFORM_READ_BIT);
    add(A::StorageRead, kShaders, VK_ACCESS_SHADER_READ_BIT);
    add(A::StorageWrite, kShaders, VK_ACCESS_SHADER_WRITE_BIT);
    add(A::CopySrc, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    add(A::CopyDst, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
    if (!s.stages) s.stages = VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT;
    return s;
}
}  // namespace

void VulkanCommandList::barrier(const gdi::BufferBarrier* barriers, uint32_t count) {
    outsidePass("barrier");
    gdi::validate::barrierArray(barriers, count);
    if (count == 0) return;
    std::vector<VkBufferMemoryBarrier> bs(count);
    VkPipelineStageFlags src = 0, dst = 0;
    for (uint32_t i = 0; i < count; ++i) {
        const gdi::BufferBarrier& in = barriers[i];
        const Buffer& buf = usedBuffer(in.buffer);
        const uint64_t size = gdi::validate::bufferBarrier(buf.desc, in, buf.name);
        const StateScope before = onQueue(bufferScope(in.before), queue_, true),
                         after = onQueue(bufferScope(in.after), queue_, false);
        VkBufferMemoryBarrier& b = bs[i];
        b = {VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
        b.srcAccessMask = before.access;
        b.dstAccessMask = after.access;
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.buffer = buf.buffer;
        b.offset = in.offset;
        b.size = size;
        src |= before.stages;
        dst |= after.stages;
    }
    vkCmdPipelineBarrier(cb_, src, dst, 0, 0, nullptr, count, bs.data(), 0, nullptr);
}

// A destroy happened since this recording began: every object it used must still be alive.
void VulkanCommandList::checkAlive() const {
    for (uint64_t u : used_) {
        const uint32_t id = uint32_t(u);
        switch (UsedKind(u >> 32)) {
            case UsedKind::Buffer:
                if (!dev_.findBuffer({id})) gdi::validate::destroyedBeforeSubmit("buffer", id);
                break;
            case UsedKind::Texture:
                if (!dev_.findTexture({id})) gdi::validate::destroyedBeforeSubmit("texture", id);
                break;
            case UsedKind::Sampler:
                if (!dev_.findSampler({id})) gdi::validate::destroyedBeforeSubmit("sampler", id);
                break;
            case UsedKind::Pipeline:
                if (!dev_.findPipeline({id})) gdi::validate::destroyedBeforeSubmit("pipeline", id);
                break;
            case UsedKind::Timer:
                if (!dev_.findTimer({id})) gdi::validate::destroyedBeforeSubmit("timer", id);
                break;
            case UsedKind::QuerySet:
                if (!dev_.findQuerySet({id})) gdi::validate::destroyedBeforeSubmit("query set", id);
                break;
        }
    }
}

void VulkanCommandList::beginRecording(const char* what) {
    checkDevice(what);
    // A buffer whose last submission has completed is reused; otherwise another one is made.
    size_t free = buffers_.size();
    for (size_t i = 0; i < buffers_.size() && free == buffers_.size(); ++i)
        if (!buffers_[i].fence || dev_.completedNoThrow(buffers_[i].fence)) free = i;
    if (free == buffers_.size()) {
        addRecordingBuffer();
    } else {
        current_ = free;
        cb_ = buffers_[current_].cb;
    }
    check(vkResetCommandPool(dev_.vkDevice(), buffers_[current_].pool, 0), "vkResetCommandPool");
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(nativeAllocation("vkBeginCommandBuffer", [&] { return vkBeginCommandBuffer(cb_, &bi); }),
          "vkBeginCommandBuffer");
    openRecording();
    recording_ = true;
    written_ = true;  // order after earlier submissions
}

// Bindings and pass state belong to a recording; they are cleared when it is submitted (and
// not when the next one begins, so binding needs no recording and no check for one).
void VulkanCommandList::submitted(gdi::FenceValue value) {
    lastSubmit_ = value;
    buffers_[current_].fence = value;
    for (const auto& s : executed_) {
        gdi::FenceValue last = s->lastFence.load();
        while (last < value && !s->lastFence.compare_exchange_weak(last, value)) {}
    }
    executed_.clear();
    clearRecording();  // push descriptors are undefined when a command buffer begins: all dirty
}

void VulkanCommandList::checkSubmittable() const {
    if (secondary_) gdi::validate::submittedSecondary();
    if (inPass_) throw gdi::Error("submit: render pass still open (missing endRenderPass)");
    if (debugDepth_ != 0)
        throw gdi::Error("submit: " + std::to_string(debugDepth_) + " debug group(s) not popped");
    queries_.finish();
    if (dev_.destroyEpoch() != destroyEpoch_) checkAlive();
}

VkCommandBuffer VulkanCommandList::finish() {
    ensureRecording("submit");
    // No barrier at the end: every recording starts with one before its first pass, copy or
    // dispatch (written_ is set when recording begins), and readback (immediate()) starts with
    // one too. A trailing barrier would also make lavapipe, which executes on submit, wait for
    // the rasterizer inside vkQueueSubmit.
    check(nativeAllocation("vkEndCommandBuffer", [&] { return vkEndCommandBuffer(cb_); }),
          "vkEndCommandBuffer");
    return cb_;
}

void VulkanCommandList::outsidePass(const char* what) {
    if (orphaned_) [[unlikely]]
        gdi::validate::listOfDestroyedDevice(what);
    ensureRecording(what);
    if (inPass_) gdi::validate::insidePass(what);
}

void VulkanCommandList::barrierIfWritten() {
    if (!written_ || !automaticBarriers_) return;
    fullBarrier(cb_);
    written_ = false;
}

// The pass's attachments, validated (the same checks and messages as GL's): its signature, and
// the textures when `textures` is given.
gdi::validate::PassSignature VulkanCommandList::checkPass(const gdi::RenderPassDesc& desc,
                                                          PassTextures* textures) {
    using gdi::validate::attachment;
    std::vector<gdi::validate::AttachmentInfo> infos, resolveInfos(desc.colors.size());
    PassTextures local;
    PassTextures& pt = textures ? *textures : local;
    pt.resolve.assign(desc.colors.size(), nullptr);
    for (size_t i = 0; i < desc.colors.size(); ++i) {
        const auto& c = desc.colors[i];
        Texture& t = usedTexture(c.texture);
        infos.push_back(attachment(t.desc, c.mipLevel, c.layer, "beginRenderPass", t.name));
        pt.colors.push_back(&t);
        if (c.resolveTexture) {
            pt.resolve[i] = &usedTexture(c.resolveTexture);
            resolveInfos[i] = attachment(pt.resolve[i]->desc, c.resolveSubresource.mipLevel,
                                         c.resolveSubresource.layer, "beginRenderPass resolve",
                                         pt.resolve[i]->name);
        }
    }
    pt.depth = desc.depth.texture ? &usedTexture(desc.depth.texture) : nullptr;
    pt.depthResolve = desc.depth.resolveTexture ? &usedTexture(desc.depth.resolveTexture) : nullptr;
    gdi::validate::AttachmentInfo depthInfo{}, depthResolveInfo{};
    if (pt.depth)
        depthInfo = attachment(pt.depth->desc, desc.depth.mipLevel, desc.depth.layer,
                               "beginRenderPass", pt.depth->name);
    if (pt.depthResolve)
        depthResolveInfo = attachment(pt.depthResolve->desc, desc.depth.resolveSubresource.mipLevel,
                                      desc.depth.resolveSubresource.layer,
                                      "beginRenderPass resolve", pt.depthResolve->name);
    if (pt.depthResolve && !pt.depth)
        throw gdi::Error("beginRenderPass: a depth resolve target without a depth attachment");
    const gdi::Rect area = gdi::validate::renderPass(
        desc, infos, resolveInfos, pt.depth ? &depthInfo : nullptr,
        pt.depthResolve ? &depthResolveInfo : nullptr, dev_.info().limits);
    return gdi::validate::passSignature(infos, pt.depth ? &depthInfo : nullptr, area);
}

void VulkanCommandList::beginRenderPass(const gdi::RenderPassDesc& desc) {
    gdi::validate::queueAllows(queue_, gdi::QueueKind::Graphics, "beginRenderPass");
    if (secondary_) gdi::validate::notInSecondary("beginRenderPass");
    outsidePass("beginRenderPass");
    PassTextures pt;
    signature_ = checkPass(desc, &pt);
    beginPassFeedback(desc);
    renderArea_ = gdi::validate::renderArea(signature_);
    passSamples_ = signature_.samples;
    std::vector<Texture*>& colorTex = pt.colors;
    std::vector<Texture*>& resolveTex = pt.resolve;
    Texture* depthTex = pt.depth;
    Texture* depthResolveTex = pt.depthResolve;

    barrierIfWritten();
    std::vector<VkRenderingAttachmentInfo> colors(desc.colors.size());
    for (size_t i = 0; i < desc.colors.size(); ++i) {
        const auto& c = desc.colors[i];
        auto& a = colors[i];
        a = {VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        a.imageView = dev_.attachmentView(*colorTex[i], c.mipLevel, c.layer);
        a.imageLayout = VK_IMAGE_LAYOUT_GENERAL;
        a.loadOp = toLoad(c.load);
        a.storeOp = toStore(c.store);
        const bool integer = gdi::formatInfo(colorTex[i]->desc.format).isInteger;
        if (integer)
            for (int k = 0; k < 4; ++k) a.clearValue.color.uint32[k] = uint32_t(c.clear[k]);
        else
            for (int k = 0; k < 4; ++k) a.clearValue.color.float32[k] = c.clear[k];
        if (resolveTex[i]) {
            // Integer formats cannot be averaged: they resolve to sample 0, like depth.
            a.resolveMode = integer ? VK_RESOLVE_MODE_SAMPLE_ZERO_BIT : VK_RESOLVE_MODE_AVERAGE_BIT;
            a.resolveImageView = dev_.attachmentView(*resolveTex[i], c.resolveSubresource.mipLevel,
                                                     c.resolveSubresource.layer);
            a.resolveImageLayout = VK_IMAGE_LAYOUT_GENERAL;
        }
    }
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    VkRenderingAttachmentInfo stencil{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
    if (depthTex) {
        depth.imageView = dev_.attachmentView(*depthTex, desc.depth.mipLevel, desc.depth.layer);
        depth.imageLayout = VK_IMAGE_LAYOUT_GENERAL;
        depth.loadOp = toLoad(desc.depth.load);
        depth.storeOp = toStore(desc.depth.store);
        depth.clearValue.depthStencil = {desc.depth.clearDepth, desc.depth.clearStencil};
        if (depthResolveTex) {
            depth.resolveMode = VK_RESOLVE_MODE_SAMPLE_ZERO_BIT;  // see DepthAttachment in Device.h
            depth.resolveImageView =
                dev_.attachmentView(*depthResolveTex, desc.depth.resolveSubresource.mipLevel,
                                    desc.depth.resolveSubresource.layer);
            depth.resolveImageLayout = VK_IMAGE_LAYOUT_GENERAL;
        }
        if (gdi::formatInfo(depthTex->desc.format).hasDepth)
            ri.pDepthAttachment = &depth;  // S8: stencil only
        if (gdi::formatInfo(depthTex->desc.format).hasStencil) {
            stencil = depth;
            stencil.resolveMode =
                depthResolveTex ? VK_RESOLVE_MODE_SAMPLE_ZERO_BIT : VK_RESOLVE_MODE_NONE;
            ri.pStencilAttachment = &stencil;
        }
    }
    ri.renderArea = {{0, 0}, {renderArea_.width, renderArea_.height}};
    ri.layerCount = 1;
    ri.colorAttachmentCount = uint32_t(colors.size());
    ri.pColorAttachments = colors.data();
    if (desc.debugName) pushDebugGroup(desc.debugName);
    if (desc.secondaryLists) {  // kept to resume the instance around each executeSecondary
        passInstance_.colors = std::move(colors);
        passInstance_.depth = depth;
        passInstance_.stencil = stencil;
        passInstance_.info = ri;
        passInstance_.info.pColorAttachments = passInstance_.colors.data();
        if (ri.pDepthAttachment) passInstance_.info.pDepthAttachment = &passInstance_.depth;
        if (ri.pStencilAttachment) passInstance_.info.pStencilAttachment = &passInstance_.stencil;
        passInstance_.begin(cb_, VK_RENDERING_SUSPENDING_BIT);
    } else {
        vkCmdBeginRendering(cb_, &ri);
    }
    inPass_ = true;
    dynamicSet_ = 0;      // each pass starts from its pipelines' values
    pipeline_ = nullptr;  // a render pass starts with no pipeline, as on GL (see Device.h)
    eagerSlots_ = {};     // nor a layout to push with
    computeBound_ = false;
    updateReadyToDraw();
    passHasLabel_ = desc.debugName != nullptr;
    secondaryPass_ = desc.secondaryLists;  // the primary draws between the executed lists
    setViewport({0, 0, float(renderArea_.width), float(renderArea_.height), 0, 1});
    setScissor(renderArea_);
}

void VulkanCommandList::PassInstance::begin(VkCommandBuffer cb, VkRenderingFlags flags) {
    info.flags = flags;
    vkCmdBeginRendering(cb, &info);
}

void VulkanCommandList::endRenderPass() {
    checkDevice("endRenderPass");
    if (secondary_) gdi::validate::notInSecondary("endRenderPass");
    if (!inPass_) throw gdi::Error("endRenderPass without beginRenderPass");
    queries_.endPass();
    vkCmdEndRendering(cb_);
    if (secondaryPass_) {  // the last instance of the chain: it stores and resolves
        passInstance_.begin(cb_, VK_RENDERING_RESUMING_BIT);
        vkCmdEndRendering(cb_);
    }
    inPass_ = false;
    endPassFeedback();
    setNotReady();
    written_ = true;
    if (secondaryPass_) {  // vkCmdExecuteCommands left the primary's state undefined
        secondaryPass_ = false;
        unbindAll();
    }
    if (passHasLabel_) popDebugGroup();
}

void VulkanCommandList::beginPassFeedback(const gdi::RenderPassDesc& desc) {
    uint64_t textures = 0;
    for (uint32_t slot = 0; slot < 64; ++slot)
        if (holdsTexture(bindings_[slot].kind)) textures |= uint64_t(1) << slot;
    auto spanOf = [&](gdi::TextureHandle h) {
        const Texture& t = dev_.texture(h);
        return gdi::validate::bindingSpanOf(h.id, t, t.name);
    };
    if (feedback_.beginPass(desc, spanOf, textures)) refreshFeedback();
}

void VulkanCommandList::refreshFeedback() {
    const bool writesDepth = pipeline_ && pipeline_->writesDepthStencil;
    for (uint64_t m = feedback_.reaching(); m; m &= m - 1) {
        Binding& b = bindings_[std::countr_zero(m)];
        if (!holdsTexture(b.kind)) continue;  // a buffer replaced the texture
        b.kind = feedback_.refused(uint32_t(std::countr_zero(m)), writesDepth)
                     ? b.kind | kFeedback
                     : b.kind & ~kFeedback;
    }
    dirtySlots_ |= feedback_.reaching();
}

void VulkanCommandList::endPassFeedback() {
    for (uint64_t m = feedback_.endPass(); m; m &= m - 1)
        if (Binding& b = bindings_[std::countr_zero(m)]; holdsTexture(b.kind)) b.kind &= ~kFeedback;
}

void VulkanCommandList::unbindAll() {
    pipeline_ = nullptr;
    writesFor_ = 0;
    eagerSlots_ = {};
    computeBound_ = false;
    setNotReady();
    requiredSlots_ = 0;
    vertexInputs_.clear();
    vertexInputs_.setPipeline(nullptr, nullptr);
    for (Binding& b : bindings_) b.kind = kUnbound;
    dirtySlots_ = ~uint64_t(0);
}

// A call that an ended secondary list refuses.
void VulkanCommandList::restrictedCall(const char* what) const {
    if (orphaned_) gdi::validate::listOfDestroyedDevice(what);
    gdi::validate::afterEndSecondary(what);
}

void VulkanCommandList::beginSecondary(const gdi::RenderPassDesc& desc) {
    gdi::validate::queueAllows(queue_, gdi::QueueKind::Graphics, "beginSecondary");
    checkDevice("beginSecondary");
    if (ended_) {  // recorded anew: primaries that executed the old recording keep it
        lease_.reset();
        clearRecording();
    }
    bool bound = false;
    for (const Binding& b : bindings_) bound |= b.kind != kUnbound;
    if (recording_ || secondary_ || inPass_ || bound) gdi::validate::secondaryNotEmpty();
    signature_ = checkPass(desc, nullptr);
    beginPassFeedback(desc);  // no texture is bound yet: checks the attachments
    lease_ = std::make_shared<SharedSecondary>(dev_, dev_.acquireSecondary());
    std::array<VkFormat, 8> formats{};
    for (uint32_t i = 0; i < signature_.colorCount; ++i)
        formats[i] = toVkFormat(signature_.colors[i]);
    VkCommandBufferInheritanceRenderingInfo ir{
        VK_STRUCTURE_TYPE_COMMAND_BUFFER_INHERITANCE_RENDERING_INFO};
    ir.colorAttachmentCount = signature_.colorCount;
    ir.pColorAttachmentFormats = formats.data();
    if (signature_.depth != gdi::Format::Undefined) {
        const VkFormat f = toVkFormat(signature_.depth);
        if (gdi::formatInfo(signature_.depth).hasDepth) ir.depthAttachmentFormat = f;
        if (gdi::formatInfo(signature_.depth).hasStencil) ir.stencilAttachmentFormat = f;
    }
    ir.rasterizationSamples = VkSampleCountFlagBits(signature_.samples);
    ir.flags = VK_RENDERING_RESUMING_BIT | VK_RENDERING_SUSPENDING_BIT;  // executeSecondary's
    VkCommandBufferInheritanceInfo ii{VK_STRUCTURE_TYPE_COMMAND_BUFFER_INHERITANCE_INFO};
    ii.pNext = &ir;
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    // Executed any number of times, also while an earlier execution is pending.
    bi.flags = VK_COMMAND_BUFFER_USAGE_SIMULTANEOUS_USE_BIT |
               VK_COMMAND_BUFFER_USAGE_RENDER_PASS_CONTINUE_BIT;
    bi.pInheritanceInfo = &ii;
    if (VkResult r =
            nativeAllocation("vkBeginCommandBuffer",
                             [&] { return vkBeginCommandBuffer(lease_->recording.cb, &bi); });
        r != VK_SUCCESS) {
        lease_.reset();
        check(r, "vkBeginCommandBuffer");
    }
    cb_ = lease_->recording.cb;
    openRecording();
    recording_ = secondary_ = inPass_ = true;
    dynamicSet_ = 0;
    renderArea_ = gdi::validate::renderArea(signature_);
    passSamples_ = signature_.samples;
    passHasLabel_ = false;
    written_ = false;  // barriers are the primary's business
    unbindAll();
    constants_ = {};
    setViewport({0, 0, float(renderArea_.width), float(renderArea_.height), 0, 1});
    setScissor(renderArea_);
}

// An unsubmitted command buffer is left as it is: the next recording resets its pool.
void VulkanCommandList::reset() {
    checkDevice("reset");
    lease_.reset();
    executed_.clear();  // never submitted here: the secondaries' fences stay as they were
    clearRecording();
}

void VulkanCommandList::endSecondary() {
    checkDevice("endSecondary");
    if (!secondary_ || ended_) throw gdi::Error("endSecondary without beginSecondary");
    if (debugDepth_ != 0)
        throw gdi::Error("endSecondary: " + std::to_string(debugDepth_) +
                         " debug group(s) not popped");
    check(nativeAllocation("vkEndCommandBuffer", [&] { return vkEndCommandBuffer(cb_); }),
          "vkEndCommandBuffer");
    ended_ = restricted_ = true;
    endPassFeedback();
    setNotReady();
}

void VulkanCommandList::executeSecondary(std::span<gdi::CommandList* const> lists) {
    checkDevice("executeSecondary");
    const auto parts =
        gdi::validate::executedLists(lists, this, [&](const VulkanCommandList& l, size_t i) {
            if (&l.dev_ != &dev_) gdi::validate::secondaryOfAnotherDevice(i);
            gdi::validate::executedSecondary(inPass_ && secondaryPass_, l.secondary_, l.ended_,
                                             l.signature_, signature_, i);
        });
    std::vector<VkCommandBuffer> cbs;
    for (VulkanCommandList* l : parts) {  // shared, not taken: the list may run again
        cbs.push_back(l->lease_->recording.cb);
        executed_.push_back(l->lease_);
        used_.insert(used_.end(), l->used_.begin(), l->used_.end());
        lastBuffer_ = 0;
        if (l->destroyEpoch_ < destroyEpoch_) {  // this recording now holds back what that one did
            dev_.openRecording(l->destroyEpoch_);
            closeRecording();
            openSince_ = destroyEpoch_ = l->destroyEpoch_;
        }
    }
    if (cbs.empty()) return;
    // The primary's instance is suspended; the lists run in one of their own, then the
    // primary's resumes (Vulkan: one instance holds either inline commands or secondaries).
    vkCmdEndRendering(cb_);
    passInstance_.begin(cb_, VK_RENDERING_RESUMING_BIT | VK_RENDERING_SUSPENDING_BIT |
                                 VK_RENDERING_CONTENTS_SECONDARY_COMMAND_BUFFERS_BIT);
    vkCmdExecuteCommands(cb_, uint32_t(cbs.size()), cbs.data());
    vkCmdEndRendering(cb_);
    passInstance_.begin(cb_, VK_RENDERING_RESUMING_BIT | VK_RENDERING_SUSPENDING_BIT);
    // vkCmdExecuteCommands left the primary's state undefined: pipeline and bindings unset,
    // dynamic state from the next pipeline, viewport and scissor the render area (as on GL).
    unbindAll();
    pipeline_ = nullptr;
    dynamicSet_ = 0;
    updateReadyToDraw();
    setViewport({0, 0, float(renderArea_.width), float(renderArea_.height), 0, 1});
    setScissor(renderArea_);
}

// The state of a list with nothing recorded (after submit, or after its secondary recording
// was executed).
void VulkanCommandList::clearRecording() {
    closeRecording();
    used_.clear();
    lastBuffer_ = 0;
    lastBound_ = {};
    destroyEpoch_ = dev_.destroyEpoch();
    recording_ = secondary_ = ended_ = restricted_ = secondaryPass_ = false;
    inPass_ = false;
    feedback_.clear();
    unbindAll();
    constants_ = {};
    queries_.clear();
    debugDepth_ = 0;
    automaticBarriers_ = true;
}

void VulkanCommandList::setPipeline(gdi::PipelineHandle h) {
    ensureRecording("setPipeline");
    checkUnrestricted("setPipeline");
    Pipeline& p = usedPipeline(h);
    if (inPass_ && p.bindPoint == VK_PIPELINE_BIND_POINT_GRAPHICS)
        gdi::validate::pipelineFitsPass(p.signature, signature_, p.name.c_str());
    vkCmdBindPipeline(cb_, p.bindPoint, p.pipeline);
    if (p.bindPoint == VK_PIPELINE_BIND_POINT_GRAPHICS) {  // the pipeline's, unless set in the pass
        if (!(dynamicSet_ & kBlendConstantSet)) vkCmdSetBlendConstants(cb_, p.blendConstant.data());
        if (!(dynamicSet_ & kStencilReferenceSet))
            vkCmdSetStencilReference(cb_, VK_STENCIL_FACE_FRONT_AND_BACK, p.stencilReference);
        if (!(dynamicSet_ & kDepthBiasSet))
            vkCmdSetDepthBias(cb_, p.depthBias[0], p.depthBias[2], p.depthBias[1]);
    }
    if (!pipeline_ || pipeline_->layout != p.layout) dirtySlots_ = ~uint64_t(0);
    // The list's constants, whatever the previous pipeline was (a list's values outlive it).
    if (p.constantBytes)
        vkCmdPushConstants(cb_, p.layout, p.constantStages, 0, p.constantBytes, constants_.data());
    pipeline_ = &p;
    requiredSlots_ = p.requiredSlots;
    layout_ = p.layout;
    if (feedback_.reaching()) [[unlikely]]
        refreshFeedback();  // read-only depth depends on the pipeline
    computeBound_ = p.bindPoint == VK_PIPELINE_BIND_POINT_COMPUTE;
    vertexInputs_.setPipeline(computeBound_ ? nullptr : &p.vertexBindings, &p.name);
    updateReadyToDraw();
    // By handle id, not address: a destroyed pipeline's slot (same address) may hold a new one.
    if (writesFor_ !=
        h.id) {  // writes_[slot] = the pipeline's write for slot, pointing at bindings_[slot]
        for (uint64_t m = p.requiredSlots; m; m &= m - 1) {
            const uint32_t slot = uint32_t(std::countr_zero(m));
            writes_[slot] = p.writeTemplates[slot];
            expectedKinds_[slot] =
                kindCode(p.writeTemplates[slot].descriptorType, p.slotDimensions[slot]);
            writes_[slot].pBufferInfo =
                &bindings_[slot].buffer;  // the one the type does not use is ignored
            writes_[slot].pImageInfo = &bindings_[slot].image;
        }
        writesFor_ = h.id;
    }
    eagerSlots_ = p.bufferSlots;
    bindPoint_ = p.bindPoint;
}

void VulkanCommandList::setViewport(const gdi::Viewport& v) {
    ensureRecording("setViewport");
    checkUnrestricted("setViewport");
    if (!inPass_) [[unlikely]]
        gdi::validate::stateOutsidePass("setViewport");
    gdi::validate::viewport(v, viewportLimits_);
    VkViewport vp{v.x, v.y, v.width, v.height, v.minDepth, v.maxDepth};
    vkCmdSetViewport(cb_, 0, 1, &vp);
}

// Kept in the list (setPipeline pushes them for the next pipeline) and pushed at once for the
// bound one, up to the size of its block.
void VulkanCommandList::setConstants(uint32_t offset, gdi::ByteSpan data) {
    gdi::validate::constantsRange(offset, data.size());
    ensureRecording("setConstants");
    checkUnrestricted("setConstants");
    std::memcpy(constants_.data() + offset, data.data(), data.size());
    if (pipeline_ && offset < pipeline_->constantBytes)
        vkCmdPushConstants(cb_, layout_, pipeline_->constantStages, offset,
                           std::min(uint32_t(data.size()), pipeline_->constantBytes - offset),
                           data.data());
}

void VulkanCommandList::setBlendConstant(const std::array<float, 4>& rgba) {
    ensureRecording("setBlendConstant");
    checkUnrestricted("setBlendConstant");
    if (!inPass_) [[unlikely]]
        gdi::validate::stateOutsidePass("setBlendConstant");
    gdi::validate::blendConstant(rgba.data(), "setBlendConstant");
    vkCmdSetBlendConstants(cb_, rgba.data());
    dynamicSet_ |= kBlendConstantSet;
}

void VulkanCommandList::setStencilReference(uint8_t reference) {
    ensureRecording("setStencilReference");
    checkUnrestricted("setStencilReference");
    if (!inPass_) [[unlikely]]
        gdi::validate::stateOutsidePass("setStencilReference");
    vkCmdSetStencilReference(cb_, VK_STENCIL_FACE_FRONT_AND_BACK, reference);
    dynamicSet_ |= kStencilReferenceSet;
}

void VulkanCommandList::setDepthBias(float constant, float slope, float clamp) {
    ensureRecording("setDepthBias");
    checkUnrestricted("setDepthBias");
    if (!inPass_) [[unlikely]]
        gdi::validate::stateOutsidePass("setDepthBias");
    gdi::validate::depthBias(constant, slope, clamp, dev_.info().features);
    vkCmdSetDepthBias(cb_, constant, clamp, slope);
    dynamicSet_ |= kDepthBiasSet;
}

void VulkanCommandList::setScissor(const gdi::Rect& r) {
    ensureRecording("setScissor");
    checkUnrestricted("setScissor");
    if (!inPass_) [[unlikely]]
        gdi::validate::stateOutsidePass("setScissor");
    const gdi::Rect c = gdi::validate::scissor(r);
    VkRect2D rect{{c.x, c.y}, {c.width, c.height}};
    vkCmdSetScissor(cb_, 0, 1, &rect);
}

void VulkanCommandList::setVertexBuffer(uint32_t index, gdi::BufferHandle h, uint64_t offset) {
    ensureRecording("setVertexBuffer");
    checkUnrestricted("setVertexBuffer");
    Buffer& b = usedBuffer(h);
    vertexInputs_.setVertexBuffer(index, b.desc, b.name, offset);
    updateReadyToDraw();
    VkDeviceSize off = offset;
    vkCmdBindVertexBuffers(cb_, index, 1, &b.buffer, &off);
}

void VulkanCommandList::setIndexBuffer(gdi::BufferHandle h, gdi::IndexType type, uint64_t offset) {
    ensureRecording("setIndexBuffer");
    checkUnrestricted("setIndexBuffer");
    Buffer& b = usedBuffer(h);
    vertexInputs_.setIndexBuffer(b.desc, b.name, type, offset);
    vkCmdBindIndexBuffer(cb_, b.buffer, offset,
                         type == gdi::IndexType::U16 ? VK_INDEX_TYPE_UINT16 : VK_INDEX_TYPE_UINT32);
}

// The setters below are the per-object path: the fast path is a leaf (no call, no saved
// registers) that takes the arguments as they are when all of them are plainly valid; the
// checked path handles the rest and owns every error message.
template <VkDescriptorType kType>
inline void VulkanCommandList::setBuffer(uint32_t slot, gdi::BufferHandle h, uint64_t offset,
                                         uint64_t size) {
    // The per-object case binds one buffer at many offsets: the buffer the checked path passed
    // last, with nothing destroyed since, is still alive and of the usage checked then, so only
    // the range is checked here (no handle lookup). Anything else goes to the checked path, which
    // notes the buffer for submit's liveness check; this one stays a leaf.
    constexpr size_t kind = kType == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER ? 0 : 1;
    const BoundBuffer& last = lastBound_[kind];
    if (h.id != last.id || last.destroyEpoch != dev_.destroyEpoch()) [[unlikely]]
        return setBufferChecked<kType>(slot, h, offset, size);
    const gdi::validate::BindingLimits& limits = kind == 0 ? uniformLimits_ : storageLimits_;
    const uint64_t bindSize =
        gdi::validate::plainBindingSize(slot, last.size, offset, size, limits);
    if (!bindSize) [[unlikely]]
        return setBufferChecked<kType>(slot, h, offset, size);
    if (eagerSlots_[kind] >> slot & 1) {  // the pipeline takes this kind here: push it now
        bindings_[slot].kind = kType;
        bindings_[slot].buffer = {last.buffer, offset, bindSize};
        if (validating_) [[unlikely]]
            return pushValidatedSlot(slot);
        return pushDescriptorSet_(cb_, bindPoint_, layout_, 0, 1, &writes_[slot]);
    }
    bindBuffer(slot, kType, last.buffer, offset, bindSize);
}

template <VkDescriptorType kType>
void VulkanCommandList::setBufferChecked(uint32_t slot, gdi::BufferHandle h, uint64_t offset,
                                         uint64_t size) {
    const char* what =
        kType == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER ? "setUniformBuffer" : "setStorageBuffer";
    checkDevice(what);
    if (slot >= 64) slotOutOfRange(what, slot);
    const uint64_t epoch =
        dev_.destroyEpoch();  // before the lookup: a destroy after it invalidates
    Buffer& b = usedBuffer(h);
    const bool uniform = kType == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    gdi::validate::bufferUsage(
        b.desc, uniform ? gdi::BufferUsage::Uniform : gdi::BufferUsage::Storage, b.name, what);
    const gdi::validate::BindingLimits& limits = uniform ? uniformLimits_ : storageLimits_;
    if (size == 0) size = std::min(b.desc.size - std::min(offset, b.desc.size), limits.maxRange);
    gdi::validate::bindingRange(b.desc, offset, size, what);
    gdi::validate::bindingLimits(offset, size, limits, what);
    lastBound_[uniform ? 0 : 1] = {
        .id = h.id, .destroyEpoch = epoch, .buffer = b.buffer, .size = b.desc.size};
    bindBuffer(slot, kType, b.buffer, offset, size);
}

void VulkanCommandList::setUniformBuffer(uint32_t slot, gdi::BufferHandle h, uint64_t offset,
                                         uint64_t size) {
    setBuffer<VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER>(slot, h, offset, size);
}

void VulkanCommandList::setStorageBuffer(uint32_t slot, gdi::BufferHandle h, uint64_t offset,
                                         uint64_t size) {
    setBuffer<VK_DESCRIPTOR_TYPE_STORAGE_BUFFER>(slot, h, offset, size);
}

void VulkanCommandList::setTexture(uint32_t slot, gdi::TextureHandle th, gdi::SamplerHandle sh) {
    checkDevice("setTexture");
    if (slot >= 64) throw gdi::Error("setTexture: slot " + std::to_string(slot) + " out of range");
    Texture& t = usedTexture(th);
    Sampler& s = usedSampler(sh);
    if (!any(t.desc.usage, gdi::TextureUsage::Sampled))
        throw gdi::Error("setTexture: texture '" + t.name + "' lacks Sampled usage");
    if (s.filtersLinearly && !t.linearFilter)
        gdi::validate::notFilterable(t.name, t.desc.format, s.name);
    bindings_[slot] = {kindCode(VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                t.desc.sampleCount > 1 ? gdi::kTexture2DMultisampleKind
                                                       : uint8_t(1 + uint8_t(t.desc.dimension))),
                       {},
                       {s.sampler, t.view, VK_IMAGE_LAYOUT_GENERAL}};
    const auto span = gdi::validate::bindingSpanOf(th.id, t, t.name,
                                                   s.readsMips ? std::nullopt : std::optional(0u));
    if (feedback_.bind(slot, span, false)) refreshFeedback();
    dirtySlots_ |= uint64_t(1) << slot;
}

void VulkanCommandList::setStorageTexture(uint32_t slot, gdi::TextureHandle th, uint32_t mip) {
    checkDevice("setStorageTexture");
    if (slot >= 64)
        throw gdi::Error("setStorageTexture: slot " + std::to_string(slot) + " out of range");
    Texture& t = usedTexture(th);
    if (!any(t.desc.usage, gdi::TextureUsage::Storage))
        throw gdi::Error("setStorageTexture: texture '" + t.name + "' lacks Storage usage");
    if (mip >= t.desc.mipLevels) throw gdi::Error("setStorageTexture: mip level out of range");
    bindings_[slot] = {
        kindCode(VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, uint8_t(1 + uint8_t(t.desc.dimension))),
        {},
        {VK_NULL_HANDLE, t.mipViews[mip], VK_IMAGE_LAYOUT_GENERAL}};
    if (feedback_.bind(slot, gdi::validate::bindingSpanOf(th.id, t, t.name, mip), true))
        refreshFeedback();
    dirtySlots_ |= uint64_t(1) << slot;
}

void VulkanCommandList::notReadyToDraw(const char* what) const {
    checkUnrestricted(what);
    if (!inPass_) fail((std::string(what) + " outside a render pass").c_str());
    if (!pipeline_)
        fail((std::string(what) + " without a pipeline (call setPipeline first)").c_str());
    if (computeBound_)
        wrongPipelineKind((std::string(what) + " with compute").c_str(), pipeline_->name);
    vertexInputs_.notReady(what);
}

// Unbound required slots first (the likelier mistake), then a slot bound with the wrong kind.
void VulkanCommandList::badBindings() const {
    for (uint64_t m = requiredSlots_; m; m &= m - 1) {
        const uint32_t slot = uint32_t(std::countr_zero(m));
        if (holdsTexture(bindings_[slot].kind) && (bindings_[slot].kind & kFeedback))
            feedback_.check(slot, pipeline_->writesDepthStencil, pipeline_->name.c_str());
    }
    uint64_t missing = 0;
    for (uint64_t m = requiredSlots_; m; m &= m - 1)
        if (bindings_[std::countr_zero(m)].kind == kUnbound) missing |= m & -m;
    gdi::validate::missingBindings(requiredSlots_, ~missing, pipeline_->name.c_str());
    for (uint64_t m = requiredSlots_; m; m &= m - 1) {
        const uint32_t slot = uint32_t(std::countr_zero(m));
        const uint32_t bound = bindings_[slot].kind, expected = expectedKinds_[slot];
        if ((bound & 0xFFFFFFu) != (expected & 0xFFFFFFu))
            gdi::validate::wrongBindingKindFailed(
                slot, kindOf(VkDescriptorType(expected & 0xFFFFFFu)),
                kindOf(VkDescriptorType(bound & 0xFFFFFFu)), pipeline_->name.c_str());
        if (!slotAcceptable(slot))
            gdi::validate::wrongTextureDimensionFailed(
                slot, uint8_t(expected >> 24), uint8_t(bound >> 24), pipeline_->name.c_str());
    }
    fail("internal: badBindings found nothing wrong");
}

// Pushes the slots in push (dirty and used by the pipeline) after checking them. The common
// per-object case, one changed slot, pushes its prepared write in place; several are gathered.
// Required slots outside push were checked when they were last pushed and have not changed.
// Validation mode: each buffer a draw or dispatch is about to use covers the block its pipeline
// declares there (a warning where not: validate::rangeCoversBlock).
void VulkanCommandList::checkRanges(uint64_t slots) const {
    for (uint64_t m = slots; m; m &= m - 1) {
        const uint32_t slot = uint32_t(std::countr_zero(m));
        const uint32_t kind = bindings_[slot].kind;
        if (kind == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER || kind == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER)
            gdi::validate::rangeCoversBlock(slot, bindings_[slot].buffer.range,
                                            pipeline_->slotBlockBytes[slot], pipeline_->name);
    }
}

inline void VulkanCommandList::pushDirty(uint64_t push, VkPipelineBindPoint bindPoint) {
    if (validating_) [[unlikely]]
        checkRanges(push);
    if (push & (push - 1)) [[unlikely]]
        return pushGathered(push);
    const uint32_t slot = uint32_t(std::countr_zero(push));
    if (!slotMatches(slot)) [[unlikely]]
        checkSlots(push);
    dirtySlots_ &= ~push;
    pushDescriptorSet_(cb_, bindPoint, layout_, 0, 1, &writes_[slot]);
}

// Validation mode's eager push: the slot stays dirty, so the draw that uses it checks its range
// against the block (a range rebound before any draw is no mistake) and pushes it again.
void VulkanCommandList::pushValidatedSlot(uint32_t slot) {
    dirtySlots_ |= uint64_t(1) << slot;
    pushDescriptorSet_(cb_, bindPoint_, layout_, 0, 1, &writes_[slot]);
}

void VulkanCommandList::pushGathered(uint64_t push) {
    for (uint64_t m = push; m; m &= m - 1) {
        const uint32_t slot = uint32_t(std::countr_zero(m));
        if (!slotMatches(slot)) [[unlikely]]
            checkSlots(uint64_t(1) << slot);
    }
    dirtySlots_ &= ~push;
    VkWriteDescriptorSet gathered[64];
    uint32_t n = 0;
    for (; push; push &= push - 1) gathered[n++] = writes_[std::countr_zero(push)];
    pushDescriptorSet_(cb_, pipeline_->bindPoint, layout_, 0, n, gathered);
}

// Draws: one state check (render pass open, graphics pipeline bound), then only the slots
// that changed since the last draw are checked and pushed.
void VulkanCommandList::drawRefused(uint32_t vertexCount, uint32_t instanceCount,
                                    uint32_t firstVertex, uint32_t firstInstance) const {
    if (!readyToDraw_) notReadyToDraw("draw");
    vertexInputs_.draw(vertexCount, instanceCount, firstVertex, firstInstance);
    fail("internal: drawRefused found nothing wrong");
}

// One comparison covers the draw state and the vertices (drawVertexLimit_), one the instances.
void VulkanCommandList::draw(uint32_t vertexCount, uint32_t instanceCount, uint32_t firstVertex,
                             uint32_t firstInstance) {
    if (int64_t(firstVertex) + vertexCount > drawVertexLimit_ ||
        uint64_t(firstInstance) + instanceCount > vertexInputs_.instanceCapacity()) [[unlikely]]
        drawRefused(vertexCount, instanceCount, firstVertex, firstInstance);
    if (dirtySlots_ & requiredSlots_) [[unlikely]]  // the draw stays a leaf without
        return drawPushing(vertexCount, instanceCount, firstVertex, firstInstance);
    vkCmdDraw(cb_, vertexCount, instanceCount, firstVertex, firstInstance);
}
void VulkanCommandList::drawPushing(uint32_t vertexCount, uint32_t instanceCount,
                                    uint32_t firstVertex, uint32_t firstInstance) {
    // Parked in members across the push: cheaper than keeping four arguments in saved registers.
    draw_ = {vertexCount, instanceCount, firstVertex, firstInstance};
    pushDirty(dirtySlots_ & requiredSlots_, VK_PIPELINE_BIND_POINT_GRAPHICS);
    vkCmdDraw(cb_, draw_[0], draw_[1], draw_[2], draw_[3]);
}

void VulkanCommandList::drawIndexed(uint32_t indexCount, uint32_t instanceCount,
                                    uint32_t firstIndex, int32_t baseVertex,
                                    uint32_t firstInstance) {
    if (!readyToDraw_) [[unlikely]]
        notReadyToDraw("drawIndexed");
    vertexInputs_.drawIndexed(indexCount, instanceCount, firstIndex, firstInstance);
    if (const uint64_t push = dirtySlots_ & requiredSlots_)
        pushDirty(push, VK_PIPELINE_BIND_POINT_GRAPHICS);
    vkCmdDrawIndexed(cb_, indexCount, instanceCount, firstIndex, baseVertex, firstInstance);
}

// Indirect draws: the buffer checks of validate::indirect, then the same binding push as draw().
const Buffer& VulkanCommandList::indirectArgs(gdi::BufferHandle h, uint64_t offset,
                                              uint32_t drawCount, uint32_t stride,
                                              uint32_t recordSize, const char* what) {
    if (!readyToDraw_) [[unlikely]]
        notReadyToDraw(what);
    const Buffer& b = usedBuffer(h);
    gdi::validate::indirect(b.desc, b.name, offset, drawCount, stride, recordSize,
                            dev_.info().features, what);
    if (const uint64_t push = dirtySlots_ & requiredSlots_)
        pushDirty(push, VK_PIPELINE_BIND_POINT_GRAPHICS);
    return b;
}

const Buffer& VulkanCommandList::countBuffer(gdi::BufferHandle h, uint64_t offset,
                                             const char* what) {
    checkDevice(what);
    if (!dev_.info().features.drawIndirectCount)
        throw gdi::Error(std::string(what) +
                         ": not supported on this device (DeviceFeatures::drawIndirectCount)");
    const Buffer& b = usedBuffer(h);
    gdi::validate::indirect(b.desc, b.name, offset, 1, 4, 4, dev_.info().features, what);
    return b;
}

void VulkanCommandList::drawIndirect(gdi::BufferHandle args, uint64_t offset, uint32_t drawCount,
                                     uint32_t stride) {
    const Buffer& b = indirectArgs(args, offset, drawCount, stride, sizeof(gdi::DrawIndirectArgs),
                                   "drawIndirect");
    vkCmdDrawIndirect(cb_, b.buffer, offset, drawCount, stride);
}

// GL reads indexed records relative to the element buffer's start, so gdi asks for offset 0 on
// every backend (the records' firstIndex does the offsetting).
void VulkanCommandList::indexedIndirect(const char* what) const {
    checkDevice(what);
    vertexInputs_.indexedIndirect(what);
}

void VulkanCommandList::drawIndexedIndirect(gdi::BufferHandle args, uint64_t offset,
                                            uint32_t drawCount, uint32_t stride) {
    indexedIndirect("drawIndexedIndirect");
    const Buffer& b = indirectArgs(args, offset, drawCount, stride,
                                   sizeof(gdi::DrawIndexedIndirectArgs), "drawIndexedIndirect");
    vkCmdDrawIndexedIndirect(cb_, b.buffer, offset, drawCount, stride);
}

void VulkanCommandList::drawIndirectCount(gdi::BufferHandle args, uint64_t offset,
                                          gdi::BufferHandle count, uint64_t countOffset,
                                          uint32_t maxDrawCount, uint32_t stride) {
    const Buffer& c = countBuffer(count, countOffset, "drawIndirectCount");
    const Buffer& b = indirectArgs(args, offset, maxDrawCount, stride,
                                   sizeof(gdi::DrawIndirectArgs), "drawIndirectCount");
    dev_.cmdDrawIndirectCount(cb_, b.buffer, offset, c.buffer, countOffset, maxDrawCount, stride);
}

void VulkanCommandList::drawIndexedIndirectCount(gdi::BufferHandle args, uint64_t offset,
                                                 gdi::BufferHandle count, uint64_t countOffset,
                                                 uint32_t maxDrawCount, uint32_t stride) {
    indexedIndirect("drawIndexedIndirectCount");
    const Buffer& c = countBuffer(count, countOffset, "drawIndexedIndirectCount");
    const Buffer& b =
        indirectArgs(args, offset, maxDrawCount, stride, sizeof(gdi::DrawIndexedIndirectArgs),
                     "drawIndexedIndirectCount");
    dev_.cmdDrawIndexedIndirectCount(cb_, b.buffer, offset, c.buffer, countOffset, maxDrawCount,
                                     stride);
}

void VulkanCommandList::dispatchIndirect(gdi::BufferHandle args, uint64_t offset) {
    gdi::validate::queueAllows(queue_, gdi::QueueKind::Compute, "dispatchIndirect");
    outsidePass("dispatchIndirect");
    if (!pipeline_) fail("dispatchIndirect without a pipeline (call setPipeline first)");
    if (pipeline_->bindPoint != VK_PIPELINE_BIND_POINT_COMPUTE)
        throw gdi::Error("dispatchIndirect with graphics pipeline '" + pipeline_->name + "'");
    const Buffer& b = usedBuffer(args);
    gdi::validate::indirect(b.desc, b.name, offset, 1, sizeof(gdi::DispatchIndirectArgs),
                            sizeof(gdi::DispatchIndirectArgs), dev_.info().features,
                            "dispatchIndirect");
    if (const uint64_t push = dirtySlots_ & requiredSlots_)
        pushDirty(push, VK_PIPELINE_BIND_POINT_COMPUTE);
    barrierIfWritten();
    vkCmdDispatchIndirect(cb_, b.buffer, offset);
    written_ = true;
}

void VulkanCommandList::dispatch(uint32_t x, uint32_t y, uint32_t z) {
    gdi::validate::queueAllows(queue_, gdi::QueueKind::Compute, "dispatch");
    outsidePass("dispatch");
    if (pipeline_ && pipeline_->bindPoint != VK_PIPELINE_BIND_POINT_COMPUTE)
        throw gdi::Error("dispatch with graphics pipeline '" + pipeline_->name + "'");
    if (!pipeline_) fail("dispatch without a pipeline (call setPipeline first)");
    gdi::validate::dispatchSize(x, y, z, dev_.info().limits);
    if (const uint64_t push = dirtySlots_ & requiredSlots_)
        pushDirty(push, VK_PIPELINE_BIND_POINT_COMPUTE);
    barrierIfWritten();
    vkCmdDispatch(cb_, x, y, z);
    written_ = true;
}

void VulkanCommandList::copyBuffer(gdi::BufferHandle dst, uint64_t dstOffset, gdi::BufferHandle src,
                                   uint64_t srcOffset, uint64_t size) {
    outsidePass("copyBuffer");
    Buffer& d = usedBuffer(dst);
    Buffer& s = usedBuffer(src);
    gdi::validate::bufferCopy(d.desc, d.name, dstOffset, s.desc, s.name, srcOffset, size, &d == &s);
    if (size == 0) return;
    barrierIfWritten();
    VkBufferCopy r{srcOffset, dstOffset, size};
    vkCmdCopyBuffer(cb_, s.buffer, d.buffer, 1, &r);
    written_ = true;
    if (d.desc.access == gdi::MemoryAccess::Readback) hostReadable(d);
}

void VulkanCommandList::clearBuffer(gdi::BufferHandle h, uint64_t offset, uint64_t size,
                                    uint32_t value) {
    outsidePass("clearBuffer");
    Buffer& b = usedBuffer(h);
    const uint64_t bytes = gdi::validate::clearRange(b.desc, b.name, offset, size);
    if (bytes == 0) return;
    barrierIfWritten();
    vkCmdFillBuffer(cb_, b.buffer, offset, bytes, value);
    written_ = true;
    if (b.desc.access == gdi::MemoryAccess::Readback) hostReadable(b);
}

void VulkanCommandList::insertDebugLabel(const char* name) {
    ensureRecording("insertDebugLabel");
    checkUnrestricted("insertDebugLabel");
    if (!dev_.cmdInsertLabel) return;
    VkDebugUtilsLabelEXT l{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
    l.pLabelName = name ? name : "";
    dev_.cmdInsertLabel(cb_, &l);
}

void VulkanCommandList::copyTexture(gdi::TextureHandle dst, gdi::TextureHandle src, uint32_t mip) {
    outsidePass("copyTexture");
    Texture& d = copiedTexture(dst);
    Texture& s = copiedTexture(src);
    gdi::validate::wholeTextureCopy(d.desc, d.name, s.desc, s.name, mip);
    barrierIfWritten();
    const gdi::validate::Extent3 e = gdi::validate::mipExtent(d.desc, mip);
    const bool is3D = d.desc.dimension == gdi::TextureDimension::Texture3D;
    VkImageCopy r{};
    r.srcSubresource = r.dstSubresource = {aspectOf(d.desc.format), mip, 0, arrayLayers(d.desc)};
    r.extent = {e.width, e.height, is3D ? e.depthOrLayers : 1};
    vkCmdCopyImage(cb_, s.image, VK_IMAGE_LAYOUT_GENERAL, d.image, VK_IMAGE_LAYOUT_GENERAL, 1, &r);
    written_ = true;
}

// One whole subresource (checked by the shared rules) as a copy region.
static VkBufferImageCopy bufferTextureRegion(const Texture& t, gdi::Subresource at, const Buffer& b,
                                             uint64_t offset, bool toTexture, const char* what) {
    gdi::validate::subresourceBufferCopy(t.desc, t.name, at, b.desc, b.name, offset, toTexture,
                                         what);
    return copyRegion(t.desc, at, offset);
}

void VulkanCommandList::copyBufferToTexture(gdi::TextureHandle dst, gdi::Subresource at,
                                            gdi::BufferHandle src, uint64_t srcOffset) {
    outsidePass("copyBufferToTexture");
    Texture& t = copiedTexture(dst);
    Buffer& b = usedBuffer(src);
    const VkBufferImageCopy r =
        bufferTextureRegion(t, at, b, srcOffset, true, "copyBufferToTexture");
    barrierIfWritten();
    vkCmdCopyBufferToImage(cb_, b.buffer, t.image, VK_IMAGE_LAYOUT_GENERAL, 1, &r);
    written_ = true;
}

void VulkanCommandList::copyTextureToBuffer(gdi::BufferHandle dst, uint64_t dstOffset,
                                            gdi::TextureHandle src, gdi::Subresource at) {
    outsidePass("copyTextureToBuffer");
    Texture& t = copiedTexture(src);
    Buffer& b = usedBuffer(dst);
    const VkBufferImageCopy r =
        bufferTextureRegion(t, at, b, dstOffset, false, "copyTextureToBuffer");
    barrierIfWritten();
    vkCmdCopyImageToBuffer(cb_, t.image, VK_IMAGE_LAYOUT_GENERAL, b.buffer, 1, &r);
    written_ = true;
    if (b.desc.access == gdi::MemoryAccess::Readback) hostReadable(b);
}

// Regions (validated and resolved by the shared rules, then one copy each).
void VulkanCommandList::copyBufferToTexture(gdi::TextureHandle dst,
                                            const gdi::TextureRegion& region, gdi::BufferHandle src,
                                            const gdi::TexelLayout& layout) {
    outsidePass("copyBufferToTexture");
    Texture& t = copiedTexture(dst);
    Buffer& b = usedBuffer(src);
    const auto [r, l] = gdi::validate::bufferTextureRegion(t.desc, t.name, b.desc, b.name, region,
                                                           layout, true, "copyBufferToTexture");
    barrierIfWritten();
    const VkBufferImageCopy c = regionCopy(t.desc, r, l);
    vkCmdCopyBufferToImage(cb_, b.buffer, t.image, VK_IMAGE_LAYOUT_GENERAL, 1, &c);
    written_ = true;
}

void VulkanCommandList::copyTextureToBuffer(gdi::BufferHandle dst, const gdi::TexelLayout& layout,
                                            gdi::TextureHandle src,
                                            const gdi::TextureRegion& region) {
    outsidePass("copyTextureToBuffer");
    Texture& t = copiedTexture(src);
    Buffer& b = usedBuffer(dst);
    const auto [r, l] = gdi::validate::bufferTextureRegion(t.desc, t.name, b.desc, b.name, region,
                                                           layout, false, "copyTextureToBuffer");
    barrierIfWritten();
    const VkBufferImageCopy c = regionCopy(t.desc, r, l);
    vkCmdCopyImageToBuffer(cb_, t.image, VK_IMAGE_LAYOUT_GENERAL, b.buffer, 1, &c);
    written_ = true;
    if (b.desc.access == gdi::MemoryAccess::Readback) hostReadable(b);
}

void VulkanCommandList::copyTexture(gdi::TextureHandle dst, const gdi::TextureRegion& dstAt,
                                    gdi::TextureHandle src, const gdi::TextureRegion& srcRegion) {
    outsidePass("copyTexture");
    Texture& d = copiedTexture(dst);
    Texture& s = copiedTexture(src);
    const auto [dr, sr] =
        gdi::validate::textureCopy(d.desc, d.name, dstAt, dst == src, s.desc, s.name, srcRegion);
    barrierIfWritten();
    const VkImageCopy c = imageCopy(d.desc, dr, s.desc, sr);
    vkCmdCopyImage(cb_, s.image, VK_IMAGE_LAYOUT_GENERAL, d.image, VK_IMAGE_LAYOUT_GENERAL, 1, &c);
    written_ = true;
}

void VulkanCommandList::resolveTexture(gdi::TextureHandle dst, const gdi::TextureRegion& dstAt,
                                       gdi::TextureHandle src,
                                       const gdi::TextureRegion& srcRegion) {
    gdi::validate::queueAllows(queue_, gdi::QueueKind::Graphics, "resolveTexture");
    outsidePass("resolveTexture");
    Texture& d = copiedTexture(dst);
    Texture& s = copiedTexture(src);
    const auto [dr, sr] =
        gdi::validate::textureResolve(d.desc, d.name, dstAt, s.desc, s.name, srcRegion);
    barrierIfWritten();
    const VkImageCopy c = imageCopy(d.desc, dr, s.desc, sr);
    const VkImageResolve r{c.srcSubresource, c.srcOffset, c.dstSubresource, c.dstOffset, c.extent};
    vkCmdResolveImage(cb_, s.image, VK_IMAGE_LAYOUT_GENERAL, d.image, VK_IMAGE_LAYOUT_GENERAL, 1,
                      &r);
    written_ = true;
}

// The host reads Readback memory through map() once the fence has signalled; a fence does not
// make device writes available to the host by itself, this barrier does.
void VulkanCommandList::hostReadable(const Buffer& b) {
    VkBufferMemoryBarrier mb{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
    mb.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    mb.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    mb.srcQueueFamilyIndex = mb.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    mb.buffer = b.buffer;
    mb.size = VK_WHOLE_SIZE;
    vkCmdPipelineBarrier(cb_, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0,
                         nullptr, 1, &mb, 0, nullptr);
}

// Each level is a linear blit of the one above (an exact 2x2 or 2x2x2 average where sizes
// halve evenly), every layer at once; a barrier orders each level's write before its read.
void VulkanCommandList::generateMips(gdi::TextureHandle h) {
    gdi::validate::queueAllows(queue_, gdi::QueueKind::Graphics, "generateMips");
    outsidePass("generateMips");
    Texture& t = copiedTexture(h);
    gdi::validate::mipGeneration(t.desc, t.name);
    if (!dev_.linearBlit(t.desc.format))
        throw gdi::Error("generateMips: format " +
                         std::string(gdi::formatInfo(t.desc.format).name) +
                         " cannot be filtered by a blit on this device");
    barrierIfWritten();
    const bool is3D = t.desc.dimension == gdi::TextureDimension::Texture3D;
    for (uint32_t m = 1; m < t.desc.mipLevels; ++m) {
        const gdi::validate::Extent3 a = gdi::validate::mipExtent(t.desc, m - 1),
                                     b = gdi::validate::mipExtent(t.desc, m);
        VkImageBlit blit{};
        blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, m - 1, 0, arrayLayers(t.desc)};
        blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, m, 0, arrayLayers(t.desc)};
        blit.srcOffsets[1] = {int32_t(a.width), int32_t(a.height),
                              is3D ? int32_t(a.depthOrLayers) : 1};
        blit.dstOffsets[1] = {int32_t(b.width), int32_t(b.height),
                              is3D ? int32_t(b.depthOrLayers) : 1};
        vkCmdBlitImage(cb_, t.image, VK_IMAGE_LAYOUT_GENERAL, t.image, VK_IMAGE_LAYOUT_GENERAL, 1,
                       &blit, VK_FILTER_LINEAR);
        VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        mb.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        mb.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
        vkCmdPipelineBarrier(cb_, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
                             1, &mb, 0, nullptr, 0, nullptr);
    }
    written_ = true;
}

void VulkanCommandList::beginTimer(gdi::TimerHandle h) {
    gdi::validate::queueAllows(queue_, gdi::QueueKind::Compute, "beginTimer");
    outsidePass("beginTimer");  // the query reset below must be outside rendering
    Timer& t = usedTimer(h);
    queries_.beginTimer(h.id);
    vkCmdResetQueryPool(cb_, dev_.queryPool(), t.firstQuery, 2);
    vkCmdWriteTimestamp(cb_, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, dev_.queryPool(), t.firstQuery);
}

void VulkanCommandList::endTimer(gdi::TimerHandle h) {
    gdi::validate::queueAllows(queue_, gdi::QueueKind::Compute, "endTimer");
    ensureRecording("endTimer");
    checkUnrestricted("endTimer");
    if (secondary_) gdi::validate::notInSecondary("endTimer");
    Timer& t = usedTimer(h);
    queries_.endTimer(h.id);
    vkCmdWriteTimestamp(cb_, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, dev_.queryPool(),
                        t.firstQuery + 1);
}

// Queries: the device resets every query a submission uses before it runs (VulkanDevice::submit).
QuerySet& VulkanCommandList::usedQuerySet(gdi::QuerySetHandle h, const char* what) {
    ensureRecording(what);
    checkUnrestricted(what);
    if (secondary_) gdi::validate::notInSecondary(what);
    QuerySet& q = dev_.querySet(h);
    note(UsedKind::QuerySet, h.id);
    return q;
}

void VulkanCommandList::beginQuery(gdi::QuerySetHandle h, uint32_t index) {
    gdi::validate::queueAllows(queue_, gdi::QueueKind::Compute, "beginQuery");
    QuerySet& q = usedQuerySet(h, "beginQuery");
    queries_.begin(q.desc, q.name, h.id, index, inPass_);
    vkCmdBeginQuery(cb_, q.pool, index,
                    q.desc.type == gdi::QueryType::Occlusion ? VK_QUERY_CONTROL_PRECISE_BIT : 0);
}

void VulkanCommandList::endQuery(gdi::QuerySetHandle h, uint32_t index) {
    QuerySet& q = usedQuerySet(h, "endQuery");
    queries_.end(q.desc, q.name, h.id, index, inPass_);
    vkCmdEndQuery(cb_, q.pool, index);
}

void VulkanCommandList::writeTimestamp(gdi::QuerySetHandle h, uint32_t index) {
    gdi::validate::queueAllows(queue_, gdi::QueueKind::Compute, "writeTimestamp");
    QuerySet& q = usedQuerySet(h, "writeTimestamp");
    queries_.timestamp(q.desc, q.name, h.id, index, inPass_);
    vkCmdWriteTimestamp(cb_, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, q.pool, index);
}

void VulkanCommandList::resolveQueries(gdi::QuerySetHandle h, uint32_t first, uint32_t count,
                                       gdi::BufferHandle dst, uint64_t dstOffset) {
    gdi::validate::queueAllows(queue_, gdi::QueueKind::Compute, "resolveQueries");
    outsidePass("resolveQueries");
    QuerySet& q = usedQuerySet(h, "resolveQueries");
    Buffer& b = usedBuffer(dst);
    const uint64_t stride = 8 * gdi::validate::queryValues(q.desc.type);
    gdi::validate::queryDestination(b.desc, b.name, dstOffset, stride * count);
    queries_.resolve(q.desc, q.name, h.id, first, count);  // last: it keeps what it resolves
    barrierIfWritten();
    vkCmdCopyQueryPoolResults(cb_, q.pool, first, count, b.buffer, dstOffset, stride,
                              VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT);
    written_ = true;
    if (b.desc.access == gdi::MemoryAccess::Readback) hostReadable(b);
}

void VulkanCommandList::pushDebugGroup(const char* name) {
    ensureRecording("pushDebugGroup");
    checkUnrestricted("pushDebugGroup");
    debugDepth_++;
    if (!dev_.cmdBeginLabel) return;
    VkDebugUtilsLabelEXT l{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
    l.pLabelName = name ? name : "";
    dev_.cmdBeginLabel(cb_, &l);
}

void VulkanCommandList::popDebugGroup() {
    ensureRecording("popDebugGroup");
    checkUnrestricted("popDebugGroup");
    if (debugDepth_ == 0) throw gdi::Error("popDebugGroup without pushDebugGroup");
    debugDepth_--;
    if (dev_.cmdEndLabel) dev_.cmdEndLabel(cb_);
}

}  // namespace fe::vk

// Buffers, textures, samplers and timers.
#include <algorithm>
#include <cstring>

#include "VulkanCommandList.h"
#include "VulkanDevice.h"
#include "VulkanFaults.h"
#include "fe/gdi/Validation.h"

namespace fe::vk {

namespace {
VkFormatFeatureFlags requiredFeatures(gdi::Format f, gdi::TextureUsage u) {
    VkFormatFeatureFlags r = 0;
    if (any(u, gdi::TextureUsage::Sampled)) r |= VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT;
    if (any(u, gdi::TextureUsage::Storage)) r |= VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT;
    if (any(u, gdi::TextureUsage::RenderTarget))
        r |= gdi::isDepthFormat(f) ? VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT
                                   : VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT;
    return r | VK_FORMAT_FEATURE_TRANSFER_SRC_BIT | VK_FORMAT_FEATURE_TRANSFER_DST_BIT;
}

}  // namespace

bool VulkanDevice::supportsFormat(gdi::Format format, gdi::TextureUsage usage) const {
    VkFormat vf = toVkFormat(format);
    if (vf == VK_FORMAT_UNDEFINED) return false;
    if (gdi::isCompressedFormat(format) && !info_.features.textureCompressionBC) return false;
    // No SPIR-V image format names BGRA or a depth/stencil format (formatCaps agrees), though
    // drivers may offer the storage feature (NVIDIA does for D16 and D32F; the case
    // storage_image_every_format caught it there).
    if (any(usage, gdi::TextureUsage::Storage) &&
        (format == gdi::Format::BGRA8 || format == gdi::Format::BGRA8_SRGB ||
         gdi::isDepthFormat(format)))
        return false;
    VkFormatProperties p;
    vkGetPhysicalDeviceFormatProperties(physical_, vf, &p);
    VkFormatFeatureFlags need = requiredFeatures(format, usage);
    return (p.optimalTilingFeatures & need) == need;
}

gdi::FormatCaps VulkanDevice::formatCaps(gdi::Format format) const {
    gdi::FormatCaps c;
    const VkFormat vf = toVkFormat(format);
    if (vf == VK_FORMAT_UNDEFINED ||
        (gdi::isCompressedFormat(format) && !info_.features.textureCompressionBC))
        return c;
    VkFormatProperties p;
    vkGetPhysicalDeviceFormatProperties(physical_, vf, &p);
    const VkFormatFeatureFlags f = p.optimalTilingFeatures;
    const bool depth = gdi::isDepthFormat(format);
    c.sampled = f & VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT;
    c.linearFilter = c.sampled && (f & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT);
    c.renderTarget = f & (depth ? VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT
                                : VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT);
    c.blend = !depth && (f & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT);
    // The formats beyond the base set need the shader feature as well (enabled when offered).
    c.storage =
        (f & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT) &&
        supportsFormat(format, gdi::TextureUsage::Storage) &&
        (!gdi::isExtendedStorageFormat(format) || enabled_.shaderStorageImageExtendedFormats);
    if (c.renderTarget) {
        VkImageFormatProperties ip{};
        const VkImageUsageFlags usage = depth ? VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT
                                              : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
        if (vkGetPhysicalDeviceImageFormatProperties(physical_, vf, VK_IMAGE_TYPE_2D,
                                                     VK_IMAGE_TILING_OPTIMAL, usage, 0,
                                                     &ip) == VK_SUCCESS)
            c.sampleCounts = uint32_t(ip.sampleCounts) & 0xf;  // 1, 2, 4, 8: what the engine offers
    }
    return c;
}

bool VulkanDevice::linearBlit(gdi::Format format) const {
    VkFormatProperties p;
    vkGetPhysicalDeviceFormatProperties(physical_, toVkFormat(format), &p);
    const VkFormatFeatureFlags need = VK_FORMAT_FEATURE_BLIT_SRC_BIT |
                                      VK_FORMAT_FEATURE_BLIT_DST_BIT |
                                      VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
    return (p.optimalTilingFeatures & need) == need;
}

Buffer VulkanDevice::makeBuffer(VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage mem,
                                const char* kind, const std::string& name) {
    const std::string object = gdi::describeObject(kind, name, std::to_string(size) + " bytes");
    Buffer b;
    VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    ci.size = size;
    ci.usage = usage;
    setSharing(ci);
    check(nativeAllocation("vkCreateBuffer",
                           [&] { return vkCreateBuffer(device_, &ci, nullptr, &b.buffer); }),
          "vkCreateBuffer", object);
    ++nativeObjects_;
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device_, b.buffer, &req);
    try {
        b.memory = allocator_->allocate(req, mem, object);
        check(vkBindBufferMemory(device_, b.buffer, b.memory.memory, b.memory.offset),
              "vkBindBufferMemory", object);
    } catch (...) {
        freeBuffer(b);
        throw;
    }
    return b;
}

void VulkanDevice::freeBuffer(Buffer& b) {
    if (b.buffer) vkDestroyBuffer(device_, b.buffer, nullptr), --nativeObjects_;
    allocator_->free(b.memory);
    b = Buffer{};
}

gdi::BufferHandle VulkanDevice::createBuffer(const gdi::BufferDesc& desc,
                                             gdi::ByteSpan initialData) {
    const DeviceCall call(*this);
    loss_.check("createBuffer");
    const gdi::fault::ObjectScope faultObject(desc.debugName);
    gdi::validate::bufferDesc(desc, info_.limits);
    gdi::validate::initialData(desc, initialData.size());
    using U = gdi::BufferUsage;
    // Copies in and out are always allowed: writeBuffer/readBuffer stage through them.
    VkBufferUsageFlags usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    if (any(desc.usage, U::Vertex)) usage |= VK_BUFFER_USAGE_VERTEX_BUFFER_BIT;
    if (any(desc.usage, U::Index)) usage |= VK_BUFFER_USAGE_INDEX_BUFFER_BIT;
    if (any(desc.usage, U::Uniform)) usage |= VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT;
    if (any(desc.usage, U::Storage)) usage |= VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    if (any(desc.usage, U::Indirect)) usage |= VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
    MemoryUsage mem = desc.access == gdi::MemoryAccess::Upload     ? MemoryUsage::Upload
                      : desc.access == gdi::MemoryAccess::Readback ? MemoryUsage::Readback
                                                                   : MemoryUsage::GpuOnly;
    Buffer b = makeBuffer(desc.size, usage, mem, "buffer", desc.debugName ? desc.debugName : "");
    b.desc = desc;
    b.name = desc.debugName ? desc.debugName : "";
    b.desc.debugName = nullptr;  // the caller's string may not outlive the buffer
    setName(VK_OBJECT_TYPE_BUFFER, uint64_t(b.buffer), desc.debugName);
    // New buffers read as zeros on every backend (Device.h): host-visible memory is cleared
    // here, device memory by a fill recorded in front of the next submission.
    const bool zero = initialData.empty();
    if (zero && b.memory.mapped) std::memset(b.memory.mapped, 0, desc.size);
    const VkBuffer native = b.buffer;
    const bool fill = zero && !b.memory.mapped;
    gdi::BufferHandle h = buffers_.add(std::move(b));
    try {
        if (!zero) writeBuffer(h, 0, initialData);
        if (fill) {
            recordInitialTransition(
                [native](VkCommandBuffer cb) { vkCmdFillBuffer(cb, native, 0, VK_WHOLE_SIZE, 0); },
                0, h.id);
        }
    } catch (...) {
        destroy(h);
        throw;
    }
    return h;
}

VkImageView VulkanDevice::makeView(VkImage image, VkImageViewType type, gdi::Format format,
                                   VkImageSubresourceRange range, const std::string& object,
                                   VkComponentMapping swizzle) {
    VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vi.image = image;
    vi.viewType = type;
    vi.format = toVkFormat(format);
    vi.components = swizzle;
    // Views for sampling and attachments see depth only; stencil is reached through the attachment.
    range.aspectMask = viewAspectOf(format);
    vi.subresourceRange = range;
    VkImageView v;
    check(nativeAllocation("vkCreateImageView",
                           [&] { return vkCreateImageView(device_, &vi, nullptr, &v); }),
          "vkCreateImageView", object);
    return v;
}

namespace {
VkImageViewType viewType(gdi::TextureDimension d) {
    switch (d) {
        case gdi::TextureDimension::Texture2DArray:
            return VK_IMAGE_VIEW_TYPE_2D_ARRAY;
        case gdi::TextureDimension::TextureCube:
            return VK_IMAGE_VIEW_TYPE_CUBE;
        case gdi::TextureDimension::TextureCubeArray:
            return VK_IMAGE_VIEW_TYPE_CUBE_ARRAY;
        case gdi::TextureDimension::Texture3D:
            return VK_IMAGE_VIEW_TYPE_3D;
        default:
            return VK_IMAGE_VIEW_TYPE_2D;
    }
}
}  // namespace

VkImageView VulkanDevice::attachmentView(Texture& t, uint32_t mip, uint32_t layer) {
    const DeviceCall call(*this);
    const uint32_t layers = t.desc.depthOrLayers;
    if (t.attachmentViews.empty())
        t.attachmentViews.assign(size_t(t.desc.mipLevels) * layers, VK_NULL_HANDLE);
    VkImageView& v = t.attachmentViews[size_t(mip) * layers + layer];
    // A 3D slice is a 2D view of one layer of the 2D-array-compatible image (VK_KHR_maintenance1).
    if (!v)
        v = makeView(t.image, VK_IMAGE_VIEW_TYPE_2D, t.desc.format,
                     {0, t.baseMip + mip, 1, t.baseLayer + layer, 1},
                     gdi::describeObject("texture", t.name, {}));
    return v;
}

VkImageCreateInfo VulkanDevice::imageInfo(const gdi::TextureDesc& desc) const {
    using U = gdi::TextureUsage;
    // Transient attachments may have no other usage than attachment ones (not even the
    // transfers every other texture gets for readback and its first clear to zero).
    const bool transient = any(desc.usage, U::Transient);
    VkImageUsageFlags usage =
        transient ? VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT
                  : VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    if (any(desc.usage, U::Sampled)) usage |= VK_IMAGE_USAGE_SAMPLED_BIT;
    if (any(desc.usage, U::Storage)) usage |= VK_IMAGE_USAGE_STORAGE_BIT;
    if (any(desc.usage, U::RenderTarget))
        usage |= gdi::isDepthFormat(desc.format) ? VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT
                                                 : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    const bool is3D = desc.dimension == gdi::TextureDimension::Texture3D;
    VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    // Cube views of square arrays, and views in the formats TextureDesc::viewFormats lists.
    if (gdi::validate::isCube(desc.dimension) ||
        (desc.dimension == gdi::TextureDimension::Texture2DArray && desc.width == desc.height &&
         desc.depthOrLayers >= 6))
        ci.flags |= VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT;
    if (!desc.viewFormats.empty()) ci.flags |= VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT;
    if (is3D && any(desc.usage, U::RenderTarget))
        ci.flags |= VK_IMAGE_CREATE_2D_ARRAY_COMPATIBLE_BIT;
    ci.imageType = is3D ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D;
    ci.format = toVkFormat(desc.format);
    ci.extent = {desc.width, desc.height, is3D ? desc.depthOrLayers : 1};
    ci.mipLevels = desc.mipLevels;
    ci.arrayLayers = arrayLayers(desc);
    ci.samples = VkSampleCountFlagBits(desc.sampleCount);
    ci.tiling = VK_IMAGE_TILING_OPTIMAL;
    ci.usage = usage;
    ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    setSharing(ci);
    return ci;
}

gdi::MemoryRequirements VulkanDevice::textureMemoryRequirements(
    const gdi::TextureDesc& desc) const {
    gdi::validate::textureDesc(desc, info_);
    VkImageCreateInfo ci = imageInfo(desc);
    VkImage image;
    check(nativeAllocation("vkCreateImage",
                           [&] { return vkCreateImage(device_, &ci, nullptr, &image); }),
          "vkCreateImage",
          gdi::describeObject("texture", desc.debugName ? desc.debugName : "",
                              "memory requirements"));
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(device_, image, &req);
    vkDestroyImage(device_, image, nullptr);
    return {req.size, req.alignment};
}

gdi::HeapHandle VulkanDevice::createHeap(const gdi::HeapDesc& desc) {
    const DeviceCall call(*this);
    loss_.check("createHeap");
    const std::string name = desc.debugName ? desc.debugName : "";
    if (desc.size == 0) throw gdi::Error("heap '" + name + "': size is 0");
    // Memory types every render-target/sampled image kind accepts, found from sample images.
    uint32_t typeBits = ~0u;
    VkDeviceSize alignment = 1;
    for (gdi::Format f :
         {gdi::Format::RGBA8, gdi::Format::RGBA16F, gdi::Format::R32F, gdi::Format::D32F}) {
        gdi::TextureDesc probe{
            .format = f,
            .width = 64,
            .height = 64,
            .usage = gdi::TextureUsage::RenderTarget | gdi::TextureUsage::Sampled};
        VkImageCreateInfo ci = imageInfo(probe);
        VkImage image;
        check(nativeAllocation("vkCreateImage",
                               [&] { return vkCreateImage(device_, &ci, nullptr, &image); }),
              "vkCreateImage", gdi::describeObject("heap", name, "memory type probe"));
        VkMemoryRequirements req;
        vkGetImageMemoryRequirements(device_, image, &req);
        vkDestroyImage(device_, image, nullptr);
        typeBits &= req.memoryTypeBits;
        alignment = std::max(alignment, req.alignment);
    }
    if (!typeBits) throw gdi::Error("heap '" + name + "': no memory type fits all texture kinds");
    Heap h;
    h.memory = allocator_->allocate(
        {desc.size, alignment, typeBits}, MemoryUsage::GpuOnly,
        gdi::describeObject("heap", name, std::to_string(desc.size) + " bytes"));
    h.size = desc.size;
    h.name = name;
    return heaps_.add(std::move(h));
}

void VulkanDevice::destroy(gdi::HeapHandle h) {
    const DeviceCall call(*this);
    Heap heap;
    if (!h) return;
    if (!heaps_.find(h)) gdi::validate::destroyedHandle("heap", h.id);
    releaseRetiredNow();  // textures destroyed before the heap are released now, not later
    if (heaps_.find(h)->placed)
        throw gdi::Error("destroy heap '" + heaps_.find(h)->name +
                         "': textures are still placed in it");
    idle();
    heaps_.remove(h, heap);
    allocator_->free(heap.memory);
}

gdi::TextureHandle VulkanDevice::createTexture(const gdi::TextureDesc& desc) {
    const DeviceCall call(*this);
    loss_.check("createTexture");
    const gdi::fault::ObjectScope faultObject(desc.debugName);
    gdi::validate::textureDesc(desc, info_);
    const std::string name = desc.debugName ? desc.debugName : "";
    if (!supportsFormat(desc.format, desc.usage)) gdi::validate::unsupportedTextureUsage(desc);
    Heap* heap = desc.heap ? &heaps_.get(desc.heap, "heap") : nullptr;
    Texture t;
    t.desc = desc;
    t.desc.debugName = nullptr;
    t.name = name;
    t.linearFilter = formatCaps(desc.format).linearFilter;
    VkImageCreateInfo ci = imageInfo(desc);
    // The formats views may take, so a driver keeps compression where it can.
    std::vector<VkFormat> viewFormats = {toVkFormat(desc.format)};
    for (gdi::Format f : desc.viewFormats) viewFormats.push_back(toVkFormat(f));
    VkImageFormatListCreateInfo formatList{VK_STRUCTURE_TYPE_IMAGE_FORMAT_LIST_CREATE_INFO};
    formatList.viewFormatCount = uint32_t(viewFormats.size());
    formatList.pViewFormats = viewFormats.data();
    if (!desc.viewFormats.empty()) ci.pNext = &formatList;
    const std::string object =
        gdi::describeObject("texture", name,
                            std::to_string(desc.width) + "x" + std::to_string(desc.height) + " " +
                                std::string(gdi::formatInfo(desc.format).name));
    check(nativeAllocation("vkCreateImage",
                           [&] { return vkCreateImage(device_, &ci, nullptr, &t.image); }),
          "vkCreateImage", object);
    ++nativeObjects_;
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(device_, t.image, &req);
    try {
        if (heap) {
            if (desc.heapOffset % req.alignment != 0 || desc.heapOffset + req.size > heap->size)
                throw gdi::Error("texture '" + name + "': placement at offset " +
                                 std::to_string(desc.heapOffset) + " (size " +
                                 std::to_string(req.size) + ", alignment " +
                                 std::to_string(req.alignment) + ") does not fit heap '" +
                                 heap->name + "' of " + std::to_string(heap->size) + " bytes");
            t.ownsMemory = false;
            heap->placed++;  // from here on destroyTexture() counts it out again, also when this fails
            t.memory = heap->memory;
            t.memory.offset += desc.heapOffset;
            t.memory.size = req.size;
        } else {
            t.memory = allocator_->allocate(req,
                                            any(desc.usage, gdi::TextureUsage::Transient)
                                                ? MemoryUsage::Transient
                                                : MemoryUsage::GpuOnly,
                                            object);
        }
        check(vkBindImageMemory(device_, t.image, t.memory.memory, t.memory.offset),
              "vkBindImageMemory", object);
        const VkImageViewType type = viewType(desc.dimension);
        const uint32_t layers = arrayLayers(desc);
        // Multisampled images have a view only when sampled (their attachments take views of
        // their own); an image only copied to and from has no usage a view may have
        // (VUID-VkImageViewCreateInfo-image-04441).
        using U = gdi::TextureUsage;
        if ((desc.sampleCount == 1 && any(desc.usage, U::Sampled | U::Storage | U::RenderTarget)) ||
            any(desc.usage, U::Sampled)) {  // multisampled: read per sample (sampler2DMS)
            t.view =
                makeView(t.image, type, desc.format, {0, 0, desc.mipLevels, 0, layers}, object);
            // Storage images bind one mip, every layer, of the texture's kind (image2DArray,
            // imageCube, image3D...), as GL's layered image bindings do.
            if (any(desc.usage, gdi::TextureUsage::Storage))
                for (uint32_t m = 0; m < desc.mipLevels; ++m)
                    t.mipViews.push_back(
                        makeView(t.image, type, desc.format, {0, m, 1, 0, layers}, object));
        }
    } catch (...) {
        destroyTexture(t);
        throw;
    }
    setName(VK_OBJECT_TYPE_IMAGE, uint64_t(t.image), desc.debugName);
    // Move the image into GENERAL once; it stays there (see VulkanDevice.h). Recorded into the
    // next submission (or transfer) rather than submitted and waited for here.
    const VkImage image = t.image;
    const gdi::Format format = desc.format;
    const bool zeroed = !any(desc.usage, gdi::TextureUsage::Transient);  // no one reads it
    const gdi::TextureHandle h = textures_.add(std::move(t));
    recordInitialTransition(
        [image, format, zeroed](VkCommandBuffer cb) {
            VulkanCommandList::toGeneral(cb, image, format);
            if (zeroed) clearToZero(cb, image, format);
        },
        h.id);
    return h;
}

gdi::TextureHandle VulkanDevice::createTextureView(gdi::TextureHandle h,
                                                   const gdi::TextureViewDesc& v) {
    const DeviceCall call(*this);
    loss_.check("createTextureView");
    Texture& parent = texture(h);
    Texture t;
    t.desc = gdi::validate::textureView(parent.desc, parent.name, parent.viewOf != 0, v);
    t.name = v.debugName ? v.debugName : "";
    t.image = parent.image;
    t.ownsMemory = false;
    t.viewOf = h.id;
    t.baseMip = v.baseMip;
    t.baseLayer = t.desc.dimension == gdi::TextureDimension::Texture3D ? 0 : v.baseLayer;
    t.linearFilter = formatCaps(t.desc.format).linearFilter;
    auto channel = [](gdi::Swizzle s) {
        static constexpr VkComponentSwizzle k[] = {
            VK_COMPONENT_SWIZZLE_IDENTITY, VK_COMPONENT_SWIZZLE_ZERO, VK_COMPONENT_SWIZZLE_ONE,
            VK_COMPONENT_SWIZZLE_R,        VK_COMPONENT_SWIZZLE_G,    VK_COMPONENT_SWIZZLE_B,
            VK_COMPONENT_SWIZZLE_A};
        return k[int(s)];
    };
    const VkComponentMapping swizzle{channel(v.swizzle[0]), channel(v.swizzle[1]),
                                     channel(v.swizzle[2]), channel(v.swizzle[3])};
    const std::string object =
        gdi::describeObject("texture view", t.name, "of '" + parent.name + "'");
    const VkImageViewType type = viewType(t.desc.dimension);
    const uint32_t layers = arrayLayers(t.desc);
    try {
        t.view = makeView(t.image, type, t.desc.format,
                          {0, t.baseMip, t.desc.mipLevels, t.baseLayer, layers}, object, swizzle);
        if (any(t.desc.usage, gdi::TextureUsage::Storage))
            for (uint32_t m = 0; m < t.desc.mipLevels; ++m)
                t.mipViews.push_back(makeView(t.image, type, t.desc.format,
                                              {0, t.baseMip + m, 1, t.baseLayer, layers}, object));
    } catch (...) {
        destroyTexture(t);
        throw;
    }
    setName(VK_OBJECT_TYPE_IMAGE_VIEW, uint64_t(t.view), v.debugName);
    ++parent.views;
    return textures_.add(std::move(t));
}

void VulkanDevice::destroyTexture(Texture& t) {
    for (VkImageView v : t.mipViews) vkDestroyImageView(device_, v, nullptr);
    for (VkImageView v : t.attachmentViews)
        if (v) vkDestroyImageView(device_, v, nullptr);
    if (t.view) vkDestroyImageView(device_, t.view, nullptr);
    if (t.viewOf) {  // the image is the texture's (destroy() counted the view out)
        t = Texture{};
        return;
    }
    if (t.image) vkDestroyImage(device_, t.image, nullptr), --nativeObjects_;
    if (t.ownsMemory) {
        allocator_->free(t.memory);
    } else if (t.desc.heap) {
        if (Heap* h = heaps_.find(t.desc.heap)) h->placed--;
    }
    t = Texture{};
}

// New textures read as zeros on every backend (Device.h), block-compressed ones excepted: they
// cannot be cleared and are uploaded before use.
// A new texture's zero clear (in GENERAL, after its transition); the barrier after every
// pending object's commands orders it before use.
void VulkanDevice::clearToZero(VkCommandBuffer cb, VkImage image, gdi::Format format) {
    if (gdi::isCompressedFormat(format)) return;
    const VkImageSubresourceRange all{aspectOf(format), 0, VK_REMAINING_MIP_LEVELS, 0,
                                      VK_REMAINING_ARRAY_LAYERS};
    if (gdi::isDepthFormat(format)) {
        const VkClearDepthStencilValue zero{0.0f, 0};
        vkCmdClearDepthStencilImage(cb, image, VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &all);
    } else {
        const VkClearColorValue zero{};
        vkCmdClearColorImage(cb, image, VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &all);
    }
}

gdi::SamplerHandle VulkanDevice::createSampler(const gdi::SamplerDesc& d) {
    const DeviceCall call(*this);
    loss_.check("createSampler");
    const gdi::fault::ObjectScope faultObject(d.debugName);
    gdi::validate::samplerDesc(d);
    auto filter = [](gdi::Filter f) {
        return f == gdi::Filter::Nearest ? VK_FILTER_NEAREST : VK_FILTER_LINEAR;
    };
    auto address = [](gdi::AddressMode a) {
        switch (a) {
            case gdi::AddressMode::MirroredRepeat:
                return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
            case gdi::AddressMode::ClampToEdge:
                return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
            case gdi::AddressMode::ClampToBorder:
                return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
            default:
                return VK_SAMPLER_ADDRESS_MODE_REPEAT;
        }
    };
    VkSamplerCreateInfo ci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    ci.magFilter = filter(d.magFilter);
    ci.minFilter = filter(d.minFilter);
    ci.mipmapMode = d.mipFilter == gdi::MipFilter::Linear ? VK_SAMPLER_MIPMAP_MODE_LINEAR
                                                          : VK_SAMPLER_MIPMAP_MODE_NEAREST;
    ci.addressModeU = address(d.addressU);
    ci.addressModeV = address(d.addressV);
    ci.addressModeW = address(d.addressW);
    ci.compareEnable = d.compareEnable;
    ci.compareOp = VkCompareOp(int(d.compare));  // same order as VkCompareOp
    ci.anisotropyEnable = anisotropy_ && d.maxAnisotropy > 1.0f;
    ci.maxAnisotropy = std::min(d.maxAnisotropy, props_.limits.maxSamplerAnisotropy);
    static constexpr VkBorderColor kBorder[] = {VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK,
                                                VK_BORDER_COLOR_FLOAT_OPAQUE_BLACK,
                                                VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE};
    ci.borderColor = kBorder[int(d.borderColor)];
    ci.mipLodBias =
        std::clamp(d.lodBias, -props_.limits.maxSamplerLodBias, props_.limits.maxSamplerLodBias);
    // MipFilter::None samples the base level only, with minFilter when minifying, as GL's
    // non-mipmap filters do. Clamping the level of detail to 0 would make every lookup a
    // magnification (magFilter); 0.25 keeps minification visible while NEAREST mipmapping still
    // rounds to level 0 (the Vulkan specification's own advice for this GL mode).
    const bool baseOnly = d.mipFilter == gdi::MipFilter::None;
    ci.minLod = baseOnly ? 0.0f : d.minLod;
    ci.maxLod = baseOnly ? 0.25f : d.maxLod;
    Sampler s;
    s.filtersLinearly = gdi::validate::filtersLinearly(d);
    s.readsMips = d.mipFilter != gdi::MipFilter::None;
    s.name = d.debugName ? d.debugName : "";
    check(nativeAllocation("vkCreateSampler",
                           [&] { return vkCreateSampler(device_, &ci, nullptr, &s.sampler); }),
          "vkCreateSampler");
    setName(VK_OBJECT_TYPE_SAMPLER, uint64_t(s.sampler), d.debugName);
    return samplers_.add(std::move(s));
}

gdi::TimerHandle VulkanDevice::createTimer() {
    const DeviceCall call(*this);
    loss_.check("createTimer");
    if (freeTimerSlots_.empty())
        throw gdi::Error("Vulkan: out of timers (" + std::to_string(kMaxTimers) + " live)");
    Timer t{freeTimerSlots_.back()};
    freeTimerSlots_.pop_back();
    vkResetQueryPool(device_, queryPool_, t.firstQuery, 2);
    return timers_.add(std::move(t));
}

// Destruction waits for the GPU so nothing in flight still uses the object (on a lost device
// nothing is: destroy works after a loss). Resources are created and destroyed at load time,
// not per frame (the render graph pools its transients).
// Destruction is deferred past the submissions that may use the object (retire()); the
// handle is invalid at once.
void VulkanDevice::destroy(gdi::BufferHandle h) {
    const DeviceCall call(*this);
    if (!h) return;
    if (!buffers_.retire(h)) gdi::validate::destroyedHandle("buffer", h.id);
    dropInitialCommands(0, h.id);  // a zero fill not yet submitted never runs
    retire([this, h] {
        Buffer b;
        buffers_.release(h, b);
        freeBuffer(b);
    });
}

void VulkanDevice::destroy(gdi::TextureHandle h) {
    const DeviceCall call(*this);
    if (const Texture* live = h ? textures_.find(h) : nullptr; live && live->views)
        gdi::validate::viewsAlive(live->name, live->views);
    if (!h) return;
    if (!textures_.retire(h)) gdi::validate::destroyedHandle("texture", h.id);
    if (Texture* parent =
            textures_.at(h).viewOf ? textures_.find({textures_.at(h).viewOf}) : nullptr)
        --parent->views;
    dropInitialCommands(h.id, 0);  // nor a first transition and clear
    retire([this, h] {
        Texture t;
        textures_.release(h, t);
        destroyTexture(t);
    });
}

void VulkanDevice::destroy(gdi::SamplerHandle h) {
    const DeviceCall call(*this);
    if (!h) return;
    if (!samplers_.retire(h)) gdi::validate::destroyedHandle("sampler", h.id);
    retire([this, h] {
        Sampler s;
        samplers_.release(h, s);
        vkDestroySampler(device_, s.sampler, nullptr);
    });
}

void VulkanDevice::destroy(gdi::ShaderHandle h) {
    const DeviceCall call(*this);
    Shader s;
    if (!h) return;
    if (!shaders_.remove(h, s)) gdi::validate::destroyedHandle("shader", h.id);
    vkDestroyShaderModule(device_, s.module, nullptr);  // pipelines keep their own copy of the code
}

void VulkanDevice::destroy(gdi::PipelineHandle h) {
    const DeviceCall call(*this);
    if (!h) return;
    if (!pipelines_.retire(h)) gdi::validate::destroyedHandle("pipeline", h.id);
    retire([this, h] {
        Pipeline p;
        pipelines_.release(h, p);
        for (const Pipeline& unused : sharedPipelines_.release(p.sharedKey))
            destroyPipelineObjects(unused);
    });
}

void VulkanDevice::destroy(gdi::TimerHandle h) {
    const DeviceCall call(*this);
    if (!h) return;
    if (!timers_.retire(h)) gdi::validate::destroyedHandle("timer", h.id);
    retire([this, h] {
        Timer t;
        timers_.release(h, t);
        freeTimerSlots_.push_back(t.firstQuery);
    });
}

gdi::QuerySetHandle VulkanDevice::createQuerySet(const gdi::QuerySetDesc& desc) {
    const DeviceCall call(*this);
    loss_.check("createQuerySet");
    gdi::validate::querySetDesc(desc, info_.features);
    QuerySet q;
    q.desc = desc;
    q.name = desc.debugName ? desc.debugName : "";
    q.desc.debugName = nullptr;
    q.submitted.assign(desc.count, 0);
    VkQueryPoolCreateInfo ci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    ci.queryCount = desc.count;
    switch (desc.type) {
        case gdi::QueryType::Occlusion:
        case gdi::QueryType::AnySamplesPassed:
            ci.queryType = VK_QUERY_TYPE_OCCLUSION;
            break;
        case gdi::QueryType::Timestamp:
            ci.queryType = VK_QUERY_TYPE_TIMESTAMP;
            break;
        case gdi::QueryType::PipelineStatistics:
            ci.queryType = VK_QUERY_TYPE_PIPELINE_STATISTICS;
            // Results come in bit order: primitives, vertex, fragment, compute (PipelineStatistics).
            ci.pipelineStatistics = VK_QUERY_PIPELINE_STATISTIC_INPUT_ASSEMBLY_PRIMITIVES_BIT |
                                    VK_QUERY_PIPELINE_STATISTIC_VERTEX_SHADER_INVOCATIONS_BIT |
                                    VK_QUERY_PIPELINE_STATISTIC_FRAGMENT_SHADER_INVOCATIONS_BIT |
                                    VK_QUERY_PIPELINE_STATISTIC_COMPUTE_SHADER_INVOCATIONS_BIT;
            break;
    }
    check(nativeAllocation("vkCreateQueryPool",
                           [&] { return vkCreateQueryPool(device_, &ci, nullptr, &q.pool); }),
          "vkCreateQueryPool", q.name);
    vkResetQueryPool(device_, q.pool, 0, desc.count);
    setName(VK_OBJECT_TYPE_QUERY_POOL, uint64_t(q.pool), desc.debugName);
    return querySets_.add(std::move(q));
}

void VulkanDevice::destroy(gdi::QuerySetHandle h) {
    const DeviceCall call(*this);
    if (!h) return;
    if (!querySets_.retire(h)) gdi::validate::destroyedHandle("query set", h.id);
    retire([this, h] {
        QuerySet q;
        querySets_.release(h, q);
        vkDestroyQueryPool(device_, q.pool, nullptr);
    });
}

bool VulkanDevice::queryResults(gdi::QuerySetHandle h, uint32_t first, uint32_t count,
                                std::span<uint64_t> out) {
    const DeviceCall call(*this);
    loss_.check("queryResults");
    QuerySet& q = querySets_.get(h, "query set");
    gdi::validate::queryRead(q.desc, q.name, first, count, out.size());
    pollFences();
    for (uint32_t i = first; i < first + count; ++i)
        if (q.submitted[i] == 0 || q.submitted[i] > completed_) return false;
    const uint32_t values = gdi::validate::queryValues(q.desc.type);
    const VkResult r = vkGetQueryPoolResults(device_, q.pool, first, count, count * values * 8,
                                             out.data(), values * 8, VK_QUERY_RESULT_64_BIT);
    if (r == VK_NOT_READY) return false;
    check(r, "vkGetQueryPoolResults", q.name);
    for (uint32_t i = 0; i < count * values; ++i) {
        if (q.desc.type == gdi::QueryType::Timestamp)
            out[i] = uint64_t(double(out[i]) * double(props_.limits.timestampPeriod));
        else if (q.desc.type == gdi::QueryType::AnySamplesPassed)
            out[i] = out[i] != 0;
    }
    return true;
}

}  // namespace fe::vk

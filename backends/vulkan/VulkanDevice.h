// The Vulkan implementation of gdi::Device (layer 3: how gdi objects are represented in Vulkan).
//
// Design choices, each for a reason:
//  - Dynamic rendering (Vulkan 1.3 / VK_KHR_dynamic_rendering): no VkRenderPass/VkFramebuffer
//    objects to cache; a gdi render pass maps 1:1 onto vkCmdBeginRendering.
//  - Push descriptors (VK_KHR_push_descriptor): gdi's flat slot bindings are written at draw
//    time with no descriptor pools or set lifetimes to manage.
//  - Every image lives in VK_IMAGE_LAYOUT_GENERAL after creation, and hazards between passes,
//    dispatches and copies are covered by one full memory barrier whenever the previous
//    command wrote something. Coarse but provably correct; the render graph (layer 6) knows
//    exact read/write sets and is where finer barriers belong.
#pragma once
#include <vulkan/vulkan.h>

#include <array>
#include <atomic>
#include <mutex>
#include <deque>
#include <functional>
#include <memory>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "VulkanFaults.h"
#include "VulkanMemory.h"
#include "fe/gdi/LiveLists.h"
#include "fe/gdi/Device.h"
#include "fe/gdi/ExclusiveUse.h"
#include "fe/gdi/Validation.h"
#include "fe/gdi/HandlePool.h"
#include "fe/gdi/MessageLog.h"
#include "fe/gdi/PipelineSharing.h"

namespace fe::vk {

// Error for a failed call; `object` names what it was for. VK_ERROR_DEVICE_LOST: DeviceLostError.
[[noreturn]] void throwVk(VkResult r, const char* what, const std::string& object = {});
inline void check(VkResult r, const char* what, const std::string& object = {}) {
    if (r != VK_SUCCESS) throwVk(r, what, object);
}

VkFormat toVkFormat(gdi::Format f);
VkFormat toVkVertexFormat(gdi::VertexFormat f);
VkImageAspectFlags aspectOf(gdi::Format f);
// The aspect views, copies and readback address: depth only for depth/stencil formats.
VkImageAspectFlags viewAspectOf(gdi::Format f);
// Buffer <-> image copy region of one subresource (3D: `layer` is the depth slice).
VkBufferImageCopy copyRegion(const gdi::TextureDesc& d, gdi::Subresource at,
                             VkDeviceSize bufferOffset);
uint32_t arrayLayers(const gdi::TextureDesc& d);  // Vulkan array layers (1 for 3D)
// A resolved region (validate::textureRegion) and layout (validate::texelLayout) as a copy.
VkBufferImageCopy regionCopy(const gdi::TextureDesc& d, const gdi::TextureRegion& r,
                             const gdi::TexelLayout& l);
VkImageCopy imageCopy(const gdi::TextureDesc& dst, const gdi::TextureRegion& d,
                      const gdi::TextureDesc& src, const gdi::TextureRegion& s);

struct Buffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    Allocation memory;
    gdi::BufferDesc desc;
    std::string name;
};

struct Texture {
    VkImage image = VK_NULL_HANDLE;
    bool ownsMemory = true;  // false when placed in a Heap
    VkImageView view =
        VK_NULL_HANDLE;  // every mip and layer, of the texture's dimension: for sampling
    std::vector<VkImageView>
        mipViews;  // one per mip, every layer, same view type: for storage images
    // One 2D view per (mip, layer), made on first use as an attachment: index mip * layers + layer.
    std::vector<VkImageView> attachmentViews;
    Allocation memory;
    gdi::TextureDesc desc;
    std::string name;
    bool linearFilter = false;  // FormatCaps::linearFilter of its format
    // Views (createTextureView): the texture's image seen from baseMip and baseLayer on; the
    // image and memory are the texture's (viewOf), which counts its live views.
    uint32_t viewOf = 0;
    uint32_t baseMip = 0, baseLayer = 0;
    uint32_t views = 0;
};

struct Sampler {
    VkSampler sampler = VK_NULL_HANDLE;
    bool filtersLinearly =
        false;               // a Linear filter without comparison: needs FormatCaps::linearFilter
    bool readsMips = false;  // a MipFilter other than None: reads more than the base mip
    std::string name;
};

struct Shader {
    VkShaderModule module = VK_NULL_HANDLE;
    gdi::ShaderStage stage = gdi::ShaderStage::None;
    std::string name;
    std::string entry;
    gdi::ShaderInterface iface;  // reflected: pipelines are checked against it
    uint64_t codeHash = 0;       // its code, entry point and stage: pipeline keys name it so
};

struct Pipeline {
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    VkPipelineBindPoint bindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    std::vector<gdi::BindingSlot> bindings;
    uint64_t requiredSlots = 0;
    // Per slot: the descriptor write flushBindings copies (type, binding; pointers filled at
    // flush time), so the per-draw path does no translation.
    std::array<VkWriteDescriptorSet, 64> writeTemplates{};
    std::array<uint64_t, 2> bufferSlots{};  // per kind (uniform, storage): the slots of that kind
    gdi::validate::PassSignature
        signature;  // attachment formats and samples, checked at setPipeline
    bool writesDepthStencil =
        false;  // validate::writesDepthStencil: may not sample its depth attachment
    std::vector<gdi::validate::VertexBinding> vertexBindings;  // what each draw checks it may read
    std::array<uint8_t, 64>
        slotDimensions{};  // validate::slotDimensions: the texture kind a slot takes
    std::array<uint32_t, 64> slotBlockBytes{};  // validate::slotBlockBytes (validation mode)
    // Dynamic state set to the pipeline's values by setPipeline (CommandList may change it).
    std::array<float, 4> blendConstant{};
    uint8_t stencilReference = 0;
    std::array<float, 3> depthBias{};  // constant, slope, clamp
    uint32_t constantBytes = 0;        // the shaders' constants block (push-constant range)
    VkShaderStageFlags constantStages = 0;
    std::string name;
    std::string sharedKey;  // PipelineSharing.h: the native objects are shared by this key
};

struct Timer {
    uint32_t firstQuery = 0;
    gdi::FenceValue submitted = 0;  // the submission that last used it (0: none)
};

struct QuerySet {
    VkQueryPool pool = VK_NULL_HANDLE;
    gdi::QuerySetDesc desc;
    std::string name;
    std::vector<gdi::FenceValue>
        submitted;  // per query: the submission that last wrote it (0: none)
};

struct Heap {
    Allocation memory;
    uint64_t size = 0;
    uint32_t placed = 0;  // live textures placed in it
    std::string name;
};

class VulkanCommandList;
class VulkanSwapchain;

class VulkanDevice final : public gdi::Device {
public:
    // `window`: the vulkan-glfw backend (VulkanSwapchain.h); null: headless.
    explicit VulkanDevice(bool validation, std::unique_ptr<VulkanSwapchain> window = nullptr,
                          bool robustBufferAccess = false);
    ~VulkanDevice() override;

    const gdi::DeviceInfo& info() const override { return info_; }
#include "fe/gdi/DeviceOverrides.inc"

    void destroy(gdi::HeapHandle) override;

    const gdi::BufferDesc& desc(gdi::BufferHandle h) const override {
        return buffers_.get(h, "buffer").desc;
    }
    const gdi::TextureDesc& desc(gdi::TextureHandle h) const override {
        return textures_.get(h, "texture").desc;
    }
    const gdi::ShaderInterface& shaderInterface(gdi::ShaderHandle h) const override {
        return shaders_.get(h, "shader").iface;
    }

    uint32_t validationErrorCount() const override { return validationErrors_.load(); }
    gdi::InputState input() const override;

    // Internal, for the command list.
    Buffer& buffer(gdi::BufferHandle h) { return buffers_.get(h, "buffer"); }
    const Buffer* findBuffer(gdi::BufferHandle h) const {
        return buffers_.find(h);
    }  // null if invalid
    Texture& texture(gdi::TextureHandle h) { return textures_.get(h, "texture"); }
    const Texture* findTexture(gdi::TextureHandle h) const { return textures_.find(h); }
    const Sampler* findSampler(gdi::SamplerHandle h) const { return samplers_.find(h); }
    const Pipeline* findPipeline(gdi::PipelineHandle h) const { return pipelines_.find(h); }
    const Timer* findTimer(gdi::TimerHandle h) const { return timers_.find(h); }
    const QuerySet* findQuerySet(gdi::QuerySetHandle h) const { return querySets_.find(h); }
    QuerySet& querySet(gdi::QuerySetHandle h) { return querySets_.get(h, "query set"); }
    // How many destroy() calls so far (a list compares it at submit with its value at start).
    uint64_t destroyEpoch() const { return destroyEpoch_.load(std::memory_order_acquire); }
    gdi::LiveLists<VulkanCommandList>& liveLists() { return liveLists_; }
    // A command buffer being recorded holds native handles of what it uses, and Vulkan forbids
    // recording on after one of them is destroyed (GL records nothing native before submit). So
    // a destroyed object's native release waits until every recording open since before its
    // destroy is closed: submitted, executed by a primary, or dropped with its list. Its submit
    // is refused the same on every backend (destroyedBeforeSubmit). `since`: the destroy epoch of
    // the list's state, taken before any of its lookups.
    void openRecording(uint64_t since);
    void closeRecording(uint64_t since);  // also runs the releases it no longer holds back
    // Whether the submission has completed, without waiting; a lost device's work counts as done.
    bool completedNoThrow(gdi::FenceValue fence);
    Sampler& sampler(gdi::SamplerHandle h) { return samplers_.get(h, "sampler"); }
    Pipeline& pipeline(gdi::PipelineHandle h) { return pipelines_.get(h, "pipeline"); }
    Timer& timer(gdi::TimerHandle h) { return timers_.get(h, "timer"); }
    VkDevice vkDevice() const { return device_; }
    VkQueryPool queryPool() const { return queryPool_; }
    PFN_vkCmdPushDescriptorSetKHR cmdPushDescriptorSet = nullptr;
    PFN_vkCmdBeginDebugUtilsLabelEXT cmdBeginLabel = nullptr;
    PFN_vkCmdEndDebugUtilsLabelEXT cmdEndLabel = nullptr;
    PFN_vkCmdInsertDebugUtilsLabelEXT cmdInsertLabel = nullptr;
    uint32_t queueFamily(gdi::QueueKind q) const { return queues_[size_t(q)].family; }
    bool linearBlit(gdi::Format format) const;
    gdi::FormatCaps formatCaps(
        gdi::Format format) const override;  // vkCmdBlitImage with VK_FILTER_LINEAR works
    // The 2D view of one subresource, for attachments (made on first use, kept with the texture).
    VkImageView attachmentView(Texture& t, uint32_t mipLevel, uint32_t layer);
    PFN_vkCmdDrawIndirectCount cmdDrawIndirectCount = nullptr;
    PFN_vkCmdDrawIndexedIndirectCount cmdDrawIndexedIndirectCount = nullptr;
    // Secondary command buffers, one pool each, shared by every list of the device: a primary
    // list that executes one owns it until its submission, so a secondary list never waits for
    // the primary's work and may be destroyed right after executeSecondary.
    struct SecondaryRecording {
        VkCommandPool pool = VK_NULL_HANDLE;
        VkCommandBuffer cb = VK_NULL_HANDLE;
        gdi::FenceValue fence = 0;  // of the submission that ran it; 0: none pending
        std::thread::id
            recordedOn;  // a recording goes back to its thread: malloc arenas stay local
    };
    SecondaryRecording acquireSecondary();  // reset, ready to begin
    void releaseSecondary(std::span<const SecondaryRecording> recordings, gdi::FenceValue fence);
    // wait(), except that a lost device is recorded, not thrown (the next entry point throws):
    // for destruction and recording, which must work on a lost device.
    void settle(gdi::FenceValue fence);

    static VKAPI_ATTR VkBool32 VKAPI_CALL debugCallback(
        VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT type,
        const VkDebugUtilsMessengerCallbackDataEXT* data, void* user);

private:
    void createInstance(bool validation);
    void pickPhysicalDevice();
    void createLogicalDevice();
    void fillInfo();
    void setName(VkObjectType type, uint64_t object, const char* name);
    VkImageView makeView(VkImage image, VkImageViewType type, gdi::Format format,
                         VkImageSubresourceRange range, const std::string& object,
                         VkComponentMapping swizzle = {});
    // Records with `record` into a one-time command buffer, submits it and waits.
    // Records, submits and waits for a one-off command buffer; `object` names it in errors.
    void immediate(const std::string& object, const std::function<void(VkCommandBuffer)>& record);
    // The first commands of new objects (a texture's layout transition and zero clear, a
    // buffer's zero fill, query resets), kept as closures until the next submission or transfer
    // records them, with one barrier after them all, into a command buffer that goes in front.
    // An object destroyed before then drops its own: a texture made and destroyed between two
    // submissions costs no GPU work and is freed at once.
    struct InitialCommands {
        uint32_t texture = 0, buffer = 0;  // the object they are for (0: none)
        std::function<void(VkCommandBuffer)> record;
    };
    void recordInitialTransition(std::function<void(VkCommandBuffer)> record, uint32_t texture = 0,
                                 uint32_t buffer = 0);
    void dropInitialCommands(uint32_t texture, uint32_t buffer);
    static void clearToZero(VkCommandBuffer cb, VkImage image, gdi::Format format);
    // Ended, ready to submit; null when none. `object`: what errors name (the transfer's object).
    VkCommandBuffer takeInitialTransitions(
        const std::string& object = "first commands of new objects");
    void freeAfter(gdi::FenceValue fence, VkCommandBuffer cb);
    std::vector<InitialCommands> pendingInit_;
    // kind and name say what the buffer is in errors (gdi::describeObject).
    Buffer makeBuffer(VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage mem,
                      const char* kind, const std::string& name);
    void freeBuffer(Buffer& b);
    void release();
    // VkResults of the device's own calls: vk::check, and VK_ERROR_DEVICE_LOST marks the device
    // lost. As members they hide the free check() in every VulkanDevice member function.
    void check(VkResult r, const char* call, const std::string& object = {}) const {
        if (r != VK_SUCCESS) [[unlikely]]
            fail(r, call, object);
    }
    [[noreturn]] void fail(VkResult r, const char* call, const std::string& object) const;
    void idle();  // destroy's wait: settle() everything
    // Deferred destruction: `release` runs once every submission made so far has completed.
    void retire(std::function<void()> release);
    void collectRetired();     // runs the releases whose submissions have completed
    void releaseRetiredNow();  // waits for the queue (pending transitions included), releases all
    void pollFences();         // completes finished submissions without waiting
    struct Retired {
        gdi::FenceValue after;
        uint64_t epoch;  // the destroy's: recordings open since before it hold the release back
        std::function<void()> release;
    };
    std::deque<Retired> retired_;
    bool heldByRecording(uint64_t epoch) const {
        return !openRecordings_.empty() && *openRecordings_.begin() < epoch;
    }
    std::multiset<uint64_t> openRecordings_;         // the `since` of each open recording
    gdi::MessageLog messages_{"Vulkan validation"};  // each message once; repeats counted
    std::vector<SecondaryRecording> secondaries_;    // free, or pending until their fence
    // present() copies through the swap chain's own submissions, which no device fence covers:
    // the next destroy waits for the queue, as every destroy did before deferred release.
    bool presentedSinceIdle_ = false;
    std::atomic<uint64_t> destroyEpoch_{0};
    gdi::LiveLists<VulkanCommandList> liveLists_;  // lists to orphan when the device goes first
    // One lock for everything but recording: creation, destruction, transfers, submission and
    // fences, attachment views made while recording. Recursive: transfers wait through waitIdle.
    mutable std::recursive_mutex mutex_;
    // Every device call: the validation layer's lock (gdi::NativeLayerLock, shared) when the layer
    // is loaded, then this device's mutex.
    class DeviceCall {
    public:
        explicit DeviceCall(const VulkanDevice& d)
            : layer_(d.info_.features.validation), lock_(d.mutex_) {}

    private:
        gdi::NativeLayerLock::Call layer_;
        std::lock_guard<std::recursive_mutex> lock_;
    };

    gdi::DeviceInfo info_;
    std::unique_ptr<VulkanSwapchain> swapchain_;  // vulkan-glfw only
    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    bool debugUtils_ = false;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties props_{};
    bool anisotropy_ = false;
    bool robustRequested_ = false;        // DeviceCreateDesc::robustBufferAccess
    VkPhysicalDeviceFeatures enabled_{};  // the core features the device was created with
    bool drawIndirectCount_ = false;
    VkDevice device_ = VK_NULL_HANDLE;
    uint32_t queueFamily_ = 0;        // the graphics queue's (queues_[Graphics])
    VkQueue queue_ = VK_NULL_HANDLE;  // the graphics queue, which also presents
    // The three queues of Device.h's "Queues", by QueueKind. Compute and copy take a family or a
    // queue of their own where the device has one (DeviceFeatures::asyncCompute/asyncCopy), else
    // the graphics VkQueue. Each logical queue signals its timeline semaphore with the fence
    // value of each of its submissions; a SubmitDesc::waitFor waits on the others' timelines.
    struct QueueSlot {
        VkQueue queue = VK_NULL_HANDLE;
        uint32_t family = 0;
        uint32_t index = 0;
        VkSemaphore timeline = VK_NULL_HANDLE;
    };
    std::array<QueueSlot, 3> queues_;
    // Objects' first commands (clears, query resets: pendingInit_) always run on the graphics
    // queue; before another queue's submission they are a graphics submission of their own,
    // which signals this timeline, and every compute or copy submission waits for its last value.
    VkSemaphore initTimeline_ = VK_NULL_HANDLE;
    uint64_t initSignalled_ = 0;
    // The distinct families of queues_: resources are VK_SHARING_MODE_CONCURRENT over them when
    // there are several (images stay in GENERAL, so no layout or ownership moves between them).
    std::vector<uint32_t> sharingFamilies_;
    void chooseQueues(const std::vector<VkQueueFamilyProperties>& families);
    void createQueueTimelines();
    void settleOtherQueues();
    // EXCLUSIVE with one queue family; CONCURRENT over sharingFamilies_ with several.
    template <class CreateInfo>
    void setSharing(CreateInfo& ci) const {
        const bool several = sharingFamilies_.size() > 1;
        ci.sharingMode = several ? VK_SHARING_MODE_CONCURRENT : VK_SHARING_MODE_EXCLUSIVE;
        ci.queueFamilyIndexCount = several ? uint32_t(sharingFamilies_.size()) : 0;
        ci.pQueueFamilyIndices = several ? sharingFamilies_.data() : nullptr;
    }
    void submitInitialCommands(VkCommandBuffer init);
    gdi::FenceValue lastInFlightOn(gdi::QueueKind q, gdi::FenceValue atMost) const;
    std::unique_ptr<MemoryAllocator> allocator_;
    VkCommandPool immediatePool_ = VK_NULL_HANDLE;
    VkQueryPool queryPool_ = VK_NULL_HANDLE;
    static constexpr uint32_t kMaxTimers = 512;
    std::vector<uint32_t> freeTimerSlots_;
    PFN_vkSetDebugUtilsObjectNameEXT setObjectName_ = nullptr;
    std::atomic<uint32_t> validationErrors_{0};  // the layer calls back on recording threads too
    mutable gdi::DeviceLoss loss_;
    uint32_t nativeObjects_ =
        0;  // VkBuffers and VkImages of buffers, textures and staging (liveObjects)

    struct Submission {
        gdi::FenceValue value;
        VkFence fence;
        gdi::QueueKind queue = gdi::QueueKind::Graphics;
    };
    std::deque<Submission> inFlight_;
    std::vector<VkFence> freeFences_;
    gdi::FenceValue nextFence_ = 1;
    gdi::FenceValue completed_ = 0;

    const uint32_t handleSalt_ = gdi::nextHandleSalt();  // before the pools it salts
    gdi::HandlePool<gdi::BufferHandle, Buffer> buffers_{handleSalt_};
    gdi::HandlePool<gdi::TextureHandle, Texture> textures_{handleSalt_};
    gdi::HandlePool<gdi::SamplerHandle, Sampler> samplers_{handleSalt_};
    gdi::HandlePool<gdi::ShaderHandle, Shader> shaders_{handleSalt_};
    gdi::HandlePool<gdi::PipelineHandle, Pipeline> pipelines_{
        handleSalt_};  // command lists point at the bound one (objects never move)
    // Native pipelines by key, shared by equal pipelines and kept a while when unused.
    gdi::SharedPipelines<Pipeline> sharedPipelines_;
    void destroyPipelineObjects(const Pipeline& p);
    gdi::PipelineHandle addShared(Pipeline p, const std::string& key);
    uint64_t codeHash(gdi::ShaderHandle h) const {
        const Shader* s = h ? shaders_.find(h) : nullptr;
        return s ? s->codeHash : 0;
    }
    gdi::HandlePool<gdi::TimerHandle, Timer> timers_{handleSalt_};
    gdi::HandlePool<gdi::HeapHandle, Heap> heaps_{handleSalt_};
    gdi::HandlePool<gdi::QuerySetHandle, QuerySet> querySets_{handleSalt_};
    VkPipelineCache pipelineCache_ = VK_NULL_HANDLE;
    gdi::PipelineCacheStats cacheStats_;
    void countCacheUse(const VkPipelineCreationFeedback& feedback);
    VkImageCreateInfo imageInfo(const gdi::TextureDesc& desc) const;
    void destroyTexture(Texture& t);
};

}  // namespace fe::vk

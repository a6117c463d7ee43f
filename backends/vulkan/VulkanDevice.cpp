// Instance, physical/logical device, queue submission and blocking transfers.
#include "VulkanDevice.h"
#include "VulkanFaults.h"

#include <algorithm>
#include <utility>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <mutex>

#include "VulkanBackend.h"
#include "VulkanCommandList.h"
#include "VulkanSwapchain.h"
#include "fe/gdi/ExclusiveUse.h"
#include "fe/gdi/PipelineCacheFile.h"
#include "fe/gdi/Validation.h"

namespace fe::vk {

namespace {
constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

bool hasLayer(const char* name) {
    uint32_t n = 0;
    vkEnumerateInstanceLayerProperties(&n, nullptr);
    std::vector<VkLayerProperties> layers(n);
    vkEnumerateInstanceLayerProperties(&n, layers.data());
    return std::any_of(layers.begin(), layers.end(),
                       [&](auto& l) { return std::strcmp(l.layerName, name) == 0; });
}

// `layer`: an extension the layer provides (null: the loader's and drivers').
bool hasInstanceExtension(const char* name, const char* layer = nullptr) {
    uint32_t n = 0;
    vkEnumerateInstanceExtensionProperties(layer, &n, nullptr);
    std::vector<VkExtensionProperties> ext(n);
    vkEnumerateInstanceExtensionProperties(layer, &n, ext.data());
    return std::any_of(ext.begin(), ext.end(),
                       [&](auto& e) { return std::strcmp(e.extensionName, name) == 0; });
}

bool hasDeviceExtension(VkPhysicalDevice pd, const char* name) {
    uint32_t n = 0;
    vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, nullptr);
    std::vector<VkExtensionProperties> ext(n);
    vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, ext.data());
    return std::any_of(ext.begin(), ext.end(),
                       [&](auto& e) { return std::strcmp(e.extensionName, name) == 0; });
}

// Runs `f` when the scope ends, however it ends (staging buffers of transfers that may throw).
template <class F>
struct OnExit {
    F f;
    ~OnExit() { f(); }
};
template <class F>
OnExit(F) -> OnExit<F>;

std::string versionString(uint32_t v) {
    return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) +
           "." + std::to_string(VK_API_VERSION_PATCH(v));
}
}  // namespace

std::unique_ptr<gdi::Device> createVulkanDevice(bool validation, bool robustBufferAccess) {
    return std::make_unique<VulkanDevice>(validation, nullptr, robustBufferAccess);
}

VKAPI_ATTR VkBool32 VKAPI_CALL VulkanDevice::debugCallback(
    VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
    const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    auto* device = static_cast<VulkanDevice*>(user);
    const char* message = data && data->pMessage ? data->pMessage : "";
    if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
        device->validationErrors_++;
        device->messages_.report("error", message);
    } else if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
        device->messages_.report("warning", message);
    }
    return VK_FALSE;
}

VulkanDevice::VulkanDevice(bool validation, std::unique_ptr<VulkanSwapchain> window,
                           bool robustBufferAccess)
    : swapchain_(std::move(window)), robustRequested_(robustBufferAccess) {
    const gdi::NativeLayerLock::Change layerChange(
        validation);  // the layer adds this device and instance
    try {
        createInstance(validation);
        pickPhysicalDevice();
        createLogicalDevice();
        fillInfo();
    } catch (...) {
        release();  // the destructor does not run when the constructor throws
        throw;
    }
}

void VulkanDevice::createInstance(bool validation) {
    uint32_t loaderVersion = 0;
    if (vkEnumerateInstanceVersion(&loaderVersion) != VK_SUCCESS ||
        loaderVersion < VK_API_VERSION_1_2)
        throw gdi::Error("Vulkan: loader reports version " + versionString(loaderVersion) +
                         ", 1.2 or newer is required");
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "fe";
    app.pEngineName = "Fools Engine";
    app.apiVersion = VK_API_VERSION_1_3;

    std::vector<const char*> layers, extensions;
    if (validation) {
        if (!hasLayer(kValidationLayer))
            throw gdi::Error(
                "Vulkan: validation requested but VK_LAYER_KHRONOS_validation is not installed (apt-get install "
                "vulkan-validationlayers)");
        layers.push_back(kValidationLayer);
    }
    debugUtils_ = hasInstanceExtension(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    if (debugUtils_) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    if (swapchain_)
        for (const char* e : swapchain_->instanceExtensions()) extensions.push_back(e);

    VkDebugUtilsMessengerCreateInfoEXT mci{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    mci.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT |
                          VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT;
    // Performance messages are left out: they flag the GENERAL layout policy on every use.
    mci.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                      VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
    mci.pfnUserCallback = &VulkanDevice::debugCallback;
    mci.pUserData = this;

    VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ci.pApplicationInfo = &app;
    ci.enabledLayerCount = uint32_t(layers.size());
    ci.ppEnabledLayerNames = layers.data();
    ci.enabledExtensionCount = uint32_t(extensions.size());
    ci.ppEnabledExtensionNames = extensions.data();
    if (validation && debugUtils_) ci.pNext = &mci;  // also catches instance creation messages
    // With validation, synchronization validation too: a missing or wrong barrier (a hazard) is
    // reported as an error like any other, so tests fail on it. FE_VK_SYNC_VALIDATION=0 turns
    // it off (it slows recording down).
    const VkValidationFeatureEnableEXT sync =
        VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    const char* syncSetting = std::getenv("FE_VK_SYNC_VALIDATION");
    if (validation && !(syncSetting && std::string(syncSetting) == "0") &&
        hasInstanceExtension(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME, kValidationLayer)) {
        extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
        ci.enabledExtensionCount = uint32_t(extensions.size());
        ci.ppEnabledExtensionNames = extensions.data();
        features.enabledValidationFeatureCount = 1;
        features.pEnabledValidationFeatures = &sync;
        features.pNext = ci.pNext;
        ci.pNext = &features;
    }
    check(nativeAllocation("vkCreateInstance",
                           [&] { return vkCreateInstance(&ci, nullptr, &instance_); }),
          "vkCreateInstance");

    if (debugUtils_) {
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
        if (validation && create)
            check(create(instance_, &mci, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");
        setObjectName_ = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
            vkGetInstanceProcAddr(instance_, "vkSetDebugUtilsObjectNameEXT"));
        cmdBeginLabel = reinterpret_cast<PFN_vkCmdBeginDebugUtilsLabelEXT>(
            vkGetInstanceProcAddr(instance_, "vkCmdBeginDebugUtilsLabelEXT"));
        cmdEndLabel = reinterpret_cast<PFN_vkCmdEndDebugUtilsLabelEXT>(
            vkGetInstanceProcAddr(instance_, "vkCmdEndDebugUtilsLabelEXT"));
        cmdInsertLabel = reinterpret_cast<PFN_vkCmdInsertDebugUtilsLabelEXT>(
            vkGetInstanceProcAddr(instance_, "vkCmdInsertDebugUtilsLabelEXT"));
    }
    info_.features.validation = validation;
    if (swapchain_) swapchain_->createSurface(instance_);
}

void VulkanDevice::pickPhysicalDevice() {
    uint32_t n = 0;
    vkEnumeratePhysicalDevices(instance_, &n, nullptr);
    if (n == 0)
        throw gdi::Error(
            "Vulkan: no physical device (no ICD installed? apt-get install mesa-vulkan-drivers)");
    std::vector<VkPhysicalDevice> devices(n);
    vkEnumeratePhysicalDevices(instance_, &n, devices.data());
    std::string rejected;
    int bestScore = -1;
    for (VkPhysicalDevice pd : devices) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(pd, &p);
        std::string why;
        if (p.apiVersion < VK_API_VERSION_1_3 &&
            !hasDeviceExtension(pd, VK_KHR_DYNAMIC_RENDERING_EXTENSION_NAME))
            why = "no dynamic rendering";
        if (p.apiVersion < VK_API_VERSION_1_2)
            why = "Vulkan " + versionString(p.apiVersion) + " < 1.2";
        if (!hasDeviceExtension(pd, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME))
            why = "no VK_KHR_push_descriptor";
        if (swapchain_ && !hasDeviceExtension(pd, VK_KHR_SWAPCHAIN_EXTENSION_NAME))
            why = "no VK_KHR_swapchain";
        uint32_t qn = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(pd, &qn, nullptr);
        std::vector<VkQueueFamilyProperties> qf(qn);
        vkGetPhysicalDeviceQueueFamilyProperties(pd, &qn, qf.data());
        int family = -1;
        for (uint32_t i = 0; i < qn; ++i)
            if ((qf[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) &&
                (qf[i].queueFlags & VK_QUEUE_COMPUTE_BIT) &&
                (!swapchain_ || swapchain_->canPresent(pd, i))) {  // one queue draws and presents
                family = int(i);
                break;
            }
        if (family < 0)
            why = swapchain_ ? "no graphics+compute queue that can present to the window"
                             : "no graphics+compute queue";
        if (!why.empty()) {
            rejected += std::string("; ") + p.deviceName + ": " + why;
            continue;
        }
        int score = p.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU     ? 4
                    : p.deviceType == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU ? 3
                    : p.deviceType == VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU    ? 2
                                                                             : 1;
        if (score > bestScore) {
            bestScore = score;
            physical_ = pd;
            props_ = p;
            queueFamily_ = uint32_t(family);
        }
    }
    if (!physical_) throw gdi::Error("Vulkan: no suitable device" + rejected);
}

// Compute and copy prefer a family of their own (NVIDIA: a compute-only and a transfer-only
// family), then another queue of a family in use, and share the graphics queue when the device
// has no more (lavapipe: one queue). A transfer family must copy any region (granularity 1).
void VulkanDevice::chooseQueues(const std::vector<VkQueueFamilyProperties>& families) {
    std::vector<uint32_t> used(families.size(), 0);
    queues_[0] = {.family = queueFamily_, .index = 0};
    used[queueFamily_] = 1;
    auto pick = [&](VkQueueFlags need, VkQueueFlags without) -> QueueSlot {
        for (uint32_t f = 0; f < families.size(); ++f) {
            const VkExtent3D g = families[f].minImageTransferGranularity;
            if ((families[f].queueFlags & need) == need && !(families[f].queueFlags & without) &&
                used[f] < families[f].queueCount && g.width == 1 && g.height == 1 && g.depth == 1)
                return {.family = f, .index = used[f]++};
        }
        for (uint32_t f = 0; f < families.size(); ++f)  // another queue of a family in use
            if ((families[f].queueFlags & need) == need && used[f] &&
                used[f] < families[f].queueCount)
                return {.family = f, .index = used[f]++};
        return queues_[0];
    };
    queues_[1] = pick(VK_QUEUE_COMPUTE_BIT, VK_QUEUE_GRAPHICS_BIT);
    queues_[2] = pick(VK_QUEUE_TRANSFER_BIT, VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT);
    sharingFamilies_.clear();
    for (const QueueSlot& q : queues_)
        if (std::find(sharingFamilies_.begin(), sharingFamilies_.end(), q.family) ==
            sharingFamilies_.end())
            sharingFamilies_.push_back(q.family);
}

void VulkanDevice::createQueueTimelines() {
    VkSemaphoreTypeCreateInfo type{VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO};
    type.semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE;
    VkSemaphoreCreateInfo ci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    ci.pNext = &type;
    for (VkSemaphore* s :
         {&queues_[0].timeline, &queues_[1].timeline, &queues_[2].timeline, &initTimeline_})
        check(nativeAllocation("vkCreateSemaphore",
                               [&] { return vkCreateSemaphore(device_, &ci, nullptr, s); }),
              "vkCreateSemaphore");
}

void VulkanDevice::createLogicalDevice() {
    uint32_t qn = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical_, &qn, nullptr);
    std::vector<VkQueueFamilyProperties> families(qn);
    vkGetPhysicalDeviceQueueFamilyProperties(physical_, &qn, families.data());
    chooseQueues(families);
    const float priorities[3] = {1.0f, 1.0f, 1.0f};
    std::vector<VkDeviceQueueCreateInfo> qcis;
    for (uint32_t family : sharingFamilies_) {
        VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        qci.queueFamilyIndex = family;
        for (const QueueSlot& q : queues_)
            if (q.family == family) qci.queueCount = std::max(qci.queueCount, q.index + 1);
        qci.pQueuePriorities = priorities;
        qcis.push_back(qci);
    }

    VkPhysicalDeviceFeatures supported;
    vkGetPhysicalDeviceFeatures(physical_, &supported);
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    anisotropy_ = supported.samplerAnisotropy;
    features.features.samplerAnisotropy = supported.samplerAnisotropy;
    features.features.fragmentStoresAndAtomics = supported.fragmentStoresAndAtomics;
    features.features.vertexPipelineStoresAndAtomics = supported.vertexPipelineStoresAndAtomics;
    features.features.shaderStorageImageWriteWithoutFormat =
        supported.shaderStorageImageWriteWithoutFormat;
    features.features.independentBlend = supported.independentBlend;
    features.features.imageCubeArray = supported.imageCubeArray;
    features.features.shaderStorageImageExtendedFormats =
        supported.shaderStorageImageExtendedFormats;
    features.features.depthClamp = supported.depthClamp;
    features.features.geometryShader = supported.geometryShader;
    features.features.tessellationShader = supported.tessellationShader;
    features.features.depthBiasClamp = supported.depthBiasClamp;
    features.features.multiDrawIndirect = supported.multiDrawIndirect;
    features.features.drawIndirectFirstInstance = supported.drawIndirectFirstInstance;
    features.features.textureCompressionBC = supported.textureCompressionBC;
    features.features.occlusionQueryPrecise = supported.occlusionQueryPrecise;
    features.features.pipelineStatisticsQuery = supported.pipelineStatisticsQuery;
    // Bounds checks on every buffer access cost time on hardware: only when asked for.
    features.features.robustBufferAccess = robustRequested_ && supported.robustBufferAccess;
    features.features.alphaToOne = VK_FALSE;
    enabled_ = features.features;
    VkPhysicalDeviceVulkan12Features supported12{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceFeatures2 query{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    query.pNext = &supported12;
    vkGetPhysicalDeviceFeatures2(physical_, &query);
    VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    f12.hostQueryReset = VK_TRUE;
    f12.timelineSemaphore = VK_TRUE;  // required by Vulkan 1.2: waits between queues
    f12.drawIndirectCount = supported12.drawIndirectCount;
    drawIndirectCount_ = supported12.drawIndirectCount;
    VkPhysicalDeviceDynamicRenderingFeatures dyn{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DYNAMIC_RENDERING_FEATURES};
    dyn.dynamicRendering = VK_TRUE;
    features.pNext = &f12;
    f12.pNext = &dyn;

    std::vector<const char*> extensions = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
    if (props_.apiVersion < VK_API_VERSION_1_3)
        extensions.push_back(VK_KHR_DYNAMIC_RENDERING_EXTENSION_NAME);
    if (swapchain_) extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);

    VkDeviceCreateInfo ci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    ci.pNext = &features;
    ci.queueCreateInfoCount = uint32_t(qcis.size());
    ci.pQueueCreateInfos = qcis.data();
    ci.enabledExtensionCount = uint32_t(extensions.size());
    ci.ppEnabledExtensionNames = extensions.data();
    check(nativeAllocation("vkCreateDevice",
                           [&] { return vkCreateDevice(physical_, &ci, nullptr, &device_); }),
          "vkCreateDevice");
    for (QueueSlot& q : queues_) vkGetDeviceQueue(device_, q.family, q.index, &q.queue);
    queue_ = queues_[0].queue;
    createQueueTimelines();
    cmdPushDescriptorSet = reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(
        vkGetDeviceProcAddr(device_, "vkCmdPushDescriptorSetKHR"));
    if (!cmdPushDescriptorSet) throw gdi::Error("Vulkan: vkCmdPushDescriptorSetKHR not found");
    if (drawIndirectCount_) {
        cmdDrawIndirectCount = reinterpret_cast<PFN_vkCmdDrawIndirectCount>(
            vkGetDeviceProcAddr(device_, "vkCmdDrawIndirectCount"));
        cmdDrawIndexedIndirectCount = reinterpret_cast<PFN_vkCmdDrawIndexedIndirectCount>(
            vkGetDeviceProcAddr(device_, "vkCmdDrawIndexedIndirectCount"));
        drawIndirectCount_ = cmdDrawIndirectCount && cmdDrawIndexedIndirectCount;
    }

    allocator_ = std::make_unique<MemoryAllocator>(physical_, device_);

    VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pci.flags =
        VK_COMMAND_POOL_CREATE_TRANSIENT_BIT | VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pci.queueFamilyIndex = queueFamily_;
    check(nativeAllocation(
              "vkCreateCommandPool",
              [&] { return vkCreateCommandPool(device_, &pci, nullptr, &immediatePool_); }),
          "vkCreateCommandPool");

    VkQueryPoolCreateInfo qpi{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    qpi.queryType = VK_QUERY_TYPE_TIMESTAMP;
    qpi.queryCount = kMaxTimers * 2;
    check(nativeAllocation("vkCreateQueryPool",
                           [&] { return vkCreateQueryPool(device_, &qpi, nullptr, &queryPool_); }),
          "vkCreateQueryPool");
    vkResetQueryPool(device_, queryPool_, 0, kMaxTimers * 2);
    for (uint32_t i = kMaxTimers; i-- > 0;) freeTimerSlots_.push_back(i * 2);
    VkPipelineCacheCreateInfo cci{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
    check(nativeAllocation(
              "vkCreatePipelineCache",
              [&] { return vkCreatePipelineCache(device_, &cci, nullptr, &pipelineCache_); }),
          "vkCreatePipelineCache");
    if (swapchain_) swapchain_->attach(physical_, device_, queue_, queueFamily_);
}

// The file's data seeds a new cache, which takes in what the old one holds (pipelines made
// before the call); a file that is not this device's is never handed to the driver.
gdi::PipelineCacheStats VulkanDevice::openPipelineCache(const std::string& path) {
    const DeviceCall call(*this);
    // Read first: a path refused with an Error leaves the cache as it was (GL's order too).
    const gdi::PipelineCacheLoad file =
        gdi::readPipelineCache(path, gdi::pipelineCacheIdentity(info_));
    cacheStats_ = {.path = path};
    cacheStats_.warning = file.warning;
    if (file.payload.empty()) return cacheStats_;
    VkPipelineCacheCreateInfo cci{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
    cci.initialDataSize = file.payload.size();
    cci.pInitialData = file.payload.data();
    VkPipelineCache loaded = VK_NULL_HANDLE;
    if (vkCreatePipelineCache(device_, &cci, nullptr, &loaded) != VK_SUCCESS) {
        cacheStats_.warning = "pipeline cache '" + path + "' ignored: the driver refused its data";
        return cacheStats_;
    }
    vkMergePipelineCaches(device_, loaded, 1, &pipelineCache_);
    vkDestroyPipelineCache(device_, pipelineCache_, nullptr);
    pipelineCache_ = loaded;
    cacheStats_.loaded = true;
    cacheStats_.loadedBytes = file.payload.size();
    return cacheStats_;
}

void VulkanDevice::savePipelineCache() {
    const DeviceCall call(*this);
    if (cacheStats_.path.empty()) return;
    size_t size = 0;
    check(vkGetPipelineCacheData(device_, pipelineCache_, &size, nullptr),
          "vkGetPipelineCacheData");
    std::vector<uint8_t> data(size);
    check(vkGetPipelineCacheData(device_, pipelineCache_, &size, data.data()),
          "vkGetPipelineCacheData");
    data.resize(size);
    gdi::writePipelineCache(cacheStats_.path, gdi::pipelineCacheIdentity(info_), data);
}

gdi::PipelineCacheStats VulkanDevice::pipelineCacheStats() const {
    const DeviceCall call(*this);
    gdi::PipelineCacheStats stats = cacheStats_;
    stats.shared = sharedPipelines_.sharedCount();
    return stats;
}

// Whether the pipeline just made came from the cache (VK_EXT_pipeline_creation_feedback, core
// in 1.3): counted in the stats.
void VulkanDevice::countCacheUse(const VkPipelineCreationFeedback& feedback) {
    if (!(feedback.flags & VK_PIPELINE_CREATION_FEEDBACK_VALID_BIT)) return;
    if (feedback.flags & VK_PIPELINE_CREATION_FEEDBACK_APPLICATION_PIPELINE_CACHE_HIT_BIT)
        ++cacheStats_.hits;
    else
        ++cacheStats_.misses;
}

void VulkanDevice::fillInfo() {
    info_.backend = swapchain_ ? "vulkan-glfw" : "vulkan";
    info_.deviceName = props_.deviceName;
    info_.apiVersion = "Vulkan " + versionString(props_.apiVersion);
    switch (props_.deviceType) {
        case VK_PHYSICAL_DEVICE_TYPE_CPU:
            info_.deviceType = "cpu";
            break;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
            info_.deviceType = "integrated-gpu";
            break;
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
            info_.deviceType = "discrete-gpu";
            break;
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
            info_.deviceType = "virtual-gpu";
            break;
        default:
            info_.deviceType = "other";
            break;
    }
    info_.softwareRasterizer = props_.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    const VkPhysicalDeviceLimits& l = props_.limits;
    info_.limits.maxTextureSize2D = l.maxImageDimension2D;
    info_.limits.maxTextureSize3D = l.maxImageDimension3D;
    info_.limits.maxTextureSizeCube = l.maxImageDimensionCube;
    info_.limits.maxTextureArrayLayers = l.maxImageArrayLayers;
    // Counts every render-target format supports; each is one sample-count bit, as in Vulkan.
    info_.limits.colorSampleCounts =
        l.framebufferColorSampleCounts & l.framebufferNoAttachmentsSampleCounts & 0xf;
    info_.limits.depthSampleCounts = l.framebufferDepthSampleCounts & 0xf;
    info_.limits.maxColorAttachments = l.maxColorAttachments;
    info_.limits.maxViewportSize = std::min(l.maxViewportDimensions[0], l.maxViewportDimensions[1]);
    info_.limits.maxTessellationPatchSize =
        enabled_.tessellationShader ? l.maxTessellationPatchSize : 0;
    info_.limits.viewportBounds = {l.viewportBoundsRange[0], l.viewportBoundsRange[1]};
    info_.limits.maxComputeWorkGroupInvocations = l.maxComputeWorkGroupInvocations;
    for (int axis = 0; axis < 3; ++axis)
        info_.limits.maxComputeWorkGroupCount[axis] = l.maxComputeWorkGroupCount[axis];
    info_.limits.maxStorageTextures =
        std::min(l.maxPerStageDescriptorStorageImages, l.maxDescriptorSetStorageImages);
    info_.limits.maxUniformBufferRange = l.maxUniformBufferRange;
    info_.limits.maxStorageBufferRange = l.maxStorageBufferRange;
    VkPhysicalDeviceMaintenance3Properties m3{
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES};
    // The driver's own name and version text (core in 1.2, which the device requires): the
    // packed driverVersion means nothing without the vendor's encoding.
    VkPhysicalDeviceDriverProperties driver{
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES, .pNext = &m3};
    VkPhysicalDeviceProperties2 p2{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2,
                                   .pNext = &driver};
    vkGetPhysicalDeviceProperties2(physical_, &p2);
    info_.driverName = driver.driverName;
    info_.driverInfo = driver.driverInfo;
    const VkConformanceVersion& cts = driver.conformanceVersion;
    info_.conformanceVersion = std::to_string(cts.major) + "." + std::to_string(cts.minor) + "." +
                               std::to_string(cts.subminor) + "." + std::to_string(cts.patch);
    uint32_t extensionCount = 0;
    vkEnumerateDeviceExtensionProperties(physical_, nullptr, &extensionCount, nullptr);
    std::vector<VkExtensionProperties> extensions(extensionCount);
    vkEnumerateDeviceExtensionProperties(physical_, nullptr, &extensionCount, extensions.data());
    info_.extensions.clear();
    for (uint32_t i = 0; i < extensionCount; ++i)
        info_.extensions.push_back(extensions[i].extensionName);
    std::sort(info_.extensions.begin(), info_.extensions.end());
    VkPhysicalDeviceMemoryProperties memory{};
    vkGetPhysicalDeviceMemoryProperties(physical_, &memory);
    info_.memoryHeaps.clear();
    for (uint32_t h = 0; h < memory.memoryHeapCount; ++h)
        info_.memoryHeaps.push_back(
            {.bytes = memory.memoryHeaps[h].size,
             .deviceLocal = (memory.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) != 0});
    VkDeviceSize largestHeap = 0;
    for (uint32_t h = 0; h < memory.memoryHeapCount; ++h)
        largestHeap = std::max(largestHeap, memory.memoryHeaps[h].size);
    info_.limits.maxAllocationSize = std::min(m3.maxMemoryAllocationSize, largestHeap);
    info_.limits.uniformBufferOffsetAlignment = uint32_t(l.minUniformBufferOffsetAlignment);
    info_.limits.storageBufferOffsetAlignment = uint32_t(l.minStorageBufferOffsetAlignment);
    info_.limits.timestampPeriodNs = l.timestampPeriod;
    uint32_t qn = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical_, &qn, nullptr);
    std::vector<VkQueueFamilyProperties> qf(qn);
    vkGetPhysicalDeviceQueueFamilyProperties(physical_, &qn, qf.data());
    info_.features.timestamps = qf[queueFamily_].timestampValidBits > 0 && l.timestampPeriod > 0;
    info_.features.computeShaders = true;
    info_.features.geometryShaders = enabled_.geometryShader;
    info_.features.tessellationShaders = enabled_.tessellationShader;
    info_.features.asyncCompute = queues_[1].queue != queue_;
    info_.features.asyncCopy = queues_[2].queue != queue_;
    info_.features.debugLabels = cmdBeginLabel != nullptr;
    info_.features.memoryAliasing = true;
    info_.features.textureCubeArray = enabled_.imageCubeArray;
    info_.features.storageImageExtendedFormats = enabled_.shaderStorageImageExtendedFormats;
    info_.features.robustBufferAccess = enabled_.robustBufferAccess;
    for (uint32_t i = 0; i < memory.memoryTypeCount; ++i)
        if (memory.memoryTypes[i].propertyFlags & VK_MEMORY_PROPERTY_LAZILY_ALLOCATED_BIT)
            info_.features.lazilyAllocatedMemory = true;
    info_.features.depthClamp = enabled_.depthClamp;
    info_.features.depthBiasClamp = enabled_.depthBiasClamp;
    // Multi-draw needs a firstInstance in the records too (the engine's instancing uses it).
    info_.features.multiDrawIndirect =
        enabled_.multiDrawIndirect && enabled_.drawIndirectFirstInstance;
    info_.features.drawIndirectCount = drawIndirectCount_ && info_.features.multiDrawIndirect;
    info_.features.textureCompressionBC = enabled_.textureCompressionBC;
    info_.features.occlusionQueries = enabled_.occlusionQueryPrecise;
    info_.features.pipelineStatistics = enabled_.pipelineStatisticsQuery;
    info_.features.window = swapchain_ != nullptr;
    if (swapchain_) info_.presentMode = swapchain_->presentMode();
}

VulkanDevice::~VulkanDevice() {
    const gdi::NativeLayerLock::Change layerChange(
        info_.features.validation);  // the layer forgets them
    liveLists_.orphanAll();          // lists that outlive the device let go of it now
    if (device_) {                   // what was destroyed is not a leak: release it first
        vkDeviceWaitIdle(device_);
        for (Retired& r : retired_) r.release();
        retired_.clear();
    }
    if (gdi::leakCheckEnabled()) {
        std::vector<std::string> named;
        buffers_.forEach([&](Buffer& b) { named.push_back("buffer '" + b.name + "'"); });
        textures_.forEach([&](Texture& t) { named.push_back("texture '" + t.name + "'"); });
        gdi::reportLeaksAtDestruction(info_.backend, liveObjects(), named);
    }
    release();
}

void VulkanDevice::release() {
    if (swapchain_)
        swapchain_->release();  // swap chain and surface go before the device and instance
    if (device_ && !cacheStats_.path.empty() && !loss_.lost()) {
        try {
            savePipelineCache();
        } catch (const gdi::Error& e) {
            std::cerr << "fe: " << e.what() << "\n";
        }
    }
    if (device_) {
        vkDeviceWaitIdle(device_);
        for (Retired& r : retired_) r.release();
        retired_.clear();
        pendingInit_.clear();
        for (const SecondaryRecording& r : secondaries_)
            vkDestroyCommandPool(device_, r.pool, nullptr);
        secondaries_.clear();
        buffers_.forEach([&](Buffer& b) { freeBuffer(b); });
        textures_.forEach([&](Texture& t) { destroyTexture(t); });
        heaps_.forEach([&](Heap& h) { allocator_->free(h.memory); });
        querySets_.forEach([&](QuerySet& q) { vkDestroyQueryPool(device_, q.pool, nullptr); });
        samplers_.forEach([&](Sampler& s) { vkDestroySampler(device_, s.sampler, nullptr); });
        shaders_.forEach([&](Shader& s) { vkDestroyShaderModule(device_, s.module, nullptr); });
        // Every live pipeline's objects are among the shared ones, each destroyed once.
        for (const Pipeline& p : sharedPipelines_.clear()) destroyPipelineObjects(p);
        for (auto& s : inFlight_) vkDestroyFence(device_, s.fence, nullptr);
        for (VkFence f : freeFences_) vkDestroyFence(device_, f, nullptr);
        for (VkSemaphore s :
             {queues_[0].timeline, queues_[1].timeline, queues_[2].timeline, initTimeline_})
            if (s) vkDestroySemaphore(device_, s, nullptr);
        if (queryPool_) vkDestroyQueryPool(device_, queryPool_, nullptr);
        if (pipelineCache_) vkDestroyPipelineCache(device_, pipelineCache_, nullptr);
        if (immediatePool_) vkDestroyCommandPool(device_, immediatePool_, nullptr);
        allocator_.reset();
        vkDestroyDevice(device_, nullptr);
        device_ = VK_NULL_HANDLE;
    }
    if (messenger_) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy) destroy(instance_, messenger_, nullptr);
        messenger_ = VK_NULL_HANDLE;
    }
    if (instance_) {
        vkDestroyInstance(instance_, nullptr);
        instance_ = VK_NULL_HANDLE;
    }
}

void VulkanDevice::setName(VkObjectType type, uint64_t object, const char* name) {
    if (!setObjectName_ || !name || !*name) return;
    VkDebugUtilsObjectNameInfoEXT ni{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
    ni.objectType = type;
    ni.objectHandle = object;
    ni.pObjectName = name;
    // One name at a time in the whole process: with two devices created from two threads, the
    // loader's and validation layer's naming path crashed under ASan (a SEGV inside
    // vkSetDebugUtilsObjectNameEXT, CI of 761697f). Naming happens at creation only, so the lock
    // costs nothing per frame.
    static std::mutex namingMutex;
    std::lock_guard lock(namingMutex);
    setObjectName_(device_, &ni);
}

// ---------------------------------------------------------------------------------------------
// Submission
// ---------------------------------------------------------------------------------------------
std::unique_ptr<gdi::CommandList> VulkanDevice::createCommandList(
    const gdi::CommandListDesc& desc) {
    loss_.check("createCommandList");
    auto list = std::make_unique<VulkanCommandList>(*this, desc.queue);
    return info_.features.validation ? gdi::exclusiveUse(std::move(list), true) : std::move(list);
}

gdi::FenceValue VulkanDevice::submit(std::span<gdi::CommandList* const> lists,
                                     const gdi::SubmitDesc& desc) {
    const DeviceCall call(*this);
    loss_.check("submit");
    std::vector<VulkanCommandList*> vk;
    std::vector<VkCommandBuffer> cbs;
    const gdi::ClaimedLists claimed(lists, "submit");  // null, twice, in use on another thread
    const gdi::QueueKind queue =
        gdi::validate::submissionQueue(claimed.lists(), desc, nextFence_ - 1);
    for (gdi::CommandList* l : claimed.lists()) {
        auto* list = dynamic_cast<VulkanCommandList*>(l);
        if (!list || !list->madeBy(*this))
            throw gdi::Error("submit: a command list of another device");
        vk.push_back(list);
    }
    for (VulkanCommandList* list : vk) list->checkSubmittable();
    std::vector<const gdi::validate::QueryRecording*> queries;
    for (VulkanCommandList* list : vk) queries.push_back(&list->queries());
    gdi::validate::querySubmission(queries, [&](uint32_t set, uint32_t index) {
        return querySets_.get({set}, "query set").submitted[index] != 0;
    });
    std::vector<std::pair<QuerySet*, uint32_t>> usedQueries;  // reset before the lists run
    std::vector<std::pair<VkQueryPool, uint32_t>>
        resets;  // (the closure outlives this call on failure)
    for (const auto* q : queries)
        for (const auto& u : q->used())
            usedQueries.push_back({&querySets_.get({u.set}, "query set"), u.index});
    for (auto [set, index] : usedQueries) resets.push_back({set->pool, index});
    std::vector<Timer*> usedTimers;  // copied: finishing a list may start its next recording
    for (const auto* q : queries)
        for (const auto& t : q->timers()) usedTimers.push_back(&timer({t.first}));
    if (!resets.empty())
        recordInitialTransition([resets](VkCommandBuffer cb) {
            for (auto [pool, index] : resets) vkCmdResetQueryPool(cb, pool, index, 1);
        });
    VkCommandBuffer init = takeInitialTransitions();
    const bool graphics = queue == gdi::QueueKind::Graphics;
    if (init && graphics) cbs.push_back(init);
    if (init && !graphics) submitInitialCommands(init);  // throws before any list is touched
    for (VulkanCommandList* list : vk) cbs.push_back(list->finish());
    // What this submission waits for: the other queues' last submissions up to waitFor, and,
    // off the graphics queue, the objects' first commands submitted there.
    std::vector<VkSemaphore> waitSemaphores;
    std::vector<uint64_t> waitValues;
    for (gdi::QueueKind other :
         {gdi::QueueKind::Graphics, gdi::QueueKind::Compute, gdi::QueueKind::Copy})
        if (other != queue && desc.waitFor)
            if (const gdi::FenceValue v = lastInFlightOn(other, desc.waitFor)) {
                waitSemaphores.push_back(queues_[size_t(other)].timeline);
                waitValues.push_back(v);
            }
    if (!graphics && initSignalled_) {
        waitSemaphores.push_back(initTimeline_);
        waitValues.push_back(initSignalled_);
    }
    const std::vector<VkPipelineStageFlags> waitStages(waitSemaphores.size(),
                                                       VK_PIPELINE_STAGE_ALL_COMMANDS_BIT);
    const gdi::FenceValue value = nextFence_;
    VkTimelineSemaphoreSubmitInfo timeline{VK_STRUCTURE_TYPE_TIMELINE_SEMAPHORE_SUBMIT_INFO};
    timeline.waitSemaphoreValueCount = uint32_t(waitValues.size());
    timeline.pWaitSemaphoreValues = waitValues.data();
    timeline.signalSemaphoreValueCount = 1;
    timeline.pSignalSemaphoreValues = &value;
    VkFence fence;
    if (!freeFences_.empty()) {
        fence = freeFences_.back();
        freeFences_.pop_back();
    } else {
        VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        check(nativeAllocation("vkCreateFence",
                               [&] { return vkCreateFence(device_, &fci, nullptr, &fence); }),
              "vkCreateFence");
    }
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.pNext = &timeline;
    si.waitSemaphoreCount = uint32_t(waitSemaphores.size());
    si.pWaitSemaphores = waitSemaphores.data();
    si.pWaitDstStageMask = waitStages.data();
    si.commandBufferCount = uint32_t(cbs.size());
    si.pCommandBuffers = cbs.data();
    si.signalSemaphoreCount = 1;
    si.pSignalSemaphores = &queues_[size_t(queue)].timeline;
    const VkQueue target = queues_[size_t(queue)].queue;
    if (VkResult r =
            nativeSubmission("vkQueueSubmit", [&] { return vkQueueSubmit(target, 1, &si, fence); });
        r != VK_SUCCESS) {
        freeFences_.push_back(fence);  // never submitted
        for (VulkanCommandList* list : vk)
            list->submitted(nextFence_ - 1);                   // the recordings are dropped
        if (init && !graphics) (void)vkQueueWaitIdle(queue_);  // it was submitted there
        if (init) vkFreeCommandBuffers(device_, immediatePool_, 1, &init);
        check(r, "vkQueueSubmit");
    }
    ++nextFence_;
    inFlight_.push_back({value, fence, queue});
    for (auto [set, index] : usedQueries) set->submitted[index] = value;
    for (Timer* t : usedTimers) t->submitted = value;
    for (VulkanCommandList* list : vk) list->submitted(value);
    if (init) freeAfter(value, init);
    pollFences();
    collectRetired();
    return value;
}

// Objects' first commands before a compute or copy submission: on the graphics queue, which
// every command they record can run on, signalling initTimeline_ (the submission waits for it).
void VulkanDevice::submitInitialCommands(VkCommandBuffer init) {
    const uint64_t value = initSignalled_ + 1;
    VkTimelineSemaphoreSubmitInfo timeline{VK_STRUCTURE_TYPE_TIMELINE_SEMAPHORE_SUBMIT_INFO};
    timeline.signalSemaphoreValueCount = 1;
    timeline.pSignalSemaphoreValues = &value;
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.pNext = &timeline;
    si.commandBufferCount = 1;
    si.pCommandBuffers = &init;
    si.signalSemaphoreCount = 1;
    si.pSignalSemaphores = &initTimeline_;
    if (VkResult r = nativeSubmission(
            "vkQueueSubmit", [&] { return vkQueueSubmit(queue_, 1, &si, VK_NULL_HANDLE); });
        r != VK_SUCCESS) {
        vkFreeCommandBuffers(device_, immediatePool_, 1, &init);
        check(r, "vkQueueSubmit");
    }
    initSignalled_ = value;
}

// The last submission to queue `q` with a fence at most `atMost` not yet known to be complete
// (0: none): waiting for it waits for every earlier one on that queue too.
gdi::FenceValue VulkanDevice::lastInFlightOn(gdi::QueueKind q, gdi::FenceValue atMost) const {
    gdi::FenceValue last = 0;
    for (const Submission& s : inFlight_)
        if (s.queue == q && s.value <= atMost) last = s.value;
    return last;
}

// Before work on the graphics queue that must follow everything submitted so far (the device's
// own transfers): the other queues' submissions are waited for on the CPU.
void VulkanDevice::settleOtherQueues() {
    gdi::FenceValue last = 0;
    for (gdi::QueueKind q : {gdi::QueueKind::Compute, gdi::QueueKind::Copy})
        last = std::max(last, lastInFlightOn(q, nextFence_ - 1));
    if (last) settle(last);
}

void VulkanDevice::wait(gdi::FenceValue fence) {
    const DeviceCall call(*this);
    loss_.check("wait");
    gdi::validate::issuedFence(fence, nextFence_ - 1, "wait");
    settle(fence);
    loss_.check("wait");
    collectRetired();
}

bool VulkanDevice::isComplete(gdi::FenceValue fence) {
    const DeviceCall call(*this);
    loss_.check("isComplete");
    gdi::validate::issuedFence(fence, nextFence_ - 1, "isComplete");
    pollFences();
    loss_.check("isComplete");
    collectRetired();
    return completed_ >= std::min(fence, nextFence_ - 1);
}

bool VulkanDevice::completedNoThrow(gdi::FenceValue fence) {
    const DeviceCall call(*this);
    if (loss_.lost()) return true;
    pollFences();
    return completed_ >= fence;
}

void VulkanDevice::pollFences() {
    while (!inFlight_.empty()) {
        Submission s = inFlight_.front();
        const VkResult r = vkGetFenceStatus(device_, s.fence);
        if (r == VK_NOT_READY) break;
        if (r == VK_ERROR_DEVICE_LOST)
            (void)loss_.lose("vulkan", "vkGetFenceStatus returned VK_ERROR_DEVICE_LOST");
        else
            check(r, "vkGetFenceStatus");
        vkResetFences(device_, 1, &s.fence);
        freeFences_.push_back(s.fence);
        completed_ = s.value;
        inFlight_.pop_front();
    }
    if (inFlight_.empty()) completed_ = nextFence_ - 1;
}

void VulkanDevice::retire(std::function<void()> release) {
    const uint64_t epoch = destroyEpoch_.fetch_add(1, std::memory_order_release) + 1;
    if (std::exchange(presentedSinceIdle_, false)) idle();
    pollFences();
    // An object's own unsubmitted initial commands were dropped by its destroy; none else names it.
    const gdi::FenceValue after = nextFence_ - 1;
    if (completed_ >= after && !heldByRecording(epoch)) return release();  // nothing can use it
    retired_.push_back({after, epoch, std::move(release)});
}

void VulkanDevice::openRecording(uint64_t since) {
    const DeviceCall call(*this);
    openRecordings_.insert(since);
}

void VulkanDevice::closeRecording(uint64_t since) {
    const DeviceCall call(*this);
    openRecordings_.erase(openRecordings_.find(since));
    collectRetired();
}

// In destroy order: a release held back by a recording holds back the later ones too.
void VulkanDevice::collectRetired() {
    while (!retired_.empty() &&
           ((retired_.front().after <= completed_ && !heldByRecording(retired_.front().epoch)) ||
            loss_.lost())) {
        auto release = std::move(retired_.front().release);
        retired_.pop_front();
        release();
    }
}

void VulkanDevice::releaseRetiredNow() {
    if (!pendingInit_.empty())
        immediate("pending layout transitions", [](VkCommandBuffer) {});  // waits: waitIdle
    idle();
    for (Retired& r : retired_) r.release();
    retired_.clear();
}

void VulkanDevice::settle(gdi::FenceValue fence) {
    const DeviceCall call(*this);
    while (!inFlight_.empty() && inFlight_.front().value <= fence) {
        Submission s = inFlight_.front();
        const VkResult r = vkWaitForFences(device_, 1, &s.fence, VK_TRUE, UINT64_MAX);
        // A lost device runs nothing more: its submissions count as done.
        if (r == VK_ERROR_DEVICE_LOST)
            (void)loss_.lose("vulkan", "vkWaitForFences returned VK_ERROR_DEVICE_LOST");
        else
            check(r, "vkWaitForFences");
        vkResetFences(device_, 1, &s.fence);
        freeFences_.push_back(s.fence);
        completed_ = s.value;
        inFlight_.pop_front();
    }
    completed_ = std::max(completed_, std::min(fence, nextFence_ - 1));
}

void VulkanDevice::waitIdle() {
    const DeviceCall call(*this);
    loss_.check("waitIdle");
    if (!pendingInit_.empty()) return releaseRetiredNow();  // submits the pending transitions too
    wait(nextFence_ - 1);
    for (const QueueSlot& q : queues_) check(vkQueueWaitIdle(q.queue), "vkQueueWaitIdle");
    collectRetired();  // nothing in flight, nothing pending: all but what open recordings hold
}

void VulkanDevice::idle() {
    settle(nextFence_ - 1);
    for (const QueueSlot& q : queues_) {
        const VkResult r = vkQueueWaitIdle(q.queue);
        if (r == VK_ERROR_DEVICE_LOST)
            (void)loss_.lose("vulkan", "vkQueueWaitIdle returned VK_ERROR_DEVICE_LOST");
        else
            check(r, "vkQueueWaitIdle");
    }
}

void VulkanDevice::fail(VkResult r, const char* call, const std::string& object) const {
    if (r == VK_ERROR_DEVICE_LOST)
        throw loss_.lose("vulkan", std::string(call) + " returned VK_ERROR_DEVICE_LOST");
    throwVk(r, call, object);
}

gdi::LiveObjects VulkanDevice::liveObjects() const {
    const DeviceCall call(*this);
    // Destroyed objects whose submissions have completed are gone: release them first.
    auto* self = const_cast<VulkanDevice*>(this);
    if (!loss_.lost()) self->pollFences();
    self->collectRetired();
    return {.buffers = buffers_.size(),
            .textures = textures_.size(),
            .samplers = samplers_.size(),
            .shaders = shaders_.size(),
            .pipelines = pipelines_.size(),
            .timers = timers_.size(),
            .heaps = heaps_.size(),
            .querySets = querySets_.size(),
            .nativeObjects = nativeObjects_ + allocator_->stats().placements};
}

void VulkanDevice::recordInitialTransition(std::function<void(VkCommandBuffer)> record,
                                           uint32_t texture, uint32_t buffer) {
    pendingInit_.push_back({texture, buffer, std::move(record)});
}

void VulkanDevice::dropInitialCommands(uint32_t texture, uint32_t buffer) {
    std::erase_if(pendingInit_, [&](const InitialCommands& c) {
        return (texture && c.texture == texture) || (buffer && c.buffer == buffer);
    });
}

// Records every pending object's first commands into one command buffer, then one full barrier
// that orders them before whatever follows in the submission. On failure they stay pending.
VkCommandBuffer VulkanDevice::takeInitialTransitions(const std::string& object) {
    if (pendingInit_.empty()) return VK_NULL_HANDLE;
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = immediatePool_;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    VkCommandBuffer cb;
    check(nativeAllocation("vkAllocateCommandBuffers",
                           [&] { return vkAllocateCommandBuffers(device_, &ai, &cb); }),
          "vkAllocateCommandBuffers", object);
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    const char* call = "vkBeginCommandBuffer";
    VkResult r = nativeAllocation(call, [&] { return vkBeginCommandBuffer(cb, &bi); });
    if (r == VK_SUCCESS) {
        for (const InitialCommands& c : pendingInit_) c.record(cb);
        VulkanCommandList::fullBarrier(cb);
        call = "vkEndCommandBuffer";
        r = vkEndCommandBuffer(cb);
    }
    if (r != VK_SUCCESS) {
        vkFreeCommandBuffers(device_, immediatePool_, 1, &cb);
        check(r, call, object);
    }
    pendingInit_.clear();
    return cb;
}

void VulkanDevice::freeAfter(gdi::FenceValue fence, VkCommandBuffer cb) {
    // Epoch 0: no list records into an immediate command buffer, so none holds it back.
    retired_.push_back({fence, 0, [this, cb]() mutable {
                            vkFreeCommandBuffers(device_, immediatePool_, 1, &cb);
                        }});
}

void VulkanDevice::immediate(const std::string& object,
                             const std::function<void(VkCommandBuffer)>& record) {
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = immediatePool_;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    VkCommandBuffer cb;
    check(nativeAllocation("vkAllocateCommandBuffers",
                           [&] { return vkAllocateCommandBuffers(device_, &ai, &cb); }),
          "vkAllocateCommandBuffers", object);
    // Freed however this ends: after the wait, or unsubmitted when a step before it throws.
    struct Release {
        VkDevice device;
        VkCommandPool pool;
        VkCommandBuffer cb;
        ~Release() { vkFreeCommandBuffers(device, pool, 1, &cb); }
    } release{device_, immediatePool_, cb};
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(nativeAllocation("vkBeginCommandBuffer", [&] { return vkBeginCommandBuffer(cb, &bi); }),
          "vkBeginCommandBuffer", object);
    VulkanCommandList::fullBarrier(cb);  // order after everything submitted before
    record(cb);
    settleOtherQueues();  // the barrier orders the graphics queue's work, this the others'
    VulkanCommandList::fullBarrier(cb);
    check(nativeAllocation("vkEndCommandBuffer", [&] { return vkEndCommandBuffer(cb); }),
          "vkEndCommandBuffer", object);
    // Textures made since the last submission get their first transitions first, in the same
    // submission (taken only now, so a failure above leaves them pending); freed after the wait.
    const VkCommandBuffer init = takeInitialTransitions(object);
    struct ReleaseInit {
        VkDevice device;
        VkCommandPool pool;
        VkCommandBuffer cb;
        ~ReleaseInit() {
            if (cb) vkFreeCommandBuffers(device, pool, 1, &cb);
        }
    } releaseInit{device_, immediatePool_, init};
    const VkCommandBuffer both[] = {init, cb};
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = init ? 2 : 1;
    si.pCommandBuffers = init ? both : &cb;
    check(nativeSubmission("vkQueueSubmit",
                           [&] { return vkQueueSubmit(queue_, 1, &si, VK_NULL_HANDLE); }),
          "vkQueueSubmit");
    waitIdle();
}

// ---------------------------------------------------------------------------------------------
// Blocking transfers
// ---------------------------------------------------------------------------------------------
void* VulkanDevice::map(gdi::BufferHandle h) {
    const Buffer& b = buffer(h);
    gdi::validate::mappable(b.desc, b.name);
    return b.memory.mapped;  // host-visible, coherent memory, mapped for the buffer's life
}

void VulkanDevice::writeBuffer(gdi::BufferHandle h, uint64_t offset, gdi::ByteSpan data) {
    const DeviceCall call(*this);
    loss_.check("writeBuffer");
    Buffer& b = buffer(h);
    const uint64_t size = data.size();
    gdi::validate::bufferRange(b.desc, offset, size, "writeBuffer");
    if (size == 0) return;
    if (b.desc.access == gdi::MemoryAccess::Upload && b.memory.mapped) {
        // Queue order: work submitted before may still read these bytes (map() does not wait).
        settle(nextFence_ - 1);
        std::memcpy(static_cast<uint8_t*>(b.memory.mapped) + offset, data.data(), size);
        return;
    }
    Buffer staging = makeBuffer(size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::Upload,
                                "staging buffer for buffer", b.name);
    OnExit freeStaging{[&] { freeBuffer(staging); }};
    std::memcpy(staging.memory.mapped, data.data(), size);
    immediate("writeBuffer of " + gdi::describeObject("buffer", b.name, {}),
              [&](VkCommandBuffer cb) {
                  VkBufferCopy region{0, offset, size};
                  vkCmdCopyBuffer(cb, staging.buffer, b.buffer, 1, &region);
              });
}

void VulkanDevice::writeTexture(gdi::TextureHandle h, gdi::Subresource at, gdi::ByteSpan data) {
    const DeviceCall call(*this);
    loss_.check("writeTexture");
    Texture& t = texture(h);
    gdi::validate::notAView(t.viewOf != 0, t.name, "writeTexture");
    gdi::validate::uploadSize(t.desc, at, data.size(), "writeTexture", t.name);
    if (t.desc.sampleCount > 1)
        throw gdi::Error("writeTexture: multisampled textures cannot be uploaded");
    // Depth-stencil texels (gdi's readback layout, Device.h) go in as two aspects: the depth
    // words first (D32F_S8: packed from 8-byte texels), then one stencil byte per texel.
    const gdi::FormatInfo& fi = gdi::formatInfo(t.desc.format);
    const bool split = fi.hasDepth && fi.hasStencil;  // S8 is one (stencil) aspect, copied as it is
    const uint64_t texels = split ? data.size() / fi.bytesPerPixel : 0;
    const uint64_t depthBytes = split ? texels * 4 : data.size();
    Buffer staging = makeBuffer(depthBytes + texels, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                MemoryUsage::Upload, "staging buffer for texture", t.name);
    OnExit freeStaging{[&] { freeBuffer(staging); }};
    auto* staged = static_cast<uint8_t*>(staging.memory.mapped);
    const auto* in = reinterpret_cast<const uint8_t*>(data.data());
    if (!split) {
        std::memcpy(staged, in, data.size());
    } else {
        for (uint64_t i = 0; i < texels; ++i) {
            const uint8_t* texel = in + i * fi.bytesPerPixel;
            std::memcpy(staged + 4 * i, texel,
                        4);  // D24S8: the high byte is ignored by the depth copy
            staged[depthBytes + i] = t.desc.format == gdi::Format::D24S8 ? texel[3] : texel[4];
        }
    }
    immediate(
        "writeTexture of " + gdi::describeObject("texture", t.name, {}), [&](VkCommandBuffer cb) {
            const VkBufferImageCopy r = copyRegion(t.desc, at, 0);
            vkCmdCopyBufferToImage(cb, staging.buffer, t.image, VK_IMAGE_LAYOUT_GENERAL, 1, &r);
            if (split) {
                VkBufferImageCopy s = r;
                s.bufferOffset = depthBytes;
                s.imageSubresource.aspectMask = VK_IMAGE_ASPECT_STENCIL_BIT;
                vkCmdCopyBufferToImage(cb, staging.buffer, t.image, VK_IMAGE_LAYOUT_GENERAL, 1, &s);
            }
        });
}

void VulkanDevice::writeTextureRegion(gdi::TextureHandle h, const gdi::TextureRegion& region,
                                      gdi::ByteSpan data, const gdi::TexelLayout& layout) {
    const DeviceCall call(*this);
    loss_.check("writeTextureRegion");
    Texture& t = texture(h);
    gdi::validate::notAView(t.viewOf != 0, t.name, "writeTexture");
    const gdi::TextureRegion r =
        gdi::validate::textureRegion(t.desc, region, t.name, "writeTextureRegion");
    const gdi::validate::ResolvedLayout l =
        gdi::validate::texelLayout(t.desc.format, r, layout, "writeTextureRegion");
    gdi::validate::dataSpan(data.size(), l.end, "writeTextureRegion");
    // The spanned bytes are staged as they are; the copy reads them with the caller's pitch.
    const uint64_t bytes = l.end - l.layout.offset;
    Buffer staging = makeBuffer(bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::Upload,
                                "staging buffer for texture", t.name);
    OnExit freeStaging{[&] { freeBuffer(staging); }};
    std::memcpy(staging.memory.mapped, data.data() + l.layout.offset, bytes);
    gdi::TexelLayout staged = l.layout;
    staged.offset = 0;
    immediate(
        "writeTexture of " + gdi::describeObject("texture", t.name, {}), [&](VkCommandBuffer cb) {
            const VkBufferImageCopy c = regionCopy(t.desc, r, staged);
            vkCmdCopyBufferToImage(cb, staging.buffer, t.image, VK_IMAGE_LAYOUT_GENERAL, 1, &c);
        });
}

std::vector<uint8_t> VulkanDevice::readBuffer(gdi::BufferHandle h, uint64_t offset, uint64_t size) {
    const DeviceCall call(*this);
    loss_.check("readBuffer");
    Buffer& b = buffer(h);
    gdi::validate::bufferRange(b.desc, offset, size, "readBuffer");
    std::vector<uint8_t> out(size);
    if (size == 0) return out;
    Buffer staging = makeBuffer(size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::Readback,
                                "staging buffer for buffer", b.name);
    OnExit freeStaging{[&] { freeBuffer(staging); }};
    immediate("readBuffer of " + gdi::describeObject("buffer", b.name, {}),
              [&](VkCommandBuffer cb) {
                  VkBufferCopy region{offset, 0, size};
                  vkCmdCopyBuffer(cb, b.buffer, staging.buffer, 1, &region);
              });
    std::memcpy(out.data(), staging.memory.mapped, size);
    return out;
}

gdi::Image VulkanDevice::readTexture(gdi::TextureHandle h, gdi::Subresource at) {
    const DeviceCall call(*this);
    loss_.check("readTexture");
    Texture& t = texture(h);
    gdi::validate::notAView(t.viewOf != 0, t.name, "readTexture");
    gdi::validate::readable(t.desc, at, "readTexture", t.name);
    const gdi::validate::Extent3 e = gdi::validate::mipExtent(t.desc, at.mipLevel);
    gdi::Image img;
    img.width = e.width;
    img.height = e.height;
    img.format = t.desc.format;
    const uint64_t size = gdi::imageByteSize(t.desc.format, e.width, e.height);
    // Depth/stencil: the depth aspect (D24S8 lands as X8D24, depth in the low 24 bits), then the
    // stencil aspect (one byte per texel) after it, merged into the high byte as GL returns it.
    const bool stencil = gdi::formatInfo(t.desc.format).hasStencil &&
                         gdi::formatInfo(t.desc.format).hasDepth;  // S8: one aspect
    const uint64_t stencilBytes = stencil ? uint64_t(e.width) * e.height : 0;
    Buffer staging = makeBuffer(size + stencilBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                MemoryUsage::Readback, "staging buffer for texture", t.name);
    OnExit freeStaging{[&] { freeBuffer(staging); }};
    immediate(
        "readTexture of " + gdi::describeObject("texture", t.name, {}), [&](VkCommandBuffer cb) {
            const VkBufferImageCopy r = copyRegion(t.desc, at, 0);
            vkCmdCopyImageToBuffer(cb, t.image, VK_IMAGE_LAYOUT_GENERAL, staging.buffer, 1, &r);
            if (stencil) {
                VkBufferImageCopy s = r;
                s.bufferOffset = size;
                s.imageSubresource.aspectMask = VK_IMAGE_ASPECT_STENCIL_BIT;
                vkCmdCopyImageToBuffer(cb, t.image, VK_IMAGE_LAYOUT_GENERAL, staging.buffer, 1, &s);
            }
        });
    img.data.resize(size);
    const auto* staged = static_cast<const uint8_t*>(staging.memory.mapped);
    if (t.desc.format ==
        gdi::Format::D32F_S8) {  // depth aspect packed as floats: spread to 8-byte texels
        std::fill(img.data.begin(), img.data.end(), uint8_t(0));
        for (uint64_t i = 0; i < stencilBytes; ++i) {
            std::memcpy(&img.data[8 * i], staged + 4 * i, 4);
            img.data[8 * i + 4] = staged[size + i];
        }
        return img;
    }
    std::memcpy(img.data.data(), staged, size);
    if (stencil && t.desc.format == gdi::Format::D24S8) {
        const auto* s = static_cast<const uint8_t*>(staging.memory.mapped) + size;
        for (uint64_t i = 0; i < stencilBytes; ++i) {
            uint32_t v;
            std::memcpy(&v, &img.data[4 * i], 4);
            v = (v & 0xffffffu) | (uint32_t(s[i]) << 24);
            std::memcpy(&img.data[4 * i], &v, 4);
        }
    }
    return img;
}

uint64_t VulkanDevice::nativeObject(gdi::NativeObject what, uint32_t id) const {
    using N = gdi::NativeObject;
    switch (what) {
        case N::Device:
            return uint64_t(device_);
        case N::PhysicalDevice:
            return uint64_t(physical_);
        case N::Queue:
            return uint64_t(queue_);
        case N::QueueFamily:
            return queueFamily_;
        case N::Buffer:
            if (auto* b = buffers_.find(gdi::BufferHandle{id})) return uint64_t(b->buffer);
            break;
        case N::Texture:
            if (auto* t = textures_.find(gdi::TextureHandle{id})) return uint64_t(t->image);
            break;
        case N::TextureView:
            if (auto* t = textures_.find(gdi::TextureHandle{id})) return uint64_t(t->view);
            break;
        case N::Pipeline:
            if (auto* p = pipelines_.find(gdi::PipelineHandle{id})) return uint64_t(p->pipeline);
            break;
        case N::PipelineLayout:
            if (auto* p = pipelines_.find(gdi::PipelineHandle{id})) return uint64_t(p->layout);
            break;
        default:
            break;
    }
    return 0;
}

std::optional<double> VulkanDevice::timerNanoseconds(gdi::TimerHandle h) {
    const DeviceCall call(*this);
    loss_.check("timerNanoseconds");
    Timer& t = timer(h);
    // Not before its submission completed: lavapipe's vkGetQueryPoolResults waited for it.
    pollFences();
    if (t.submitted == 0 || t.submitted > completed_) return std::nullopt;
    uint64_t ticks[2];
    VkResult r = vkGetQueryPoolResults(device_, queryPool_, t.firstQuery, 2, sizeof(ticks), ticks,
                                       sizeof(uint64_t), VK_QUERY_RESULT_64_BIT);
    if (r == VK_ERROR_DEVICE_LOST) check(r, "vkGetQueryPoolResults");
    if (r != VK_SUCCESS) return std::nullopt;
    return double(ticks[1] - ticks[0]) * double(props_.limits.timestampPeriod);
}

}  // namespace fe::vk

namespace fe::vk {

VulkanDevice::SecondaryRecording VulkanDevice::acquireSecondary() {
    SecondaryRecording r;
    const std::thread::id self = std::this_thread::get_id();
    {
        // A free recording this thread made before comes first: lavapipe, like most drivers,
        // allocates commands with malloc, and a pool reset on another thread frees into a
        // foreign arena (measured: secondary lists recorded slower than primary ones).
        const DeviceCall call(*this);
        size_t pick = secondaries_.size();
        for (size_t i = 0; i < secondaries_.size(); ++i)
            if (!secondaries_[i].fence || completedNoThrow(secondaries_[i].fence)) {
                if (pick == secondaries_.size() || secondaries_[i].recordedOn == self) pick = i;
                if (secondaries_[i].recordedOn == self) break;
            }
        if (pick < secondaries_.size()) {
            r = secondaries_[pick];
            secondaries_[pick] = secondaries_.back();
            secondaries_.pop_back();
        }
    }
    r.recordedOn = self;
    if (r.pool) {  // now this list's alone: no lock needed to reset it
        check(vkResetCommandPool(device_, r.pool, 0), "vkResetCommandPool");
        return r;
    }
    VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pci.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
    pci.queueFamilyIndex = queueFamily_;
    check(nativeAllocation("vkCreateCommandPool",
                           [&] { return vkCreateCommandPool(device_, &pci, nullptr, &r.pool); }),
          "vkCreateCommandPool");
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = r.pool;
    ai.level = VK_COMMAND_BUFFER_LEVEL_SECONDARY;
    ai.commandBufferCount = 1;
    if (VkResult res =
            nativeAllocation("vkAllocateCommandBuffers",
                             [&] { return vkAllocateCommandBuffers(device_, &ai, &r.cb); });
        res != VK_SUCCESS) {
        vkDestroyCommandPool(device_, r.pool, nullptr);
        check(res, "vkAllocateCommandBuffers");
    }
    return r;
}

void VulkanDevice::releaseSecondary(std::span<const SecondaryRecording> recordings,
                                    gdi::FenceValue fence) {
    if (recordings.empty()) return;
    const DeviceCall call(*this);
    for (SecondaryRecording r : recordings) {
        r.fence = fence;
        secondaries_.push_back(r);
    }
}

}  // namespace fe::vk

// Shader modules and graphics/compute pipelines (dynamic rendering, push-descriptor layouts).
#include <string>
#include <utility>

#include "fe/gdi/ShaderCompiler.h"
#include "VulkanDevice.h"
#include "VulkanFaults.h"
#include "fe/gdi/PipelineCacheFile.h"
#include "fe/gdi/Validation.h"

namespace fe::vk {

namespace {
constexpr uint32_t kSpirvMagic = 0x07230203;

VkShaderStageFlags toStages(gdi::ShaderStage s) {
    VkShaderStageFlags f = 0;
    if (any(s, gdi::ShaderStage::Vertex)) f |= VK_SHADER_STAGE_VERTEX_BIT;
    if (any(s, gdi::ShaderStage::Fragment)) f |= VK_SHADER_STAGE_FRAGMENT_BIT;
    if (any(s, gdi::ShaderStage::Compute)) f |= VK_SHADER_STAGE_COMPUTE_BIT;
    if (any(s, gdi::ShaderStage::Geometry)) f |= VK_SHADER_STAGE_GEOMETRY_BIT;
    if (any(s, gdi::ShaderStage::TessControl)) f |= VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT;
    if (any(s, gdi::ShaderStage::TessEvaluation)) f |= VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT;
    return f;
}

VkDescriptorType toDescriptorType(gdi::BindingType t) {
    switch (t) {
        case gdi::BindingType::UniformBuffer:
            return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
        case gdi::BindingType::StorageBuffer:
            return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        case gdi::BindingType::SampledTexture:
            return VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        case gdi::BindingType::StorageTexture:
            return VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    }
    return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
}

VkCompareOp toCompare(gdi::CompareOp c) {
    return VkCompareOp(int(c));
}  // same order as VkCompareOp
VkStencilOp toStencilOp(gdi::StencilOp o) {
    return VkStencilOp(int(o));
}  // same order as VkStencilOp

VkBlendFactor toBlendFactor(gdi::BlendFactor f) {
    using B = gdi::BlendFactor;
    switch (f) {
        case B::Zero:
            return VK_BLEND_FACTOR_ZERO;
        case B::One:
            return VK_BLEND_FACTOR_ONE;
        case B::SrcColor:
            return VK_BLEND_FACTOR_SRC_COLOR;
        case B::OneMinusSrcColor:
            return VK_BLEND_FACTOR_ONE_MINUS_SRC_COLOR;
        case B::DstColor:
            return VK_BLEND_FACTOR_DST_COLOR;
        case B::OneMinusDstColor:
            return VK_BLEND_FACTOR_ONE_MINUS_DST_COLOR;
        case B::SrcAlpha:
            return VK_BLEND_FACTOR_SRC_ALPHA;
        case B::OneMinusSrcAlpha:
            return VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
        case B::DstAlpha:
            return VK_BLEND_FACTOR_DST_ALPHA;
        case B::OneMinusDstAlpha:
            return VK_BLEND_FACTOR_ONE_MINUS_DST_ALPHA;
        case B::ConstantColor:
            return VK_BLEND_FACTOR_CONSTANT_COLOR;
        case B::OneMinusConstantColor:
            return VK_BLEND_FACTOR_ONE_MINUS_CONSTANT_COLOR;
    }
    return VK_BLEND_FACTOR_ONE;
}

VkBlendOp toBlendOp(gdi::BlendOp o) {
    switch (o) {
        case gdi::BlendOp::Subtract:
            return VK_BLEND_OP_SUBTRACT;
        case gdi::BlendOp::ReverseSubtract:
            return VK_BLEND_OP_REVERSE_SUBTRACT;
        case gdi::BlendOp::Min:
            return VK_BLEND_OP_MIN;
        case gdi::BlendOp::Max:
            return VK_BLEND_OP_MAX;
        default:
            return VK_BLEND_OP_ADD;
    }
}

VkPrimitiveTopology toTopology(gdi::PrimitiveTopology t) {
    switch (t) {
        case gdi::PrimitiveTopology::TriangleStrip:
            return VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP;
        case gdi::PrimitiveTopology::LineList:
            return VK_PRIMITIVE_TOPOLOGY_LINE_LIST;
        case gdi::PrimitiveTopology::LineStrip:
            return VK_PRIMITIVE_TOPOLOGY_LINE_STRIP;
        case gdi::PrimitiveTopology::PointList:
            return VK_PRIMITIVE_TOPOLOGY_POINT_LIST;
        case gdi::PrimitiveTopology::PatchList:
            return VK_PRIMITIVE_TOPOLOGY_PATCH_LIST;
        default:
            return VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    }
}
}  // namespace

gdi::ShaderHandle VulkanDevice::createShader(const gdi::ShaderDesc& given) {
    const DeviceCall call(*this);
    loss_.check("createShader");
    // Source text is compiled first (ShaderCompiler.h), the same on every backend.
    const gdi::ShaderDesc desc = gdi::withCompiledSource(given);
    gdi::validate::shaderDesc(desc);
    const gdi::fault::ObjectScope faultObject(desc.binary.name);
    const std::string name = desc.binary.name ? desc.binary.name : "";
    const auto& code = desc.binary.vulkan;
    if (code.size() < 5 || code[0] != kSpirvMagic)
        throw gdi::Error("shader '" + name + "': not a SPIR-V binary for Vulkan (" +
                         std::to_string(code.size()) + " words, missing magic number)");
    Shader s;
    const auto rules = props_.apiVersion >= VK_API_VERSION_1_3 ? gdi::SpirvRules::Vulkan13
                                                               : gdi::SpirvRules::Vulkan12;
    gdi::validateShaderBinary(desc, rules, info_.features);
    s.iface = gdi::reflectShader(code, desc.stage, desc.entryPoint, name, rules);
    VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    ci.codeSize = code.size_bytes();
    ci.pCode = code.data();
    check(nativeAllocation("vkCreateShaderModule",
                           [&] { return vkCreateShaderModule(device_, &ci, nullptr, &s.module); }),
          ("vkCreateShaderModule for '" + name + "'").c_str());
    s.stage = desc.stage;
    s.name = name;
    s.entry = desc.entryPoint;
    const uint64_t stage = uint64_t(desc.stage);
    s.codeHash = gdi::fnv1a(
        {reinterpret_cast<const uint8_t*>(code.data()), code.size_bytes()},
        gdi::fnv1a({reinterpret_cast<const uint8_t*>(s.entry.data()), s.entry.size()},
                   gdi::fnv1a({reinterpret_cast<const uint8_t*>(&stage), sizeof stage})));
    setName(VK_OBJECT_TYPE_SHADER_MODULE, uint64_t(s.module), desc.binary.name);
    return shaders_.add(std::move(s));
}

// Specialization data for one stage: every value given (Vulkan ignores ids a stage does not
// declare), each 32 bits.
struct StageSpecialization {
    std::vector<VkSpecializationMapEntry> entries;
    VkSpecializationInfo info{};
    explicit StageSpecialization(const std::vector<gdi::SpecializationConstant>& values) {
        for (size_t i = 0; i < values.size(); ++i)
            entries.push_back(
                {values[i].id, uint32_t(i * sizeof(gdi::SpecializationConstant) + 4), 4});
        info = {uint32_t(entries.size()), entries.data(),
                values.size() * sizeof(gdi::SpecializationConstant), values.data()};
    }
    const VkSpecializationInfo* get() const { return entries.empty() ? nullptr : &info; }
};

// The constants block, one push-constant range over every stage of the pipeline.
static Pipeline makeLayout(VkDevice device, const std::vector<gdi::BindingSlot>& bindings,
                           const char* debugName, uint32_t constantBytes,
                           VkShaderStageFlags stages) {
    Pipeline p;
    p.constantBytes = constantBytes;
    p.constantStages = stages;
    p.bindings = bindings;
    p.requiredSlots = gdi::validate::requiredSlotMask(bindings);
    p.name = debugName ? debugName : "";
    std::vector<VkDescriptorSetLayoutBinding> vb;
    for (const gdi::BindingSlot& b : bindings) {
        vb.push_back({b.slot, toDescriptorType(b.type), 1, toStages(b.stages), nullptr});
        VkWriteDescriptorSet& w = p.writeTemplates[b.slot & 63];
        w = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        w.dstBinding = b.slot;
        w.descriptorCount = 1;
        w.descriptorType = toDescriptorType(b.type);
        if (b.type == gdi::BindingType::UniformBuffer)
            p.bufferSlots[0] |= uint64_t(1) << (b.slot & 63);
        if (b.type == gdi::BindingType::StorageBuffer)
            p.bufferSlots[1] |= uint64_t(1) << (b.slot & 63);
    }
    VkDescriptorSetLayoutCreateInfo li{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    li.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
    li.bindingCount = uint32_t(vb.size());
    li.pBindings = vb.data();
    check(nativeAllocation(
              "vkCreateDescriptorSetLayout",
              [&] { return vkCreateDescriptorSetLayout(device, &li, nullptr, &p.setLayout); }),
          "vkCreateDescriptorSetLayout");
    VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    pli.setLayoutCount = 1;
    pli.pSetLayouts = &p.setLayout;
    const VkPushConstantRange range{stages, 0, constantBytes};
    pli.pushConstantRangeCount = constantBytes ? 1 : 0;
    pli.pPushConstantRanges = &range;
    if (VkResult r = nativeAllocation(
            "vkCreatePipelineLayout",
            [&] { return vkCreatePipelineLayout(device, &pli, nullptr, &p.layout); });
        r != VK_SUCCESS) {
        vkDestroyDescriptorSetLayout(device, p.setLayout, nullptr);
        throwVk(r, "vkCreatePipelineLayout");
    }
    return p;
}

gdi::PipelineHandle VulkanDevice::createGraphicsPipeline(const gdi::GraphicsPipelineDesc& d) {
    const DeviceCall call(*this);
    loss_.check("createGraphicsPipeline");
    const gdi::fault::ObjectScope faultObject(d.debugName);
    gdi::validate::graphicsPipelineDesc(d, info_);
    gdi::validate::blendedTargets(d, [&](gdi::Format f) { return formatCaps(f); });
    const std::string name = d.debugName ? d.debugName : "";
    std::vector<std::pair<gdi::ShaderStage, Shader*>> shaders;  // in stage order
    std::vector<const gdi::ShaderInterface*> ifaces;
    for (const gdi::validate::PipelineStage& st : gdi::validate::graphicsStages(d)) {
        Shader& s = shaders_.get(st.shader, st.kind);
        gdi::validate::shaderOfStage(s.stage, st, name);
        shaders.push_back({st.stage, &s});
        ifaces.push_back(&s.iface);
    }
    const Shader& vs = *shaders.front().second;
    const Shader* fs = d.fragmentShader ? shaders.back().second : nullptr;
    gdi::validate::vertexInputs(d, vs.iface, name);
    gdi::validate::stageInterfaces(ifaces, name);
    if (fs) gdi::validate::fragmentOutputs(d, fs->iface, name);
    const std::vector<gdi::BindingSlot> bindings =
        gdi::validate::pipelineBindings(d.bindings, ifaces, name, info_.limits);
    const std::array<uint8_t, 64> dimensions = gdi::validate::slotDimensions(ifaces, name);
    for (gdi::Format f : d.colorFormats)
        if (!supportsFormat(f, gdi::TextureUsage::RenderTarget))
            throw gdi::Error("pipeline '" + name + "': format " +
                             std::string(gdi::formatInfo(f).name) +
                             " cannot be a render target on this device");

    const uint32_t constantBytes = gdi::validate::pipelineConstants(ifaces, name);
    gdi::validate::specialization(d.specialization, ifaces, name);
    const std::string key = gdi::pipelineKey(d, [&](gdi::ShaderHandle h) { return codeHash(h); });
    if (std::optional<Pipeline> shared = sharedPipelines_.acquire(key))
        return pipelines_.add(std::move(*shared));
    const StageSpecialization spec(d.specialization);

    std::vector<VkPipelineShaderStageCreateInfo> stages;
    for (const auto& [stage, s] : shaders)
        stages.push_back({VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0,
                          VkShaderStageFlagBits(toStages(stage)), s->module, s->entry.c_str(),
                          spec.get()});
    VkPipelineTessellationStateCreateInfo tess{
        VK_STRUCTURE_TYPE_PIPELINE_TESSELLATION_STATE_CREATE_INFO};
    tess.patchControlPoints = d.patchControlPoints;

    std::vector<VkVertexInputBindingDescription> vbind;
    std::vector<VkVertexInputAttributeDescription> vattr;
    for (uint32_t i = 0; i < d.vertexBuffers.size(); ++i) {
        const auto& vb = d.vertexBuffers[i];
        vbind.push_back(
            {i, vb.stride,
             vb.perInstance ? VK_VERTEX_INPUT_RATE_INSTANCE : VK_VERTEX_INPUT_RATE_VERTEX});
        for (const auto& a : vb.attributes)
            vattr.push_back({a.location, i, toVkVertexFormat(a.format), a.offset});
    }
    VkPipelineVertexInputStateCreateInfo vi{
        VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    vi.vertexBindingDescriptionCount = uint32_t(vbind.size());
    vi.pVertexBindingDescriptions = vbind.data();
    vi.vertexAttributeDescriptionCount = uint32_t(vattr.size());
    vi.pVertexAttributeDescriptions = vattr.data();

    VkPipelineInputAssemblyStateCreateInfo ia{
        VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    ia.topology = toTopology(d.topology);
    ia.primitiveRestartEnable = d.primitiveRestart;

    VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    vp.viewportCount = 1;
    vp.scissorCount = 1;

    VkPipelineRasterizationStateCreateInfo rs{
        VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    rs.polygonMode = VK_POLYGON_MODE_FILL;
    rs.cullMode = d.raster.cullMode == gdi::CullMode::Back    ? VK_CULL_MODE_BACK_BIT
                  : d.raster.cullMode == gdi::CullMode::Front ? VK_CULL_MODE_FRONT_BIT
                                                              : VK_CULL_MODE_NONE;
    // gdi's CounterClockwise means CCW as seen in framebuffer coordinates (y down), which is
    // exactly how Vulkan evaluates VK_FRONT_FACE_COUNTER_CLOCKWISE.
    rs.frontFace = d.raster.frontFace == gdi::FrontFace::Clockwise
                       ? VK_FRONT_FACE_CLOCKWISE
                       : VK_FRONT_FACE_COUNTER_CLOCKWISE;
    rs.lineWidth = 1.0f;
    rs.depthClampEnable = d.raster.depthClamp;
    // Always on: the values are dynamic state (setPipeline sets the pipeline's, setDepthBias
    // others), and a bias of 0 and 0 is no bias.
    rs.depthBiasEnable = VK_TRUE;
    rs.depthBiasConstantFactor = d.raster.depthBiasConstant;
    rs.depthBiasSlopeFactor = d.raster.depthBiasSlope;
    rs.depthBiasClamp = d.raster.depthBiasClamp;

    VkPipelineMultisampleStateCreateInfo ms{
        VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    ms.rasterizationSamples = VkSampleCountFlagBits(d.multisample.sampleCount);
    ms.alphaToCoverageEnable = d.multisample.alphaToCoverage;
    // Only the bits of existing samples count (GL ignores the others; lavapipe drew a
    // single-sample target whenever any bit was set).
    const VkSampleMask sampleMask =
        d.multisample.sampleMask & uint32_t((uint64_t(1) << d.multisample.sampleCount) - 1);
    ms.pSampleMask = &sampleMask;

    const auto& ds = d.depthStencil;
    auto face = [&](const gdi::StencilFaceState& f) {
        return VkStencilOpState{toStencilOp(f.failOp),      toStencilOp(f.passOp),
                                toStencilOp(f.depthFailOp), toCompare(f.compare),
                                ds.stencilReadMask,         ds.stencilWriteMask,
                                ds.stencilReference};
    };
    VkPipelineDepthStencilStateCreateInfo dss{
        VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    // depthWrite without depthTest writes every fragment's depth, as on GL (Device.h): Vulkan
    // writes depth only with the test enabled, so the test runs and always passes.
    dss.depthTestEnable = ds.depthTest || ds.depthWrite;
    dss.depthWriteEnable = ds.depthWrite;
    dss.depthCompareOp = ds.depthTest ? toCompare(ds.depthCompare) : VK_COMPARE_OP_ALWAYS;
    dss.stencilTestEnable = ds.stencilTest;
    dss.front = face(ds.front);
    dss.back = face(ds.back);

    const std::vector<gdi::BlendTargetState> written =
        gdi::validate::writtenTargetBlends(d, fs ? &fs->iface : nullptr);
    std::vector<VkPipelineColorBlendAttachmentState> blends(d.colorFormats.size());
    for (size_t i = 0; i < blends.size(); ++i) {
        const gdi::BlendTargetState& b = written[i];
        blends[i].blendEnable = b.enable;
        blends[i].srcColorBlendFactor = toBlendFactor(b.srcColor);
        blends[i].dstColorBlendFactor = toBlendFactor(b.dstColor);
        blends[i].colorBlendOp = toBlendOp(b.colorOp);
        blends[i].srcAlphaBlendFactor = toBlendFactor(b.srcAlpha);
        blends[i].dstAlphaBlendFactor = toBlendFactor(b.dstAlpha);
        blends[i].alphaBlendOp = toBlendOp(b.alphaOp);
        blends[i].colorWriteMask =
            VkColorComponentFlags(uint8_t(b.writeMask));  // R,G,B,A bits match
    }
    VkPipelineColorBlendStateCreateInfo cb{
        VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    cb.attachmentCount = uint32_t(blends.size());
    cb.pAttachments = blends.data();
    for (int i = 0; i < 4; ++i) cb.blendConstants[i] = d.blendConstant[i];

    VkDynamicState dyn[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR,
                            VK_DYNAMIC_STATE_BLEND_CONSTANTS, VK_DYNAMIC_STATE_STENCIL_REFERENCE,
                            VK_DYNAMIC_STATE_DEPTH_BIAS};
    VkPipelineDynamicStateCreateInfo dy{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dy.dynamicStateCount = uint32_t(std::size(dyn));
    dy.pDynamicStates = dyn;

    std::vector<VkFormat> colorFormats;
    for (gdi::Format f : d.colorFormats) colorFormats.push_back(toVkFormat(f));
    VkPipelineRenderingCreateInfo ri{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    ri.colorAttachmentCount = uint32_t(colorFormats.size());
    ri.pColorAttachmentFormats = colorFormats.data();
    ri.depthAttachmentFormat =
        gdi::formatInfo(d.depthFormat).hasDepth ? toVkFormat(d.depthFormat) : VK_FORMAT_UNDEFINED;
    ri.stencilAttachmentFormat =
        gdi::formatInfo(d.depthFormat).hasStencil ? toVkFormat(d.depthFormat) : VK_FORMAT_UNDEFINED;

    // The constants range covers only the stages that read the block: drivers update per stage.
    VkShaderStageFlags constantStages = 0;
    for (const auto& [stage, s] : shaders)
        if (s->iface.pushConstantBytes) constantStages |= toStages(stage);
    Pipeline p = makeLayout(device_, bindings, d.debugName, constantBytes, constantStages);
    p.signature = gdi::validate::pipelineSignature(d);
    p.writesDepthStencil = gdi::validate::writesDepthStencil(d);
    p.vertexBindings = gdi::validate::vertexBindings(d);
    p.slotDimensions = dimensions;
    p.slotBlockBytes = gdi::validate::slotBlockBytes(ifaces);
    std::copy(std::begin(d.blendConstant), std::end(d.blendConstant), p.blendConstant.begin());
    p.stencilReference = d.depthStencil.stencilReference;
    p.depthBias = {d.raster.depthBiasConstant, d.raster.depthBiasSlope, d.raster.depthBiasClamp};
    VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    ci.pNext = &ri;
    ci.stageCount = uint32_t(stages.size());
    ci.pStages = stages.data();
    ci.pVertexInputState = &vi;
    ci.pInputAssemblyState = &ia;
    if (d.patchControlPoints) ci.pTessellationState = &tess;
    ci.pViewportState = &vp;
    ci.pRasterizationState = &rs;
    ci.pMultisampleState = &ms;
    ci.pDepthStencilState = &dss;
    ci.pColorBlendState = &cb;
    ci.pDynamicState = &dy;
    ci.layout = p.layout;
    VkPipelineCreationFeedback feedback{};
    VkPipelineCreationFeedbackCreateInfo fi{
        VK_STRUCTURE_TYPE_PIPELINE_CREATION_FEEDBACK_CREATE_INFO};
    fi.pPipelineCreationFeedback = &feedback;
    if (props_.apiVersion >= VK_API_VERSION_1_3) fi.pNext = std::exchange(ci.pNext, &fi);
    VkResult r = nativeAllocation("vkCreateGraphicsPipelines", [&] {
        return vkCreateGraphicsPipelines(device_, pipelineCache_, 1, &ci, nullptr, &p.pipeline);
    });
    if (r == VK_SUCCESS) countCacheUse(feedback);
    if (r != VK_SUCCESS) {
        vkDestroyPipelineLayout(device_, p.layout, nullptr);
        vkDestroyDescriptorSetLayout(device_, p.setLayout, nullptr);
        throwVk(r, ("vkCreateGraphicsPipelines for '" + name + "'").c_str());
    }
    setName(VK_OBJECT_TYPE_PIPELINE, uint64_t(p.pipeline), d.debugName);
    return addShared(std::move(p), key);
}

gdi::PipelineHandle VulkanDevice::createComputePipeline(const gdi::ComputePipelineDesc& d) {
    const DeviceCall call(*this);
    loss_.check("createComputePipeline");
    const gdi::fault::ObjectScope faultObject(d.debugName);
    gdi::validate::computePipelineDesc(d);
    Shader& cs = shaders_.get(d.computeShader, "compute shader");
    gdi::validate::computeShaderStage(cs.stage, d);
    const std::string name = d.debugName ? d.debugName : "";
    gdi::validate::workgroup(cs.iface, info_.limits, name);
    const uint32_t constantBytes = gdi::validate::pipelineConstants({&cs.iface}, name);
    gdi::validate::specialization(d.specialization, {&cs.iface}, name);
    const StageSpecialization spec(d.specialization);
    const std::array<uint8_t, 64> dimensions = gdi::validate::slotDimensions({&cs.iface}, name);
    const std::array<uint32_t, 64> blockBytes = gdi::validate::slotBlockBytes({&cs.iface});
    const std::string key = gdi::pipelineKey(d, [&](gdi::ShaderHandle h) { return codeHash(h); });
    if (std::optional<Pipeline> shared = sharedPipelines_.acquire(key))
        return pipelines_.add(std::move(*shared));
    Pipeline p = makeLayout(
        device_, gdi::validate::pipelineBindings(d.bindings, {&cs.iface}, name, info_.limits),
        d.debugName, constantBytes, VK_SHADER_STAGE_COMPUTE_BIT);
    p.slotBlockBytes = blockBytes;
    p.slotDimensions = dimensions;
    p.bindPoint = VK_PIPELINE_BIND_POINT_COMPUTE;
    VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                nullptr,
                0,
                VK_SHADER_STAGE_COMPUTE_BIT,
                cs.module,
                cs.entry.c_str(),
                spec.get()};
    ci.layout = p.layout;
    VkPipelineCreationFeedback feedback{};
    VkPipelineCreationFeedbackCreateInfo fi{
        VK_STRUCTURE_TYPE_PIPELINE_CREATION_FEEDBACK_CREATE_INFO};
    fi.pPipelineCreationFeedback = &feedback;
    if (props_.apiVersion >= VK_API_VERSION_1_3) ci.pNext = &fi;
    VkResult r = nativeAllocation("vkCreateComputePipelines", [&] {
        return vkCreateComputePipelines(device_, pipelineCache_, 1, &ci, nullptr, &p.pipeline);
    });
    if (r == VK_SUCCESS) countCacheUse(feedback);
    if (r != VK_SUCCESS) {
        vkDestroyPipelineLayout(device_, p.layout, nullptr);
        vkDestroyDescriptorSetLayout(device_, p.setLayout, nullptr);
        throwVk(r, "vkCreateComputePipelines");
    }
    setName(VK_OBJECT_TYPE_PIPELINE, uint64_t(p.pipeline), d.debugName);
    return addShared(std::move(p), key);
}

// A pipeline just made: its objects shared from now on under `key`.
gdi::PipelineHandle VulkanDevice::addShared(Pipeline p, const std::string& key) {
    p.sharedKey = key;
    sharedPipelines_.add(key, p);
    return pipelines_.add(std::move(p));
}

void VulkanDevice::destroyPipelineObjects(const Pipeline& p) {
    vkDestroyPipeline(device_, p.pipeline, nullptr);
    vkDestroyPipelineLayout(device_, p.layout, nullptr);
    vkDestroyDescriptorSetLayout(device_, p.setLayout, nullptr);
}

}  // namespace fe::vk

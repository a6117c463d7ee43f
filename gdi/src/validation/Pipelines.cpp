// Shared validation: Shaders and pipelines: descriptions, bindings against the shaders' reflection, vertex inputs,
// fragment outputs, blending, workgroups and specialization constants.
#include "ValidationSupport.h"

#include <atomic>

#include "fe/gdi/MessageLog.h"

namespace fe::gdi::validate {

namespace {

ScalarKind vertexKind(VertexFormat f) {
    return f == VertexFormat::UInt32 ? ScalarKind::Uint : ScalarKind::Float;
}

}  // namespace

void shaderDesc(const ShaderDesc& d) {
    const std::string what = label("shader", d.binary.name);
    if (d.stage != ShaderStage::Vertex && d.stage != ShaderStage::Fragment &&
        d.stage != ShaderStage::Compute && d.stage != ShaderStage::Geometry &&
        d.stage != ShaderStage::TessControl && d.stage != ShaderStage::TessEvaluation)
        fail(what,
             "stage must be exactly one of Vertex, TessControl, TessEvaluation, Geometry, "
             "Fragment, Compute");
    if (!d.entryPoint || !*d.entryPoint) fail(what, "entry point is empty");
    if (d.binary.vulkan.empty() && d.binary.opengl.empty())
        fail(
            what,
            "the binary is empty (no SPIR-V for Vulkan or for OpenGL: fe_add_shaders and shaders::find make both)");
}

static void bindingList(const std::vector<BindingSlot>& bindings, const std::string& what) {
    uint64_t seen = 0;
    for (const BindingSlot& b : bindings) {
        if (b.slot >= 64)
            fail(what, "binding slot " + std::to_string(b.slot) + " is out of range (0..63)");
        if (seen & (uint64_t(1) << b.slot))
            fail(what, "binding slot " + std::to_string(b.slot) + " is declared twice");
        seen |= uint64_t(1) << b.slot;
    }
}

// The optional stages: present on the device, tessellation as a pair with PatchList.
static void stagesOfPipeline(const GraphicsPipelineDesc& d, const DeviceInfo& device,
                             const std::string& what) {
    const bool tessellated = d.tessControlShader || d.tessEvaluationShader;
    if (tessellated && !(d.tessControlShader && d.tessEvaluationShader))
        fail(what,
             "tessellation needs both a tessControlShader and a tessEvaluationShader (one is "
             "missing)");
    if (tessellated && !device.features.tessellationShaders)
        fail(what, "tessellation shaders are not supported on " + device.backend);
    if (d.geometryShader && !device.features.geometryShaders)
        fail(what, "geometry shaders are not supported on " + device.backend);
    const bool patches = d.topology == PrimitiveTopology::PatchList;
    if (tessellated && !patches)
        fail(what, "tessellation shaders draw patches: set topology PrimitiveTopology::PatchList");
    if (patches && !tessellated)
        fail(what,
             "topology PatchList needs tessellation shaders (tessControlShader and "
             "tessEvaluationShader)");
    const uint32_t most = device.limits.maxTessellationPatchSize;
    if (patches && (d.patchControlPoints == 0 || d.patchControlPoints > most))
        fail(what, "patchControlPoints " + std::to_string(d.patchControlPoints) + " is not 1 to " +
                       std::to_string(most));
    if (!patches && d.patchControlPoints != 0)
        fail(what, "patchControlPoints is for topology PatchList only");
}

void graphicsPipelineDesc(const GraphicsPipelineDesc& d, const DeviceInfo& device) {
    const DeviceLimits& limits = device.limits;
    const std::string what = label("graphics pipeline", d.debugName);
    const uint32_t samples = d.multisample.sampleCount;
    if (samples != 1 && samples != 2 && samples != 4 && samples != 8)
        fail(what, "sampleCount " + std::to_string(samples) + " is not 1, 2, 4 or 8");
    if (samples > 1 && !(limits.colorSampleCounts & limits.depthSampleCounts & samples))
        fail(what, std::to_string(samples) + " samples are not supported on " + device.backend);
    if (d.raster.depthClamp && !device.features.depthClamp)
        fail(what, "depth clamp is not supported on " + device.backend);
    if (d.raster.depthBiasClamp != 0 && !device.features.depthBiasClamp)
        fail(what, "depth bias clamp is not supported on " + device.backend);
    for (float v : {d.raster.depthBiasConstant, d.raster.depthBiasSlope, d.raster.depthBiasClamp})
        if (!std::isfinite(v)) fail(what, "depth bias values must be finite");
    for (Format f : d.colorFormats)
        if (isCompressedFormat(f))
            fail(what,
                 "colour target format " + std::string(formatInfo(f).name) + " is compressed");
    if (!d.vertexShader) fail(what, "no vertex shader");
    if (d.colorFormats.empty() && d.depthFormat == Format::Undefined)
        fail(what, "no colour or depth target format");
    if (limits.maxColorAttachments && d.colorFormats.size() > limits.maxColorAttachments)
        fail(what, std::to_string(d.colorFormats.size()) +
                       " colour targets exceed the device limit " +
                       std::to_string(limits.maxColorAttachments));
    for (Format f : d.colorFormats)
        if (f == Format::Undefined || isDepthFormat(f))
            fail(what, "colour target format " + std::string(formatInfo(f).name) +
                           " is not a colour format");
    if (d.depthFormat != Format::Undefined && !isDepthFormat(d.depthFormat))
        fail(what, "depth format " + std::string(formatInfo(d.depthFormat).name) +
                       " is not a depth format");
    if ((d.depthStencil.depthTest || d.depthStencil.depthWrite) &&
        d.depthFormat == Format::Undefined)
        fail(what, "depth test/write enabled without a depth format");
    if (d.depthStencil.stencilTest && !formatInfo(d.depthFormat).hasStencil)
        fail(what, "stencil test enabled but depth format has no stencil");
    if ((d.depthStencil.depthTest || d.depthStencil.depthWrite) &&
        !formatInfo(d.depthFormat).hasDepth)
        fail(what, "depth test or write enabled but the depth format has no depth");
    if (d.blend.size() > d.colorFormats.size()) fail(what, "more blend states than colour targets");
    blendConstant(d.blendConstant, what.c_str());
    if (d.primitiveRestart && d.topology != PrimitiveTopology::TriangleStrip &&
        d.topology != PrimitiveTopology::LineStrip)
        fail(what, "primitiveRestart needs a strip topology (TriangleStrip or LineStrip)");
    if (d.vertexBuffers.size() > kMaxVertexBuffers)
        fail(what, std::to_string(d.vertexBuffers.size()) + " vertex buffers (at most " +
                       std::to_string(kMaxVertexBuffers) + ")");
    uint32_t locations = 0;
    for (size_t i = 0; i < d.vertexBuffers.size(); ++i) {
        const VertexBufferLayout& vb = d.vertexBuffers[i];
        for (const VertexAttribute& a : vb.attributes) {
            if (a.format >= VertexFormat::Count)
                fail(what, "vertex attribute has an invalid format");
            if (a.location >= 16)
                fail(what, "vertex attribute location " + std::to_string(a.location) + " >= 16");
            if (locations & (1u << a.location))
                fail(what,
                     "vertex attribute location " + std::to_string(a.location) + " is used twice");
            locations |= 1u << a.location;
            if (vb.stride != 0 &&
                a.offset + vertexFormatInfo(a.format).bytes > vb.stride)  // 0: one element for all
                fail(what, "vertex attribute at location " + std::to_string(a.location) +
                               " overruns stride " + std::to_string(vb.stride));
        }
    }
    bindingList(d.bindings, what);
    stagesOfPipeline(d, device, what);
}

std::array<uint32_t, 64> slotBlockBytes(const std::vector<const ShaderInterface*>& shaders) {
    std::array<uint32_t, 64> bytes{};
    for (const ShaderInterface* s : shaders)
        for (const ShaderInterface::Binding& b :
             s ? s->bindings : std::vector<ShaderInterface::Binding>{})
            if (b.slot < 64 &&
                (b.type == BindingType::UniformBuffer || b.type == BindingType::StorageBuffer))
                bytes[b.slot] = std::max(bytes[b.slot], b.blockBytes);
    return bytes;
}

namespace {
std::atomic<uint64_t> warnings{0};
}

void rangeSmallerThanBlock(uint32_t slot, uint64_t bound, uint32_t declared,
                           const std::string& pipeline) {
    static MessageLog log("fe validation");
    ++warnings;
    log.report("warning", "slot " + std::to_string(slot) + " holds a range of " +
                              std::to_string(bound) + " bytes where pipeline '" + pipeline +
                              "' declares a block of " + std::to_string(declared) +
                              " bytes: a read past the range is undefined");
}

uint64_t warningCount() { return warnings.load(); }

std::vector<PipelineStage> graphicsStages(const GraphicsPipelineDesc& d) {
    std::vector<PipelineStage> out;
    auto add = [&](ShaderStage stage, ShaderHandle h, const char* field, const char* kind) {
        if (h) out.push_back({stage, h, field, kind});
    };
    add(ShaderStage::Vertex, d.vertexShader, "vertexShader", "vertex shader");
    add(ShaderStage::TessControl, d.tessControlShader, "tessControlShader",
        "tessellation control shader");
    add(ShaderStage::TessEvaluation, d.tessEvaluationShader, "tessEvaluationShader",
        "tessellation evaluation shader");
    add(ShaderStage::Geometry, d.geometryShader, "geometryShader", "geometry shader");
    add(ShaderStage::Fragment, d.fragmentShader, "fragmentShader", "fragment shader");
    return out;
}

void shaderOfStage(ShaderStage actual, const PipelineStage& s, const std::string& pipeline) {
    if (actual != s.stage)
        throw Error("pipeline '" + pipeline + "': " + s.field + " is not a " +
                    shaderStageName(s.stage) + " shader (it is a " + shaderStageName(actual) +
                    " shader)");
}

void stageInterfaces(const std::vector<const ShaderInterface*>& shaders,
                     const std::string& pipeline) {
    const std::string what = "pipeline '" + pipeline + "'";
    for (size_t i = 1; i < shaders.size(); ++i) {
        const ShaderInterface& from = *shaders[i - 1];
        const ShaderInterface& to = *shaders[i];
        const std::string fromName = shaderStageName(from.stage),
                          toName = shaderStageName(to.stage);
        for (const ShaderInterface::Variable& in : to.inputs) {
            const ShaderInterface::Variable* out = nullptr;
            for (const ShaderInterface::Variable& o : from.outputs)
                if (in.location >= o.location && in.location < o.location + o.locations) out = &o;
            const std::string input = toName + " shader input '" + in.name + "' (location " +
                                      std::to_string(in.location) + ")";
            if (!out) fail(what, input + " is not written by the " + fromName + " shader");
            if (out->kind != in.kind || out->components < in.components)
                fail(what, input + " is " + scalarKindName(in.kind) + " x" +
                               std::to_string(in.components) + ", the " + fromName +
                               " shader writes '" + out->name + "' there as " +
                               scalarKindName(out->kind) + " x" + std::to_string(out->components));
            if (out->patch != in.patch)
                fail(what, input + (in.patch ? " is" : " is not") + " per-patch, '" + out->name +
                               "' of the " + fromName + " shader" +
                               (out->patch ? " is" : " is not"));
        }
    }
}

void computePipelineDesc(const ComputePipelineDesc& d) {
    const std::string what = label("compute pipeline", d.debugName);
    if (!d.computeShader) fail(what, "no compute shader");
    bindingList(d.bindings, what);
}

std::array<uint8_t, 64> slotDimensions(const std::vector<const ShaderInterface*>& shaders,
                                       const std::string& pipeline) {
    std::array<uint8_t, 64> dims{};
    for (const ShaderInterface* s : shaders) {
        if (!s) continue;
        for (const ShaderInterface::Binding& b : s->bindings) {
            if (b.slot >= 64 || !b.dimension) continue;
            if (dims[b.slot] && dims[b.slot] != b.dimension)
                fail(label("pipeline", pipeline.c_str()),
                     "slot " + std::to_string(b.slot) + " is a " + textureKindName(dims[b.slot]) +
                         " in one stage and a " + textureKindName(b.dimension) + " in another");
            dims[b.slot] = b.dimension;
        }
    }
    return dims;
}

void computeShaderStage(ShaderStage stage, const ComputePipelineDesc& d) {
    if (stage != ShaderStage::Compute)
        fail(label("compute pipeline", d.debugName), "computeShader is not a compute shader");
}

std::vector<VertexBinding> vertexBindings(const GraphicsPipelineDesc& d) {
    std::vector<VertexBinding> out;
    for (const VertexBufferLayout& vb : d.vertexBuffers) {
        VertexBinding b{.stride = vb.stride, .perInstance = vb.perInstance};
        for (const VertexAttribute& a : vb.attributes)
            b.extent = std::max(b.extent, a.offset + vertexFormatInfo(a.format).bytes);
        out.push_back(b);
    }
    return out;
}

std::array<uint8_t, 64> slotKinds(const std::vector<BindingSlot>& bindings) {
    std::array<uint8_t, 64> kinds{};
    for (const BindingSlot& b : bindings) kinds[b.slot & 63] = uint8_t(1 + uint8_t(b.type));
    return kinds;
}

uint64_t requiredSlotMask(const std::vector<BindingSlot>& bindings) {
    uint64_t m = 0;
    for (const BindingSlot& b : bindings) m |= uint64_t(1) << (b.slot & 63);
    return m;
}

std::vector<BindingSlot> pipelineBindings(const std::vector<BindingSlot>& declared,
                                          const std::vector<const ShaderInterface*>& shaders,
                                          const std::string& pipeline, const DeviceLimits& limits) {
    const std::string what = "pipeline '" + pipeline + "'";
    std::vector<BindingSlot> used;  // by slot, stages merged
    for (const ShaderInterface* sh : shaders) {
        if (!sh) continue;
        for (const ShaderInterface::Binding& b : sh->bindings) {
            if (b.slot >= 64)
                fail(what, std::string("the ") + shaderStageName(sh->stage) +
                               " shader uses binding " + std::to_string(b.slot) + " ('" + b.name +
                               "'); slots are 0 to 63");
            auto it = std::find_if(used.begin(), used.end(),
                                   [&](const BindingSlot& u) { return u.slot == b.slot; });
            if (it == used.end()) {
                used.push_back({b.slot, b.type, sh->stage});
            } else if (it->type != b.type) {
                fail(what, "slot " + std::to_string(b.slot) + " is a " + bindingTypeName(it->type) +
                               " in one shader and a " + bindingTypeName(b.type) + " ('" + b.name +
                               "') in the " + shaderStageName(sh->stage) + " shader");
            } else {
                it->stages = it->stages | sh->stage;
            }
        }
    }
    std::sort(used.begin(), used.end(),
              [](const BindingSlot& a, const BindingSlot& b) { return a.slot < b.slot; });
    const auto images = std::count_if(used.begin(), used.end(), [](const BindingSlot& u) {
        return u.type == BindingType::StorageTexture;
    });
    if (limits.maxStorageTextures && uint64_t(images) > limits.maxStorageTextures)
        fail(what, "the shaders use " + std::to_string(images) +
                       " storage textures; this device binds at most " +
                       std::to_string(limits.maxStorageTextures) +
                       " to one pipeline (limits.maxStorageTextures)");
    if (declared.empty()) return used;
    for (const BindingSlot& u : used) {
        auto it = std::find_if(declared.begin(), declared.end(),
                               [&](const BindingSlot& d) { return d.slot == u.slot; });
        std::string user;
        for (const ShaderInterface* sh : shaders)
            if (sh && any(u.stages, sh->stage))
                user += std::string(user.empty() ? "the " : " and ") + shaderStageName(sh->stage);
        if (it == declared.end())
            fail(
                what,
                "binding slot " + std::to_string(u.slot) + " (" + bindingTypeName(u.type) +
                    ") is used by " + user +
                    " shader but missing from the pipeline's bindings (leave bindings empty to take them from the shaders)");
        if (it->type != u.type)
            fail(what, "binding slot " + std::to_string(u.slot) + " is declared a " +
                           bindingTypeName(it->type) + ", but " + user + " shader uses a " +
                           bindingTypeName(u.type));
        if ((uint32_t(it->stages) & uint32_t(u.stages)) != uint32_t(u.stages))
            fail(what, "binding slot " + std::to_string(u.slot) + " is used by " + user +
                           " shader, which its declared stages leave out");
    }
    return declared;
}

void vertexInputs(const GraphicsPipelineDesc& d, const ShaderInterface& vs,
                  const std::string& pipeline) {
    const std::string what = "pipeline '" + pipeline + "'";
    for (const ShaderInterface::Variable& in : vs.inputs) {
        const VertexAttribute* found = nullptr;
        for (const VertexBufferLayout& vb : d.vertexBuffers)
            for (const VertexAttribute& a : vb.attributes)
                if (a.location == in.location) found = &a;
        if (!found)
            fail(what, "vertex shader input '" + in.name + "' (location " +
                           std::to_string(in.location) + ") has no attribute in the vertex layout");
        if (vertexKind(found->format) != in.kind)
            fail(what, "vertex shader input '" + in.name + "' (location " +
                           std::to_string(in.location) + ") is " + scalarKindName(in.kind) +
                           ", its attribute's format gives " +
                           scalarKindName(vertexKind(found->format)));
    }
}

void fragmentOutputs(const GraphicsPipelineDesc& d, const ShaderInterface& fs,
                     const std::string& pipeline) {
    const std::string what = "pipeline '" + pipeline + "'";
    for (const ShaderInterface::Variable& out : fs.outputs) {
        if (out.location >= d.colorFormats.size())
            continue;  // no target there: the value is dropped, as both APIs do
        const FormatInfo& f = formatInfo(d.colorFormats[out.location]);
        const ScalarKind want = f.isInteger ? ScalarKind::Uint : ScalarKind::Float;
        if (out.kind != want)
            fail(what, "fragment output '" + out.name + "' (location " +
                           std::to_string(out.location) + ") is " + scalarKindName(out.kind) +
                           ", colour target " + std::to_string(out.location) + " is " +
                           std::string(f.name) + " (" + scalarKindName(want) + ")");
    }
}

void blendedTargets(const GraphicsPipelineDesc& d, const std::function<FormatCaps(Format)>& caps) {
    for (size_t i = 0; i < d.blend.size() && i < d.colorFormats.size(); ++i)
        if (d.blend[i].enable && !caps(d.colorFormats[i]).blend)
            fail(
                label("graphics pipeline", d.debugName),
                "colour target " + std::to_string(i) + " (" +
                    std::string(formatInfo(d.colorFormats[i]).name) +
                    ") is blended, which this device cannot do for that format (FormatCaps::blend)");
}

std::vector<BlendTargetState> writtenTargetBlends(const GraphicsPipelineDesc& d,
                                                  const ShaderInterface* fs) {
    std::vector<BlendTargetState> blends(d.colorFormats.size());
    for (size_t i = 0; i < blends.size(); ++i) {
        if (i < d.blend.size()) blends[i] = d.blend[i];
        const bool written =
            fs && std::any_of(fs->outputs.begin(), fs->outputs.end(),
                              [&](const ShaderInterface::Variable& o) {
                                  return i >= o.location && i < o.location + o.locations;
                              });
        if (!written) blends[i].writeMask = ColorMask::None;
    }
    return blends;
}

void workgroup(const ShaderInterface& cs, const DeviceLimits& limits, const std::string& pipeline) {
    const uint64_t n = uint64_t(cs.workgroupSize[0]) * cs.workgroupSize[1] * cs.workgroupSize[2];
    if (limits.maxComputeWorkGroupInvocations && n > limits.maxComputeWorkGroupInvocations)
        fail("compute pipeline '" + pipeline + "'",
             "work group of " + std::to_string(n) + " invocations exceeds the device's " +
                 std::to_string(limits.maxComputeWorkGroupInvocations));
}

uint32_t pipelineConstants(const std::vector<const ShaderInterface*>& shaders,
                           const std::string& pipeline) {
    uint32_t bytes = 0;
    for (const ShaderInterface* sh : shaders) {
        if (!sh) continue;
        if (sh->pushConstantBytes > kMaxConstantBytes)
            fail("pipeline '" + pipeline + "'",
                 std::string("the ") + shaderStageName(sh->stage) +
                     " shader's constants block is " + std::to_string(sh->pushConstantBytes) +
                     " bytes; at most " + std::to_string(kMaxConstantBytes) +
                     " (kMaxConstantBytes)");
        bytes = std::max(bytes, sh->pushConstantBytes);
    }
    return bytes;
}

void specialization(const std::vector<SpecializationConstant>& values,
                    const std::vector<const ShaderInterface*>& shaders,
                    const std::string& pipeline) {
    const std::string what = "pipeline '" + pipeline + "'";
    for (size_t i = 0; i < values.size(); ++i) {
        const SpecializationConstant& v = values[i];
        for (size_t j = 0; j < i; ++j)
            if (values[j].id == v.id)
                fail(what, "specialization constant " + std::to_string(v.id) + " is given twice");
        const ShaderInterface::SpecConstant* declared = nullptr;
        for (const ShaderInterface* sh : shaders) {
            if (!sh) continue;
            for (const ShaderInterface::SpecConstant& c : sh->specConstants)
                if (c.id == v.id) {
                    if (declared && (declared->isBool != c.isBool || declared->kind != c.kind))
                        fail(what, "specialization constant " + std::to_string(v.id) +
                                       " has a different type in the " +
                                       shaderStageName(sh->stage) + " shader");
                    declared = &c;
                }
        }
        if (!declared)
            fail(what, "specialization constant " + std::to_string(v.id) +
                           " is not declared by its shaders (layout(constant_id = " +
                           std::to_string(v.id) + "))");
        if (declared->isBool && v.bits > 1)
            fail(what, "specialization constant " + std::to_string(v.id) + " ('" + declared->name +
                           "') is a bool: its value is 0 or 1, not " + std::to_string(v.bits));
        if (!declared->isBool && declared->kind == ScalarKind::Other)
            fail(what, "specialization constant " + std::to_string(v.id) + " ('" + declared->name +
                           "') is not a 32-bit bool, int, uint or float");
    }
}

PassSignature pipelineSignature(const GraphicsPipelineDesc& d) {
    PassSignature s;
    s.colorCount = uint32_t(std::min(d.colorFormats.size(), s.colors.size()));
    for (uint32_t i = 0; i < s.colorCount; ++i) s.colors[i] = d.colorFormats[i];
    s.depth = d.depthFormat;
    s.samples = d.multisample.sampleCount;
    return s;
}

bool writesDepthStencil(const GraphicsPipelineDesc& d) {
    const DepthStencilState& ds = d.depthStencil;
    auto writes = [](const StencilFaceState& f) {
        return f.failOp != StencilOp::Keep || f.depthFailOp != StencilOp::Keep ||
               f.passOp != StencilOp::Keep;
    };
    return ds.depthWrite ||
           (ds.stencilTest && ds.stencilWriteMask && (writes(ds.front) || writes(ds.back)));
}

}  // namespace fe::gdi::validate

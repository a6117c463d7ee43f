// The GL backend's shaders and pipelines: specialization, linking, program binaries (the pipeline
// cache file), image units.
#include "fe/gdi/ShaderCompiler.h"
#include "gl/GlDevice.h"

#include <algorithm>
#include <bitset>
#include <cstring>
#include <iostream>

#include "fe/gdi/Validation.h"
#include "fe/gdi/PipelineCacheFile.h"

namespace fe::gl {

gdi::ShaderHandle GlDevice::createShader(const gdi::ShaderDesc& given) {
    loss_.check("createShader");
    // Source text is compiled first (ShaderCompiler.h), the same on every backend.
    const gdi::ShaderDesc desc = gdi::withCompiledSource(given);
    gdi::validate::shaderDesc(desc);
    const std::string label = desc.binary.name ? desc.binary.name : "";
    const auto& code = desc.binary.opengl;
    // Both halves, the Vulkan one first under the newest Vulkan rules a device takes, so that a
    // damaged binary reads the same here as on Vulkan (see validateShaderBinary); then this one's.
    gdi::validateShaderBinary(desc, gdi::SpirvRules::Vulkan13, info_.features);
    if (code.size() < 5 || code[0] != 0x07230203)
        throw gdi::Error("shader '" + label + "': not a SPIR-V binary for OpenGL (" +
                         std::to_string(code.size()) + " words, missing magic number)");
    Shader s;
    s.iface = gdi::reflectShader(code, desc.stage, desc.entryPoint, label,
                                 gdi::SpirvRules::OpenGL45);  // on this thread: no GL needed
    s.stage = desc.stage;
    s.label = label;
    s.entry = desc.entryPoint ? desc.entryPoint : "main";
    s.codeHash =
        gdi::fnv1a({reinterpret_cast<const uint8_t*>(code.data()), code.size_bytes()},
                   gdi::fnv1a({reinterpret_cast<const uint8_t*>(s.entry.data()), s.entry.size()}));
    const std::vector<uint32_t> stageNamed =
        gdi::withNamesPrefixed(code, std::string(gdi::shaderStageName(desc.stage)) + ".");
    const bool images =
        std::any_of(s.iface.bindings.begin(), s.iface.bindings.end(),
                    [](const auto& b) { return b.type == gdi::BindingType::StorageTexture; });
    if (!s.iface.specConstants.empty() || images || s.iface.writesSampleMask) s.spirv = stageNamed;
    return thread_.runCreation([&]() -> gdi::ShaderHandle {  // a new object: no queued work uses it
        loss_.check("createShader");
        s.name = specializedShader(s, stageNamed, {});
        return shaders_.add(std::move(s));
    });
}

// A shader object of `code` with these specialization constants (context thread).
GLuint GlDevice::specializedShader(const Shader& s, std::span<const uint32_t> code,
                                   const std::vector<gdi::SpecializationConstant>& values) {
    using S = gdi::ShaderStage;
    const GLenum type = s.stage == S::Vertex           ? GL_VERTEX_SHADER
                        : s.stage == S::Fragment       ? GL_FRAGMENT_SHADER
                        : s.stage == S::Geometry       ? GL_GEOMETRY_SHADER
                        : s.stage == S::TessControl    ? GL_TESS_CONTROL_SHADER
                        : s.stage == S::TessEvaluation ? GL_TESS_EVALUATION_SHADER
                                                       : GL_COMPUTE_SHADER;
    // Only the ids this stage declares: glSpecializeShader fails on any other.
    std::vector<GLuint> ids, bits;
    for (const gdi::SpecializationConstant& v : values)
        for (const auto& c : s.iface.specConstants)
            if (c.id == v.id) ids.push_back(v.id), bits.push_back(v.bits);
    const GLuint name = gl_.CreateShader(type);
    gl_.ShaderBinary(1, &name, GL_SHADER_BINARY_FORMAT_SPIR_V, code.data(),
                     GLsizei(code.size_bytes()));
    gl_.SpecializeShader(name, s.entry.c_str(), GLuint(ids.size()), ids.data(), bits.data());
    GLint ok = 0;
    gl_.GetShaderiv(name, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[2048] = {};
        gl_.GetShaderInfoLog(name, sizeof log, nullptr, log);
        gl_.DeleteShader(name);
        throw gdi::Error("shader '" + s.label + "': SPIR-V specialization failed: " + log);
    }
    return name;
}

// Links `p` (its shaders attached) and labels it; a failed link is an Error with the driver's log.
GLuint GlDevice::checkLinked(GLuint p, const std::string& label) {
    const GlFunctions& gl = gl_;
    gl.LinkProgram(p);
    GLint ok = 0;
    gl.GetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[2048] = {};
        gl.GetProgramInfoLog(p, sizeof log, nullptr, log);
        gl.DeleteProgram(p);
        throw gdi::Error("pipeline '" + label + "': link failed: " + log);
    }
    if (!label.empty()) gl.ObjectLabel(GL_PROGRAM, p, -1, label.c_str());
    return p;
}

// GL image units: each storage-texture slot the shaders use, in slot order, takes the next unit.
// The slots by unit (Pipeline::imageSlots)...
static std::vector<uint8_t> imageSlots(const std::vector<const Shader*>& shaders) {
    std::bitset<64> used;
    for (const Shader* sh : shaders)
        for (const auto& b : sh ? sh->iface.bindings : std::vector<gdi::ShaderInterface::Binding>{})
            if (b.type == gdi::BindingType::StorageTexture && b.slot < used.size())
                used.set(b.slot);
    std::vector<uint8_t> slots;
    for (uint8_t slot = 0; slot < used.size(); ++slot)
        if (used[slot]) slots.push_back(slot);
    return slots;
}
// ... and the unit by slot (0xff: not a storage texture of theirs), as the shaders are renumbered.
static std::array<uint8_t, 64> imageUnits(const std::vector<const Shader*>& shaders) {
    std::array<uint8_t, 64> unit;
    unit.fill(0xff);
    const std::vector<uint8_t> slots = imageSlots(shaders);
    for (size_t u = 0; u < slots.size(); ++u) unit[slots[u]] = uint8_t(u);
    return unit;
}

// Links the pipeline's shaders: each one's own shader object, or one of its own (deleted once
// linked) for the stages that declare the pipeline's specialization constants, whose storage
// textures take other image units in this pipeline than their slot numbers, or whose
// gl_SampleMask must act on a single-sample target.
GLuint GlDevice::linkPipeline(const std::vector<const Shader*>& shaders,
                              const std::vector<gdi::SpecializationConstant>& values,
                              const std::string& label, bool singleSample) {
    std::vector<GLuint> names, owned;
    auto dropOwned = [&] {
        for (GLuint n : owned) gl_.DeleteShader(n);
    };
    const std::array<uint8_t, 64> units = imageUnits(shaders);
    try {
        for (const Shader* sh : shaders) {
            if (!sh) continue;
            const bool specialize = std::any_of(
                values.begin(), values.end(), [&](const gdi::SpecializationConstant& v) {
                    return std::any_of(sh->iface.specConstants.begin(),
                                       sh->iface.specConstants.end(),
                                       [&](const auto& c) { return c.id == v.id; });
                });
            const bool renumber = std::any_of(
                sh->iface.bindings.begin(), sh->iface.bindings.end(), [&](const auto& b) {
                    return b.type == gdi::BindingType::StorageTexture && units[b.slot] != b.slot;
                });
            const bool maskAsDiscard = singleSample && sh->iface.writesSampleMask;
            if (renumber || maskAsDiscard) {
                std::vector<uint32_t> code = sh->spirv;
                if (renumber) code = gdi::withStorageTextureSlots(code, units);
                if (maskAsDiscard) code = gdi::withSampleMaskAsDiscard(code);
                owned.push_back(specializedShader(*sh, code, values));
            } else if (specialize) {
                owned.push_back(specializedShader(*sh, sh->spirv, values));
            }
            names.push_back(specialize || renumber || maskAsDiscard ? owned.back() : sh->name);
        }
        GLuint program = gl_.CreateProgram();
        gl_.ProgramParameteri(program, GL_PROGRAM_BINARY_RETRIEVABLE_HINT,
                              GL_TRUE);  // for the pipeline cache
        for (GLuint n : names) gl_.AttachShader(program, n);
        program = checkLinked(program, label);
        dropOwned();
        return program;
    } catch (...) {
        dropOwned();
        throw;
    }
}

// A program's cache key: its shaders' code and entry points, the specialization values, and
// whether a shader's gl_SampleMask was rewritten for single-sample targets.
static uint64_t programKey(const std::vector<const Shader*>& shaders,
                           const std::vector<gdi::SpecializationConstant>& values,
                           bool singleSample) {
    uint64_t key = 0xcbf29ce484222325ull;
    for (const Shader* s : shaders) {
        key = (key ^ (s ? s->codeHash : 0)) * 0x100000001b3ull;
        if (s && singleSample && s->iface.writesSampleMask) key = (key ^ 1) * 0x100000001b3ull;
    }
    return gdi::fnv1a(
        {reinterpret_cast<const uint8_t*>(values.data()), values.size() * sizeof(values[0])}, key);
}

// The program for `key`: from its cached binary when the driver takes it back, else linked by
// `link` and its binary kept for the cache (context thread).
GLuint GlDevice::cachedProgram(const std::vector<const Shader*>& shaders,
                               const std::vector<gdi::SpecializationConstant>& values,
                               const std::string& label, std::string& sharedKey,
                               bool singleSample) {
    // The label is part of the key: debug output and captures name the program by it.
    sharedKey = std::to_string(programKey(shaders, values, singleSample)) + ' ' + label;
    if (std::optional<GLuint> shared = sharedPrograms_.acquire(sharedKey)) return *shared;
    const GLuint program = compiledProgram(shaders, values, label, singleSample);
    sharedPrograms_.add(sharedKey, program);
    return program;
}

GLuint GlDevice::compiledProgram(const std::vector<const Shader*>& shaders,
                                 const std::vector<gdi::SpecializationConstant>& values,
                                 const std::string& label, bool singleSample) {
    const uint64_t key = programKey(shaders, values, singleSample);
    if (auto it = programs_.find(key); it != programs_.end()) {
        const GLuint p = gl_.CreateProgram();
        gl_.ProgramBinary(p, it->second.format, it->second.bytes.data(),
                          GLsizei(it->second.bytes.size()));
        GLint ok = 0;
        gl_.GetProgramiv(p, GL_LINK_STATUS, &ok);
        if (ok) {
            if (!label.empty()) gl_.ObjectLabel(GL_PROGRAM, p, -1, label.c_str());
            std::lock_guard lock(cacheMutex_);
            ++cacheStats_.hits;
            return p;
        }
        gl_.DeleteProgram(p);  // the driver may refuse a binary (an update): link it again
        programs_.erase(it);
    }
    const GLuint p = linkPipeline(shaders, values, label, singleSample);
    {
        std::lock_guard lock(cacheMutex_);
        ++cacheStats_.misses;
    }
    GLint length = 0;
    if (binaryFormats_ > 0) gl_.GetProgramiv(p, GL_PROGRAM_BINARY_LENGTH, &length);
    if (length > 0) {
        gdi::ProgramBinary& b = programs_[key];
        b.bytes.resize(size_t(length));
        GLenum format = 0;
        gl_.GetProgramBinary(p, length, nullptr, &format, b.bytes.data());
        b.format = format;
    }
    return p;
}

gdi::PipelineCacheStats GlDevice::openPipelineCache(const std::string& path) {
    const gdi::PipelineCacheLoad file =
        gdi::readPipelineCache(path, gdi::pipelineCacheIdentity(info_));
    gdi::PipelineCacheStats stats{.path = path, .warning = file.warning};
    std::map<uint64_t, gdi::ProgramBinary> programs;
    std::string why;
    if (!file.payload.empty() && !gdi::decodeProgramBinaries(file.payload, programs, why))
        stats.warning = "pipeline cache '" + path + "' ignored: " + why;
    else if (!file.payload.empty())
        stats.loaded = true, stats.loadedBytes = file.payload.size();
    if (binaryFormats_ == 0 && stats.warning.empty() && !path.empty())
        stats.warning =
            "pipeline cache '" + path + "': GL programs are not cached here: " +
            (info_.apiVersion.find("Mesa") != std::string::npos
                 ? "Mesa's glGetProgramBinary crashes on SPIR-V programs with uniform blocks"
                 : "the driver offers no program binary format (GL_NUM_PROGRAM_BINARY_FORMATS is 0)");
    thread_.run([&] {
        programs_ = stats.loaded ? std::move(programs) : std::map<uint64_t, gdi::ProgramBinary>{};
    });
    std::lock_guard lock(cacheMutex_);
    cacheStats_ = stats;
    return stats;
}

void GlDevice::savePipelineCacheOnContext() {
    std::string path;
    {
        std::lock_guard lock(cacheMutex_);
        path = cacheStats_.path;
    }
    if (!path.empty())
        gdi::writePipelineCache(path, gdi::pipelineCacheIdentity(info_),
                                gdi::encodeProgramBinaries(programs_));
}

void GlDevice::savePipelineCache() {
    thread_.run([&] { savePipelineCacheOnContext(); });
}

gdi::PipelineCacheStats GlDevice::pipelineCacheStats() const {
    std::lock_guard lock(cacheMutex_);
    gdi::PipelineCacheStats stats = cacheStats_;
    stats.shared = sharedPrograms_.sharedCount();
    return stats;
}

gdi::PipelineHandle GlDevice::createGraphicsPipeline(const gdi::GraphicsPipelineDesc& d) {
    return thread_.runCreation(
        [&]() -> gdi::PipelineHandle {  // a new object: no queued work uses it
            loss_.check("createGraphicsPipeline");
            gdi::validate::graphicsPipelineDesc(d, info_);
            gdi::validate::blendedTargets(d, [&](gdi::Format f) { return formatCaps(f); });
            Pipeline p;
            p.label = d.debugName ? d.debugName : "";
            std::vector<const Shader*> shaders;  // in stage order
            std::vector<const gdi::ShaderInterface*> ifaces;
            for (const gdi::validate::PipelineStage& st : gdi::validate::graphicsStages(d)) {
                const Shader& s = shaders_.get(st.shader, st.kind);
                gdi::validate::shaderOfStage(s.stage, st, p.label);
                shaders.push_back(&s);
                ifaces.push_back(&s.iface);
            }
            const Shader& vs = *shaders.front();
            const gdi::ShaderInterface* fsIface = d.fragmentShader ? ifaces.back() : nullptr;
            gdi::validate::vertexInputs(d, vs.iface, p.label);
            gdi::validate::stageInterfaces(ifaces, p.label);
            if (fsIface) gdi::validate::fragmentOutputs(d, *fsIface, p.label);
            const std::vector<gdi::BindingSlot> bindings =
                gdi::validate::pipelineBindings(d.bindings, ifaces, p.label, info_.limits);
            p.constantBytes = gdi::validate::pipelineConstants(ifaces, p.label);
            gdi::validate::specialization(d.specialization, ifaces, p.label);
            p.program = cachedProgram(shaders, d.specialization, p.label, p.programKey,
                                      d.multisample.sampleCount <= 1);
            p.imageSlots = imageSlots(shaders);
            gl_.CreateVertexArrays(1, &p.vao);
            for (uint32_t i = 0; i < d.vertexBuffers.size(); ++i) {
                const auto& vb = d.vertexBuffers[i];
                p.strides.push_back(vb.stride);
                gl_.VertexArrayBindingDivisor(p.vao, i, vb.perInstance ? 1 : 0);
                for (const auto& a : vb.attributes) {
                    using V = gdi::VertexFormat;
                    gl_.EnableVertexArrayAttrib(p.vao, a.location);
                    gl_.VertexArrayAttribBinding(p.vao, a.location, i);
                    switch (a.format) {
                        case V::Float:
                        case V::Float2:
                        case V::Float3:
                        case V::Float4:
                            gl_.VertexArrayAttribFormat(p.vao, a.location,
                                                        GLint(int(a.format) - int(V::Float) + 1),
                                                        GL_FLOAT, GL_FALSE, a.offset);
                            break;
                        case V::Half2:
                            gl_.VertexArrayAttribFormat(p.vao, a.location, 2, GL_HALF_FLOAT,
                                                        GL_FALSE, a.offset);
                            break;
                        case V::Half4:
                            gl_.VertexArrayAttribFormat(p.vao, a.location, 4, GL_HALF_FLOAT,
                                                        GL_FALSE, a.offset);
                            break;
                        case V::UNorm8x4:
                            gl_.VertexArrayAttribFormat(p.vao, a.location, 4, GL_UNSIGNED_BYTE,
                                                        GL_TRUE, a.offset);
                            break;
                        case V::SNorm8x4:
                            gl_.VertexArrayAttribFormat(p.vao, a.location, 4, GL_BYTE, GL_TRUE,
                                                        a.offset);
                            break;
                        case V::UNorm16x2:
                            gl_.VertexArrayAttribFormat(p.vao, a.location, 2, GL_UNSIGNED_SHORT,
                                                        GL_TRUE, a.offset);
                            break;
                        case V::SNorm16x2:
                            gl_.VertexArrayAttribFormat(p.vao, a.location, 2, GL_SHORT, GL_TRUE,
                                                        a.offset);
                            break;
                        case V::UInt32:
                            gl_.VertexArrayAttribIFormat(p.vao, a.location, 1, GL_UNSIGNED_INT,
                                                         a.offset);
                            break;
                        default:
                            break;
                    }
                }
            }
            p.desc = d;
            p.desc.blend = gdi::validate::writtenTargetBlends(d, fsIface);
            p.desc.debugName = nullptr;
            p.desc.bindings = bindings;
            p.requiredSlots = gdi::validate::requiredSlotMask(bindings);
            p.slotKinds = gdi::validate::slotKinds(bindings);
            p.slotDimensions = gdi::validate::slotDimensions(ifaces, p.label);
            p.slotBlockBytes = gdi::validate::slotBlockBytes(ifaces);
            p.signature = gdi::validate::pipelineSignature(d);
            p.writesDepthStencil = gdi::validate::writesDepthStencil(d);
            p.vertexBindings = gdi::validate::vertexBindings(d);
            return pipelines_.add(std::move(p));
        });
}

gdi::PipelineHandle GlDevice::createComputePipeline(const gdi::ComputePipelineDesc& d) {
    return thread_.runCreation(
        [&]() -> gdi::PipelineHandle {  // a new object: no queued work uses it
            loss_.check("createComputePipeline");
            gdi::validate::computePipelineDesc(d);
            Pipeline p;
            p.label = d.debugName ? d.debugName : "";
            Shader& cs = shaders_.get(d.computeShader, "compute shader");
            gdi::validate::computeShaderStage(cs.stage, d);
            gdi::validate::workgroup(cs.iface, info_.limits, p.label);
            const std::vector<gdi::BindingSlot> bindings =
                gdi::validate::pipelineBindings(d.bindings, {&cs.iface}, p.label, info_.limits);
            p.constantBytes = gdi::validate::pipelineConstants({&cs.iface}, p.label);
            gdi::validate::specialization(d.specialization, {&cs.iface}, p.label);
            p.program = cachedProgram({&cs}, d.specialization, p.label, p.programKey);
            p.imageSlots = imageSlots({&cs});
            p.compute = true;
            p.desc.bindings = bindings;
            p.requiredSlots = gdi::validate::requiredSlotMask(bindings);
            p.slotKinds = gdi::validate::slotKinds(bindings);
            p.slotDimensions = gdi::validate::slotDimensions({&cs.iface}, p.label);
            p.slotBlockBytes = gdi::validate::slotBlockBytes({&cs.iface});
            return pipelines_.add(std::move(p));
        });
}

}  // namespace fe::gl

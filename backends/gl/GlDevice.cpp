// Context set-up, resources, pipelines and transfers of the GL backend.
#include "gl/GlDevice.h"

#include <bitset>
#include <algorithm>
#include <cstring>
#include <iostream>

#include <unistd.h>

#include "fe/gdi/ExclusiveUse.h"
#include "fe/gdi/Validation.h"
#include "gl/GlBackend.h"
#include "gl/GlCommandList.h"
#include "gl/GlReplay.h"

namespace fe::gl {

std::unique_ptr<gdi::Device> createGlDevice(PlatformKind platform, bool validation, bool vsync) {
    return std::make_unique<GlDevice>(platform, validation, vsync);
}

namespace {
// EXT_texture_sRGB's S3TC tokens, which glcorearb.h does not carry.
constexpr GLenum kCompressedSrgbAlphaS3tcDxt1 = 0x8C4D;
constexpr GLenum kCompressedSrgbAlphaS3tcDxt5 = 0x8C4F;
}  // namespace

GlFormat toGlFormat(gdi::Format f) {
    using F = gdi::Format;
    switch (f) {
        case F::RGBA8: return {GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE};
        case F::RGBA8_SRGB: return {GL_SRGB8_ALPHA8, GL_RGBA, GL_UNSIGNED_BYTE};
        case F::RGBA16F: return {GL_RGBA16F, GL_RGBA, GL_HALF_FLOAT};
        case F::RG16F: return {GL_RG16F, GL_RG, GL_HALF_FLOAT};
        case F::R16F: return {GL_R16F, GL_RED, GL_HALF_FLOAT};
        case F::RGBA32F: return {GL_RGBA32F, GL_RGBA, GL_FLOAT};
        case F::RG32F: return {GL_RG32F, GL_RG, GL_FLOAT};
        case F::R32F: return {GL_R32F, GL_RED, GL_FLOAT};
        case F::R32U: return {GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT};
        case F::R11G11B10F: return {GL_R11F_G11F_B10F, GL_RGB, GL_UNSIGNED_INT_10F_11F_11F_REV};
        case F::D32F: return {GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT};
        case F::D24S8: return {GL_DEPTH24_STENCIL8, GL_DEPTH_STENCIL, GL_UNSIGNED_INT_24_8};
        case F::D16: return {GL_DEPTH_COMPONENT16, GL_DEPTH_COMPONENT, GL_UNSIGNED_SHORT};
        case F::D32F_S8: return {GL_DEPTH32F_STENCIL8, GL_DEPTH_STENCIL, GL_FLOAT_32_UNSIGNED_INT_24_8_REV};
        case F::S8: return {GL_STENCIL_INDEX8, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE};
        // Compressed: the internal format only (uploads use glCompressedTextureSubImage*).
        case F::BC1: return {GL_COMPRESSED_RGBA_S3TC_DXT1_EXT, 0, 0};
        case F::BC1_SRGB: return {kCompressedSrgbAlphaS3tcDxt1, 0, 0};
        case F::BC3: return {GL_COMPRESSED_RGBA_S3TC_DXT5_EXT, 0, 0};
        case F::BC3_SRGB: return {kCompressedSrgbAlphaS3tcDxt5, 0, 0};
        case F::BC4: return {GL_COMPRESSED_RED_RGTC1, 0, 0};
        case F::BC5: return {GL_COMPRESSED_RG_RGTC2, 0, 0};
        case F::BC7: return {GL_COMPRESSED_RGBA_BPTC_UNORM, 0, 0};
        case F::BC7_SRGB: return {GL_COMPRESSED_SRGB_ALPHA_BPTC_UNORM, 0, 0};
        default: return {0, 0, 0};
    }
}

GLenum textureTarget(const gdi::TextureDesc& d) {
    switch (d.dimension) {
        case gdi::TextureDimension::Texture2DArray: return GL_TEXTURE_2D_ARRAY;
        case gdi::TextureDimension::TextureCube: return GL_TEXTURE_CUBE_MAP;
        case gdi::TextureDimension::TextureCubeArray: return GL_TEXTURE_CUBE_MAP_ARRAY;
        case gdi::TextureDimension::Texture3D: return GL_TEXTURE_3D;
        default: return d.sampleCount > 1 ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D;
    }
}

namespace {
const char* glErrorName(GLenum e) {
    switch (e) {
        case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
        case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
        case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
        case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
        case GL_CONTEXT_LOST: return "GL_CONTEXT_LOST";
        case GL_GUILTY_CONTEXT_RESET: return "GL_GUILTY_CONTEXT_RESET";
        case GL_INNOCENT_CONTEXT_RESET: return "GL_INNOCENT_CONTEXT_RESET";
        case GL_UNKNOWN_CONTEXT_RESET: return "GL_UNKNOWN_CONTEXT_RESET";
        default: return "GL error";
    }
}
}  // namespace

template <class Call>
GLenum GlDevice::allocateStorage(const char* name, Call&& call) {
    if (gdi::fault::hit(gdi::fault::Site::Allocation, name)) return GL_OUT_OF_MEMORY;
    // Errors of earlier calls are not this one's (the debug output reports them); a lost
    // context may repeat GL_CONTEXT_LOST, hence the bound.
    for (int i = 0; i < 8 && gl_.GetError() != GL_NO_ERROR; ++i) {
    }
    call();
    return gl_.GetError();
}

void GlDevice::checkReset(bool injected) {
    const GLenum status = injected ? GL_UNKNOWN_CONTEXT_RESET : gl_.GetGraphicsResetStatus();
    if (status != GL_NO_ERROR)
        throw loss_.lose(info_.backend, std::string("glGetGraphicsResetStatus returned ") + glErrorName(status));
}

gdi::LiveObjects GlDevice::liveObjects() const {
    // After the queue: destroys already called count as done.
    if (!thread_.onThisThread()) return thread_.run([&] { return liveObjects(); });
    return {.buffers = buffers_.size(), .textures = textures_.size(), .samplers = samplers_.size(),
            .shaders = shaders_.size(), .pipelines = pipelines_.size(), .timers = timers_.size(), .heaps = 0,
            .querySets = querySets_.size(),
            .nativeObjects = nativeObjects_};
}

void APIENTRY GlDevice::debugCallback(GLenum, GLenum type, GLuint, GLenum severity, GLsizei, const GLchar* message,
                                        const void* user) {
    if (type == GL_DEBUG_TYPE_ERROR || severity == GL_DEBUG_SEVERITY_HIGH) {
        auto* device = const_cast<GlDevice*>(static_cast<const GlDevice*>(user));
        device->errors_++;
        device->messages_.report("error", message ? message : "");
    }
}

void runOnContextThread(gdi::Device& device, const std::function<void()>& task) {
    auto* gl = dynamic_cast<GlDevice*>(&device);
    if (!gl) throw gdi::Error(device.info().backend + ": runOnContextThread needs an OpenGL device");
    gl->runOnContextThread(task);
}

// The platform is made on the calling thread (a GLFW window must be), then its context moves
// to the context thread, where everything else happens.
GlDevice::GlDevice(PlatformKind kind, bool validation, bool vsync) {
    platform_ = createPlatform(kind, validation, vsync);
    platform_->releaseCurrent();
    try {
        thread_.run([&] {
            platform_->makeCurrent();
            initialize(validation);
        });
    } catch (...) {
        thread_.run([&] { platform_->releaseCurrent(); });
        thread_.stop();
        throw;
    }
}

void GlDevice::initialize(bool validation) {
#define FE_GL_LOAD(type, fn)                                                                          \
    gl_.fn = reinterpret_cast<type>(platform_->getProcAddress("gl" #fn));                             \
    if (!gl_.fn) throw gdi::Error(std::string(platform_->name()) + ": GL entry point gl" #fn " missing");
    FE_GL_FUNCTIONS(FE_GL_LOAD)
#undef FE_GL_LOAD
    GLint major = 0, minor = 0, n = 0;
    gl_.GetIntegerv(GL_MAJOR_VERSION, &major);
    gl_.GetIntegerv(GL_MINOR_VERSION, &minor);
    if (major * 10 + minor < 45)
        throw gdi::Error(std::string(platform_->name()) + ": OpenGL " + std::to_string(major) + "." + std::to_string(minor) +
                         " < 4.5");
    std::vector<std::string> extensions;
    gl_.GetIntegerv(GL_NUM_EXTENSIONS, &n);
    for (GLint i = 0; i < n; ++i) extensions.emplace_back(reinterpret_cast<const char*>(gl_.GetStringi(GL_EXTENSIONS, i)));
    auto has = [&](const char* e) { return std::find(extensions.begin(), extensions.end(), e) != extensions.end(); };
    if (!has("GL_ARB_gl_spirv")) throw gdi::Error(std::string(platform_->name()) + ": GL_ARB_gl_spirv missing (shaders are SPIR-V)");
    if (has("GL_ARB_indirect_parameters")) {
        gl_.MultiDrawArraysIndirectCount = reinterpret_cast<PFNGLMULTIDRAWARRAYSINDIRECTCOUNTPROC>(
            platform_->getProcAddress("glMultiDrawArraysIndirectCountARB"));
        gl_.MultiDrawElementsIndirectCount = reinterpret_cast<PFNGLMULTIDRAWELEMENTSINDIRECTCOUNTPROC>(
            platform_->getProcAddress("glMultiDrawElementsIndirectCountARB"));
    }
    if (has("GL_ARB_polygon_offset_clamp"))
        gl_.PolygonOffsetClamp = reinterpret_cast<PFNGLPOLYGONOFFSETCLAMPPROC>(platform_->getProcAddress("glPolygonOffsetClamp"));
    // S3TC (BC1, BC3) and its sRGB forms are extensions; RGTC (BC4, BC5) and BPTC (BC7) are core.
    const bool bc = has("GL_EXT_texture_compression_s3tc") &&
                    (has("GL_EXT_texture_sRGB") || has("GL_EXT_texture_compression_s3tc_srgb"));
    if (validation) {
        gl_.Enable(GL_DEBUG_OUTPUT);
        gl_.Enable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
        gl_.DebugMessageCallback(&GlDevice::debugCallback, this);
    }
    gl_.ClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);  // NDC y=-1 lands in memory row 0, as on Vulkan
    gl_.Enable(GL_FRAMEBUFFER_SRGB);  // sRGB targets encode on write, as on Vulkan
    gl_.ProvokingVertex(GL_FIRST_VERTEX_CONVENTION);  // flat outputs come from a primitive's first vertex, as on Vulkan
    gl_.Enable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    gl_.Enable(GL_SCISSOR_TEST);
    // Points: gl_PointSize is honoured (Vulkan always does), and gl_PointCoord's (0, 0) is the
    // point's first row in memory, Vulkan's top left: with the lower-left clip origin above,
    // memory row 0 is GL's window bottom, so the sprite origin is GL's lower left.
    gl_.Enable(GL_PROGRAM_POINT_SIZE);
    gl_.PointParameteri(GL_POINT_SPRITE_COORD_ORIGIN, GL_LOWER_LEFT);
    gl_.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 1);

    info_.backend = platform_->name();
    info_.deviceName = reinterpret_cast<const char*>(gl_.GetString(GL_RENDERER));
    info_.apiVersion = std::string("OpenGL ") + reinterpret_cast<const char*>(gl_.GetString(GL_VERSION));
    GLint strategy = 0, flags = 0;
    gl_.GetIntegerv(GL_RESET_NOTIFICATION_STRATEGY, &strategy);
    gl_.GetIntegerv(GL_CONTEXT_FLAGS, &flags);
    info_.driverInfo = reinterpret_cast<const char*>(gl_.GetString(GL_VENDOR)) +
                       std::string(strategy == GL_LOSE_CONTEXT_ON_RESET ? ", resets are reported" : ", no reset notification") +
                       std::string((flags & GL_CONTEXT_FLAG_ROBUST_ACCESS_BIT) ? ", robust buffer access" : "");
    info_.presentMode = platform_->presentMode();
    info_.softwareRasterizer = info_.deviceName.find("llvmpipe") != std::string::npos ||
                               info_.deviceName.find("softpipe") != std::string::npos;
    thread_.serializeAcrossDevices(info_.softwareRasterizer);  // GlContextThread: Mesa's software drivers
    auto get = [&](GLenum e) { GLint v = 0; gl_.GetIntegerv(e, &v); return uint32_t(std::max(v, 0)); };
    info_.limits.maxTextureSize2D = get(GL_MAX_TEXTURE_SIZE);
    info_.limits.maxTextureSize3D = get(GL_MAX_3D_TEXTURE_SIZE);
    info_.limits.maxTextureSizeCube = get(GL_MAX_CUBE_MAP_TEXTURE_SIZE);
    info_.limits.maxTextureArrayLayers = get(GL_MAX_ARRAY_TEXTURE_LAYERS);
    // Sample counts every format the engine renders to accepts, as Vulkan-style bits.
    const uint32_t maxColor = std::min(get(GL_MAX_COLOR_TEXTURE_SAMPLES), get(GL_MAX_SAMPLES));
    const uint32_t maxDepth = std::min(get(GL_MAX_DEPTH_TEXTURE_SAMPLES), get(GL_MAX_SAMPLES));
    auto countsFor = [&](uint32_t maxSamples, std::initializer_list<gdi::Format> formats) {
        uint32_t bits = 1;
        for (uint32_t c = 2; c <= 8 && c <= maxSamples; c *= 2) {
            bool all = true;
            for (gdi::Format f : formats) {  // the counts a format supports, from the driver
                GLint num = 0;
                gl_.GetInternalformativ(GL_TEXTURE_2D_MULTISAMPLE, toGlFormat(f).internal, GL_NUM_SAMPLE_COUNTS, 1, &num);
                std::vector<GLint> counts(size_t(std::max(num, 0)));
                if (num > 0)
                    gl_.GetInternalformativ(GL_TEXTURE_2D_MULTISAMPLE, toGlFormat(f).internal, GL_SAMPLES, num, counts.data());
                all = all && std::find(counts.begin(), counts.end(), GLint(c)) != counts.end();
            }
            if (all) bits |= c;
        }
        return bits;
    };
    using F = gdi::Format;
    info_.limits.colorSampleCounts = countsFor(maxColor, {F::RGBA8, F::RGBA8_SRGB, F::RGBA16F, F::RG16F, F::R16F, F::RGBA32F,
                                                          F::RG32F, F::R32F, F::R32U, F::R11G11B10F});
    info_.limits.depthSampleCounts = countsFor(maxDepth, {F::D32F, F::D24S8});
    info_.limits.maxColorAttachments = get(GL_MAX_COLOR_ATTACHMENTS);
    GLint dims[2] = {0, 0};
    gl_.GetIntegerv(GL_MAX_VIEWPORT_DIMS, dims);
    info_.limits.maxViewportSize = uint32_t(std::max(0, std::min(dims[0], dims[1])));
    GLfloat bounds[2] = {0, 0};
    gl_.GetFloatv(GL_VIEWPORT_BOUNDS_RANGE, bounds);
    info_.limits.viewportBounds = {bounds[0], bounds[1]};
    info_.limits.maxComputeWorkGroupInvocations = get(GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS);
    for (GLuint axis = 0; axis < 3; ++axis) {
        GLint groups = 0;
        gl_.GetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, axis, &groups);
        info_.limits.maxComputeWorkGroupCount[axis] = uint32_t(std::max(groups, 0));
    }
    info_.limits.maxStorageTextures = uint32_t(std::min({get(GL_MAX_IMAGE_UNITS), get(GL_MAX_FRAGMENT_IMAGE_UNIFORMS),
                                                         get(GL_MAX_COMPUTE_IMAGE_UNIFORMS), get(GL_MAX_COMBINED_IMAGE_UNIFORMS)}));
    info_.limits.maxUniformBufferRange = get(GL_MAX_UNIFORM_BLOCK_SIZE);
    info_.limits.maxStorageBufferRange = get(GL_MAX_SHADER_STORAGE_BLOCK_SIZE);
    // GL states no allocation limit: the video memory where the driver says it (NVIDIA, and
    // Mesa's hardware drivers), else the machine's memory (llvmpipe's buffers live there).
    constexpr GLenum kDedicatedVideoMemoryNvx = 0x9047;  // GL_GPU_MEMORY_INFO_DEDICATED_VIDMEM_NVX (not in glcorearb.h)
    GLint videoKiB = 0;
    if (has("GL_NVX_gpu_memory_info")) gl_.GetIntegerv(kDedicatedVideoMemoryNvx, &videoKiB);
    info_.limits.maxAllocationSize = videoKiB > 0 ? uint64_t(videoKiB) * 1024
                                                  : uint64_t(sysconf(_SC_PHYS_PAGES)) * uint64_t(sysconf(_SC_PAGE_SIZE));
    info_.limits.uniformBufferOffsetAlignment = get(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT);
    info_.limits.storageBufferOffsetAlignment = get(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT);
    // Mesa 22.3 crashes (strlen in the driver) serialising a SPIR-V program that has uniform
    // blocks for glGetProgramBinary (seen on llvmpipe): no program binaries there.
    binaryFormats_ = info_.apiVersion.find("Mesa") == std::string::npos ? get(GL_NUM_PROGRAM_BINARY_FORMATS) : 0;
    info_.features = {.timestamps = true, .computeShaders = true, .debugLabels = true, .validation = validation,
                      .memoryAliasing = false, .window = platform_->hasWindow(),
                      .textureCubeArray = true, .depthClamp = true,  // core in 4.0 and 3.2
                      .depthBiasClamp = gl_.PolygonOffsetClamp != nullptr,
                      .multiDrawIndirect = true,  // core in 4.3
                      .drawIndirectCount = gl_.MultiDrawArraysIndirectCount && gl_.MultiDrawElementsIndirectCount,
                      .textureCompressionBC = bc,
                      .occlusionQueries = true,  // GL_SAMPLES_PASSED counts exactly
                      .pipelineStatistics = has("GL_ARB_pipeline_statistics_query")};
    // What each format can do, from the driver's internal-format queries (ARB_internalformat_query2).
    auto supported = [&](GLenum target, GLenum internal, GLenum pname) {
        GLint v = GL_NONE;
        gl_.GetInternalformativ(target, internal, pname, 1, &v);
        return v == GL_FULL_SUPPORT || v == GL_CAVEAT_SUPPORT;
    };
    for (size_t i = 1; i < size_t(F::Count); ++i) {
        const auto f = F(i);
        const GLenum internal = toGlFormat(f).internal;
        gdi::FormatCaps& c = formatCaps_[i];
        if (!internal || !supportsFormat(f, gdi::TextureUsage::Sampled)) continue;
        const gdi::FormatInfo& fi = gdi::formatInfo(f);
        c.sampled = true;
        c.linearFilter = !fi.isInteger && supported(GL_TEXTURE_2D, internal, GL_FILTER);
        c.renderTarget = supportsFormat(f, gdi::TextureUsage::RenderTarget);
        c.blend = c.renderTarget && !gdi::isDepthFormat(f) && !fi.isInteger && supported(GL_TEXTURE_2D, internal, GL_FRAMEBUFFER_BLEND);
        c.storage = supportsFormat(f, gdi::TextureUsage::Storage);
        if (c.renderTarget) c.sampleCounts = countsFor(gdi::isDepthFormat(f) ? maxDepth : maxColor, {f});
    }
}

GlDevice::~GlDevice() {
    liveLists_.orphanAll();  // lists that outlive the device let go of it now
    try {
        thread_.run([&] {
            if (!loss_.lost()) {
                try {
                    savePipelineCacheOnContext();
                } catch (const gdi::Error& e) {
                    std::cerr << "fe: " << e.what() << "\n";
                }
            }
            releaseAll();
            platform_->releaseCurrent();
        });
    } catch (...) {  // a destructor must not throw; the context goes with the platform
    }
    thread_.stop();
}

void GlDevice::releaseAll() {
    if (gdi::leakCheckEnabled()) {
        std::vector<std::string> named;
        buffers_.forEach([&](Buffer& b) { named.push_back("buffer '" + b.label + "'"); });
        textures_.forEach([&](Texture& t) { named.push_back("texture '" + t.label + "'"); });
        gdi::reportLeaksAtDestruction(info_.backend, liveObjects(), named);
    }
    buffers_.forEach([&](Buffer& b) { gl_.DeleteBuffers(1, &b.name); });
    textures_.forEach([&](Texture& t) { gl_.DeleteTextures(1, &t.name); });
    samplers_.forEach([&](Sampler& s) { gl_.DeleteSamplers(1, &s.name); });
    shaders_.forEach([&](Shader& s) { gl_.DeleteShader(s.name); });
    constantsRing_.release(gl_);
    pipelines_.forEach([&](Pipeline& p) {
        gl_.DeleteProgram(p.program);
        if (p.vao) gl_.DeleteVertexArrays(1, &p.vao);
    });
    timers_.forEach([&](Timer& t) { gl_.DeleteQueries(2, t.queries); });
    querySets_.forEach([&](QuerySet& q) { gl_.DeleteQueries(GLsizei(q.names.size()), q.names.data()); });
    for (auto& f : fbos_) gl_.DeleteFramebuffers(1, &f.fbo);
    for (auto& [v, s] : fences_) gl_.DeleteSync(s);
}

bool GlDevice::supportsFormat(gdi::Format format, gdi::TextureUsage usage) const {
    if (toGlFormat(format).internal == 0) return false;
    if (gdi::isCompressedFormat(format))
        return info_.features.textureCompressionBC && !any(usage, gdi::TextureUsage::RenderTarget | gdi::TextureUsage::Storage);
    // GL 4.5 core requires every format here as texture and render target; image load/store
    // has no sRGB, packed-float-to-RGB or depth formats.
    if (any(usage, gdi::TextureUsage::Storage) &&
        (format == gdi::Format::RGBA8_SRGB || gdi::isDepthFormat(format)))
        return false;
    return true;
}

gdi::BufferHandle GlDevice::createBuffer(const gdi::BufferDesc& desc, gdi::ByteSpan initialData) {
    return thread_.runCreation([&]() -> gdi::BufferHandle {  // a new object: no queued work uses it
        loss_.check("createBuffer");
        gdi::validate::bufferDesc(desc, info_.limits);
        gdi::validate::initialData(desc, initialData.size());
        Buffer b;
        b.desc = desc;
        b.label = desc.debugName ? desc.debugName : "";
        b.desc.debugName = nullptr;
        // Upload and Readback memory is mapped once, persistently and coherently (map()).
        const GLbitfield persistent = GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
        const GLbitfield mapFlags = desc.access == gdi::MemoryAccess::Upload     ? GL_MAP_WRITE_BIT | persistent
                                    : desc.access == gdi::MemoryAccess::Readback ? GL_MAP_READ_BIT | persistent
                                                                                 : 0;
        gl_.CreateBuffers(1, &b.name);
        ++nativeObjects_;
        if (GLenum e = allocateStorage("glNamedBufferStorage", [&] { gl_.NamedBufferStorage(b.name, GLsizeiptr(desc.size), initialData.empty() ? nullptr : initialData.data(),
                                                                     GL_DYNAMIC_STORAGE_BIT | mapFlags); });
            e != GL_NO_ERROR) {
            gl_.DeleteBuffers(1, &b.name);
            --nativeObjects_;
            if (e == GL_CONTEXT_LOST) throw loss_.lose(info_.backend, "glNamedBufferStorage raised GL_CONTEXT_LOST");
            throw gdi::Error(info_.backend + ": glNamedBufferStorage failed for " +
                             gdi::describeObject("buffer", b.label, std::to_string(desc.size) + " bytes") + ": " + glErrorName(e));
        }
        // New buffers read as zeros on every backend (Device.h); a null clear value is zero.
        if (initialData.empty()) gl_.ClearNamedBufferData(b.name, GL_R8, GL_RED, GL_UNSIGNED_BYTE, nullptr);
        if (!b.label.empty()) gl_.ObjectLabel(GL_BUFFER, b.name, -1, b.label.c_str());
        if (mapFlags) b.mapped = gl_.MapNamedBufferRange(b.name, 0, GLsizeiptr(desc.size), mapFlags);
        return buffers_.add(std::move(b));
    });
}

gdi::TextureHandle GlDevice::createTexture(const gdi::TextureDesc& desc) {
    return thread_.runCreation([&]() -> gdi::TextureHandle {  // a new object: no queued work uses it
        loss_.check("createTexture");
        gdi::validate::textureDesc(desc, info_);
        const std::string label = desc.debugName ? desc.debugName : "";
        if (desc.heap) throw gdi::Error("texture '" + label + "': heaps (memory aliasing) are not supported on OpenGL");
        if (!supportsFormat(desc.format, desc.usage)) gdi::validate::unsupportedTextureUsage(desc);
        Texture t;
        t.desc = desc;
        t.desc.debugName = nullptr;
        t.label = label;
        t.linearFilter = formatCaps_[size_t(desc.format)].linearFilter;
        t.target = textureTarget(desc);
        gl_.CreateTextures(t.target, 1, &t.name);
        ++nativeObjects_;
        const GLenum internal = toGlFormat(desc.format).internal;
        const auto w = GLsizei(desc.width), h = GLsizei(desc.height), levels = GLsizei(desc.mipLevels);
        const char* call = t.target == GL_TEXTURE_2D_MULTISAMPLE                                ? "glTextureStorage2DMultisample"
                           : (t.target == GL_TEXTURE_2D || t.target == GL_TEXTURE_CUBE_MAP) ? "glTextureStorage2D"
                                                                                              : "glTextureStorage3D";
        if (GLenum e = allocateStorage(call, [&] {
                switch (t.target) {
                    case GL_TEXTURE_2D_MULTISAMPLE:
                        gl_.TextureStorage2DMultisample(t.name, GLsizei(desc.sampleCount), internal, w, h, GL_TRUE);
                        break;
                    case GL_TEXTURE_2D:
                    case GL_TEXTURE_CUBE_MAP: gl_.TextureStorage2D(t.name, levels, internal, w, h); break;
                    default:  // layers or depth
                        gl_.TextureStorage3D(t.name, levels, internal, w, h, GLsizei(desc.depthOrLayers));
                        break;
                }
            });
            e != GL_NO_ERROR) {
            gl_.DeleteTextures(1, &t.name);
            --nativeObjects_;
            if (e == GL_CONTEXT_LOST) throw loss_.lose(info_.backend, std::string(call) + " raised GL_CONTEXT_LOST");
            throw gdi::Error(info_.backend + ": " + call + " failed for " +
                             gdi::describeObject("texture", label, std::to_string(desc.width) + "x" + std::to_string(desc.height) +
                                                                       (desc.depthOrLayers > 1 ? "x" + std::to_string(desc.depthOrLayers) : "") +
                                                                       " " + std::string(gdi::formatInfo(desc.format).name)) +
                             ": " + glErrorName(e));
        }
        if (t.target != GL_TEXTURE_2D_MULTISAMPLE) gl_.TextureParameteri(t.name, GL_TEXTURE_MAX_LEVEL, GLint(desc.mipLevels - 1));
        // New textures read as zeros on every backend (Device.h; block-compressed ones cannot be
        // cleared and are uploaded before use). A null clear value is zero in any format.
        if (!gdi::isCompressedFormat(desc.format)) {
            const GlFormat f = toGlFormat(desc.format);
            for (uint32_t m = 0; m < desc.mipLevels; ++m) gl_.ClearTexImage(t.name, GLint(m), f.format, f.type, nullptr);
        }
        if (!label.empty()) gl_.ObjectLabel(GL_TEXTURE, t.name, -1, label.c_str());
        return textures_.add(std::move(t));
    });
}

gdi::TextureHandle GlDevice::createTextureView(gdi::TextureHandle h, const gdi::TextureViewDesc& v) {
    return thread_.runCreation([&]() -> gdi::TextureHandle {  // a new object: no queued work uses it
        loss_.check("createTextureView");
        Texture& parent = texture(h);
        Texture t;
        t.desc = gdi::validate::textureView(parent.desc, parent.label, parent.viewOf != 0, v);
        t.label = v.debugName ? v.debugName : "";
        t.linearFilter = formatCaps_[size_t(t.desc.format)].linearFilter;
        t.target = textureTarget(t.desc);
        t.viewOf = h.id;
        const bool is3D = t.desc.dimension == gdi::TextureDimension::Texture3D;
        t.baseMip = v.baseMip;
        t.baseLayer = is3D ? 0 : v.baseLayer;
        gl_.GenTextures(1, &t.name);  // glTextureView wants a name that is not yet a texture
        gl_.TextureView(t.name, t.target, parent.name, toGlFormat(t.desc.format).internal, v.baseMip, t.desc.mipLevels,
                        is3D ? 0 : v.baseLayer, is3D ? 1 : t.desc.depthOrLayers);
        static constexpr GLenum kParams[] = {GL_TEXTURE_SWIZZLE_R, GL_TEXTURE_SWIZZLE_G, GL_TEXTURE_SWIZZLE_B, GL_TEXTURE_SWIZZLE_A};
        static constexpr GLint kChannels[] = {GL_RED, GL_GREEN, GL_BLUE, GL_ALPHA};
        for (size_t i = 0; i < 4; ++i) {
            const gdi::Swizzle c = v.swizzle[i];
            const GLint value = c == gdi::Swizzle::Identity ? kChannels[i]
                                : c == gdi::Swizzle::Zero   ? GL_ZERO
                                : c == gdi::Swizzle::One    ? GL_ONE
                                                            : kChannels[int(c) - int(gdi::Swizzle::R)];
            if (value != kChannels[i]) gl_.TextureParameteri(t.name, kParams[i], value);
        }
        if (!t.label.empty()) gl_.ObjectLabel(GL_TEXTURE, t.name, -1, t.label.c_str());
        std::lock_guard lock(viewsMutex_);
        ++parent.views;
        return textures_.add(std::move(t));
    });
}

gdi::SamplerHandle GlDevice::createSampler(const gdi::SamplerDesc& d) {
    return thread_.runCreation([&]() -> gdi::SamplerHandle {  // a new object: no queued work uses it
        loss_.check("createSampler");
        gdi::validate::samplerDesc(d);
        Sampler s;
        s.filtersLinearly = gdi::validate::filtersLinearly(d);
        s.readsMips = d.mipFilter != gdi::MipFilter::None;
        s.label = d.debugName ? d.debugName : "";
        gl_.CreateSamplers(1, &s.name);
        auto wrap = [](gdi::AddressMode a) {
            return a == gdi::AddressMode::ClampToEdge     ? GL_CLAMP_TO_EDGE
                   : a == gdi::AddressMode::ClampToBorder ? GL_CLAMP_TO_BORDER
                   : a == gdi::AddressMode::MirroredRepeat ? GL_MIRRORED_REPEAT : GL_REPEAT;
        };
        GLint minf;
        const bool lin = d.minFilter == gdi::Filter::Linear;
        switch (d.mipFilter) {
            case gdi::MipFilter::None: minf = lin ? GL_LINEAR : GL_NEAREST; break;
            case gdi::MipFilter::Nearest: minf = lin ? GL_LINEAR_MIPMAP_NEAREST : GL_NEAREST_MIPMAP_NEAREST; break;
            default: minf = lin ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST_MIPMAP_LINEAR; break;
        }
        gl_.SamplerParameteri(s.name, GL_TEXTURE_MIN_FILTER, minf);
        gl_.SamplerParameteri(s.name, GL_TEXTURE_MAG_FILTER, d.magFilter == gdi::Filter::Linear ? GL_LINEAR : GL_NEAREST);
        gl_.SamplerParameteri(s.name, GL_TEXTURE_WRAP_S, wrap(d.addressU));
        gl_.SamplerParameteri(s.name, GL_TEXTURE_WRAP_T, wrap(d.addressV));
        gl_.SamplerParameteri(s.name, GL_TEXTURE_WRAP_R, wrap(d.addressW));
        if (d.compareEnable) {
            gl_.SamplerParameteri(s.name, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
            gl_.SamplerParameteri(s.name, GL_TEXTURE_COMPARE_FUNC, GLint(GL_NEVER + int(d.compare)));  // same order
        }
        if (d.maxAnisotropy > 1.0f) gl_.SamplerParameterf(s.name, GL_TEXTURE_MAX_ANISOTROPY, d.maxAnisotropy);
        static constexpr GLfloat kBorder[3][4] = {{0, 0, 0, 0}, {0, 0, 0, 1}, {1, 1, 1, 1}};
        gl_.SamplerParameterfv(s.name, GL_TEXTURE_BORDER_COLOR, kBorder[int(d.borderColor)]);
        gl_.SamplerParameterf(s.name, GL_TEXTURE_LOD_BIAS, d.lodBias);
        gl_.SamplerParameterf(s.name, GL_TEXTURE_MIN_LOD, d.minLod);
        gl_.SamplerParameterf(s.name, GL_TEXTURE_MAX_LOD, d.maxLod);
        return samplers_.add(std::move(s));
    });
}

gdi::ShaderHandle GlDevice::createShader(const gdi::ShaderDesc& desc) {
    loss_.check("createShader");
    gdi::validate::shaderDesc(desc);
    const std::string label = desc.binary.name ? desc.binary.name : "";
    const auto& code = desc.binary.opengl;
    // Both halves, the Vulkan one first under the newest Vulkan rules a device takes, so that a
    // damaged binary reads the same here as on Vulkan (see validateShaderBinary); then this one's.
    gdi::validateShaderBinary(desc, gdi::SpirvRules::Vulkan13, info_.features);
    if (code.size() < 5 || code[0] != 0x07230203)
        throw gdi::Error("shader '" + label + "': not a SPIR-V binary for OpenGL (" + std::to_string(code.size()) +
                         " words, missing magic number)");
    Shader s;
    s.iface = gdi::reflectShader(code, desc.stage, desc.entryPoint, label, gdi::SpirvRules::OpenGL45);  // on this thread: no GL needed
    s.stage = desc.stage;
    s.label = label;
    s.entry = desc.entryPoint ? desc.entryPoint : "main";
    s.codeHash = gdi::fnv1a({reinterpret_cast<const uint8_t*>(code.data()), code.size_bytes()},
                            gdi::fnv1a({reinterpret_cast<const uint8_t*>(s.entry.data()), s.entry.size()}));
    const std::vector<uint32_t> stageNamed = gdi::withNamesPrefixed(code, std::string(gdi::shaderStageName(desc.stage)) + ".");
    const bool images = std::any_of(s.iface.bindings.begin(), s.iface.bindings.end(),
                                    [](const auto& b) { return b.type == gdi::BindingType::StorageTexture; });
    if (!s.iface.specConstants.empty() || images) s.spirv = stageNamed;
    return thread_.runCreation([&]() -> gdi::ShaderHandle {  // a new object: no queued work uses it
        loss_.check("createShader");
        s.name = specializedShader(s, stageNamed, {});
        return shaders_.add(std::move(s));
    });
}

// A shader object of `code` with these specialization constants (context thread).
GLuint GlDevice::specializedShader(const Shader& s, std::span<const uint32_t> code,
                                   const std::vector<gdi::SpecializationConstant>& values) {
    const GLenum type = s.stage == gdi::ShaderStage::Vertex     ? GL_VERTEX_SHADER
                        : s.stage == gdi::ShaderStage::Fragment ? GL_FRAGMENT_SHADER
                                                                : GL_COMPUTE_SHADER;
    // Only the ids this stage declares: glSpecializeShader fails on any other.
    std::vector<GLuint> ids, bits;
    for (const gdi::SpecializationConstant& v : values)
        for (const auto& c : s.iface.specConstants)
            if (c.id == v.id) ids.push_back(v.id), bits.push_back(v.bits);
    const GLuint name = gl_.CreateShader(type);
    gl_.ShaderBinary(1, &name, GL_SHADER_BINARY_FORMAT_SPIR_V, code.data(), GLsizei(code.size_bytes()));
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
static std::vector<uint8_t> imageSlots(std::initializer_list<const Shader*> shaders) {
    std::bitset<64> used;
    for (const Shader* sh : shaders)
        for (const auto& b : sh ? sh->iface.bindings : std::vector<gdi::ShaderInterface::Binding>{})
            if (b.type == gdi::BindingType::StorageTexture && b.slot < used.size()) used.set(b.slot);
    std::vector<uint8_t> slots;
    for (uint8_t slot = 0; slot < used.size(); ++slot)
        if (used[slot]) slots.push_back(slot);
    return slots;
}
// ... and the unit by slot (0xff: not a storage texture of theirs), as the shaders are renumbered.
static std::array<uint8_t, 64> imageUnits(std::initializer_list<const Shader*> shaders) {
    std::array<uint8_t, 64> unit;
    unit.fill(0xff);
    const std::vector<uint8_t> slots = imageSlots(shaders);
    for (size_t u = 0; u < slots.size(); ++u) unit[slots[u]] = uint8_t(u);
    return unit;
}

// Links the pipeline's shaders: each one's own shader object, or one of its own (deleted once
// linked) for the stages that declare the pipeline's specialization constants or whose storage
// textures take other image units in this pipeline than their slot numbers.
GLuint GlDevice::linkPipeline(std::initializer_list<const Shader*> shaders, const std::vector<gdi::SpecializationConstant>& values,
                              const std::string& label) {
    std::vector<GLuint> names, owned;
    auto dropOwned = [&] {
        for (GLuint n : owned) gl_.DeleteShader(n);
    };
    const std::array<uint8_t, 64> units = imageUnits(shaders);
    try {
        for (const Shader* sh : shaders) {
            if (!sh) continue;
            const bool specialize = std::any_of(values.begin(), values.end(), [&](const gdi::SpecializationConstant& v) {
                return std::any_of(sh->iface.specConstants.begin(), sh->iface.specConstants.end(),
                                   [&](const auto& c) { return c.id == v.id; });
            });
            const bool renumber = std::any_of(sh->iface.bindings.begin(), sh->iface.bindings.end(), [&](const auto& b) {
                return b.type == gdi::BindingType::StorageTexture && units[b.slot] != b.slot;
            });
            if (renumber) owned.push_back(specializedShader(*sh, gdi::withStorageTextureSlots(sh->spirv, units), values));
            else if (specialize) owned.push_back(specializedShader(*sh, sh->spirv, values));
            names.push_back(specialize || renumber ? owned.back() : sh->name);
        }
        GLuint program = gl_.CreateProgram();
        gl_.ProgramParameteri(program, GL_PROGRAM_BINARY_RETRIEVABLE_HINT, GL_TRUE);  // for the pipeline cache
        for (GLuint n : names) gl_.AttachShader(program, n);
        program = checkLinked(program, label);
        dropOwned();
        return program;
    } catch (...) {
        dropOwned();
        throw;
    }
}

// A program's cache key: its shaders' code and entry points, and the specialization values.
static uint64_t programKey(std::initializer_list<const Shader*> shaders, const std::vector<gdi::SpecializationConstant>& values) {
    uint64_t key = 0xcbf29ce484222325ull;
    for (const Shader* s : shaders) key = (key ^ (s ? s->codeHash : 0)) * 0x100000001b3ull;
    return gdi::fnv1a({reinterpret_cast<const uint8_t*>(values.data()), values.size() * sizeof(values[0])}, key);
}

// The program for `key`: from its cached binary when the driver takes it back, else linked by
// `link` and its binary kept for the cache (context thread).
GLuint GlDevice::cachedProgram(std::initializer_list<const Shader*> shaders, const std::vector<gdi::SpecializationConstant>& values,
                               const std::string& label) {
    const uint64_t key = programKey(shaders, values);
    if (auto it = programs_.find(key); it != programs_.end()) {
        const GLuint p = gl_.CreateProgram();
        gl_.ProgramBinary(p, it->second.format, it->second.bytes.data(), GLsizei(it->second.bytes.size()));
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
    const GLuint p = linkPipeline(shaders, values, label);
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
    const gdi::PipelineCacheLoad file = gdi::readPipelineCache(path, gdi::pipelineCacheIdentity(info_));
    gdi::PipelineCacheStats stats{.path = path, .warning = file.warning};
    std::map<uint64_t, gdi::ProgramBinary> programs;
    std::string why;
    if (!file.payload.empty() && !gdi::decodeProgramBinaries(file.payload, programs, why))
        stats.warning = "pipeline cache '" + path + "' ignored: " + why;
    else if (!file.payload.empty())
        stats.loaded = true, stats.loadedBytes = file.payload.size();
    if (binaryFormats_ == 0 && stats.warning.empty() && !path.empty())
        stats.warning = "pipeline cache '" + path + "': GL programs are not cached here: " +
                        (info_.apiVersion.find("Mesa") != std::string::npos
                             ? "Mesa's glGetProgramBinary crashes on SPIR-V programs with uniform blocks"
                             : "the driver offers no program binary format (GL_NUM_PROGRAM_BINARY_FORMATS is 0)");
    if (!stats.warning.empty()) std::cerr << "fe: " << stats.warning << "\n";
    thread_.run([&] { programs_ = stats.loaded ? std::move(programs) : std::map<uint64_t, gdi::ProgramBinary>{}; });
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
    if (!path.empty()) gdi::writePipelineCache(path, gdi::pipelineCacheIdentity(info_), gdi::encodeProgramBinaries(programs_));
}

void GlDevice::savePipelineCache() {
    thread_.run([&] { savePipelineCacheOnContext(); });
}

gdi::PipelineCacheStats GlDevice::pipelineCacheStats() const {
    std::lock_guard lock(cacheMutex_);
    return cacheStats_;
}

gdi::PipelineHandle GlDevice::createGraphicsPipeline(const gdi::GraphicsPipelineDesc& d) {
    return thread_.runCreation([&]() -> gdi::PipelineHandle {  // a new object: no queued work uses it
        loss_.check("createGraphicsPipeline");
        gdi::validate::graphicsPipelineDesc(d, info_);
        gdi::validate::blendedTargets(d, [&](gdi::Format f) { return formatCaps(f); });
        Pipeline p;
        p.label = d.debugName ? d.debugName : "";
        Shader& vs = shaders_.get(d.vertexShader, "vertex shader");
        if (vs.stage != gdi::ShaderStage::Vertex) throw gdi::Error("pipeline '" + p.label + "': vertexShader is not a vertex shader");
        const Shader* fsShader = nullptr;
        const gdi::ShaderInterface* fsIface = nullptr;
        if (d.fragmentShader) {
            fsShader = &shaders_.get(d.fragmentShader, "fragment shader");
            if (fsShader->stage != gdi::ShaderStage::Fragment)
                throw gdi::Error("pipeline '" + p.label + "': fragmentShader is not a fragment shader");
            fsIface = &fsShader->iface;
        }
        gdi::validate::vertexInputs(d, vs.iface, p.label);
        if (fsIface) gdi::validate::fragmentOutputs(d, *fsIface, p.label);
        const std::vector<gdi::BindingSlot> bindings = gdi::validate::pipelineBindings(d.bindings, {&vs.iface, fsIface}, p.label, info_.limits);
        p.constantBytes = gdi::validate::pipelineConstants({&vs.iface, fsIface}, p.label);
        gdi::validate::specialization(d.specialization, {&vs.iface, fsIface}, p.label);
        p.program = cachedProgram({&vs, fsShader}, d.specialization, p.label);
        p.imageSlots = imageSlots({&vs, fsShader});
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
                    case V::Float: case V::Float2: case V::Float3: case V::Float4:
                        gl_.VertexArrayAttribFormat(p.vao, a.location, GLint(int(a.format) - int(V::Float) + 1), GL_FLOAT, GL_FALSE, a.offset);
                        break;
                    case V::Half2: gl_.VertexArrayAttribFormat(p.vao, a.location, 2, GL_HALF_FLOAT, GL_FALSE, a.offset); break;
                    case V::Half4: gl_.VertexArrayAttribFormat(p.vao, a.location, 4, GL_HALF_FLOAT, GL_FALSE, a.offset); break;
                    case V::UNorm8x4: gl_.VertexArrayAttribFormat(p.vao, a.location, 4, GL_UNSIGNED_BYTE, GL_TRUE, a.offset); break;
                    case V::SNorm8x4: gl_.VertexArrayAttribFormat(p.vao, a.location, 4, GL_BYTE, GL_TRUE, a.offset); break;
                    case V::UNorm16x2: gl_.VertexArrayAttribFormat(p.vao, a.location, 2, GL_UNSIGNED_SHORT, GL_TRUE, a.offset); break;
                    case V::SNorm16x2: gl_.VertexArrayAttribFormat(p.vao, a.location, 2, GL_SHORT, GL_TRUE, a.offset); break;
                    case V::UInt32: gl_.VertexArrayAttribIFormat(p.vao, a.location, 1, GL_UNSIGNED_INT, a.offset); break;
                    default: break;
                }
            }
        }
        p.desc = d;
        p.desc.blend = gdi::validate::writtenTargetBlends(d, fsIface);
        p.desc.debugName = nullptr;
        p.desc.bindings = bindings;
        p.requiredSlots = gdi::validate::requiredSlotMask(bindings);
        p.slotKinds = gdi::validate::slotKinds(bindings);
        p.slotDimensions = gdi::validate::slotDimensions({&vs.iface, fsIface}, p.label);
        p.signature = gdi::validate::pipelineSignature(d);
        p.writesDepthStencil = gdi::validate::writesDepthStencil(d);
        p.vertexBindings = gdi::validate::vertexBindings(d);
        return pipelines_.add(std::move(p));
    });
}

gdi::PipelineHandle GlDevice::createComputePipeline(const gdi::ComputePipelineDesc& d) {
    return thread_.runCreation([&]() -> gdi::PipelineHandle {  // a new object: no queued work uses it
        loss_.check("createComputePipeline");
        gdi::validate::computePipelineDesc(d);
        Pipeline p;
        p.label = d.debugName ? d.debugName : "";
        Shader& cs = shaders_.get(d.computeShader, "compute shader");
        gdi::validate::computeShaderStage(cs.stage, d);
        gdi::validate::workgroup(cs.iface, info_.limits, p.label);
        const std::vector<gdi::BindingSlot> bindings = gdi::validate::pipelineBindings(d.bindings, {&cs.iface}, p.label, info_.limits);
        p.constantBytes = gdi::validate::pipelineConstants({&cs.iface}, p.label);
        gdi::validate::specialization(d.specialization, {&cs.iface}, p.label);
        p.program = cachedProgram({&cs}, d.specialization, p.label);
        p.imageSlots = imageSlots({&cs});
        p.compute = true;
        p.desc.bindings = bindings;
        p.requiredSlots = gdi::validate::requiredSlotMask(bindings);
        p.slotKinds = gdi::validate::slotKinds(bindings);
        p.slotDimensions = gdi::validate::slotDimensions({&cs.iface}, p.label);
        return pipelines_.add(std::move(p));
    });
}

gdi::TimerHandle GlDevice::createTimer() {
    return thread_.runCreation([&]() -> gdi::TimerHandle {  // a new object: no queued work uses it
        loss_.check("createTimer");
        Timer t;
        gl_.CreateQueries(GL_TIMESTAMP, 2, t.queries);
        return timers_.add(std::move(t));
    });
}

gdi::HeapHandle GlDevice::createHeap(const gdi::HeapDesc&) {
    throw gdi::Error(info_.backend + ": heaps (memory aliasing) are not supported on OpenGL; reuse whole textures");
}
gdi::MemoryRequirements GlDevice::textureMemoryRequirements(const gdi::TextureDesc&) const {
    throw gdi::Error(info_.backend + ": texture memory requirements are not exposed on OpenGL");
}

void GlDevice::forgetFramebuffers(GLuint texture) {
    for (size_t i = 0; i < fbos_.size();) {
        bool uses = fbos_[i].depth.texture == texture;
        for (auto& c : fbos_[i].colors) uses = uses || c.texture == texture;
        if (uses) {
            gl_.DeleteFramebuffers(1, &fbos_[i].fbo);
            fbos_.erase(fbos_.begin() + long(i));
        } else {
            ++i;
        }
    }
}

template <class Pool, class H, class Release>
void GlDevice::retire(Pool& pool, H h, const char* kind, Release&& release) {
    if (!h) return;
    std::lock_guard lock(submitMutex_);  // not between a submit's liveness check and its replay
    if (!pool.retire(h)) gdi::validate::destroyedHandle(kind, h.id);
    destroyEpoch_.fetch_add(1, std::memory_order_release);
    thread_.post(
        [&pool, h, release = std::forward<Release>(release)] {
            typename std::remove_reference_t<decltype(pool.at(h))> object;
            pool.release(h, object);
            release(object);
        },
        true);  // destroys come in runs, as creations do
}
void GlDevice::destroy(gdi::BufferHandle h) {
    retire(buffers_, h, "buffer", [this](Buffer& b) {
        gl_.DeleteBuffers(1, &b.name);  // unmaps a mapped buffer too
        --nativeObjects_;
    });
}
void GlDevice::destroy(gdi::TextureHandle h) {
    if (const Texture* live = h ? textures_.find(h) : nullptr) {
        std::lock_guard lock(viewsMutex_);  // views are counted on the context thread too
        if (live->views) gdi::validate::viewsAlive(live->label, live->views);
        if (Texture* parent = live->viewOf ? textures_.find({live->viewOf}) : nullptr) --parent->views;
    }
    retire(textures_, h, "texture", [this](Texture& t) {
        forgetFramebuffers(t.name);
        gl_.DeleteTextures(1, &t.name);
        if (!t.viewOf) --nativeObjects_;
    });
}
void GlDevice::destroy(gdi::SamplerHandle h) {
    retire(samplers_, h, "sampler", [this](Sampler& s) { gl_.DeleteSamplers(1, &s.name); });
}
void GlDevice::destroy(gdi::ShaderHandle h) {
    retire(shaders_, h, "shader", [this](Shader& s) { gl_.DeleteShader(s.name); });
}
void GlDevice::destroy(gdi::PipelineHandle h) {
    retire(pipelines_, h, "pipeline", [this](Pipeline& p) {
        gl_.DeleteProgram(p.program);
        if (p.vao) gl_.DeleteVertexArrays(1, &p.vao);
    });
}
std::span<const GLenum> queryTargets(gdi::QueryType t) {
    static const GLenum occlusion[] = {GL_SAMPLES_PASSED}, any[] = {GL_ANY_SAMPLES_PASSED}, time[] = {GL_TIMESTAMP};
    static const GLenum statistics[] = {GL_PRIMITIVES_SUBMITTED, GL_VERTEX_SHADER_INVOCATIONS,
                                        GL_FRAGMENT_SHADER_INVOCATIONS, GL_COMPUTE_SHADER_INVOCATIONS};
    switch (t) {
        case gdi::QueryType::Occlusion: return occlusion;
        case gdi::QueryType::AnySamplesPassed: return any;
        case gdi::QueryType::Timestamp: return time;
        case gdi::QueryType::PipelineStatistics: return statistics;
    }
    return {};
}

gdi::QuerySetHandle GlDevice::createQuerySet(const gdi::QuerySetDesc& desc) {
    gdi::validate::querySetDesc(desc, info_.features);
    return thread_.runCreation([&]() -> gdi::QuerySetHandle {  // a new object: no queued work uses it
        loss_.check("createQuerySet");
        QuerySet q;
        q.desc = desc;
        q.label = desc.debugName ? desc.debugName : "";
        q.desc.debugName = nullptr;
        q.submitted.assign(desc.count, 0);
        const auto targets = queryTargets(desc.type);
        q.names.resize(size_t(desc.count) * targets.size());
        if (desc.type == gdi::QueryType::PipelineStatistics) {
            // Mesa's glCreateQueries refuses the statistics targets (GL_INVALID_ENUM) although it
            // counts them: names from glGenQueries become queries at their first glBeginQuery.
            gl_.GenQueries(GLsizei(q.names.size()), q.names.data());
        } else {
            gl_.CreateQueries(targets[0], GLsizei(q.names.size()), q.names.data());
        }
        return querySets_.add(std::move(q));
    });
}

void GlDevice::destroy(gdi::QuerySetHandle h) {
    retire(querySets_, h, "query set", [this](QuerySet& q) { gl_.DeleteQueries(GLsizei(q.names.size()), q.names.data()); });
}

bool GlDevice::queryResults(gdi::QuerySetHandle h, uint32_t first, uint32_t count, std::span<uint64_t> out) {
    loss_.check("queryResults");
    const QuerySet& q = querySets_.get(h, "query set");
    gdi::validate::queryRead(q.desc, q.label, first, count, out.size());
    {
        std::lock_guard lock(queriesMutex_);
        for (uint32_t i = first; i < first + count; ++i)
            if (q.submitted[i] == 0 || !isComplete(q.submitted[i])) return false;
    }
    const size_t values = queryTargets(q.desc.type).size();
    thread_.runUrgent([&] {  // complete: the results are there, nothing waits
        for (size_t i = 0; i < count * values; ++i) gl_.GetQueryObjectui64v(q.names[first * values + i], GL_QUERY_RESULT, &out[i]);
    });
    return true;
}

void GlDevice::destroy(gdi::TimerHandle h) {
    retire(timers_, h, "timer", [this](Timer& t) { gl_.DeleteQueries(2, t.queries); });
}

FboAttachment GlDevice::fboAttachment(const Texture& t, uint32_t mipLevel, uint32_t layer) const {
    const bool layered = t.target != GL_TEXTURE_2D && t.target != GL_TEXTURE_2D_MULTISAMPLE;
    return {t.name, mipLevel, layered ? int32_t(layer) : -1};
}

GLenum depthAttachmentPoint(gdi::Format f) {
    const gdi::FormatInfo& fi = gdi::formatInfo(f);
    return fi.hasDepth && fi.hasStencil ? GL_DEPTH_STENCIL_ATTACHMENT : fi.hasDepth ? GL_DEPTH_ATTACHMENT : GL_STENCIL_ATTACHMENT;
}

GLuint GlDevice::framebuffer(const std::vector<FboAttachment>& colors, FboAttachment depth, GLenum depthPoint) {
    for (auto& f : fbos_)
        if (f.colors == colors && f.depth == depth) return f.fbo;
    GLuint fbo;
    gl_.CreateFramebuffers(1, &fbo);
    auto attach = [&](GLenum point, const FboAttachment& a) {
        // A layer of an array, cube (faces are layers 0-5 in DSA) or 3D texture; 2D textures whole.
        if (a.layer >= 0) gl_.NamedFramebufferTextureLayer(fbo, point, a.texture, GLint(a.mipLevel), a.layer);
        else gl_.NamedFramebufferTexture(fbo, point, a.texture, GLint(a.mipLevel));
    };
    std::vector<GLenum> draw;
    for (size_t i = 0; i < colors.size(); ++i) {
        attach(GLenum(GL_COLOR_ATTACHMENT0 + i), colors[i]);
        draw.push_back(GLenum(GL_COLOR_ATTACHMENT0 + i));
    }
    if (depth.texture) attach(depthPoint, depth);
    gl_.NamedFramebufferDrawBuffers(fbo, GLsizei(draw.size()), draw.data());
    if (gl_.CheckNamedFramebufferStatus(fbo, GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        gl_.DeleteFramebuffers(1, &fbo);
        throw gdi::Error(info_.backend + ": incomplete framebuffer for this attachment combination");
    }
    fbos_.push_back({colors, depth, fbo});
    return fbo;
}

// Queue-ordered: the bytes are copied now and written after the work queued before.
void GlDevice::writeBuffer(gdi::BufferHandle h, uint64_t offset, gdi::ByteSpan data) {
    loss_.check("writeBuffer");
    const Buffer& b = buffer(h);
    gdi::validate::bufferRange(b.desc, offset, data.size(), "writeBuffer");
    if (data.empty()) return;
    thread_.post([this, name = b.name, offset, bytes = std::vector<std::byte>(data.begin(), data.end())] {
        gl_.NamedBufferSubData(name, GLintptr(offset), GLsizeiptr(bytes.size()), bytes.data());
    });
}

void GlDevice::uploadSubresource(const Texture& t, gdi::Subresource at, const void* pixels, uint64_t bytes) {
    const gdi::validate::Extent3 e = gdi::validate::mipExtent(t.desc, at.mipLevel);
    const GlFormat f = toGlFormat(t.desc.format);
    const auto w = GLsizei(e.width), h = GLsizei(e.height), mip = GLint(at.mipLevel), layer = GLint(at.layer);
    const bool flat = t.target == GL_TEXTURE_2D;  // every other kind addresses layers, faces or slices as z
    if (gdi::isCompressedFormat(t.desc.format)) {
        if (flat) gl_.CompressedTextureSubImage2D(t.name, mip, 0, 0, w, h, f.internal, GLsizei(bytes), pixels);
        else gl_.CompressedTextureSubImage3D(t.name, mip, 0, 0, layer, w, h, 1, f.internal, GLsizei(bytes), pixels);
    } else if (flat) {
        gl_.TextureSubImage2D(t.name, mip, 0, 0, w, h, f.format, f.type, pixels);
    } else {
        gl_.TextureSubImage3D(t.name, mip, 0, 0, layer, w, h, 1, f.format, f.type, pixels);
    }
}

// Row length in texels and image height in rows: GL's pixel store, reset after each use.
static void pixelPitch(const GlFunctions& gl, bool pack, const gdi::TexelLayout& l, gdi::Format f) {
    const uint32_t texel = gdi::formatInfo(f).bytesPerPixel;
    gl.PixelStorei(pack ? GL_PACK_ROW_LENGTH : GL_UNPACK_ROW_LENGTH, texel ? GLint(l.bytesPerRow / texel) : 0);
    gl.PixelStorei(pack ? GL_PACK_IMAGE_HEIGHT : GL_UNPACK_IMAGE_HEIGHT, texel ? GLint(l.rowsPerImage) : 0);
}

void GlDevice::uploadRegion(const Texture& t, const gdi::TextureRegion& r, const gdi::TexelLayout& l, const void* pixels,
                            uint64_t bytes) {
    const GlFormat f = toGlFormat(t.desc.format);
    const bool flat = t.target == GL_TEXTURE_2D;
    const auto mip = GLint(r.mipLevel), x = GLint(r.x), y = GLint(r.y), z = GLint(r.z);
    const auto w = GLsizei(r.width), h = GLsizei(r.height), d = GLsizei(r.depth);
    if (gdi::isCompressedFormat(t.desc.format)) {  // packed tightly (validate::texelLayout)
        if (flat) gl_.CompressedTextureSubImage2D(t.name, mip, x, y, w, h, f.internal, GLsizei(bytes), pixels);
        else gl_.CompressedTextureSubImage3D(t.name, mip, x, y, z, w, h, d, f.internal, GLsizei(bytes), pixels);
        return;
    }
    pixelPitch(gl_, false, l, t.desc.format);
    if (flat) gl_.TextureSubImage2D(t.name, mip, x, y, w, h, f.format, f.type, pixels);
    else gl_.TextureSubImage3D(t.name, mip, x, y, z, w, h, d, f.format, f.type, pixels);
    pixelPitch(gl_, false, {}, t.desc.format);
}

void GlDevice::readRegion(const Texture& t, const gdi::TextureRegion& r, const gdi::TexelLayout& l, void* pixels, uint64_t bytes) {
    const GlFormat f = toGlFormat(t.desc.format);
    pixelPitch(gl_, true, l, t.desc.format);
    gl_.GetTextureSubImage(t.name, GLint(r.mipLevel), GLint(r.x), GLint(r.y), GLint(r.z), GLsizei(r.width), GLsizei(r.height),
                           GLsizei(r.depth), f.format, f.type, GLsizei(bytes), pixels);
    pixelPitch(gl_, true, {}, t.desc.format);
}

void GlDevice::writeTextureRegion(gdi::TextureHandle h, const gdi::TextureRegion& region, gdi::ByteSpan data,
                            const gdi::TexelLayout& layout) {
    loss_.check("writeTextureRegion");
    const Texture& t = texture(h);
    gdi::validate::notAView(t.viewOf != 0, t.label, "writeTexture");
    const gdi::TextureRegion r = gdi::validate::textureRegion(t.desc, region, t.label, "writeTextureRegion");
    const gdi::validate::ResolvedLayout l = gdi::validate::texelLayout(t.desc.format, r, layout, "writeTextureRegion");
    gdi::validate::dataSpan(data.size(), l.end, "writeTextureRegion");
    std::vector<std::byte> bytes(data.begin() + std::ptrdiff_t(l.layout.offset), data.begin() + std::ptrdiff_t(l.end));
    thread_.post([this, h, r, pitch = l.layout, bytes = std::move(bytes)] {
        uploadRegion(textures_.at(h), r, pitch, bytes.data(), bytes.size());
    });
}

void GlDevice::readSubresource(const Texture& t, gdi::Subresource at, void* pixels, uint64_t bytes) {
    const gdi::validate::Extent3 e = gdi::validate::mipExtent(t.desc, at.mipLevel);
    const GlFormat f = toGlFormat(t.desc.format);
    gl_.GetTextureSubImage(t.name, GLint(at.mipLevel), 0, 0, GLint(at.layer), GLsizei(e.width), GLsizei(e.height), 1, f.format,
                           f.type, GLsizei(bytes), pixels);
}

void GlDevice::writeTexture(gdi::TextureHandle h, gdi::Subresource at, gdi::ByteSpan data) {
    loss_.check("writeTexture");
    const Texture& t = texture(h);
    gdi::validate::notAView(t.viewOf != 0, t.label, "writeTexture");
    gdi::validate::uploadSize(t.desc, at, data.size(), "writeTexture", t.label);
    if (t.desc.sampleCount > 1) throw gdi::Error("writeTexture: multisampled textures cannot be uploaded");
    std::vector<std::byte> bytes(data.begin(), data.end());
    if (t.desc.format == gdi::Format::D24S8)  // gdi's X8D24 with stencil high -> GL's depth high, stencil low
        for (size_t i = 0; i + 4 <= bytes.size(); i += 4) {
            uint32_t v;
            std::memcpy(&v, &bytes[i], 4);
            v = (v << 8) | (v >> 24);
            std::memcpy(&bytes[i], &v, 4);
        }
    thread_.post([this, h, at, bytes = std::move(bytes)] {
        uploadSubresource(textures_.at(h), at, bytes.data(), bytes.size());
    });
}

std::vector<uint8_t> GlDevice::readBuffer(gdi::BufferHandle h, uint64_t offset, uint64_t size) {
    return thread_.run([&]() -> std::vector<uint8_t> {
        loss_.check("readBuffer");
        Buffer& b = buffer(h);
        gdi::validate::bufferRange(b.desc, offset, size, "readBuffer");
        std::vector<uint8_t> out(size);
        gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
        if (size) gl_.GetNamedBufferSubData(b.name, GLintptr(offset), GLsizeiptr(size), out.data());
        return out;
    });
}

gdi::Image GlDevice::readTexture(gdi::TextureHandle h, gdi::Subresource at) {
    return thread_.run([&]() -> gdi::Image {
        loss_.check("readTexture");
        Texture& t = texture(h);
        gdi::validate::notAView(t.viewOf != 0, t.label, "readTexture");
        gdi::validate::readable(t.desc, at, "readTexture", t.label);
        const gdi::validate::Extent3 e = gdi::validate::mipExtent(t.desc, at.mipLevel);
        gdi::Image img;
        img.width = e.width;
        img.height = e.height;
        img.format = t.desc.format;
        img.data.resize(gdi::imageByteSize(t.desc.format, e.width, e.height));
        gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
        readSubresource(t, at, img.data.data(), img.data.size());
        if (t.desc.format == gdi::Format::D24S8)  // GL packs depth high, stencil low; gdi uses Vulkan's X8D24
            for (size_t i = 0; i < img.data.size(); i += 4) {
                uint32_t v;
                std::memcpy(&v, &img.data[i], 4);
                v = (v >> 8) | ((v & 0xff) << 24);
                std::memcpy(&img.data[i], &v, 4);
            }
        return img;
    });
}

void* GlDevice::map(gdi::BufferHandle h) {
    const Buffer& b = buffer(h);
    gdi::validate::mappable(b.desc, b.label);
    return b.mapped;  // mapped once, persistently, when created
}

std::unique_ptr<gdi::cmd::CommandStream> GlDevice::takeStream() {
    std::lock_guard lock(streamsMutex_);
    if (freeStreams_.empty()) return std::make_unique<gdi::cmd::CommandStream>();
    auto stream = std::move(freeStreams_.back());
    freeStreams_.pop_back();
    return stream;
}
void GlDevice::returnStream(std::unique_ptr<gdi::cmd::CommandStream> stream) {
    if (!stream) return;
    for (auto& child : stream->takeChildren()) returnStream(std::move(child));
    stream->reset();
    std::lock_guard lock(streamsMutex_);
    freeStreams_.push_back(std::move(stream));
}

// A handle field of a recorded command, or one inside its payloads, that no longer names a
// live object makes the submit fail (the list was recorded before that object's destroy).
void GlDevice::checkAlive(const gdi::cmd::CommandStream& stream) const {
    auto check = [&](const auto& pool, auto h, const char* kind) {
        if (h && !pool.find(h)) gdi::validate::destroyedBeforeSubmit(kind, h.id);
    };
    auto field = [&](const char*, const auto& value) {
        using T = std::decay_t<decltype(value)>;
        if constexpr (std::is_same_v<T, gdi::BufferHandle>) check(buffers_, value, "buffer");
        else if constexpr (std::is_same_v<T, gdi::TextureHandle>) check(textures_, value, "texture");
        else if constexpr (std::is_same_v<T, gdi::SamplerHandle>) check(samplers_, value, "sampler");
        else if constexpr (std::is_same_v<T, gdi::PipelineHandle>) check(pipelines_, value, "pipeline");
        else if constexpr (std::is_same_v<T, gdi::TimerHandle>) check(timers_, value, "timer");
        else if constexpr (std::is_same_v<T, gdi::QuerySetHandle>) check(querySets_, value, "query set");
        else if constexpr (std::is_same_v<T, gdi::DepthAttachment>) {
            check(textures_, value.texture, "texture");
            check(textures_, value.resolveTexture, "texture");
        }
    };
    stream.forEach([&](const auto& record) {
        gdi::cmd::forEachField(record, field);
        using R = std::decay_t<decltype(record)>;
        if constexpr (std::is_same_v<R, gdi::cmd::ExecuteSecondary>) checkAlive(stream.child(record.child));
        if constexpr (std::is_same_v<R, gdi::cmd::BeginRenderPass>)
            for (const auto& c : gdi::cmd::view(record, record.colors)) {
                check(textures_, c.texture, "texture");
                check(textures_, c.resolveTexture, "texture");
            }
        if constexpr (std::is_same_v<R, gdi::cmd::TextureBarriers>)
            for (const auto& b : gdi::cmd::view(record, record.barriers)) check(textures_, b.texture, "texture");
        if constexpr (std::is_same_v<R, gdi::cmd::BufferBarriers>)
            for (const auto& b : gdi::cmd::view(record, record.barriers)) check(buffers_, b.buffer, "buffer");
    });
}

void GlDevice::rethrowAsyncError() {
    if (std::exception_ptr e = thread_.takeError()) std::rethrow_exception(e);
}

// Validated on the calling thread; replayed, in order, on the context thread.
gdi::FenceValue GlDevice::submit(std::span<gdi::CommandList* const> lists) {
    loss_.check("submit");
    rethrowAsyncError();
    const gdi::ClaimedLists claimed(lists, "submit");  // null, twice, in use on another thread
    std::vector<GlCommandList*> gls;
    for (gdi::CommandList* list : claimed.lists()) {
        auto* gl = dynamic_cast<GlCommandList*>(list);
        if (!gl || !gl->madeBy(*this)) throw gdi::Error("submit: a command list of another device");
        gls.push_back(gl);
    }
    // Held from the liveness check to queueing the replay: a destroy retires and queues its GL
    // delete under it too, so an object is either refused here or deleted after the replay.
    std::lock_guard lock(submitMutex_);
    for (GlCommandList* gl : gls) gl->checkSubmittable();
    std::vector<const gdi::validate::QueryRecording*> queries;
    for (GlCommandList* gl : gls) queries.push_back(&gl->queries());
    gdi::validate::queriesOncePerSubmission(queries);
    std::vector<gdi::validate::QueryRecording::Use> usedQueries;
    for (const auto* q : queries) usedQueries.insert(usedQueries.end(), q->used().begin(), q->used().end());
    std::vector<uint32_t> usedTimers;  // copied: finishing a list starts its next recording
    for (const auto* q : queries)
        for (const auto& t : q->timers()) usedTimers.push_back(t.first);
    std::vector<std::unique_ptr<gdi::cmd::CommandStream>> streams;
    for (GlCommandList* gl : gls) streams.push_back(gl->finish());
    if (gdi::fault::hit(gdi::fault::Site::Submission, "Device::submit")) {
        for (auto& s : streams) returnStream(std::move(s));
        throw loss_.lose(info_.backend, "glGetGraphicsResetStatus returned GL_UNKNOWN_CONTEXT_RESET");
    }
    const gdi::FenceValue value = nextFence_++;
    {
        std::lock_guard queriesLock(queriesMutex_);
        for (const auto& u : usedQueries)
            if (QuerySet* q = querySets_.find({u.set})) q->submitted[u.index] = value;
        for (uint32_t id : usedTimers)
            if (Timer* timer = timers_.find({id})) timer->submitted = value;
    }
    auto shared = std::make_shared<decltype(streams)>(std::move(streams));
    thread_.post([this, value, shared] {
        for (auto& stream : *shared) {
            GlReplay(*this).run(*stream, &thread_.urgentWaiting(), [this] { thread_.serviceUrgent(); });
            returnStream(std::move(stream));
        }
        gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);  // shader stores reach readback and mapped memory
        GLsync s = gl_.FenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
        gl_.Flush();
        fences_.push_back({value, s});
        replayed_.store(value, std::memory_order_release);
        checkReset(false);
    });
    return value;
}

void GlDevice::wait(gdi::FenceValue fence) {
    loss_.check("wait");
    gdi::validate::issuedFence(fence, nextFence_.load() - 1, "wait");
    // Once its submission has been replayed, a fence is waited on ahead of the queue (and in
    // between the commands of a replay in progress): not behind the next frame's replay.
    auto waitFor = [&](auto&& task) { fence <= replayed_.load(std::memory_order_acquire) ? thread_.runUrgent(task) : thread_.run(task); };
    waitFor([&] {
        while (!fences_.empty() && fences_.front().first <= fence) {
            GLsync s = fences_.front().second;
            while (gl_.ClientWaitSync(s, GL_SYNC_FLUSH_COMMANDS_BIT, 1000000000ull) == GL_TIMEOUT_EXPIRED)
                checkReset(false);  // a reset context may never signal
            gl_.DeleteSync(s);
            completed_.store(fences_.front().first, std::memory_order_release);
            fences_.erase(fences_.begin());
        }
        checkReset(false);
    });
    rethrowAsyncError();
}

bool GlDevice::isComplete(gdi::FenceValue fence) {
    loss_.check("isComplete");
    gdi::validate::issuedFence(fence, nextFence_.load() - 1, "isComplete");
    if (completed_.load(std::memory_order_acquire) >= fence) return true;
    if (fence > replayed_.load(std::memory_order_acquire)) return false;  // not even replayed yet
    return thread_.runUrgent([&] {
        while (!fences_.empty()) {
            if (gl_.ClientWaitSync(fences_.front().second, GL_SYNC_FLUSH_COMMANDS_BIT, 0) == GL_TIMEOUT_EXPIRED) break;
            gl_.DeleteSync(fences_.front().second);
            completed_.store(fences_.front().first, std::memory_order_release);
            fences_.erase(fences_.begin());
        }
        checkReset(false);
        // Nothing of `fence` still queued or pending: every submission up to it has completed.
        return fences_.empty() || fences_.front().first > fence;
    });
}

void GlDevice::waitIdle() {
    loss_.check("waitIdle");
    thread_.run([&] {
        gl_.Finish();
        for (auto& [v, s] : fences_) gl_.DeleteSync(s), completed_.store(v, std::memory_order_release);
        fences_.clear();
        checkReset(false);
    });
    rethrowAsyncError();
}

std::optional<double> GlDevice::timerNanoseconds(gdi::TimerHandle h) {
    loss_.check("timerNanoseconds");
    {
        // Not before its submission completed: the read would queue behind the replay and wait.
        std::lock_guard lock(queriesMutex_);
        const gdi::FenceValue submitted = timer(h).submitted;
        if (submitted == 0 || !isComplete(submitted)) return std::nullopt;
    }
    return thread_.runUrgent([&]() -> std::optional<double> {
        loss_.check("timerNanoseconds");
        Timer& t = timer(h);
        if (!t.used) return std::nullopt;
        if (info_.softwareRasterizer) return std::chrono::duration<double, std::nano>(t.end - t.begin).count();
        GLint available = 0;
        gl_.GetQueryObjectiv(t.queries[1], GL_QUERY_RESULT_AVAILABLE, &available);
        if (!available) return std::nullopt;
        GLuint64 a = 0, b = 0;
        gl_.GetQueryObjectui64v(t.queries[0], GL_QUERY_RESULT, &a);
        gl_.GetQueryObjectui64v(t.queries[1], GL_QUERY_RESULT, &b);
        return double(b - a);
    });
}

uint64_t GlDevice::nativeObject(gdi::NativeObject what, uint32_t id) const {
    using N = gdi::NativeObject;
    switch (what) {
        case N::Buffer: if (auto* b = buffers_.find(gdi::BufferHandle{id})) return b->name; break;
        case N::Texture: if (auto* t = textures_.find(gdi::TextureHandle{id})) return t->name; break;
        case N::Pipeline: if (auto* p = pipelines_.find(gdi::PipelineHandle{id})) return p->program; break;
        case N::VertexArray: if (auto* p = pipelines_.find(gdi::PipelineHandle{id})) return p->vao; break;
        default: break;
    }
    return 0;
}

}  // namespace fe::gl

namespace fe::gl {

// Window calls (sizing, events) stay on the calling thread, which GLFW requires to be the one
// that made the window; the blit and the swap run on the context thread.
bool GlDevice::present(gdi::TextureHandle h) {
    loss_.check("present");
    if (!platform_->hasWindow()) return gdi::Device::present(h);
    const Texture& t = texture(h);
    gdi::validate::notAView(t.viewOf != 0, t.label, "present");
    gdi::validate::presentTexture(t.desc, t.label);
    // Not a structured binding: clang 14 (the fuzz build) cannot capture one in a lambda (P1381, clang 16).
    const std::pair<uint32_t, uint32_t> framebufferSize = platform_->prepareWindow(t.desc.width, t.desc.height);
    const uint32_t fbWidth = framebufferSize.first, fbHeight = framebufferSize.second;
    thread_.run([&] {
        platform_->beforeDraw();
        GLuint fbo = framebuffer({fboAttachment(t, 0, 0)}, {}, GL_NONE);
        gl_.NamedFramebufferReadBuffer(fbo, GL_COLOR_ATTACHMENT0);
        gl_.MemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT);
        // Bytes unchanged: no sRGB decode/encode. The blit honours the scissor test, so it is off.
        gl_.Disable(GL_FRAMEBUFFER_SRGB);
        gl_.Disable(GL_SCISSOR_TEST);
        // Texture row 0 is the image's top; the window's top row is GL row fbHeight - 1.
        const GLint w = GLint(t.desc.width), hgt = GLint(t.desc.height), top = GLint(fbHeight);
        gl_.BlitNamedFramebuffer(fbo, 0, 0, 0, w, hgt, 0, top, w, top - hgt, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        gl_.Enable(GL_SCISSOR_TEST);
        gl_.Enable(GL_FRAMEBUFFER_SRGB);
        windowWidth_ = std::min(t.desc.width, fbWidth);
        windowHeight_ = std::min(t.desc.height, fbHeight);
        checkReset(gdi::fault::hit(gdi::fault::Site::Submission, "Device::present"));
        platform_->swap();
        gl_.Finish();  // the window shows the frame when present returns (readWindow reads it)
    });
    return platform_->poll();
}

gdi::Image GlDevice::readWindow() {
    loss_.check("readWindow");
    if (!platform_->hasWindow()) return gdi::Device::readWindow();
    const auto [width, height] = thread_.run([&] { return std::pair{windowWidth_, windowHeight_}; });
    return platform_->readWindow(width, height);
}

}  // namespace fe::gl

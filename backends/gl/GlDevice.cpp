// The GL backend's device: context set-up on its thread, limits and features, loss, submission and
// replay, fences and timers' results, presentation. Resources: GlResources.cpp; pipelines: GlPipeline.cpp;
// gdi values as GL names: GlFormats.cpp.
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

void GlDevice::checkReset(bool injected) {
    const GLenum status = injected ? GL_UNKNOWN_CONTEXT_RESET : gl_.GetGraphicsResetStatus();
    if (status != GL_NO_ERROR)
        throw loss_.lose(info_.backend,
                         std::string("glGetGraphicsResetStatus returned ") + glErrorName(status));
}

gdi::LiveObjects GlDevice::liveObjects() const {
    // After the queue: destroys already called count as done.
    if (!thread_.onThisThread()) return thread_.run([&] { return liveObjects(); });
    return {.buffers = buffers_.size(),
            .textures = textures_.size(),
            .samplers = samplers_.size(),
            .shaders = shaders_.size(),
            .pipelines = pipelines_.size(),
            .timers = timers_.size(),
            .heaps = 0,
            .querySets = querySets_.size(),
            .nativeObjects = nativeObjects_};
}

void APIENTRY GlDevice::debugCallback(GLenum, GLenum type, GLuint, GLenum severity, GLsizei,
                                      const GLchar* message, const void* user) {
    if (type == GL_DEBUG_TYPE_ERROR || severity == GL_DEBUG_SEVERITY_HIGH) {
        auto* device = const_cast<GlDevice*>(static_cast<const GlDevice*>(user));
        device->errors_++;
        device->messages_.report("error", message ? message : "");
    }
}

void runOnContextThread(gdi::Device& device, const std::function<void()>& task) {
    auto* gl = dynamic_cast<GlDevice*>(&device);
    if (!gl)
        throw gdi::Error(device.info().backend + ": runOnContextThread needs an OpenGL device");
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
#define FE_GL_LOAD(type, fn)                                              \
    gl_.fn = reinterpret_cast<type>(platform_->getProcAddress("gl" #fn)); \
    if (!gl_.fn)                                                          \
        throw gdi::Error(std::string(platform_->name()) + ": GL entry point gl" #fn " missing");
    FE_GL_FUNCTIONS(FE_GL_LOAD)
#undef FE_GL_LOAD
    GLint major = 0, minor = 0, n = 0;
    gl_.GetIntegerv(GL_MAJOR_VERSION, &major);
    gl_.GetIntegerv(GL_MINOR_VERSION, &minor);
    if (major * 10 + minor < 45)
        throw gdi::Error(std::string(platform_->name()) + ": OpenGL " + std::to_string(major) +
                         "." + std::to_string(minor) + " < 4.5");
    std::vector<std::string> extensions;
    gl_.GetIntegerv(GL_NUM_EXTENSIONS, &n);
    for (GLint i = 0; i < n; ++i)
        extensions.emplace_back(reinterpret_cast<const char*>(gl_.GetStringi(GL_EXTENSIONS, i)));
    auto has = [&](const char* e) {
        return std::find(extensions.begin(), extensions.end(), e) != extensions.end();
    };
    if (!has("GL_ARB_gl_spirv"))
        throw gdi::Error(std::string(platform_->name()) +
                         ": GL_ARB_gl_spirv missing (shaders are SPIR-V)");
    if (has("GL_ARB_indirect_parameters")) {
        gl_.MultiDrawArraysIndirectCount = reinterpret_cast<PFNGLMULTIDRAWARRAYSINDIRECTCOUNTPROC>(
            platform_->getProcAddress("glMultiDrawArraysIndirectCountARB"));
        gl_.MultiDrawElementsIndirectCount =
            reinterpret_cast<PFNGLMULTIDRAWELEMENTSINDIRECTCOUNTPROC>(
                platform_->getProcAddress("glMultiDrawElementsIndirectCountARB"));
    }
    if (has("GL_ARB_polygon_offset_clamp"))
        gl_.PolygonOffsetClamp = reinterpret_cast<PFNGLPOLYGONOFFSETCLAMPPROC>(
            platform_->getProcAddress("glPolygonOffsetClamp"));
    // S3TC (BC1, BC3) and its sRGB forms are extensions; RGTC (BC4, BC5) and BPTC (BC7) are core.
    const bool bc = has("GL_EXT_texture_compression_s3tc") &&
                    (has("GL_EXT_texture_sRGB") || has("GL_EXT_texture_compression_s3tc_srgb"));
    if (validation) {
        gl_.Enable(GL_DEBUG_OUTPUT);
        gl_.Enable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
        gl_.DebugMessageCallback(&GlDevice::debugCallback, this);
    }
    gl_.ClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);  // NDC y=-1 lands in memory row 0, as on Vulkan
    gl_.Enable(GL_FRAMEBUFFER_SRGB);                 // sRGB targets encode on write, as on Vulkan
    gl_.ProvokingVertex(
        GL_FIRST_VERTEX_CONVENTION);  // flat outputs come from a primitive's first vertex, as on Vulkan
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
    info_.apiVersion =
        std::string("OpenGL ") + reinterpret_cast<const char*>(gl_.GetString(GL_VERSION));
    GLint strategy = 0, flags = 0;
    gl_.GetIntegerv(GL_RESET_NOTIFICATION_STRATEGY, &strategy);
    gl_.GetIntegerv(GL_CONTEXT_FLAGS, &flags);
    info_.driverName = reinterpret_cast<const char*>(gl_.GetString(GL_VENDOR));
    info_.driverInfo =
        std::string(strategy == GL_LOSE_CONTEXT_ON_RESET ? "resets are reported"
                                                         : "no reset notification") +
        std::string((flags & GL_CONTEXT_FLAG_ROBUST_ACCESS_BIT) ? ", robust buffer access" : "");
    GLint extensionCount = 0;
    gl_.GetIntegerv(GL_NUM_EXTENSIONS, &extensionCount);
    info_.extensions.clear();
    for (GLint i = 0; i < extensionCount; ++i)
        info_.extensions.push_back(
            reinterpret_cast<const char*>(gl_.GetStringi(GL_EXTENSIONS, GLuint(i))));
    std::sort(info_.extensions.begin(), info_.extensions.end());
    info_.features.robustBufferAccess = (flags & GL_CONTEXT_FLAG_ROBUST_ACCESS_BIT) != 0;
    info_.presentMode = platform_->presentMode();
    info_.softwareRasterizer = info_.deviceName.find("llvmpipe") != std::string::npos ||
                               info_.deviceName.find("softpipe") != std::string::npos;
    info_.deviceType = info_.softwareRasterizer ? "cpu" : "gpu";
    thread_.serializeAcrossDevices(
        info_.softwareRasterizer);  // GlContextThread: Mesa's software drivers
    auto get = [&](GLenum e) {
        GLint v = 0;
        gl_.GetIntegerv(e, &v);
        return uint32_t(std::max(v, 0));
    };
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
                gl_.GetInternalformativ(GL_TEXTURE_2D_MULTISAMPLE, toGlFormat(f).internal,
                                        GL_NUM_SAMPLE_COUNTS, 1, &num);
                std::vector<GLint> counts(size_t(std::max(num, 0)));
                if (num > 0)
                    gl_.GetInternalformativ(GL_TEXTURE_2D_MULTISAMPLE, toGlFormat(f).internal,
                                            GL_SAMPLES, num, counts.data());
                all = all && std::find(counts.begin(), counts.end(), GLint(c)) != counts.end();
            }
            if (all) bits |= c;
        }
        return bits;
    };
    using F = gdi::Format;
    info_.limits.colorSampleCounts =
        countsFor(maxColor, {F::RGBA8, F::RGBA8_SRGB, F::RGBA16F, F::RG16F, F::R16F, F::RGBA32F,
                             F::RG32F, F::R32F, F::R32U, F::R11G11B10F});
    info_.limits.depthSampleCounts = countsFor(maxDepth, {F::D32F, F::D24S8});
    info_.limits.maxColorAttachments = get(GL_MAX_COLOR_ATTACHMENTS);
    GLint dims[2] = {0, 0};
    gl_.GetIntegerv(GL_MAX_VIEWPORT_DIMS, dims);
    info_.limits.maxViewportSize = uint32_t(std::max(0, std::min(dims[0], dims[1])));
    GLfloat bounds[2] = {0, 0};
    gl_.GetFloatv(GL_VIEWPORT_BOUNDS_RANGE, bounds);
    info_.limits.viewportBounds = {bounds[0], bounds[1]};
    info_.limits.maxTessellationPatchSize = get(GL_MAX_PATCH_VERTICES);  // core in 4.0
    info_.limits.maxComputeWorkGroupInvocations = get(GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS);
    for (GLuint axis = 0; axis < 3; ++axis) {
        GLint groups = 0;
        gl_.GetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, axis, &groups);
        info_.limits.maxComputeWorkGroupCount[axis] = uint32_t(std::max(groups, 0));
    }
    info_.limits.maxStorageTextures = uint32_t(
        std::min({get(GL_MAX_IMAGE_UNITS), get(GL_MAX_FRAGMENT_IMAGE_UNIFORMS),
                  get(GL_MAX_COMPUTE_IMAGE_UNIFORMS), get(GL_MAX_COMBINED_IMAGE_UNIFORMS)}));
    info_.limits.maxUniformBufferRange = get(GL_MAX_UNIFORM_BLOCK_SIZE);
    info_.limits.maxStorageBufferRange = get(GL_MAX_SHADER_STORAGE_BLOCK_SIZE);
    // GL states no allocation limit: the video memory where the driver says it (NVIDIA, and
    // Mesa's hardware drivers), else the machine's memory (llvmpipe's buffers live there).
    constexpr GLenum kDedicatedVideoMemoryNvx =
        0x9047;  // GL_GPU_MEMORY_INFO_DEDICATED_VIDMEM_NVX (not in glcorearb.h)
    GLint videoKiB = 0;
    if (has("GL_NVX_gpu_memory_info")) gl_.GetIntegerv(kDedicatedVideoMemoryNvx, &videoKiB);
    info_.limits.maxAllocationSize =
        videoKiB > 0 ? uint64_t(videoKiB) * 1024
                     : uint64_t(sysconf(_SC_PHYS_PAGES)) * uint64_t(sysconf(_SC_PAGE_SIZE));
    info_.limits.uniformBufferOffsetAlignment = get(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT);
    info_.limits.storageBufferOffsetAlignment = get(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT);
    // Mesa 22.3 crashes (strlen in the driver) serialising a SPIR-V program that has uniform
    // blocks for glGetProgramBinary (seen on llvmpipe): no program binaries there.
    binaryFormats_ =
        info_.apiVersion.find("Mesa") == std::string::npos ? get(GL_NUM_PROGRAM_BINARY_FORMATS) : 0;
    info_.features = {
        .timestamps = true,
        .computeShaders = true,
        .debugLabels = true,
        .validation = validation,
        .memoryAliasing = false,
        .window = platform_->hasWindow(),
        .textureCubeArray = true,
        .storageImageExtendedFormats = true,  // GL 4.5 core's image formats include them all
        .depthClamp = true,                   // core in 4.0 and 3.2
        .depthBiasClamp = gl_.PolygonOffsetClamp != nullptr,
        .multiDrawIndirect = true,  // core in 4.3
        .drawIndirectCount = gl_.MultiDrawArraysIndirectCount && gl_.MultiDrawElementsIndirectCount,
        .textureCompressionBC = bc,
        .occlusionQueries = true,  // GL_SAMPLES_PASSED counts exactly
        .pipelineStatistics = has("GL_ARB_pipeline_statistics_query"),
        .geometryShaders = true,       // core in 3.2
        .tessellationShaders = true};  // core in 4.0
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
        c.blend = c.renderTarget && !gdi::isDepthFormat(f) && !fi.isInteger &&
                  supported(GL_TEXTURE_2D, internal, GL_FRAMEBUFFER_BLEND);
        c.storage = supportsFormat(f, gdi::TextureUsage::Storage);
        if (c.renderTarget)
            c.sampleCounts = countsFor(gdi::isDepthFormat(f) ? maxDepth : maxColor, {f});
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
        if (p.vao) gl_.DeleteVertexArrays(1, &p.vao);
    });
    for (GLuint program : sharedPrograms_.clear()) gl_.DeleteProgram(program);  // each once
    timers_.forEach([&](Timer& t) { gl_.DeleteQueries(2, t.queries); });
    querySets_.forEach(
        [&](QuerySet& q) { gl_.DeleteQueries(GLsizei(q.names.size()), q.names.data()); });
    for (auto& f : fbos_) gl_.DeleteFramebuffers(1, &f.fbo);
    for (auto& [v, s] : fences_) gl_.DeleteSync(s);
}

bool GlDevice::supportsFormat(gdi::Format format, gdi::TextureUsage usage) const {
    if (toGlFormat(format).internal == 0) return false;
    if (gdi::isCompressedFormat(format))
        return info_.features.textureCompressionBC &&
               !any(usage, gdi::TextureUsage::RenderTarget | gdi::TextureUsage::Storage);
    // GL 4.5 core requires every format here as texture and render target; image load/store
    // has no sRGB, packed-float-to-RGB or depth formats.
    if (any(usage, gdi::TextureUsage::Storage) &&
        (format == gdi::Format::RGBA8_SRGB || format == gdi::Format::BGRA8 ||
         format == gdi::Format::BGRA8_SRGB || gdi::isDepthFormat(format)))
        return false;
    return true;
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
    stream->takeChildren();  // shared with their secondary lists, which may execute them again
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
        if constexpr (std::is_same_v<T, gdi::BufferHandle>)
            check(buffers_, value, "buffer");
        else if constexpr (std::is_same_v<T, gdi::TextureHandle>)
            check(textures_, value, "texture");
        else if constexpr (std::is_same_v<T, gdi::SamplerHandle>)
            check(samplers_, value, "sampler");
        else if constexpr (std::is_same_v<T, gdi::PipelineHandle>)
            check(pipelines_, value, "pipeline");
        else if constexpr (std::is_same_v<T, gdi::TimerHandle>)
            check(timers_, value, "timer");
        else if constexpr (std::is_same_v<T, gdi::QuerySetHandle>)
            check(querySets_, value, "query set");
        else if constexpr (std::is_same_v<T, gdi::DepthAttachment>) {
            check(textures_, value.texture, "texture");
            check(textures_, value.resolveTexture, "texture");
        }
    };
    stream.forEach([&](const auto& record) {
        gdi::cmd::forEachField(record, field);
        using R = std::decay_t<decltype(record)>;
        if constexpr (std::is_same_v<R, gdi::cmd::ExecuteSecondary>)
            checkAlive(stream.child(record.child));
        if constexpr (std::is_same_v<R, gdi::cmd::BeginRenderPass>)
            for (const auto& c : gdi::cmd::view(record, record.colors)) {
                check(textures_, c.texture, "texture");
                check(textures_, c.resolveTexture, "texture");
            }
        if constexpr (std::is_same_v<R, gdi::cmd::TextureBarriers>)
            for (const auto& b : gdi::cmd::view(record, record.barriers))
                check(textures_, b.texture, "texture");
        if constexpr (std::is_same_v<R, gdi::cmd::BufferBarriers>)
            for (const auto& b : gdi::cmd::view(record, record.barriers))
                check(buffers_, b.buffer, "buffer");
    });
}

void GlDevice::rethrowAsyncError() {
    if (std::exception_ptr e = thread_.takeError()) std::rethrow_exception(e);
}

// Validated on the calling thread; replayed, in order, on the context thread.
// One context runs every queue's work in submission order, which satisfies every
// SubmitDesc::waitFor by itself (DeviceFeatures::asyncCompute and asyncCopy are false).
gdi::FenceValue GlDevice::submit(std::span<gdi::CommandList* const> lists,
                                 const gdi::SubmitDesc& desc) {
    loss_.check("submit");
    rethrowAsyncError();
    const gdi::ClaimedLists claimed(lists, "submit");  // null, twice, in use on another thread
    (void)gdi::validate::submissionQueue(claimed.lists(), desc, nextFence_.load() - 1);
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
    gdi::validate::querySubmission(queries, [&](uint32_t set, uint32_t index) {
        return querySets_.get({set}, "query set").submitted[index] != 0;
    });
    std::vector<gdi::validate::QueryRecording::Use> usedQueries;
    for (const auto* q : queries)
        usedQueries.insert(usedQueries.end(), q->used().begin(), q->used().end());
    std::vector<uint32_t> usedTimers;  // copied: finishing a list starts its next recording
    for (const auto* q : queries)
        for (const auto& t : q->timers()) usedTimers.push_back(t.first);
    std::vector<std::unique_ptr<gdi::cmd::CommandStream>> streams;
    for (GlCommandList* gl : gls) streams.push_back(gl->finish());
    if (gdi::fault::hit(gdi::fault::Site::Submission, "Device::submit")) {
        for (auto& s : streams) returnStream(std::move(s));
        throw loss_.lose(info_.backend,
                         "glGetGraphicsResetStatus returned GL_UNKNOWN_CONTEXT_RESET");
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
            GlReplay(*this).run(*stream, &thread_.urgentWaiting(),
                                [this] { thread_.serviceUrgent(); });
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
    auto waitFor = [&](auto&& task) {
        fence <= replayed_.load(std::memory_order_acquire) ? thread_.runUrgent(task)
                                                           : thread_.run(task);
    };
    waitFor([&] {
        while (!fences_.empty() && fences_.front().first <= fence) {
            GLsync s = fences_.front().second;
            while (gl_.ClientWaitSync(s, GL_SYNC_FLUSH_COMMANDS_BIT, 1000000000ull) ==
                   GL_TIMEOUT_EXPIRED)
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
            if (gl_.ClientWaitSync(fences_.front().second, GL_SYNC_FLUSH_COMMANDS_BIT, 0) ==
                GL_TIMEOUT_EXPIRED)
                break;
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
        for (auto& [v, s] : fences_)
            gl_.DeleteSync(s), completed_.store(v, std::memory_order_release);
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
        if (info_.softwareRasterizer)
            return std::chrono::duration<double, std::nano>(t.end - t.begin).count();
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
        case N::Buffer:
            if (auto* b = buffers_.find(gdi::BufferHandle{id})) return b->name;
            break;
        case N::Texture:
            if (auto* t = textures_.find(gdi::TextureHandle{id})) return t->name;
            break;
        case N::Pipeline:
            if (auto* p = pipelines_.find(gdi::PipelineHandle{id})) return p->program;
            break;
        case N::VertexArray:
            if (auto* p = pipelines_.find(gdi::PipelineHandle{id})) return p->vao;
            break;
        default:
            break;
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
    const std::pair<uint32_t, uint32_t> framebufferSize =
        platform_->prepareWindow(t.desc.width, t.desc.height);
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
        gl_.BlitNamedFramebuffer(fbo, 0, 0, 0, w, hgt, 0, top, w, top - hgt, GL_COLOR_BUFFER_BIT,
                                 GL_NEAREST);
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
    const auto [width, height] = thread_.run([&] {
        return std::pair{windowWidth_, windowHeight_};
    });
    return platform_->readWindow(width, height);
}

}  // namespace fe::gl

// The GL backend's resources: buffers, textures and views, samplers, timers, query sets, their
// framebuffers, destruction (retired until the GPU is done with them) and transfers.
#include "gl/GlDevice.h"

#include <algorithm>
#include <cstring>

#include "fe/gdi/Validation.h"

namespace fe::gl {

template <class Call>
GLenum GlDevice::allocateStorage(const char* name, Call&& call) {
    if (gdi::fault::hit(gdi::fault::Site::Allocation, name)) return GL_OUT_OF_MEMORY;
    // Errors of earlier calls are not this one's (the debug output reports them); a lost
    // context may repeat GL_CONTEXT_LOST, hence the bound.
    for (int i = 0; i < 8 && gl_.GetError() != GL_NO_ERROR; ++i) {}
    call();
    return gl_.GetError();
}

gdi::BufferHandle GlDevice::createBuffer(const gdi::BufferDesc& desc, gdi::ByteSpan initialData) {
    return thread_.runCreation([&]() -> gdi::BufferHandle {  // a new object: no queued work uses it
        loss_.check("createBuffer");
        const gdi::fault::ObjectScope faultObject(desc.debugName);  // on the context thread
        gdi::validate::bufferDesc(desc, info_.limits);
        gdi::validate::initialData(desc, initialData.size());
        Buffer b;
        b.desc = desc;
        b.label = desc.debugName ? desc.debugName : "";
        b.desc.debugName = nullptr;
        // Upload and Readback memory is mapped once, persistently and coherently (map()).
        const GLbitfield persistent = GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
        const GLbitfield mapFlags =
            desc.access == gdi::MemoryAccess::Upload     ? GL_MAP_WRITE_BIT | persistent
            : desc.access == gdi::MemoryAccess::Readback ? GL_MAP_READ_BIT | persistent
                                                         : 0;
        gl_.CreateBuffers(1, &b.name);
        ++nativeObjects_;
        if (GLenum e = allocateStorage("glNamedBufferStorage",
                                       [&] {
                                           gl_.NamedBufferStorage(
                                               b.name, GLsizeiptr(desc.size),
                                               initialData.empty() ? nullptr : initialData.data(),
                                               GL_DYNAMIC_STORAGE_BIT | mapFlags);
                                       });
            e != GL_NO_ERROR) {
            gl_.DeleteBuffers(1, &b.name);
            --nativeObjects_;
            if (e == GL_CONTEXT_LOST)
                throw loss_.lose(info_.backend, "glNamedBufferStorage raised GL_CONTEXT_LOST");
            throw gdi::Error(
                info_.backend + ": glNamedBufferStorage failed for " +
                gdi::describeObject("buffer", b.label, std::to_string(desc.size) + " bytes") +
                ": " + glErrorName(e));
        }
        // New buffers read as zeros on every backend (Device.h); a null clear value is zero.
        if (initialData.empty())
            gl_.ClearNamedBufferData(b.name, GL_R8, GL_RED, GL_UNSIGNED_BYTE, nullptr);
        if (!b.label.empty()) gl_.ObjectLabel(GL_BUFFER, b.name, -1, b.label.c_str());
        if (mapFlags)
            b.mapped = gl_.MapNamedBufferRange(b.name, 0, GLsizeiptr(desc.size), mapFlags);
        return buffers_.add(std::move(b));
    });
}

gdi::TextureHandle GlDevice::createTexture(const gdi::TextureDesc& desc) {
    return thread_.runCreation([&]()
                                   -> gdi::TextureHandle {  // a new object: no queued work uses it
        loss_.check("createTexture");
        const gdi::fault::ObjectScope faultObject(desc.debugName);  // on the context thread
        gdi::validate::textureDesc(desc, info_);
        const std::string label = desc.debugName ? desc.debugName : "";
        if (desc.heap)
            throw gdi::Error("texture '" + label +
                             "': heaps (memory aliasing) are not supported on OpenGL");
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
        const auto w = GLsizei(desc.width), h = GLsizei(desc.height),
                   levels = GLsizei(desc.mipLevels);
        const char* call = t.target == GL_TEXTURE_2D_MULTISAMPLE ? "glTextureStorage2DMultisample"
                           : (t.target == GL_TEXTURE_2D || t.target == GL_TEXTURE_CUBE_MAP)
                               ? "glTextureStorage2D"
                               : "glTextureStorage3D";
        if (GLenum e = allocateStorage(
                call,
                [&] {
                    switch (t.target) {
                        case GL_TEXTURE_2D_MULTISAMPLE:
                            gl_.TextureStorage2DMultisample(t.name, GLsizei(desc.sampleCount),
                                                            internal, w, h, GL_TRUE);
                            break;
                        case GL_TEXTURE_2D:
                        case GL_TEXTURE_CUBE_MAP:
                            gl_.TextureStorage2D(t.name, levels, internal, w, h);
                            break;
                        default:  // layers or depth
                            gl_.TextureStorage3D(t.name, levels, internal, w, h,
                                                 GLsizei(desc.depthOrLayers));
                            break;
                    }
                });
            e != GL_NO_ERROR) {
            gl_.DeleteTextures(1, &t.name);
            --nativeObjects_;
            if (e == GL_CONTEXT_LOST)
                throw loss_.lose(info_.backend, std::string(call) + " raised GL_CONTEXT_LOST");
            throw gdi::Error(
                info_.backend + ": " + call + " failed for " +
                gdi::describeObject(
                    "texture", label,
                    std::to_string(desc.width) + "x" + std::to_string(desc.height) +
                        (desc.depthOrLayers > 1 ? "x" + std::to_string(desc.depthOrLayers) : "") +
                        " " + std::string(gdi::formatInfo(desc.format).name)) +
                ": " + glErrorName(e));
        }
        if (t.target != GL_TEXTURE_2D_MULTISAMPLE)
            gl_.TextureParameteri(t.name, GL_TEXTURE_MAX_LEVEL, GLint(desc.mipLevels - 1));
        // New textures read as zeros on every backend (Device.h; block-compressed ones cannot be
        // cleared and are uploaded before use). A null clear value is zero in any format.
        if (!gdi::isCompressedFormat(desc.format)) {
            const GlFormat f = toGlFormat(desc.format);
            for (uint32_t m = 0; m < desc.mipLevels; ++m)
                gl_.ClearTexImage(t.name, GLint(m), f.format, f.type, nullptr);
        }
        if (!label.empty()) gl_.ObjectLabel(GL_TEXTURE, t.name, -1, label.c_str());
        return textures_.add(std::move(t));
    });
}

gdi::TextureHandle GlDevice::createTextureView(gdi::TextureHandle h,
                                               const gdi::TextureViewDesc& v) {
    return thread_.runCreation(
        [&]() -> gdi::TextureHandle {  // a new object: no queued work uses it
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
            gl_.TextureView(t.name, t.target, parent.name, toGlFormat(t.desc.format).internal,
                            v.baseMip, t.desc.mipLevels, is3D ? 0 : v.baseLayer,
                            is3D ? 1 : t.desc.depthOrLayers);
            static constexpr GLenum kParams[] = {GL_TEXTURE_SWIZZLE_R, GL_TEXTURE_SWIZZLE_G,
                                                 GL_TEXTURE_SWIZZLE_B, GL_TEXTURE_SWIZZLE_A};
            static constexpr GLint kChannels[] = {GL_RED, GL_GREEN, GL_BLUE, GL_ALPHA};
            // GL stores BGRA8 as RGBA8 (its BGRA is a transfer order): a view across the channel
            // orders reads red and blue swapped, as Vulkan's view of the other byte order does.
            const bool swapRedBlue = gdi::channelOrdersDiffer(parent.desc.format, t.desc.format);
            auto stored = [&](size_t channel) {
                return swapRedBlue && (channel == 0 || channel == 2) ? kChannels[2 - channel]
                                                                     : kChannels[channel];
            };
            for (size_t i = 0; i < 4; ++i) {
                const gdi::Swizzle c = v.swizzle[i];
                const GLint value = c == gdi::Swizzle::Identity ? stored(i)
                                    : c == gdi::Swizzle::Zero   ? GL_ZERO
                                    : c == gdi::Swizzle::One
                                        ? GL_ONE
                                        : stored(size_t(int(c) - int(gdi::Swizzle::R)));
                if (value != kChannels[i]) gl_.TextureParameteri(t.name, kParams[i], value);
            }
            if (!t.label.empty()) gl_.ObjectLabel(GL_TEXTURE, t.name, -1, t.label.c_str());
            std::lock_guard lock(viewsMutex_);
            ++parent.views;
            return textures_.add(std::move(t));
        });
}

gdi::SamplerHandle GlDevice::createSampler(const gdi::SamplerDesc& d) {
    return thread_.runCreation(
        [&]() -> gdi::SamplerHandle {  // a new object: no queued work uses it
            loss_.check("createSampler");
            gdi::validate::samplerDesc(d);
            Sampler s;
            s.filtersLinearly = gdi::validate::filtersLinearly(d);
            s.readsMips = d.mipFilter != gdi::MipFilter::None;
            s.label = d.debugName ? d.debugName : "";
            gl_.CreateSamplers(1, &s.name);
            auto wrap = [](gdi::AddressMode a) {
                return a == gdi::AddressMode::ClampToEdge      ? GL_CLAMP_TO_EDGE
                       : a == gdi::AddressMode::ClampToBorder  ? GL_CLAMP_TO_BORDER
                       : a == gdi::AddressMode::MirroredRepeat ? GL_MIRRORED_REPEAT
                                                               : GL_REPEAT;
            };
            GLint minf;
            const bool lin = d.minFilter == gdi::Filter::Linear;
            switch (d.mipFilter) {
                case gdi::MipFilter::None:
                    minf = lin ? GL_LINEAR : GL_NEAREST;
                    break;
                case gdi::MipFilter::Nearest:
                    minf = lin ? GL_LINEAR_MIPMAP_NEAREST : GL_NEAREST_MIPMAP_NEAREST;
                    break;
                default:
                    minf = lin ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST_MIPMAP_LINEAR;
                    break;
            }
            gl_.SamplerParameteri(s.name, GL_TEXTURE_MIN_FILTER, minf);
            gl_.SamplerParameteri(s.name, GL_TEXTURE_MAG_FILTER,
                                  d.magFilter == gdi::Filter::Linear ? GL_LINEAR : GL_NEAREST);
            gl_.SamplerParameteri(s.name, GL_TEXTURE_WRAP_S, wrap(d.addressU));
            gl_.SamplerParameteri(s.name, GL_TEXTURE_WRAP_T, wrap(d.addressV));
            gl_.SamplerParameteri(s.name, GL_TEXTURE_WRAP_R, wrap(d.addressW));
            if (d.compareEnable) {
                gl_.SamplerParameteri(s.name, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
                gl_.SamplerParameteri(s.name, GL_TEXTURE_COMPARE_FUNC,
                                      GLint(GL_NEVER + int(d.compare)));  // same order
            }
            if (d.maxAnisotropy > 1.0f)
                gl_.SamplerParameterf(s.name, GL_TEXTURE_MAX_ANISOTROPY, d.maxAnisotropy);
            static constexpr GLfloat kBorder[3][4] = {{0, 0, 0, 0}, {0, 0, 0, 1}, {1, 1, 1, 1}};
            gl_.SamplerParameterfv(s.name, GL_TEXTURE_BORDER_COLOR, kBorder[int(d.borderColor)]);
            gl_.SamplerParameterf(s.name, GL_TEXTURE_LOD_BIAS, d.lodBias);
            gl_.SamplerParameterf(s.name, GL_TEXTURE_MIN_LOD, d.minLod);
            gl_.SamplerParameterf(s.name, GL_TEXTURE_MAX_LOD, d.maxLod);
            return samplers_.add(std::move(s));
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
    throw gdi::Error(info_.backend +
                     ": heaps (memory aliasing) are not supported on OpenGL; reuse whole textures");
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
        if (Texture* parent = live->viewOf ? textures_.find({live->viewOf}) : nullptr)
            --parent->views;
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
        for (GLuint unused : sharedPrograms_.release(p.programKey)) gl_.DeleteProgram(unused);
        if (p.vao) gl_.DeleteVertexArrays(1, &p.vao);
    });
}

gdi::QuerySetHandle GlDevice::createQuerySet(const gdi::QuerySetDesc& desc) {
    gdi::validate::querySetDesc(desc, info_.features);
    return thread_.runCreation(
        [&]() -> gdi::QuerySetHandle {  // a new object: no queued work uses it
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
    retire(querySets_, h, "query set",
           [this](QuerySet& q) { gl_.DeleteQueries(GLsizei(q.names.size()), q.names.data()); });
}

bool GlDevice::queryResults(gdi::QuerySetHandle h, uint32_t first, uint32_t count,
                            std::span<uint64_t> out) {
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
        for (size_t i = 0; i < count * values; ++i)
            gl_.GetQueryObjectui64v(q.names[first * values + i], GL_QUERY_RESULT, &out[i]);
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

GLuint GlDevice::framebuffer(const std::vector<FboAttachment>& colors, FboAttachment depth,
                             GLenum depthPoint) {
    for (auto& f : fbos_)
        if (f.colors == colors && f.depth == depth) return f.fbo;
    GLuint fbo;
    gl_.CreateFramebuffers(1, &fbo);
    auto attach = [&](GLenum point, const FboAttachment& a) {
        // A layer of an array, cube (faces are layers 0-5 in DSA) or 3D texture; 2D textures whole.
        if (a.layer >= 0)
            gl_.NamedFramebufferTextureLayer(fbo, point, a.texture, GLint(a.mipLevel), a.layer);
        else
            gl_.NamedFramebufferTexture(fbo, point, a.texture, GLint(a.mipLevel));
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
        throw gdi::Error(info_.backend +
                         ": incomplete framebuffer for this attachment combination");
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
    thread_.post(
        [this, name = b.name, offset, bytes = std::vector<std::byte>(data.begin(), data.end())] {
            gl_.NamedBufferSubData(name, GLintptr(offset), GLsizeiptr(bytes.size()), bytes.data());
        });
}

void GlDevice::uploadSubresource(const Texture& t, gdi::Subresource at, const void* pixels,
                                 uint64_t bytes) {
    const gdi::validate::Extent3 e = gdi::validate::mipExtent(t.desc, at.mipLevel);
    const GlFormat f = toGlFormat(t.desc.format);
    const auto w = GLsizei(e.width), h = GLsizei(e.height), mip = GLint(at.mipLevel),
               layer = GLint(at.layer);
    const bool flat =
        t.target == GL_TEXTURE_2D;  // every other kind addresses layers, faces or slices as z
    if (gdi::isCompressedFormat(t.desc.format)) {
        if (flat)
            gl_.CompressedTextureSubImage2D(t.name, mip, 0, 0, w, h, f.internal, GLsizei(bytes),
                                            pixels);
        else
            gl_.CompressedTextureSubImage3D(t.name, mip, 0, 0, layer, w, h, 1, f.internal,
                                            GLsizei(bytes), pixels);
    } else if (flat) {
        gl_.TextureSubImage2D(t.name, mip, 0, 0, w, h, f.format, f.type, pixels);
    } else {
        gl_.TextureSubImage3D(t.name, mip, 0, 0, layer, w, h, 1, f.format, f.type, pixels);
    }
}

// Row length in texels and image height in rows: GL's pixel store, reset after each use.
static void pixelPitch(const GlFunctions& gl, bool pack, const gdi::TexelLayout& l, gdi::Format f) {
    const uint32_t texel = gdi::formatInfo(f).bytesPerPixel;
    gl.PixelStorei(pack ? GL_PACK_ROW_LENGTH : GL_UNPACK_ROW_LENGTH,
                   texel ? GLint(l.bytesPerRow / texel) : 0);
    gl.PixelStorei(pack ? GL_PACK_IMAGE_HEIGHT : GL_UNPACK_IMAGE_HEIGHT,
                   texel ? GLint(l.rowsPerImage) : 0);
}

// D24S8 and D32F_S8 keep both aspects in one GL texel (depth in the high 24 bits and stencil in
// the low 8; a float, then a word with the stencil in its low 8 bits), and GL 4.5 has no upload
// of one aspect into them, nor an exact read of D24S8's depth alone (GL_DEPTH_COMPONENT converts
// through float). So one aspect is taken out of, or merged into, the whole texels of the region
// on the CPU, exactly; the buffer side uses Vulkan's per-aspect layouts (aspectTexelBytes).
namespace {
struct AspectTexels {
    std::vector<uint8_t> whole;  // GL's combined texels of the region, tightly packed
    uint32_t wholeBytes;         // 4 (D24S8) or 8 (D32F_S8)
    uint32_t aspectBytes;        // the buffer's texel: 4 for depth, 1 for stencil
    bool depth;
    bool d24;
};
// Visits every texel of the region: i (index into the tight combined texels), o (byte offset
// of the texel in the caller's layout).
template <class Fn>
void forEachTexel(const gdi::TextureRegion& r, const gdi::TexelLayout& l, uint32_t aspectBytes,
                  Fn&& fn) {
    size_t i = 0;
    for (uint32_t z = 0; z < r.depth; ++z)
        for (uint32_t y = 0; y < r.height; ++y)
            for (uint32_t x = 0; x < r.width; ++x, ++i)
                fn(i,
                   (uint64_t(z) * l.rowsPerImage + y) * l.bytesPerRow + uint64_t(x) * aspectBytes);
}
}  // namespace

static AspectTexels readWholeTexels(const GlFunctions& gl, const Texture& t,
                                    const gdi::TextureRegion& r) {
    const GlFormat f = toGlFormat(t.desc.format);
    AspectTexels a{.wholeBytes = gdi::formatInfo(t.desc.format).bytesPerPixel,
                   .aspectBytes = gdi::aspectTexelBytes(t.desc.format, r.aspect),
                   .depth = r.aspect == gdi::TextureAspect::Depth,
                   .d24 = t.desc.format == gdi::Format::D24S8};
    a.whole.resize(size_t(r.width) * r.height * r.depth * a.wholeBytes);
    gl.GetTextureSubImage(t.name, GLint(r.mipLevel), GLint(r.x), GLint(r.y), GLint(r.z),
                          GLsizei(r.width), GLsizei(r.height), GLsizei(r.depth), f.format, f.type,
                          GLsizei(a.whole.size()), a.whole.data());
    return a;
}

void GlDevice::readAspect(const Texture& t, const gdi::TextureRegion& r, const gdi::TexelLayout& l,
                          uint8_t* pixels) {
    const AspectTexels a = readWholeTexels(gl_, t, r);
    forEachTexel(r, l, a.aspectBytes, [&](size_t i, uint64_t o) {
        const uint8_t* w = &a.whole[i * a.wholeBytes];
        if (a.d24) {
            uint32_t v;
            std::memcpy(&v, w, 4);
            if (a.depth) {
                v >>= 8;
                std::memcpy(pixels + o, &v, 4);
            } else {
                pixels[o] = uint8_t(v & 0xff);
            }
        } else if (a.depth) {
            std::memcpy(pixels + o, w, 4);
        } else {
            pixels[o] = w[4];
        }
    });
}

void GlDevice::uploadAspect(const Texture& t, const gdi::TextureRegion& r,
                            const gdi::TexelLayout& l, const uint8_t* pixels) {
    AspectTexels a = readWholeTexels(gl_, t, r);
    forEachTexel(r, l, a.aspectBytes, [&](size_t i, uint64_t o) {
        uint8_t* w = &a.whole[i * a.wholeBytes];
        if (a.d24) {
            uint32_t v, in = 0;
            std::memcpy(&v, w, 4);
            std::memcpy(&in, pixels + o, a.aspectBytes);
            v = a.depth ? (in << 8) | (v & 0xffu) : (v & ~0xffu) | (in & 0xffu);
            std::memcpy(w, &v, 4);
        } else if (a.depth) {
            std::memcpy(w, pixels + o, 4);
        } else {
            const uint32_t word = pixels[o];
            std::memcpy(w + 4, &word, 4);
        }
    });
    const GlFormat f = toGlFormat(t.desc.format);
    const auto mip = GLint(r.mipLevel), x = GLint(r.x), y = GLint(r.y), z = GLint(r.z);
    const auto w = GLsizei(r.width), h = GLsizei(r.height), d = GLsizei(r.depth);
    if (t.target == GL_TEXTURE_2D)
        gl_.TextureSubImage2D(t.name, mip, x, y, w, h, f.format, f.type, a.whole.data());
    else
        gl_.TextureSubImage3D(t.name, mip, x, y, z, w, h, d, f.format, f.type, a.whole.data());
}

void GlDevice::uploadRegion(const Texture& t, const gdi::TextureRegion& r,
                            const gdi::TexelLayout& l, const void* pixels, uint64_t bytes) {
    if (gdi::hasTwoAspects(t.desc.format))
        return uploadAspect(t, r, l, static_cast<const uint8_t*>(pixels));
    const GlFormat f = toGlFormat(t.desc.format);
    const bool flat = t.target == GL_TEXTURE_2D;
    const auto mip = GLint(r.mipLevel), x = GLint(r.x), y = GLint(r.y), z = GLint(r.z);
    const auto w = GLsizei(r.width), h = GLsizei(r.height), d = GLsizei(r.depth);
    if (gdi::isCompressedFormat(t.desc.format)) {  // packed tightly (validate::texelLayout)
        if (flat)
            gl_.CompressedTextureSubImage2D(t.name, mip, x, y, w, h, f.internal, GLsizei(bytes),
                                            pixels);
        else
            gl_.CompressedTextureSubImage3D(t.name, mip, x, y, z, w, h, d, f.internal,
                                            GLsizei(bytes), pixels);
        return;
    }
    pixelPitch(gl_, false, l, t.desc.format);
    if (flat)
        gl_.TextureSubImage2D(t.name, mip, x, y, w, h, f.format, f.type, pixels);
    else
        gl_.TextureSubImage3D(t.name, mip, x, y, z, w, h, d, f.format, f.type, pixels);
    pixelPitch(gl_, false, {}, t.desc.format);
}

void GlDevice::readRegion(const Texture& t, const gdi::TextureRegion& r, const gdi::TexelLayout& l,
                          void* pixels, uint64_t bytes) {
    if (gdi::hasTwoAspects(t.desc.format))
        return readAspect(t, r, l, static_cast<uint8_t*>(pixels));
    const GlFormat f = toGlFormat(t.desc.format);
    pixelPitch(gl_, true, l, t.desc.format);
    gl_.GetTextureSubImage(t.name, GLint(r.mipLevel), GLint(r.x), GLint(r.y), GLint(r.z),
                           GLsizei(r.width), GLsizei(r.height), GLsizei(r.depth), f.format, f.type,
                           GLsizei(bytes), pixels);
    pixelPitch(gl_, true, {}, t.desc.format);
}

void GlDevice::writeTextureRegion(gdi::TextureHandle h, const gdi::TextureRegion& region,
                                  gdi::ByteSpan data, const gdi::TexelLayout& layout) {
    loss_.check("writeTextureRegion");
    const Texture& t = texture(h);
    gdi::validate::notAView(t.viewOf != 0, t.label, "writeTexture");
    const gdi::TextureRegion r =
        gdi::validate::textureRegion(t.desc, region, t.label, "writeTextureRegion");
    const gdi::validate::ResolvedLayout l =
        gdi::validate::texelLayout(t.desc.format, r, layout, "writeTextureRegion");
    gdi::validate::dataSpan(data.size(), l.end, "writeTextureRegion");
    std::vector<std::byte> bytes(data.begin() + std::ptrdiff_t(l.layout.offset),
                                 data.begin() + std::ptrdiff_t(l.end));
    thread_.post([this, h, r, pitch = l.layout, bytes = std::move(bytes)] {
        uploadRegion(textures_.at(h), r, pitch, bytes.data(), bytes.size());
    });
}

void GlDevice::readSubresource(const Texture& t, gdi::Subresource at, void* pixels,
                               uint64_t bytes) {
    const gdi::validate::Extent3 e = gdi::validate::mipExtent(t.desc, at.mipLevel);
    const GlFormat f = toGlFormat(t.desc.format);
    gl_.GetTextureSubImage(t.name, GLint(at.mipLevel), 0, 0, GLint(at.layer), GLsizei(e.width),
                           GLsizei(e.height), 1, f.format, f.type, GLsizei(bytes), pixels);
}

void GlDevice::writeTexture(gdi::TextureHandle h, gdi::Subresource at, gdi::ByteSpan data) {
    loss_.check("writeTexture");
    const Texture& t = texture(h);
    gdi::validate::notAView(t.viewOf != 0, t.label, "writeTexture");
    gdi::validate::uploadSize(t.desc, at, data.size(), "writeTexture", t.label);
    if (t.desc.sampleCount > 1)
        throw gdi::Error("writeTexture: multisampled textures cannot be uploaded");
    std::vector<std::byte> bytes(data.begin(), data.end());
    if (t.desc.format ==
        gdi::Format::D24S8)  // gdi's X8D24 with stencil high -> GL's depth high, stencil low
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
        if (t.desc.format ==
            gdi::Format::D24S8)  // GL packs depth high, stencil low; gdi uses Vulkan's X8D24
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

}  // namespace fe::gl

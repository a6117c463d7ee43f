// The OpenGL 4.5 core implementation of gdi::Device (direct state access, ARB_gl_spirv).
//  - glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE): depth [0,1] as on Vulkan; NDC y = -1 maps
//    to window row 0, which is memory row 0 on both APIs, so images match with no flip.
//  - One thread owns the context (GlContextThread): every GL call runs there, whichever thread
//    calls the device. Command lists record into a CommandStream without touching GL; submit
//    queues the streams, which the context thread replays in submission order (GlReplay),
//    then flushes and inserts a fence sync. Destroys and writes are queued in the same order.
//  - Vertex and index buffers are applied to the current pipeline's VAO at draw time, since
//    gdi lets them be set before the pipeline.
#pragma once
#include <array>
#include <atomic>
#include <chrono>
#include <functional>
#include <map>
#include <mutex>
#include <memory>
#include <string>
#include <vector>

#include "fe/gdi/LiveLists.h"
#include "fe/gdi/CommandStream.h"
#include "fe/gdi/Device.h"
#include "fe/gdi/PipelineSharing.h"
#include "fe/gdi/Validation.h"
#include "fe/gdi/Faults.h"
#include "fe/gdi/HandlePool.h"
#include "fe/gdi/MessageLog.h"
#include "fe/gdi/PipelineCacheFile.h"
#include "gl/GlConstantsRing.h"
#include "gl/GlContextThread.h"
#include "gl/GlFunctions.h"
#include "gl/GlPlatform.h"

namespace fe::gl {

class GlCommandList;

struct GlFormat {
    GLenum internal, format, type;
};
GlFormat toGlFormat(gdi::Format f);

struct Buffer {
    GLuint name = 0;
    gdi::BufferDesc desc;
    std::string label;
    void* mapped = nullptr;  // Upload and Readback buffers: persistently mapped, coherent
};
struct Texture {
    GLuint name = 0;
    GLenum target = GL_TEXTURE_2D;  // by dimension and sample count
    gdi::TextureDesc desc;
    std::string label;
    bool linearFilter = false;  // FormatCaps::linearFilter of its format
    uint32_t viewOf = 0;        // a view (glTextureView) of this texture handle id; 0: a texture
    uint32_t baseMip = 0, baseLayer = 0;  // a view: where it starts in its texture
    uint32_t views = 0;                   // live views of this texture
};
GLenum textureTarget(const gdi::TextureDesc& d);
// Where a depth/stencil format attaches: GL_DEPTH_STENCIL_ATTACHMENT, GL_DEPTH_ATTACHMENT or (S8)
// GL_STENCIL_ATTACHMENT.
GLenum depthAttachmentPoint(gdi::Format f);
// GL_OUT_OF_MEMORY and the other glGetError / reset-status values by name, for messages.
const char* glErrorName(GLenum e);
// One framebuffer attachment: a texture's mip level and, for layered textures, its layer.
struct FboAttachment {
    GLuint texture = 0;
    uint32_t mipLevel = 0;
    int32_t layer = -1;  // -1: the texture has no layers (Texture2D, multisampled)
    bool operator==(const FboAttachment&) const = default;
};
struct Sampler {
    GLuint name = 0;
    bool filtersLinearly =
        false;               // a Linear filter without comparison: needs FormatCaps::linearFilter
    bool readsMips = false;  // a MipFilter other than None: reads more than the base mip
    std::string label;
};
struct Shader {
    GLuint name = 0;
    gdi::ShaderStage stage = gdi::ShaderStage::None;
    std::string label;
    gdi::ShaderInterface iface;  // reflected: pipelines are checked against it
    // Names prefixed by the stage (gdi::withNamesPrefixed). Kept for shaders with specialization constants
    // or storage textures: pipelines specialize or renumber a shader object of their own.
    std::vector<uint32_t> spirv;
    std::string entry;
    uint64_t codeHash = 0;  // of the SPIR-V and entry point: part of a program's cache key
};
struct Pipeline {
    GLuint program = 0;
    GLuint vao = 0;
    bool compute = false;
    gdi::GraphicsPipelineDesc desc;  // state applied at setPipeline (shaders/bindings kept too)
    std::vector<uint32_t> strides;
    uint64_t requiredSlots = 0;
    std::array<uint8_t, 64> slotKinds{};  // validate::slotKinds: what each slot must be bound with
    std::array<uint8_t, 64>
        slotDimensions{};  // validate::slotDimensions: the texture kind a slot takes
    std::array<uint32_t, 64> slotBlockBytes{};  // validate::slotBlockBytes (validation mode)
    gdi::validate::PassSignature
        signature;  // attachment formats and samples, checked at setPipeline
    bool writesDepthStencil =
        false;  // validate::writesDepthStencil: may not sample its depth attachment
    std::vector<gdi::validate::VertexBinding> vertexBindings;  // what each draw checks it may read
    uint32_t constantBytes = 0;  // the shaders' constants block (FE_CONSTANTS)
    // The storage-texture slots its shaders use, in slot order: slot imageSlots[u] is bound to
    // image unit u (the shaders are renumbered so; GL may have only 8 units).
    std::vector<uint8_t> imageSlots;
    std::string label;
    std::string programKey;  // the program is shared by this key (PipelineSharing.h)
};
struct Timer {
    GLuint queries[2] = {0, 0};
    bool used = false;
    gdi::FenceValue submitted = 0;  // the submission that last used it (0: none; queriesMutex_)
    // Software rasterizers: wall-clock time between two glFinish calls instead of GL_TIMESTAMP.
    std::chrono::steady_clock::time_point begin, end;
};

struct QuerySet {
    std::vector<GLuint>
        names;  // validate::queryValues(type) per query (statistics: one per counter)
    gdi::QuerySetDesc desc;
    std::string label;
    std::vector<gdi::FenceValue>
        submitted;  // per query: the submission that last wrote it (0: none)
};
// The GL query targets of a set's type: one, or the four statistics in PipelineStatistics order.
std::span<const GLenum> queryTargets(gdi::QueryType t);

class GlDevice final : public gdi::Device {
public:
    GlDevice(PlatformKind kind, bool validation, bool vsync = true);
    ~GlDevice() override;

    const gdi::DeviceInfo& info() const override { return info_; }
#include "fe/gdi/DeviceOverrides.inc"
    gdi::FormatCaps formatCaps(gdi::Format format) const override {
        return formatCaps_[size_t(format)];
    }
    void destroy(gdi::HeapHandle h) override {  // no heaps on GL: only the null handle is valid
        if (h) gdi::validate::destroyedHandle("heap", h.id);
    }
    const gdi::BufferDesc& desc(gdi::BufferHandle h) const override {
        return buffers_.get(h, "buffer").desc;
    }
    const gdi::TextureDesc& desc(gdi::TextureHandle h) const override {
        return textures_.get(h, "texture").desc;
    }
    const gdi::ShaderInterface& shaderInterface(gdi::ShaderHandle h) const override {
        return shaders_.get(h, "shader").iface;
    }
    // Upload/readback of one subresource through the pixel unpack/pack state (pointer or, with a
    // bound GL_PIXEL_*_BUFFER, an offset); shared by the blocking calls and the command list.
    void uploadSubresource(const Texture& t, gdi::Subresource at, const void* pixels,
                           uint64_t bytes);
    // Regions (resolved region and layout): the pixel store's row length and image height say the
    // pitch; `pixels` is where the layout's offset points (a pointer, or a pixel-buffer offset).
    void uploadRegion(const Texture& t, const gdi::TextureRegion& r, const gdi::TexelLayout& l,
                      const void* pixels, uint64_t bytes);
    void readRegion(const Texture& t, const gdi::TextureRegion& r, const gdi::TexelLayout& l,
                    void* pixels, uint64_t bytes);
    // One aspect of D24S8 / D32F_S8 (pixels in client memory, no pixel buffer bound).
    void uploadAspect(const Texture& t, const gdi::TextureRegion& r, const gdi::TexelLayout& l,
                      const uint8_t* pixels);
    void readAspect(const Texture& t, const gdi::TextureRegion& r, const gdi::TexelLayout& l,
                    uint8_t* pixels);
    void readSubresource(const Texture& t, gdi::Subresource at, void* pixels, uint64_t bytes);
    uint32_t validationErrorCount() const override { return errors_.load(); }
    gdi::InputState input() const override { return platform_->input(); }

    // For the command list (recording, any thread: lookups only) and the replay (context thread).
    const GlFunctions& gl() const { return gl_; }
    // Objects of handles checked when recorded: live, or destroyed with the release still queued.
    Buffer& bufferAt(gdi::BufferHandle h) { return buffers_.at(h); }
    Texture& textureAt(gdi::TextureHandle h) { return textures_.at(h); }
    Sampler& samplerAt(gdi::SamplerHandle h) { return samplers_.at(h); }
    Pipeline& pipelineAt(gdi::PipelineHandle h) { return pipelines_.at(h); }
    Timer& timerAt(gdi::TimerHandle h) { return timers_.at(h); }
    QuerySet& querySetAt(gdi::QuerySetHandle h) { return querySets_.at(h); }
    QuerySet& querySet(gdi::QuerySetHandle h) { return querySets_.get(h, "query set"); }
    // Streams are reused (their blocks kept) from list to list.
    std::unique_ptr<gdi::cmd::CommandStream> takeStream();
    void returnStream(std::unique_ptr<gdi::cmd::CommandStream> stream);
    // How many destroy() calls so far: a list compares it at submit with its value when it began.
    uint64_t destroyEpoch() const { return destroyEpoch_.load(std::memory_order_acquire); }
    gdi::LiveLists<GlCommandList>& liveLists() { return liveLists_; }
    // Throws the submit error when the stream uses a destroyed object.
    void checkAlive(const gdi::cmd::CommandStream& stream) const;
    Buffer& buffer(gdi::BufferHandle h) { return buffers_.get(h, "buffer"); }
    const Buffer* findBuffer(gdi::BufferHandle h) const {
        return buffers_.find(h);
    }  // null if invalid
    Texture& texture(gdi::TextureHandle h) { return textures_.get(h, "texture"); }
    Sampler& sampler(gdi::SamplerHandle h) { return samplers_.get(h, "sampler"); }
    Pipeline& pipeline(gdi::PipelineHandle h) { return pipelines_.get(h, "pipeline"); }
    Timer& timer(gdi::TimerHandle h) { return timers_.get(h, "timer"); }
    FboAttachment fboAttachment(const Texture& t, uint32_t mipLevel, uint32_t layer) const;
    GLuint framebuffer(const std::vector<FboAttachment>& colors, FboAttachment depth,
                       GLenum depthPoint);
    GlConstantsRing& constantsRing() { return constantsRing_; }  // context thread (GlReplay)
    // Runs `task` on the context thread (gl-specific escape hatch: bench/ issues direct GL calls).
    void runOnContextThread(const std::function<void()>& task) { thread_.run(task); }

private:
    static void APIENTRY debugCallback(GLenum source, GLenum type, GLuint id, GLenum severity,
                                       GLsizei length, const GLchar* message, const void* user);
    void initialize(bool validation);  // on the context thread
    void releaseAll();                 // on the context thread, at destruction
    // Destroy: the handle is dead at once; the GL object goes after the work queued before.
    template <class Pool, class H, class Release>
    void retire(Pool& pool, H h, const char* kind, Release&& release);
    void rethrowAsyncError();
    GLuint specializedShader(const Shader& s, std::span<const uint32_t> code,
                             const std::vector<gdi::SpecializationConstant>& values);
    // singleSample: the pipeline draws into single-sample targets, where a fragment shader's
    // gl_SampleMask needs withSampleMaskAsDiscard to act as on Vulkan.
    GLuint linkPipeline(const std::vector<const Shader*>& shaders,
                        const std::vector<gdi::SpecializationConstant>& values,
                        const std::string& label, bool singleSample = false);
    GLuint checkLinked(GLuint program, const std::string& label);
    std::unique_ptr<GlPlatform> platform_;
    GlFunctions gl_;
    gdi::DeviceInfo info_;
    std::atomic<uint32_t> errors_{0};
    std::array<gdi::FormatCaps, size_t(gdi::Format::Count)> formatCaps_{};  // queried once at start
    gdi::MessageLog messages_{"GL debug"};  // each message once; repeats counted
    gdi::DeviceLoss loss_;
    uint32_t nativeObjects_ = 0;  // buffer and texture names created and not yet deleted
    // Storage for a buffer or texture: runs `call` and returns the GL error it raised, or
    // GL_OUT_OF_MEMORY without running it when fault injection fails it (fe/gdi/Faults.h).
    template <class Call>
    GLenum allocateStorage(const char* name, Call&& call);
    // A context reset (robust contexts report one through glGetGraphicsResetStatus; fault
    // injection fakes one at the N-th submit) makes the device lost.
    void checkReset(bool injected);
    std::vector<std::pair<gdi::FenceValue, GLsync>> fences_;  // context thread only
    std::mutex submitMutex_;  // fence values are handed out in the order streams are queued
    std::atomic<gdi::FenceValue> nextFence_{
        1};  // taken under submitMutex_; wait and isComplete read it
    std::atomic<gdi::FenceValue> completed_{0};  // every fence up to it has signalled
    std::atomic<gdi::FenceValue> replayed_{0};   // every submission up to it has been replayed
    std::atomic<uint64_t> destroyEpoch_{0};
    gdi::LiveLists<GlCommandList> liveLists_;  // lists to orphan when the device goes first
    std::mutex streamsMutex_;
    std::vector<std::unique_ptr<gdi::cmd::CommandStream>> freeStreams_;
    struct CachedFbo {
        std::vector<FboAttachment> colors;
        FboAttachment depth;
        GLuint fbo;
    };
    std::vector<CachedFbo> fbos_;
    GlConstantsRing constantsRing_;
    uint32_t windowWidth_ = 0, windowHeight_ = 0;        // size of the last presented image
    const uint32_t handleSalt_ = gdi::nextHandleSalt();  // before the pools it salts
    gdi::HandlePool<gdi::BufferHandle, Buffer> buffers_{handleSalt_};
    gdi::HandlePool<gdi::TextureHandle, Texture> textures_{handleSalt_};
    gdi::HandlePool<gdi::SamplerHandle, Sampler> samplers_{handleSalt_};
    gdi::HandlePool<gdi::ShaderHandle, Shader> shaders_{handleSalt_};
    gdi::HandlePool<gdi::PipelineHandle, Pipeline> pipelines_{
        handleSalt_};  // command lists point at the bound one (objects never move)
    gdi::HandlePool<gdi::TimerHandle, Timer> timers_{handleSalt_};
    gdi::HandlePool<gdi::QuerySetHandle, QuerySet> querySets_{handleSalt_};
    std::mutex queriesMutex_;
    std::mutex viewsMutex_;  // Texture::views
    // Program binaries by key (shaders, entry points, specialization), context thread only.
    std::map<uint64_t, gdi::ProgramBinary> programs_;
    gdi::PipelineCacheStats cacheStats_;
    mutable std::mutex cacheMutex_;  // cacheStats_
    GLint binaryFormats_ = 0;  // GL_NUM_PROGRAM_BINARY_FORMATS: 0, and program binaries are off
    // Linked programs by key and label, shared by the pipelines that use them (PipelineSharing.h).
    gdi::SharedPipelines<GLuint> sharedPrograms_;
    // The program of a pipeline: shared, from its cached binary, or linked; `sharedKey` is set
    // to the key the pipeline releases it by.
    GLuint cachedProgram(const std::vector<const Shader*>& shaders,
                         const std::vector<gdi::SpecializationConstant>& values,
                         const std::string& label, std::string& sharedKey,
                         bool singleSample = false);
    GLuint compiledProgram(const std::vector<const Shader*>& shaders,
                           const std::vector<gdi::SpecializationConstant>& values,
                           const std::string& label, bool singleSample);
    void
    savePipelineCacheOnContext();  // QuerySet::submitted, written by submit, read by queryResults
    void forgetFramebuffers(GLuint texture);
    mutable GlContextThread
        thread_;  // last member: stopped (in the destructor) before the rest goes
};

}  // namespace fe::gl

// Layer 2 (GDI abstraction): checks every backend runs on descriptions before touching the
// native API, so invalid input gives the same clear message on Vulkan and GL.
#pragma once
#include <algorithm>
#include <array>
#include <climits>
#include <functional>
#include <initializer_list>
#include <bit>
#include <optional>
#include <span>
#include <string_view>
#include <utility>

#include "fe/gdi/Device.h"
#include "fe/gdi/ShaderReflection.h"

namespace fe::gdi::validate {

// Each throws Error naming the object (debugName when set) and what is wrong.
void bufferDesc(const BufferDesc& d, const DeviceLimits& limits);
// Initial data of createBuffer: none (size 0) or exactly the buffer's size.
void initialData(const BufferDesc& d, uint64_t size);
void textureDesc(const TextureDesc& d, const DeviceInfo& device);
// createTexture of a format the device cannot use with every usage asked for (supportsFormat).
[[noreturn]] void unsupportedTextureUsage(const TextureDesc& d);

// Size of one mip level: width, height, and depth (3D) or layer count (arrays, cubes).
struct Extent3 {
    uint32_t width = 1, height = 1, depthOrLayers = 1;
};
Extent3 mipExtent(const TextureDesc& d, uint32_t mipLevel);
// A view checked against its texture (not itself a view); returns the view's TextureDesc.
TextureDesc textureView(const TextureDesc& texture, const std::string& name, bool textureIsView,
                        const TextureViewDesc& v);
// destroy() of a texture whose views are alive.
[[noreturn]] void viewsAlive(const std::string& name, uint32_t views);
// Views are bound, not copied: copies, uploads, readback, mips and barriers take the texture.
void notAView(bool isView, const std::string& name, const char* what);
inline bool identitySwizzle(const std::array<Swizzle, 4>& s) {
    for (size_t i = 0; i < 4; ++i)
        if (s[i] != Swizzle::Identity && s[i] != Swizzle(uint8_t(Swizzle::R) + i)) return false;
    return true;
}
// A TextureRegion checked against the texture and resolved (0 extents filled in): in its mip
// level, an aspect the format has, block-aligned when compressed, single-sample unless
// perSample (texture-to-texture copies move every sample).
TextureRegion textureRegion(const TextureDesc& d, const TextureRegion& r, const std::string& name,
                            const char* what, bool perSample = false);
// A TexelLayout checked for `region` of format `f` and resolved (0 fields filled in); `end` is
// the offset just past the last byte it spans.
struct ResolvedLayout {
    TexelLayout layout;
    uint64_t end = 0;
};
ResolvedLayout texelLayout(Format f, const TextureRegion& region, const TexelLayout& l,
                           const char* what);
// A buffer<->texture region copy: the region and layout resolved and checked, the buffer range too.
struct RegionCopy {
    TextureRegion region;
    TexelLayout layout;
};
RegionCopy bufferTextureRegion(const TextureDesc& t, const std::string& name, const BufferDesc& b,
                               const std::string& bufferName, const TextureRegion& region,
                               const TexelLayout& layout, bool toTexture, const char* what);
// writeTexture's data holds at least the `end` bytes its layout spans.
void dataSpan(size_t size, uint64_t end, const char* what);
// copyTexture between regions: compatible formats, both 3D or both layered, the destination box
// in its texture, the two boxes apart when the texture is the same. Returns the resolved pair.
// resolveTexture: src multisampled, dst single-sample of the same non-integer colour format,
// both regions resolved (dst's extent is src's); returns {dst, src}.
std::pair<TextureRegion, TextureRegion> textureResolve(const TextureDesc& dst,
                                                       const std::string& dstName,
                                                       TextureRegion dstAt, const TextureDesc& src,
                                                       const std::string& srcName,
                                                       const TextureRegion& srcRegion);
std::pair<TextureRegion, TextureRegion> textureCopy(const TextureDesc& dst,
                                                    const std::string& dstName, TextureRegion dstAt,
                                                    bool sameTexture, const TextureDesc& src,
                                                    const std::string& srcName,
                                                    const TextureRegion& srcRegion);
// copyTexture of a whole mip: the same format, kind, size and samples; the mip in both.
void wholeTextureCopy(const TextureDesc& dst, const std::string& dstName, const TextureDesc& src,
                      const std::string& srcName, uint32_t mip);
// copyBufferToTexture / copyTextureToBuffer of one whole subresource: a single-sample texture of
// one aspect (colour, D16, D32F or S8) and a tightly packed range of the buffer at a 4-byte aligned offset, with copy usages.
void subresourceBufferCopy(const TextureDesc& t, const std::string& textureName, Subresource at,
                           const BufferDesc& b, const std::string& bufferName, uint64_t offset,
                           bool toTexture, const char* what);
// Commands recorded in a list that copy need CopySrc on what they read and CopyDst on what they
// write (copies, resolveQueries; clearBuffer CopyDst or Storage). The device's own transfers
// (writeBuffer, writeTexture, readBuffer, readTexture, initial data) need neither.
void textureUsage(const TextureDesc& d, TextureUsage usage, const std::string& name,
                  const char* what);
// Throws Error unless `at` names an existing subresource of the texture; `what` names the call.
void subresource(const TextureDesc& d, Subresource at, const char* what, const std::string& name);
// readTexture: an existing subresource of a single-sample, uncompressed texture.
void readable(const TextureDesc& d, Subresource at, const char* what, const std::string& name);
// A Transient texture's contents cannot be read, written or copied outside a pass.
void transientContents(const TextureDesc& d, const std::string& what);
// generateMips: a single-sample colour texture of a filterable (not integer, not compressed) format.
void mipGeneration(const TextureDesc& d, const std::string& name);
// Vulkan and GL need a view or binding per kind; these say what each dimension is.
inline bool isArrayed(TextureDimension d) {
    return d == TextureDimension::Texture2DArray || d == TextureDimension::TextureCubeArray;
}
inline bool isCube(TextureDimension d) {
    return d == TextureDimension::TextureCube || d == TextureDimension::TextureCubeArray;
}
// An upload of `size` bytes to subresource `at` (checked with subresource()) must be exactly it.
void uploadSize(const TextureDesc& d, Subresource at, uint64_t size, const char* what,
                const std::string& name);
void samplerDesc(const SamplerDesc& d);
// Indirect arguments: an Indirect buffer holding drawCount records of `stride` bytes from
// offset (4-byte aligned); drawCount > 1 needs multiDrawIndirect.
void indirect(const BufferDesc& d, const std::string& name, uint64_t offset, uint32_t drawCount,
              uint32_t stride, uint32_t recordSize, const DeviceFeatures& features,
              const char* what);
void shaderDesc(const ShaderDesc& d);
void graphicsPipelineDesc(const GraphicsPipelineDesc& d, const DeviceInfo& device);
void computePipelineDesc(const ComputePipelineDesc& d);
// createComputePipeline: its shader's stage.
void computeShaderStage(ShaderStage stage, const ComputePipelineDesc& d);
// Device::present's texture: RGBA8 or RGBA8_SRGB (the bytes a window shows unchanged) with
// CopySrc usage, on every windowed backend.
void presentTexture(const TextureDesc& d, const std::string& name);
// Attachment formats/usages/sizes must agree; returns the render area.
struct AttachmentInfo {
    Format format = Format::Undefined;  // Undefined: no attachment (for resolves)
    uint32_t width = 0, height = 0;
    TextureUsage usage = TextureUsage::None;
    uint32_t samples = 1;
};
// The attachment view of a texture's subresource; throws for a subresource that does not exist.
AttachmentInfo attachment(const TextureDesc& d, uint32_t mipLevel, uint32_t layer, const char* what,
                          const std::string& name);
// colorResolves has one entry per colour attachment (format Undefined: none).
Rect renderPass(const RenderPassDesc& d, const std::vector<AttachmentInfo>& colors,
                const std::vector<AttachmentInfo>& colorResolves, const AttachmentInfo* depth,
                const AttachmentInfo* depthResolve, const DeviceLimits& limits);
// What a secondary list inherits from its pass: attachment formats, sample count and size.
struct PassSignature {
    std::array<Format, 8> colors{};
    uint32_t colorCount = 0;
    Format depth = Format::Undefined;
    uint32_t samples = 1;
    uint32_t width = 0, height = 0;  // the render area
    bool operator==(const PassSignature&) const = default;
};
PassSignature passSignature(const std::vector<AttachmentInfo>& colors, const AttachmentInfo* depth,
                            Rect area);
inline Rect renderArea(const PassSignature& s) { return {0, 0, s.width, s.height}; }

// Rendering feedback loops. A draw that samples or stores to a subresource its render pass
// renders into reads what the APIs leave undefined (Vulkan's feedback-loop rules, GL 4.5
// section 9.3.1), and GPUs and backends then disagree; two attachments naming one subresource
// likewise. Both are Errors, the same on every backend. Reading the depth attachment from a
// pipeline that writes neither depth nor stencil is allowed (read-only depth: soft particles,
// decals), as Vulkan's read-only depth layouts allow it.
struct TextureSpan {
    uint32_t texture = 0;  // handle id of the texture; a view's is its texture's
    uint32_t baseMip = 0, mipCount = 1;
    uint32_t baseLayer = 0, layerCount = 1;  // a 3D texture's slices count as layers
    std::string_view name;                   // for messages, valid during the call that gives it
};
// The subresources a texture (or view: `viewOf` its texture's id, `baseMip`/`baseLayer` where it
// starts) exposes to a binding: every layer, and every mip of the view, or one mip: a storage
// binding's, or the base mip for a sampler whose MipFilter is None (GL's feedback-loop rule
// takes the levels the filter can reach).
TextureSpan bindingSpan(uint32_t id, uint32_t viewOf, uint32_t baseMip, uint32_t baseLayer,
                        const TextureDesc& view, std::optional<uint32_t> oneMip = std::nullopt);
// The same for a backend's texture record (viewOf, baseMip, baseLayer, desc) named `name`.
template <class Texture>
TextureSpan bindingSpanOf(uint32_t id, const Texture& t, std::string_view name,
                          std::optional<uint32_t> oneMip = std::nullopt) {
    TextureSpan s = bindingSpan(id, t.viewOf, t.baseMip, t.baseLayer, t.desc, oneMip);
    s.name = name;
    return s;
}
class PassAttachments {
public:
    static constexpr uint8_t kColour = 1, kDepth = 2;  // what overlaps() found
    // The open pass's attachments, each as spanOf(handle) (bindingSpan of the whole texture or
    // view) narrowed to its mip and layer. Throws when two name one subresource.
    template <class SpanOf>
    void begin(const RenderPassDesc& d, SpanOf&& spanOf) {
        count_ = 0;
        auto each = [&](TextureHandle h, uint32_t mip, uint32_t layer, uint8_t role) {
            if (h) add(spanOf(h), mip, layer, role, d.debugName);
        };
        for (size_t i = 0; i < d.colors.size() && i < 8; ++i) {
            each(d.colors[i].texture, d.colors[i].mipLevel, d.colors[i].layer, uint8_t(i));
            each(d.colors[i].resolveTexture, d.colors[i].resolveSubresource.mipLevel,
                 d.colors[i].resolveSubresource.layer, uint8_t(8 + i));
        }
        each(d.depth.texture, d.depth.mipLevel, d.depth.layer, kDepthRole);
        each(d.depth.resolveTexture, d.depth.resolveSubresource.mipLevel,
             d.depth.resolveSubresource.layer, kDepthRole + 1);
    }
    void end() { count_ = 0; }
    bool empty() const { return count_ == 0; }
    // kColour and/or kDepth: which attachments of the open pass a binding of `s` reaches.
    uint8_t overlaps(const TextureSpan& s) const {
        uint8_t hit = 0;
        for (uint32_t i = 0; i < count_; ++i)
            if (reaches(s, at_[i])) hit |= kinds_[i];
        return hit;
    }
    // The Error of a draw whose pipeline reads `slot` while it reaches an attachment.
    [[noreturn]] void failed(uint32_t slot, const TextureSpan& s, bool storage,
                             const char* pipelineName) const;

private:
    static bool reaches(const TextureSpan& s, const TextureSpan& a) {
        return s.texture == a.texture && a.baseMip - s.baseMip < s.mipCount &&
               a.baseLayer - s.baseLayer < s.layerCount;
    }
    // role: colour attachment i (0-7), its resolve target (8 + i), depth (16), depth resolve (17).
    static constexpr uint8_t kDepthRole = 16;
    void add(const TextureSpan& whole, uint32_t mip, uint32_t layer, uint8_t role,
             const char* passName);
    static std::string roleName(uint8_t role);
    static constexpr uint32_t kMax = 2 * 8 + 2;
    std::array<TextureSpan, kMax> at_{};
    std::array<uint8_t, kMax> kinds_{}, roles_{};
    std::array<std::string, kMax> names_;  // the attachments' texture names, for messages
    std::string passName_;
    uint32_t count_ = 0;
};
// Per list: the texture each slot was last given (setTexture/setStorageTexture) and which slots
// reach an attachment of the open pass. The backends mark those slots (GL: every slot that
// reaches; Vulkan: those refused() for the bound pipeline) so that their per-slot kind check
// fails and the draw's checked path calls check(); no cost on the per-draw path.
class FeedbackLoops {
public:
    // A texture bound to `slot`; returns what it reaches in the open pass (PassAttachments kinds).
    uint8_t bind(uint32_t slot, const TextureSpan& s, bool storage) {
        slots_[slot] = {s.texture, s.baseMip, s.mipCount, s.baseLayer, s.layerCount, {}};
        storage_ = storage ? storage_ | bit(slot) : storage_ & ~bit(slot);
        const uint8_t hit = pass_.empty() ? 0 : pass_.overlaps(s);
        hits_[slot] = hit;
        reaching_ = hit ? reaching_ | bit(slot) : reaching_ & ~bit(slot);
        return hit;
    }
    // A pass begins: returns the slots among `textureSlots` (those now holding textures) whose
    // texture reaches one of its attachments.
    template <class SpanOf>
    uint64_t beginPass(const RenderPassDesc& d, SpanOf&& spanOf, uint64_t textureSlots) {
        pass_.begin(d, spanOf);
        reaching_ = 0;
        for (uint64_t m = textureSlots; m; m &= m - 1) {
            const uint32_t slot = uint32_t(std::countr_zero(m));
            if ((hits_[slot] = pass_.overlaps(slots_[slot]))) reaching_ |= bit(slot);
        }
        return reaching_;
    }
    // Returns the slots that reached an attachment of the pass now ended.
    uint64_t endPass() {
        pass_.end();
        return std::exchange(reaching_, 0);
    }
    uint64_t reaching() const { return reaching_; }
    // At a draw, for a slot the pipeline uses that reaches an attachment: throws unless only the
    // depth attachment is reached and the pipeline writes neither depth nor stencil.
    void check(uint32_t slot, bool pipelineWritesDepthStencil, const char* pipelineName) const;
    // Whether check() would throw for this slot.
    bool refused(uint32_t slot, bool pipelineWritesDepthStencil) const {
        return (reaching_ & bit(slot)) && ((hits_[slot] & PassAttachments::kColour) ||
                                           (storage_ & bit(slot)) || pipelineWritesDepthStencil);
    }
    void clear() { pass_.end(), reaching_ = 0; }

private:
    static uint64_t bit(uint32_t slot) { return uint64_t(1) << slot; }
    PassAttachments pass_;
    std::array<TextureSpan, 64> slots_{};
    std::array<uint8_t, 64> hits_{};  // per slot: PassAttachments::overlaps while in reaching_
    uint64_t storage_ = 0, reaching_ = 0;
};
// Whether a pipeline writes the depth attachment (depth writes, or a stencil test that writes).
bool writesDepthStencil(const GraphicsPipelineDesc& d);
// The secondary-list rules of CommandList (Device.h), with one message on every backend.
// beginSecondary on a list that is not empty, or inside a pass.
[[noreturn]] void secondaryNotEmpty();
// A recording call on a secondary list after its endSecondary.
[[noreturn]] void afterEndSecondary(const char* what);
// A call a secondary list may not hold (timers; begin/endRenderPass).
[[noreturn]] void notInSecondary(const char* what);
// executeSecondary's checks of list `index`: a secondary list, ended, for this pass.
void executedSecondary(bool inSecondaryPass, bool isSecondary, bool ended,
                       const PassSignature& list, const PassSignature& pass, size_t index);
// submit of a secondary list.
[[noreturn]] void submittedSecondary();
// Pipelines against their shaders (ShaderReflection.h). The binding slots: derived from the
// shaders when `declared` is empty; otherwise `declared`, where every slot a shader uses must
// appear with the kind the shader declares and that shader's stage. The shaders use at most
// limits.maxStorageTextures storage textures.
std::vector<BindingSlot> pipelineBindings(const std::vector<BindingSlot>& declared,
                                          const std::vector<const ShaderInterface*>& shaders,
                                          const std::string& pipeline, const DeviceLimits& limits);
// Every vertex shader input has an attribute of the same scalar kind in the vertex layout.
void vertexInputs(const GraphicsPipelineDesc& d, const ShaderInterface& vs,
                  const std::string& pipeline);
// Every fragment output that lands on a colour target has the target format's scalar kind.
void fragmentOutputs(const GraphicsPipelineDesc& d, const ShaderInterface& fs,
                     const std::string& pipeline);
// Every blended colour target's format can be blended on this device (FormatCaps::blend: never
// integer formats; 32-bit floats only where the device says so).
void blendedTargets(const GraphicsPipelineDesc& d, const std::function<FormatCaps(Format)>& caps);
// The pipeline's blend states with writes masked off for the colour targets the fragment shader
// (null: none) has no output for: such a target keeps its contents on every backend, where the
// APIs leave it undefined (Vulkan stored stale bytes there, GL zeros).
std::vector<BlendTargetState> writtenTargetBlends(const GraphicsPipelineDesc& d,
                                                  const ShaderInterface* fs);
// A compute shader's work group fits the device.
void workgroup(const ShaderInterface& cs, const DeviceLimits& limits, const std::string& pipeline);
// Queries: a set's description (feature, count), and each recording's rules, with one message
// on every backend. A list keeps a QueryRecording; the device resets what it used() at submit.
void querySetDesc(const QuerySetDesc& d, const DeviceFeatures& f);
uint32_t queryValues(QueryType t);  // uint64_t values per query: 4 for statistics, else 1
// resolveQueries' buffer: CopyDst usage, an 8-byte aligned offset, room for `bytes`.
void queryDestination(const BufferDesc& d, const std::string& name, uint64_t offset,
                      uint64_t bytes);
// queryResults: the range is in the set and `out` holds its values.
void queryRead(const QuerySetDesc& d, const std::string& name, uint32_t first, uint32_t count,
               size_t outSize);
class QueryRecording {
public:
    struct Use {
        uint32_t set = 0, index = 0;
        bool ended = false;
    };
    void begin(const QuerySetDesc& d, const std::string& name, uint32_t set, uint32_t index,
               bool inPass);
    void end(const QuerySetDesc& d, const std::string& name, uint32_t set, uint32_t index,
             bool inPass);
    void timestamp(const QuerySetDesc& d, const std::string& name, uint32_t set, uint32_t index,
                   bool inPass);
    void resolve(const QuerySetDesc& d, const std::string& name, uint32_t set, uint32_t first,
                 uint32_t count);
    void endPass() const;  // a query begun in the pass must end in it
    void finish() const;   // submit: none left active, every timer ended
    void clear() { used_.clear(), active_ = {}, timers_.clear(), resolvedEarlier_.clear(); }
    const std::vector<Use>& used() const { return used_; }
    // Queries resolved here that this recording does not write: written by an earlier list of
    // the submission or an earlier submission (checked at submit by querySubmission).
    const std::vector<Use>& resolvedEarlier() const { return resolvedEarlier_; }
    // Timers (Device::createTimer): each begun once and then ended once per recording.
    void beginTimer(uint32_t timer);
    void endTimer(uint32_t timer);
    const std::vector<std::pair<uint32_t, bool>>& timers() const { return timers_; }  // (id, ended)

private:
    void written(const QuerySetDesc& d, const std::string& name, uint32_t set, uint32_t index,
                 const char* what);
    struct Active {
        uint32_t set = 0, index = 0;
        bool inPass = false;
    };
    std::array<std::optional<Active>, 3> active_;  // per type that begins and ends
    std::vector<Use> used_;
    std::vector<Use> resolvedEarlier_;
    std::vector<std::pair<uint32_t, bool>> timers_;
};
// submit: no query written by two of the lists (each is reset once, before the submission), and
// every query a list resolves without writing it written by an earlier list of the submission
// or, when no list of it writes the query, by an earlier submission (writtenBefore(set, index)).
// Otherwise the GPU would wait for a result that never comes, or read one the reset erased.
void querySubmission(std::span<const QueryRecording* const> lists,
                     const std::function<bool(uint32_t set, uint32_t index)>& writtenBefore);

// Bytes of the uniform or storage block each slot's shaders declare (the largest over the stages;
// a runtime-sized array counted as empty; 0: no block there).
std::array<uint32_t, 64> slotBlockBytes(const std::vector<const ShaderInterface*>& shaders);
// Validation mode: a range bound at `slot` smaller than the block the pipeline declares there.
// Vulkan allows it while the shader reads no further, so it is a warning, not an Error: printed
// once per message on stderr ("fe validation warning: ..."), counted in warningCount().
[[gnu::cold]] void rangeSmallerThanBlock(uint32_t slot, uint64_t bound, uint32_t declared,
                                         const std::string& pipeline);
inline void rangeCoversBlock(uint32_t slot, uint64_t bound, uint32_t declared,
                             const std::string& pipeline) {
    if (bound < declared) [[unlikely]]
        rangeSmallerThanBlock(slot, bound, declared, pipeline);
}
// Warnings reported in this process (each time, repeats included).
uint64_t warningCount();

// A graphics pipeline's shaders in stage order: vertex, tessellation control and evaluation,
// geometry, fragment (those given). `kind` names the handle in lookups ("geometry shader").
struct PipelineStage {
    ShaderStage stage;
    ShaderHandle shader;
    const char* field;  // GraphicsPipelineDesc's member, for messages
    const char* kind;
};
std::vector<PipelineStage> graphicsStages(const GraphicsPipelineDesc& d);
// The shader given for a stage is of that stage ("geometryShader is not a geometry shader").
void shaderOfStage(ShaderStage actual, const PipelineStage& s, const std::string& pipeline);
// Each stage's inputs are outputs of the stage before it (same location, scalar kind, at least
// as many components, per-patch or not alike); `shaders` in stage order. Built-ins are left to
// the APIs. A mismatch is undefined values on both APIs (or a link error on some drivers).
void stageInterfaces(const std::vector<const ShaderInterface*>& shaders,
                     const std::string& pipeline);

// Bytes of per-draw constants the pipeline's shaders read (the largest block; 0: none), at
// most kMaxConstantBytes.
uint32_t pipelineConstants(const std::vector<const ShaderInterface*>& shaders,
                           const std::string& pipeline);
// setConstants: offset and size multiples of 4, not empty, within kMaxConstantBytes.
[[noreturn, gnu::cold]] void badConstantsRange(uint32_t offset, size_t size);
inline void constantsRange(uint32_t offset, size_t size) {
    if ((offset | size) & 3 || size == 0 || offset + size > kMaxConstantBytes) [[unlikely]]
        badConstantsRange(offset, size);
}
// Specialization constants given to a pipeline: each id declared by one of its shaders, once,
// with a value of that constant's kind.
void specialization(const std::vector<SpecializationConstant>& values,
                    const std::vector<const ShaderInterface*>& shaders,
                    const std::string& pipeline);
// The attachments a graphics pipeline renders to (formats, depth format, samples).
PassSignature pipelineSignature(const GraphicsPipelineDesc& d);
// setPipeline in a pass: the pipeline's attachment formats and sample count are the pass's.
void pipelineFitsPass(const PassSignature& pipeline, const PassSignature& pass,
                      const char* pipelineName);
// setTexture: a sampler that filters linearly needs a format that can be (FormatCaps).
inline bool filtersLinearly(const SamplerDesc& d) {
    return !d.compareEnable && (d.minFilter == Filter::Linear || d.magFilter == Filter::Linear ||
                                d.mipFilter == MipFilter::Linear);
}
[[noreturn]] void notFilterable(const std::string& texture, Format format,
                                const std::string& sampler);
// A buffer bound or copied as `usage` must have been created with it.
void bufferUsage(const BufferDesc& d, BufferUsage usage, const std::string& name, const char* what);
// clearBuffer: a range inside the buffer, offset and size multiples of 4 (size 0: to the end);
// returns the size to fill.
uint64_t clearRange(const BufferDesc& d, const std::string& name, uint64_t offset, uint64_t size);
// setDepthBias's values: finite, and a clamp only where the device has depthBiasClamp.
void depthBias(float constant, float slope, float clamp, const DeviceFeatures& features);
// A pipeline set in a pass must rasterize with the pass's sample count.
void pipelineSamples(uint32_t pipelineSamples, uint32_t passSamples, const char* pipelineName);
// Per-draw checks: inline fast paths, the message is built out of line only on failure.
[[noreturn]] void bufferRangeFailed(const BufferDesc& d, uint64_t offset, uint64_t size,
                                    const char* what);
inline void bufferRange(const BufferDesc& d, uint64_t offset, uint64_t size, const char* what) {
    if (offset > d.size || size > d.size - offset) [[unlikely]]
        bufferRangeFailed(d, offset, size, what);
}

// Vertex input, checked at every draw the same way on every backend: each vertex buffer the
// pipeline's layout names is bound, a non-indexed draw's vertices and every draw's instances
// lie inside those buffers, and an indexed draw's indices inside the index buffer (bound at an
// offset aligned to its index size). Indexed draws read vertices the GPU chooses; those are not
// checked. A list keeps one VertexInputs; the fast path is two comparisons per draw.
inline constexpr uint32_t kMaxVertexBuffers = 16;
struct VertexBinding {
    uint32_t stride = 0;  // 0: every vertex (instance) reads the same element
    uint32_t extent = 0;  // bytes one element's attributes reach (the last attribute's end)
    bool perInstance = false;
};
// The pipeline's vertex bindings (graphicsPipelineDesc checked them: at most kMaxVertexBuffers).
std::vector<VertexBinding> vertexBindings(const GraphicsPipelineDesc& d);
class VertexInputs {
public:
    // setVertexBuffer / setIndexBuffer: index below kMaxVertexBuffers, usage, offset in the buffer
    // (and, for indices, a multiple of the index size).
    void setVertexBuffer(uint32_t index, const BufferDesc& d, const std::string& name,
                         uint64_t offset);
    void setIndexBuffer(const BufferDesc& d, const std::string& name, IndexType type,
                        uint64_t offset);
    // The bound pipeline's bindings (null: none, or a compute pipeline).
    void setPipeline(const std::vector<VertexBinding>* bindings, const std::string* pipelineName);
    void clear();  // nothing bound (a new recording; after a pass of secondary lists)
    // Every buffer the pipeline reads is bound (folded into the lists' one per-draw state check).
    bool ready() const { return (required_ & ~bound_) == 0; }
    [[noreturn, gnu::cold]] void notReady(const char* what) const;
    void draw(uint32_t vertexCount, uint32_t instanceCount, uint32_t firstVertex,
              uint32_t firstInstance) const {
        if (uint64_t(firstVertex) + vertexCount > vertices_ ||
            uint64_t(firstInstance) + instanceCount > instances_) [[unlikely]]
            outside("draw", vertexCount, instanceCount, firstVertex, firstInstance);
    }
    void drawIndexed(uint32_t indexCount, uint32_t instanceCount, uint32_t firstIndex,
                     uint32_t firstInstance) const {
        if (uint64_t(firstIndex) + indexCount > indices_ ||
            uint64_t(firstInstance) + instanceCount > instances_) [[unlikely]]
            indexedOutside(indexCount, instanceCount, firstIndex, firstInstance);
    }
    // Indirect indexed draws: an index buffer bound at offset 0 (the records hold firstIndex).
    void indexedIndirect(const char* what) const;
    bool indexBound() const { return indexBound_; }
    // What a non-indexed draw may reach (first + count at most these), for a list's own fast path.
    uint64_t vertexCapacity() const { return vertices_; }
    uint64_t instanceCapacity() const { return instances_; }

private:
    [[noreturn, gnu::cold]] void outside(const char* what, uint32_t count, uint32_t instanceCount,
                                         uint32_t first, uint32_t firstInstance) const;
    [[noreturn, gnu::cold]] void indexedOutside(uint32_t count, uint32_t instanceCount,
                                                uint32_t first, uint32_t firstInstance) const;
    void update();  // the capacities below, from what is bound
    struct Bound {
        uint64_t available = 0;  // bytes from the bound offset to the buffer's end
        std::string name;
    };
    std::array<Bound, kMaxVertexBuffers> buffers_{};
    uint32_t bound_ = 0, required_ = 0;
    const std::vector<VertexBinding>* bindings_ = nullptr;
    const std::string* pipelineName_ = nullptr;
    uint64_t vertices_ = ~uint64_t(0),
             instances_ = ~uint64_t(0);  // elements every bound buffer holds
    bool indexBound_ = false;
    uint64_t indexOffset_ = 0, indices_ = 0;
    uint32_t indexBytes_ = 2;
    std::string indexName_;
};

// setBlendConstant and GraphicsPipelineDesc::blendConstant: finite values (NaN blends differently
// per driver).
inline void blendConstant(const float* rgba, const char* what) {
    for (int i = 0; i < 4; ++i)
        if (!(rgba[i] - rgba[i] == 0)) [[unlikely]]
            throw Error(std::string(what) + ": blend constant values must be finite");
}
// setViewport: finite, a positive width and height within the device's maxViewportSize, corners
// within its viewportBounds, depths within [0, 1]. Vulkan's negative height (the y flip of ports
// from GL) is refused on every backend: clip space already is Vulkan's, y down, so the
// projection flips y instead.
struct ViewportLimits {
    float maxSize = 0, lo = 0, hi = 0;  // DeviceLimits::maxViewportSize and viewportBounds
};
inline ViewportLimits viewportLimits(const DeviceLimits& l) {
    return {float(l.maxViewportSize), l.viewportBounds[0], l.viewportBounds[1]};
}
[[noreturn, gnu::cold]] void badViewport(const Viewport& v, const ViewportLimits& l);
inline void viewport(const Viewport& v, const ViewportLimits& l) {
    const bool ok = v.width > 0 && v.height > 0 && v.x - v.x == 0 && v.y - v.y == 0 &&
                    v.width - v.width == 0 && v.height - v.height == 0 && v.minDepth >= 0 &&
                    v.minDepth <= 1 && v.maxDepth >= 0 && v.maxDepth <= 1 && v.width <= l.maxSize &&
                    v.height <= l.maxSize && v.x >= l.lo && v.y >= l.lo && v.x + v.width <= l.hi &&
                    v.y + v.height <= l.hi;
    if (!ok) [[unlikely]]
        badViewport(v, l);
}
// setScissor: the part of the rectangle right of x = 0 and below y = 0, which both backends
// set (a rectangle partly outside the target clips it, as GL's does; Vulkan refuses negative
// offsets).
inline Rect scissor(const Rect& r) {
    Rect out = r;
    if (r.x < 0) out.x = 0, out.width = uint32_t(std::max<int64_t>(0, int64_t(r.width) + r.x));
    if (r.y < 0) out.y = 0, out.height = uint32_t(std::max<int64_t>(0, int64_t(r.height) + r.y));
    out.width = uint32_t(std::min<int64_t>(out.width, int64_t(INT32_MAX) - out.x));
    out.height = uint32_t(std::min<int64_t>(out.height, int64_t(INT32_MAX) - out.y));
    return out;
}
// dispatch: group counts within limits.maxComputeWorkGroupCount.
[[noreturn, gnu::cold]] void badDispatch(uint32_t x, uint32_t y, uint32_t z,
                                         const DeviceLimits& limits);
inline void dispatchSize(uint32_t x, uint32_t y, uint32_t z, const DeviceLimits& l) {
    if (x > l.maxComputeWorkGroupCount[0] || y > l.maxComputeWorkGroupCount[1] ||
        z > l.maxComputeWorkGroupCount[2]) [[unlikely]]
        badDispatch(x, y, z, l);
}
// copyBuffer: both ranges inside their buffers, and apart when the buffer is the same (Vulkan
// leaves overlapping copies undefined, GL refuses them).
void bufferCopy(const BufferDesc& dst, const std::string& dstName, uint64_t dstOffset,
                const BufferDesc& src, const std::string& srcName, uint64_t srcOffset,
                uint64_t size, bool sameBuffer);
// A call on a command list whose device was destroyed (LiveLists.h).
[[noreturn, gnu::cold]] void listOfDestroyedDevice(const char* what);
// barrier(pointer, count): count barriers need an array (a null one with count 0 is no barrier).
inline void barrierArray(const void* barriers, uint32_t count) {
    if (!barriers && count) [[unlikely]]
        throw Error("barrier: " + std::to_string(count) + " barrier(s) from a null pointer");
}
// wait / isComplete: a fence a submission returned (at most the last one issued).
[[noreturn, gnu::cold]] void fenceNotIssued(FenceValue fence, FenceValue last, const char* what);
inline void issuedFence(FenceValue fence, FenceValue last, const char* what) {
    if (fence > last) [[unlikely]]
        fenceNotIssued(fence, last, what);
}

// A range bound to a slot must also be non-empty (Vulkan and GL both reject zero-sized bindings).
[[noreturn]] void bindingRangeFailed(const BufferDesc& d, uint64_t offset, uint64_t size,
                                     const char* what);
inline void bindingRange(const BufferDesc& d, uint64_t offset, uint64_t size, const char* what) {
    if (offset >= d.size || size > d.size - offset || size == 0) [[unlikely]]
        bindingRangeFailed(d, offset, size, what);
}

// The per-object fast path's test, shared by the backends: slot below 64 and a non-empty range
// inside a buffer of bufferSize bytes (size 0: to the end). Returns the size to bind, or 0 when
// the arguments need the checked path (which gives the error, if any).
// `limits` is the device's rule for the binding's kind: the offset a multiple of its alignment
// and the range at most its maximum; size 0 binds to the end, at most that maximum.
struct BindingLimits {
    uint64_t alignMask = 0;  // offset alignment - 1 (alignments are powers of two)
    uint64_t maxRange = ~uint64_t(0);
    const char* alignmentName = "";  // for messages: "uniformBufferOffsetAlignment"
    const char* rangeName = "";
};
BindingLimits uniformBindingLimits(const DeviceLimits& l);
BindingLimits storageBindingLimits(const DeviceLimits& l);
inline uint64_t plainBindingSize(uint32_t slot, uint64_t bufferSize, uint64_t offset, uint64_t size,
                                 const BindingLimits& limits) {
    if (slot >= 64 || offset >= bufferSize || (offset & limits.alignMask)) return 0;
    const uint64_t rest = bufferSize - offset;
    if (size == 0) return rest < limits.maxRange ? rest : limits.maxRange;
    return size <= rest && size <= limits.maxRange ? size : 0;
}
// The checked path's rules (after bindingRange): alignment and maximum range, or throws.
void bindingLimits(uint64_t offset, uint64_t size, const BindingLimits& limits, const char* what);

// Bit set of slots a pipeline declares; draw/dispatch checks every declared slot is bound.
uint64_t requiredSlotMask(const std::vector<BindingSlot>& bindings);
[[noreturn]] void missingBindingsFailed(uint64_t missing, const char* pipelineName);
inline void missingBindings(uint64_t required, uint64_t bound, const char* pipelineName) {
    if (const uint64_t missing = required & ~bound) [[unlikely]]
        missingBindingsFailed(missing, pipelineName);
}
// A slot bound with another kind of resource than the pipeline declares for it.
[[noreturn]] void wrongBindingKindFailed(uint32_t slot, BindingType expected, BindingType bound,
                                         const char* pipelineName);
// Per-slot declared kind, 1 + BindingType (0: the pipeline does not use the slot).
std::array<uint8_t, 64> slotKinds(const std::vector<BindingSlot>& bindings);
// Per-slot texture kind the shaders sample or store, 1 + TextureDimension (0: any; a buffer
// slot, or one no shader uses). Stages that declare one slot with two kinds are an Error. A
// texture bound there must be of that kind (a view may give it another: createTextureView).
std::array<uint8_t, 64> slotDimensions(const std::vector<const ShaderInterface*>& shaders,
                                       const std::string& pipeline);
[[noreturn, gnu::cold]] void wrongTextureDimensionFailed(uint32_t slot, uint8_t expected,
                                                         uint8_t bound, const char* pipelineName);

// A barrier's subresources, resolved: mips [baseMip, baseMip + mipCount), layers likewise
// (array layers and cube faces; a 3D texture has one). Throws for an empty or outside range,
// or `after` Undefined, or a state the texture's usage does not allow (RenderTarget and
// DepthTarget need RenderTarget usage and a colour or depth format, ShaderRead Sampled or
// Storage, Storage Storage; the copy states any usage, as device transfers copy any texture).
struct SubresourceRange {
    uint32_t baseMip = 0, mipCount = 1, baseLayer = 0, layerCount = 1;
    bool whole = true;  // every mip and layer of the texture
};
SubresourceRange textureBarrier(const TextureDesc& d, const TextureBarrier& b,
                                const std::string& name);
// A buffer barrier's range, resolved (size 0: to the end); throws when outside the buffer or
// when an access needs a usage the buffer lacks (Vertex, Index, Indirect, Uniform; StorageRead
// and StorageWrite need Storage; the copy accesses any usage).
uint64_t bufferBarrier(const BufferDesc& d, const BufferBarrier& b, const std::string& name);
// map(): Upload and Readback buffers only.
void mappable(const BufferDesc& d, const std::string& name);
// submit(lists): no list twice, none null.
void submittedLists(std::span<CommandList* const> lists);
// Queues (Device.h): a list made for `list` records `what`, which needs a queue that can run
// `needs` (Graphics > Compute > Copy). Inline: dispatches check it.
[[noreturn]] void wrongQueue(QueueKind list, QueueKind needs, const char* what);
inline void queueAllows(QueueKind list, QueueKind needs, const char* what) {
    if (uint8_t(list) > uint8_t(needs)) [[unlikely]]
        wrongQueue(list, needs, what);
}
// submit(lists, desc): the queue they go to (all lists of one queue; none: graphics), and
// desc.waitFor issued (at most `lastIssued`).
QueueKind submissionQueue(std::span<CommandList* const> lists, const SubmitDesc& desc,
                          FenceValue lastIssued);
// executeSecondary(lists) on a backend's List `self`: the array checked as submit's is, each a
// List (else "belongs to another device") other than `self`, then `check(list, index)` (the
// backend's own: same device, executable here). Returns the lists as the backend's type.
[[noreturn]] void secondaryOfAnotherDevice(size_t index);
template <class List, class Check>
std::vector<List*> executedLists(std::span<CommandList* const> lists, const List* self,
                                 Check&& check) {
    submittedLists(lists);
    std::vector<List*> parts;
    parts.reserve(lists.size());
    for (size_t i = 0; i < lists.size(); ++i) {
        auto* l = dynamic_cast<List*>(lists[i]);
        if (!l) secondaryOfAnotherDevice(i);
        if (l == self) throw Error("executeSecondary: a list cannot execute itself");
        check(*l, i);
        parts.push_back(l);
    }
    return parts;
}
// destroy() of a handle that is not live (destroyed already, or made by another device).
[[noreturn]] void destroyedHandle(const char* kind, uint32_t id);
// Dynamic state (viewport, scissor, blend constant, stencil reference, depth bias) is set
// inside a render pass: each pass starts from its pipeline's values.
[[noreturn]] void stateOutsidePass(const char* what);
// A call only allowed outside a render pass (copies, barriers, compute, queries' resolve, ...)
// made inside one.
[[noreturn]] void insidePass(const char* what);
// Submitting a list that uses an object destroyed after it was recorded.
[[noreturn]] void destroyedBeforeSubmit(const char* kind, uint32_t id);

}  // namespace fe::gdi::validate

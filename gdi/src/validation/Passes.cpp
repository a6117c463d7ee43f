// Shared validation: Render passes: attachments, the pass signature pipelines and secondary lists must match,
// rendering feedback loops, and the rules of secondary lists.
#include "ValidationSupport.h"

namespace fe::gdi::validate {

namespace {

std::string signatureText(const PassSignature& s) {
    std::string t;
    for (uint32_t i = 0; i < s.colorCount; ++i)
        t += std::string(i ? ", " : "") + std::string(formatInfo(s.colors[i]).name);
    if (s.depth != Format::Undefined)
        t += std::string(t.empty() ? "" : ", ") + "depth " + std::string(formatInfo(s.depth).name);
    return t + "; " + std::to_string(s.samples) + " sample(s); " + std::to_string(s.width) + "x" +
           std::to_string(s.height);
}

}  // namespace

AttachmentInfo attachment(const TextureDesc& d, uint32_t mipLevel, uint32_t layer, const char* what,
                          const std::string& name) {
    subresource(d, {mipLevel, layer}, what, name);
    const Extent3 e = mipExtent(d, mipLevel);
    return {d.format, e.width, e.height, d.usage, d.sampleCount};
}

Rect renderPass(const RenderPassDesc& d, const std::vector<AttachmentInfo>& colors,
                const std::vector<AttachmentInfo>& colorResolves, const AttachmentInfo* depth,
                const AttachmentInfo* depthResolve, const DeviceLimits& limits) {
    const std::string what = label("render pass", d.debugName);
    if (colors.empty() && !depth) fail(what, "no attachments");
    if (limits.maxColorAttachments && colors.size() > limits.maxColorAttachments)
        fail(what, std::to_string(colors.size()) + " colour attachments exceed the device limit");
    uint32_t w = 0, h = 0, samples = 0;
    auto check = [&](const AttachmentInfo& a, const std::string& name, LoadOp load, StoreOp store) {
        if (!any(a.usage, TextureUsage::RenderTarget))
            fail(what, name + " texture lacks RenderTarget usage");
        if (any(a.usage, TextureUsage::Transient) &&
            (load == LoadOp::Load || store == StoreOp::Store))
            fail(what, name +
                           " is Transient: it is loaded by Clear or DontCare and stored "
                           "DontCare (its contents live inside the pass)");
        if (w == 0 && h == 0) {
            w = a.width;
            h = a.height;
            samples = a.samples;
        } else if (a.width != w || a.height != h)
            fail(what, "mismatched attachments: " + name + " is " + std::to_string(a.width) + "x" +
                           std::to_string(a.height) + ", others are " + std::to_string(w) + "x" +
                           std::to_string(h));
        else if (a.samples != samples)
            fail(what, "mismatched sample counts: " + name + " has " + std::to_string(a.samples) +
                           ", others " + std::to_string(samples));
    };
    auto checkResolve = [&](const AttachmentInfo& src, const AttachmentInfo& dst,
                            const std::string& name) {
        if (src.samples == 1) fail(what, name + " is single-sample: nothing to resolve");
        if (dst.samples != 1) fail(what, name + " resolve target must be single-sample");
        if (dst.format != src.format)
            fail(what, name + " resolve target format " + std::string(formatInfo(dst.format).name) +
                           " differs from " + std::string(formatInfo(src.format).name));
        if (dst.width != src.width || dst.height != src.height)
            fail(what, name + " resolve target size differs");
        if (!any(dst.usage, TextureUsage::RenderTarget))
            fail(what, name + " resolve target lacks RenderTarget usage");
        if (any(dst.usage, TextureUsage::Transient))
            fail(what, name + " resolve target is Transient: a resolve stores what it writes");
    };
    for (size_t i = 0; i < colors.size(); ++i) {
        const std::string name = "colour attachment " + std::to_string(i);
        if (isDepthFormat(colors[i].format)) fail(what, name + " has a depth format");
        const ColorAttachment a = i < d.colors.size() ? d.colors[i] : ColorAttachment{};
        check(colors[i], name, a.load, a.store);
        // NaN or infinity converts to a format's values differently per driver (and a unorm
        // target has no such value): a clear colour is finite.
        if (i < d.colors.size() && d.colors[i].load == LoadOp::Clear)
            for (float c : d.colors[i].clear)
                if (!std::isfinite(c)) fail(what, name + ": clear colour is not finite");
        if (i < colorResolves.size() && colorResolves[i].format != Format::Undefined)
            checkResolve(colors[i], colorResolves[i], name);
    }
    if (depth) {
        if (!isDepthFormat(depth->format))
            fail(what, "depth attachment has colour format " +
                           std::string(formatInfo(depth->format).name));
        check(*depth, "depth attachment", d.depth.load, d.depth.store);
        const float z = d.depth.clearDepth;  // Vulkan's VkClearDepthStencilValue rule
        if (d.depth.load == LoadOp::Clear && !(z >= 0.0f && z <= 1.0f))
            fail(what, "depth attachment: clearDepth " + std::to_string(z) + " is not in [0, 1]");
        if (depthResolve) checkResolve(*depth, *depthResolve, "depth attachment");
    }
    return Rect{0, 0, w, h};
}

void pipelineSamples(uint32_t pipelineSamples, uint32_t passSamples, const char* pipelineName) {
    if (pipelineSamples != passSamples) [[unlikely]]
        fail(label("setPipeline: pipeline", pipelineName),
             "rasterizes " + std::to_string(pipelineSamples) +
                 " sample(s) but the render pass has " + std::to_string(passSamples));
}

PassSignature passSignature(const std::vector<AttachmentInfo>& colors, const AttachmentInfo* depth,
                            Rect area) {
    PassSignature s;
    s.colorCount = uint32_t(std::min(colors.size(), s.colors.size()));
    for (uint32_t i = 0; i < s.colorCount; ++i) s.colors[i] = colors[i].format;
    if (depth) s.depth = depth->format;
    s.samples = colors.empty() ? (depth ? depth->samples : 1) : colors[0].samples;
    s.width = area.width;
    s.height = area.height;
    return s;
}

void secondaryNotEmpty() {
    throw Error(
        "beginSecondary: the list must be empty (a secondary list records one pass's draws from its start)");
}

void afterEndSecondary(const char* what) {
    throw Error(std::string(what) +
                " after endSecondary (the list is executed as it is; beginSecondary records it "
                "anew)");
}

void notInSecondary(const char* what) {
    throw Error(std::string(what) + " is not allowed in a secondary list");
}

void submittedSecondary() {
    throw Error(
        "submit: a secondary list is executed by a primary list (executeSecondary), not submitted");
}

void executedSecondary(bool inSecondaryPass, bool isSecondary, bool ended,
                       const PassSignature& list, const PassSignature& pass, size_t index) {
    const std::string what = "executeSecondary: list " + std::to_string(index);
    if (!inSecondaryPass)
        throw Error(
            "executeSecondary outside a render pass begun with secondaryLists (RenderPassDesc::secondaryLists)");
    if (!isSecondary)
        throw Error(what +
                    " is not a secondary list (record it between beginSecondary and endSecondary)");
    if (!ended) throw Error(what + " is still recording (missing endSecondary)");
    if (!(list == pass))
        throw Error(what + " was begun for another pass (" + signatureText(list) +
                    ") than the open one (" + signatureText(pass) + ")");
}

void pipelineFitsPass(const PassSignature& p, const PassSignature& pass, const char* pipelineName) {
    if (p.samples != pass.samples) pipelineSamples(p.samples, pass.samples, pipelineName);
    auto formats = [](const PassSignature& s) {
        std::string t = "colour [";
        for (uint32_t i = 0; i < s.colorCount; ++i)
            t += std::string(i ? ", " : "") + std::string(formatInfo(s.colors[i]).name);
        return t + "], depth " +
               (s.depth == Format::Undefined ? std::string("none")
                                             : std::string(formatInfo(s.depth).name));
    };
    bool same = p.colorCount == pass.colorCount && p.depth == pass.depth;
    for (uint32_t i = 0; same && i < p.colorCount; ++i) same = p.colors[i] == pass.colors[i];
    if (!same)
        fail(label("setPipeline: pipeline", pipelineName),
             "renders to " + formats(p) + " but the render pass has " + formats(pass));
}

void stateOutsidePass(const char* what) {
    throw Error(std::string(what) +
                " outside a render pass (each pass starts from its pipelines' state: set it "
                "after beginRenderPass, where it stays across setPipeline)");
}

void insidePass(const char* what) {
    throw Error(std::string(what) + " is not allowed inside a render pass");
}

TextureSpan bindingSpan(uint32_t id, uint32_t viewOf, uint32_t baseMip, uint32_t baseLayer,
                        const TextureDesc& view, std::optional<uint32_t> oneMip) {
    TextureSpan s{.texture = viewOf ? viewOf : id,
                  .baseMip = baseMip,
                  .mipCount = view.mipLevels,
                  .baseLayer = baseLayer,
                  .layerCount = view.depthOrLayers};
    if (view.dimension == TextureDimension::Texture3D)
        s.baseLayer = 0, s.layerCount = UINT32_MAX;  // every slice
    if (oneMip) s.baseMip += *oneMip, s.mipCount = 1;
    return s;
}

void PassAttachments::add(const TextureSpan& whole, uint32_t mip, uint32_t layer, uint8_t role,
                          const char* passName) {
    if (count_ == 0) passName_ = passName ? passName : "";
    const TextureSpan a{.texture = whole.texture,
                        .baseMip = whole.baseMip + mip,
                        .mipCount = 1,
                        .baseLayer = whole.baseLayer + layer,
                        .layerCount = 1};
    for (uint32_t i = 0; i < count_; ++i) {
        if (!reaches(a, at_[i])) continue;
        const std::string why =
            roleName(roles_[i]) + " and " + roleName(role) + " are the same subresource (" +
            label("texture", names_[i].c_str()) + ", mip " + std::to_string(a.baseMip) +
            ", layer " + std::to_string(a.baseLayer) + "): each attachment needs its own";
        count_ =
            0;  // the pass does not begin: nothing may be checked against its half-read attachments
        fail(label("render pass", passName), why);
    }
    at_[count_] = a;
    kinds_[count_] = role == kDepthRole ? kDepth : kColour;
    roles_[count_] = role;
    names_[count_].assign(whole.name);
    ++count_;
}

std::string PassAttachments::roleName(uint8_t role) {
    if (role < 8) return "colour attachment " + std::to_string(role);
    if (role < 16) return "colour attachment " + std::to_string(role - 8) + "'s resolve target";
    return role == kDepthRole ? "the depth attachment" : "the depth resolve target";
}

void PassAttachments::failed(uint32_t slot, const TextureSpan& s, bool storage,
                             const char* pipelineName) const {
    uint32_t i = 0;
    while (i + 1 < count_ && !reaches(s, at_[i])) ++i;
    const std::string how = storage ? " stores to " : " samples ";
    fail(
        label("draw with pipeline", pipelineName),
        "slot " + std::to_string(slot) + how + label("texture", names_[i].c_str()) + " (mip " +
            std::to_string(at_[i].baseMip) + ", layer " + std::to_string(at_[i].baseLayer) +
            "), which " + roleName(roles_[i]) + " of " + label("render pass", passName_.c_str()) +
            " writes: a feedback loop, undefined on every API. Read another mip or layer, or a copy" +
            (roles_[i] == kDepthRole
                 ? " (a pipeline that writes neither depth nor stencil may sample the depth attachment)"
                 : ""));
}

void FeedbackLoops::check(uint32_t slot, bool pipelineWritesDepthStencil,
                          const char* pipelineName) const {
    if (refused(slot, pipelineWritesDepthStencil))
        pass_.failed(slot, slots_[slot], storage_ & bit(slot), pipelineName);
}

}  // namespace fe::gdi::validate

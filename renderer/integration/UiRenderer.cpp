#include "integration/UiRenderer.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "fe/gdi/ShaderRegistry.h"

namespace fe::render {

namespace {
constexpr uint32_t kSlotUi = 0, kSlotAtlas = 1;
static_assert(sizeof(ImDrawIdx) == 2, "the UI renderer binds 16-bit indices");
static_assert(sizeof(ImDrawVert) == 20, "ImDrawVert is pos, uv, colour");
}  // namespace

UiRenderer::UiRenderer(gdi::Device& device, gdi::Format targetFormat)
    : objects_(device), device_(device), format_(targetFormat), queue_(device, 2, 1u << 20) {
    if (!ImGui::GetCurrentContext())
        throw gdi::Error("UiRenderer: no ImGui context (ImGui::CreateContext first)");
    ImGuiIO& io = ImGui::GetIO();
    io.BackendRendererName = "fe::render::UiRenderer";
    io.BackendFlags |= ImGuiBackendFlags_RendererHasVtxOffset;
    unsigned char* pixels = nullptr;
    int w = 0, h = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
    font_ = objects_.add(device.createTexture({.format = gdi::Format::RGBA8,
                                               .width = uint32_t(w),
                                               .height = uint32_t(h),
                                               .usage = gdi::TextureUsage::Sampled,
                                               .debugName = "ui font atlas"}));
    device.writeTexture(
        font_, {},
        gdi::ByteSpan(reinterpret_cast<const std::byte*>(pixels), size_t(w) * size_t(h) * 4));
    sampler_ = objects_.add(device.createSampler(
        {.addressU = gdi::AddressMode::ClampToEdge, .addressV = gdi::AddressMode::ClampToEdge}));
    vs_ = objects_.add(device.createShader(
        {.stage = gdi::ShaderStage::Vertex, .binary = shaders::find("scene/ui.vert")}));
    fs_ = objects_.add(device.createShader(
        {.stage = gdi::ShaderStage::Fragment, .binary = shaders::find("scene/ui.frag")}));
    pipeline_ = objects_.add(device.createGraphicsPipeline(
        {.vertexShader = vs_,
         .fragmentShader = fs_,
         .vertexBuffers =
             {{.stride = sizeof(ImDrawVert),
               .attributes = {{0, gdi::VertexFormat::Float2, offsetof(ImDrawVert, pos)},
                              {1, gdi::VertexFormat::Float2, offsetof(ImDrawVert, uv)},
                              {2, gdi::VertexFormat::UNorm8x4, offsetof(ImDrawVert, col)}}}},
         .blend = {{.enable = true,
                    .srcColor = gdi::BlendFactor::SrcAlpha,
                    .dstColor = gdi::BlendFactor::OneMinusSrcAlpha,
                    .srcAlpha = gdi::BlendFactor::One,
                    .dstAlpha = gdi::BlendFactor::OneMinusSrcAlpha}},
         .colorFormats = {targetFormat},
         .debugName = "ui"}));
    io.Fonts->SetTexID(
        textureId(font_));  // last: should anything above throw, ImGui names no freed texture
}

UiRenderer::~UiRenderer() {
    device_.waitIdleOrLost();  // a destructor must not throw, and a lost device runs nothing more
    if (ImGui::GetCurrentContext()) ImGui::GetIO().Fonts->SetTexID(nullptr);
}

void* UiRenderer::textureId(gdi::TextureHandle texture) {
    return reinterpret_cast<void*>(uintptr_t(texture.id));
}

void UiRenderer::render(const ImDrawData& data, gdi::TextureHandle target) {
    const gdi::TextureDesc& desc = device_.desc(target);
    if (desc.format != format_)
        throw gdi::Error(
            "UiRenderer: target format differs from the one the renderer was made for");
    gdi::CommandList& cmd = queue_.beginFrame();
    cmd.beginRenderPass({.colors = {{.texture = target, .load = gdi::LoadOp::Load}}});
    const float sx = 2.0f / data.DisplaySize.x, sy = 2.0f / data.DisplaySize.y;
    struct {
        float scaleTranslate[4];
    } constants{{sx, sy, -1.0f - data.DisplayPos.x * sx, -1.0f - data.DisplayPos.y * sy}};
    const UploadAllocation ui = queue_.upload(constants);
    cmd.setPipeline(pipeline_);
    cmd.setUniformBuffer(kSlotUi, ui.buffer, ui.offset, ui.size);
    for (int n = 0; n < data.CmdListsCount; ++n) {
        const ImDrawList& list = *data.CmdLists[n];
        if (list.VtxBuffer.Size == 0 || list.IdxBuffer.Size == 0) continue;
        const UploadAllocation v =
            queue_.upload(gdi::ByteSpan(reinterpret_cast<const std::byte*>(list.VtxBuffer.Data),
                                        size_t(list.VtxBuffer.Size) * sizeof(ImDrawVert)));
        const UploadAllocation i =
            queue_.upload(gdi::ByteSpan(reinterpret_cast<const std::byte*>(list.IdxBuffer.Data),
                                        size_t(list.IdxBuffer.Size) * sizeof(ImDrawIdx)));
        cmd.setVertexBuffer(0, v.buffer, v.offset);
        cmd.setIndexBuffer(i.buffer, gdi::IndexType::U16, i.offset);
        for (const ImDrawCmd& dc : list.CmdBuffer) {
            if (dc.UserCallback) continue;  // the engine's UIs register none
            // The clip rectangle in framebuffer pixels, clamped to the target.
            const float x0 = std::max(0.0f, dc.ClipRect.x - data.DisplayPos.x);
            const float y0 = std::max(0.0f, dc.ClipRect.y - data.DisplayPos.y);
            const float x1 = std::min(float(desc.width), dc.ClipRect.z - data.DisplayPos.x);
            const float y1 = std::min(float(desc.height), dc.ClipRect.w - data.DisplayPos.y);
            if (x1 <= x0 || y1 <= y0) continue;
            cmd.setScissor({int32_t(x0), int32_t(y0), uint32_t(std::ceil(x1) - int32_t(x0)),
                            uint32_t(std::ceil(y1) - int32_t(y0))});
            cmd.setTexture(kSlotAtlas,
                           gdi::TextureHandle{uint32_t(reinterpret_cast<uintptr_t>(dc.GetTexID()))},
                           sampler_);
            cmd.drawIndexed(dc.ElemCount, 1, dc.IdxOffset, int32_t(dc.VtxOffset));
        }
    }
    cmd.endRenderPass();
    queue_.endFrame();
}

}  // namespace fe::render

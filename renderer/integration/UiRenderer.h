// Layer 8 (Integration): the UI renderer. Dear ImGui's draw lists (libimgui-dev) drawn through
// the engine's own pipeline on the abstract device, not through ImGui's native backends, so the
// same UI runs on every backend, windowed and headless. The application owns the ImGui context
// and builds the UI; this draws ImGui::GetDrawData() over a texture (usually the display image).
#pragma once
#include <memory>

#include "fe/gdi/Device.h"
#include "fe/gdi/DeviceObjects.h"
#include "frame/CommandQueue.h"

struct ImDrawData;

namespace fe::render {

class UiRenderer {
public:
    // Uploads the current ImGui context's font atlas; `targetFormat` is what render() draws into
    // (RGBA8_SRGB: colours are decoded from sRGB so the target's encoding restores them).
    UiRenderer(gdi::Device& device, gdi::Format targetFormat = gdi::Format::RGBA8_SRGB);
    ~UiRenderer();
    UiRenderer(const UiRenderer&) = delete;
    UiRenderer& operator=(const UiRenderer&) = delete;

    // Draws `data` over `target`, keeping its contents; submitted on the device's queue after
    // whatever was submitted before (e.g. the frame the UI overlays).
    void render(const ImDrawData& data, gdi::TextureHandle target);
    // An ImTextureID for ImGui::Image: any sampled 2D texture of the device.
    static void* textureId(gdi::TextureHandle texture);

private:
    gdi::DeviceObjects objects_;
    gdi::Device& device_;
    gdi::Format format_;
    CommandQueue queue_;
    gdi::TextureHandle font_;
    gdi::SamplerHandle sampler_;
    gdi::ShaderHandle vs_, fs_;
    gdi::PipelineHandle pipeline_;
};

}  // namespace fe::render

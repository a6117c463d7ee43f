// Layer 7: what a frame shows where no surface is (RenderSettings::Background), as one render
// graph pass on L_o and the scene depth after the technique's opaque passes:
//   environment: the environment map drawn at the far plane (EnvironmentMap::drawBackground);
//   colour or transparent: L_o's alpha becomes the coverage, 0 where the depth is 1 (and no
//   radiance there) and 1 where a surface was drawn (its radiance kept: only alpha is written), so the
//   translucent passes that follow blend "over" it and the display pass composites the result
//   over the colour or writes it with its alpha (fe_display_pass.glsl).
#pragma once
#include "fe/gdi/Device.h"
#include "fe/gdi/DeviceObjects.h"
#include "frame/CommandQueue.h"
#include "graph/RenderGraph.h"
#include "render/EnvironmentMap.h"
#include "render/RenderSettings.h"

namespace fe::render {

// The background a frame gets: Auto resolved against whether the scene has an environment.
// Throws gdi::Error for Environment without one.
Background::Kind resolveBackground(const Background& background, bool sceneHasEnvironment);

class BackgroundPass {
public:
    // `environment` is the scene's (null without one); read when the pass executes.
    BackgroundPass(gdi::Device& device, CommandQueue& queue, const RenderSettings& settings,
                   const EnvironmentMap* environment, const UploadAllocation& frameConstants);
    BackgroundPass(const BackgroundPass&) = delete;
    BackgroundPass& operator=(const BackgroundPass&) = delete;

    Background::Kind kind() const { return kind_; }
    // Declares the "background" pass (none for a black background under Auto without an
    // environment: what the technique cleared to is shown).
    void declare(graph::RenderGraph& graph, graph::TextureId radiance, graph::TextureId depth);
    // FrameConstants::shading.y and .z (fe_display_pass.glsl): 0 none, 1 colour, 2 transparent;
    // the colour as sRGB RGBA8.
    glm::uvec2 displayConstants() const;

private:
    gdi::DeviceObjects objects_;
    CommandQueue& queue_;
    const RenderSettings& settings_;
    const EnvironmentMap* environment_;
    const UploadAllocation& frameConstants_;
    Background::Kind kind_;
    gdi::ShaderHandle vs_, fs_;
    gdi::PipelineHandle uncovered_,
        covered_;  // colour or transparent: depth 1 / a surface's pixels
};

}  // namespace fe::render

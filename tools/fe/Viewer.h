// fe view: the interactive viewer. A window on either API (vulkan-glfw, gl-glfw), a scene drawn
// by any technique, and a Dear ImGui panel drawn by the engine's UiRenderer: the technique and
// its options, environment, shadows, tone mapping and antialiasing switched live; the backend
// switched by restarting the device in place; frame and per-pass GPU times; debug views of the
// frame's intermediate textures; a screenshot key.
#pragma once
#include <optional>
#include <string>

#include "Cli.h"

namespace fe::tools {

struct ViewerOptions {
    // The look, from fe render's options in fe render's units (cli::renderJob): technique,
    // environment, image-based light, shadows, tone mapping, antialiasing, exposure, ...; its
    // applyScene lights the scene as fe render would. Unset: the defaults below.
    std::optional<cli::RenderJob> look;
    std::string scene = "builtin:spheres";
    // No scene named: the quick start's image, lit by its environment through the fast path
    // (prefiltered: interactive on a CPU rasterizer) with shadows on.
    bool quickStartLighting = false;
    std::string backend = "auto";  // auto | vulkan | gl | vulkan-glfw | gl-glfw
    std::string technique = "deferred-tiled";
    std::string environment;  // "", builtin:sky or an .hdr
    uint32_t width = 640, height = 480;
    uint32_t frames = 0;      // 0: until the window is closed
    std::string screenshot;   // written after the last frame (PNG); F12 writes fe-view-NNN.png
    bool validation = false;  // Khronos layer / GL debug output on; an error fails the run (tests)
    bool ui = true;           // the panel (false: the scene alone, e.g. to compare)
    std::string debugView;    // a texture of the frame's graph to show instead of L_o
    std::string animation;    // index or name: played from the start (default: the first, if any)
    std::string camera;       // index or name of the file's camera to look through (default: orbit)
    // Tests: input as if typed or dropped at a frame (from 0), "FRAME:KEY" (Esc, F12, F1, R, F)
    // or "FRAME:drop=PATH", comma-separated: the keys' and drops' handling without a person.
    std::string inputScript;
    // A fragment shader over the displayed image, recompiled when its file changes (PostShader.h).
    std::string postShader;
    uint32_t switchBackendAt =
        0;  // tests: at this frame, switch to the other API as the panel does
};

// Runs the viewer; returns the process exit code. Throws gdi::Error / AssetError on failure.
int runViewer(const ViewerOptions& options);

}  // namespace fe::tools

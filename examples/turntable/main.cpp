// Example (b): a glTF model turning, lit and textured, with a UI panel, written once against the
// engine (fe::renderer, fe::ui) and run unchanged on every backend: the backend is only a startup
// argument. The panel (Dear ImGui drawn by the engine's UiRenderer) shows the frame time and
// lets a window user pause the turn and change its speed; headless there is no one to use it, so
// the image is the model alone.
//   fe_example_turntable [MODEL.gltf|.glb|builtin:NAME] [--backend NAME] [--technique NAME]
//                        [--frames N] [--size WxH] [--out FILE.png] [--window] [--validation]
// Headless it renders N frames (default 24) of one turn about the model and writes the last;
// with --window it shows the turn until the window is closed, or for --frames N. A model with
// animations (Fox.glb, builtin:crowd) plays its first one meanwhile, at 30 frames a second:
// assets::poseScene moves the scene, SceneRenderer::updatePose shows it (skins and morph
// targets are deformed on the device).
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "assets/Animation.h"
#include "assets/AssetError.h"
#include "assets/BuiltinScenes.h"
#include "fe/gdi/Backend.h"
#include "integration/SceneRenderer.h"
#include "integration/UiRenderer.h"

#include <imgui.h>
#include <chrono>

using namespace fe;

int main(int argc, char** argv) {
    // A program rendering many frames keeps the memory it frees: on the CPU rasterizers a frame
    // costs 13-15 % more when freed blocks go back to the kernel (gdi/Backend.h).
    gdi::keepFreedMemory();
    std::string model = "builtin:shadows", backend = "auto", out = "turntable.png";
    render::RenderSettings settings{.technique = "deferred-tiled", .width = 320, .height = 240};
    settings.tonemap = shading::Tonemap::PbrNeutral;  // a display image, not a measurement
    settings.antiAliasing = render::AntiAliasing::Fxaa;
    settings.displayImage = true;
    uint32_t frames = 0;  // 0: headless 24, windowed until the window is closed
    bool window = false, validation = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const bool value = i + 1 < argc;
        if (a == "--backend" && value)
            backend = argv[++i];
        else if (a == "--technique" && value)
            settings.technique = argv[++i];
        else if (a == "--frames" && value)
            frames = uint32_t(std::strtoul(argv[++i], nullptr, 10));
        else if (a == "--size" && value &&
                 std::sscanf(argv[++i], "%ux%u", &settings.width, &settings.height) == 2)
            continue;
        else if (a == "--out" && value)
            out = argv[++i];
        else if (a == "--window")
            window = true;
        else if (a == "--validation")
            validation = true;  // tests: Khronos layer / GL debug output on, errors fail
        else if (a[0] != '-')
            model = a;
        else {
            std::fprintf(
                stderr,
                "usage: %s [MODEL] [--backend NAME] [--technique NAME] [--frames N] [--size WxH] "
                "[--out FILE.png] [--window] [--validation]\n",
                argv[0]);
            return 2;
        }
    }
    const bool untilClosed = window && frames == 0;
    if (frames == 0) frames = 24;
    try {
        assets::Scene scene = assets::loadScene(model);
        auto device =
            gdi::createDevice({.backend = backend, .validation = validation, .window = window});
        render::SceneRenderer renderer(*device, scene, settings);
        ImGui::CreateContext();
        struct ImGuiContextGuard {
            ~ImGuiContextGuard() { ImGui::DestroyContext(); }
        } imguiContext;  // outlives the UI renderer below
        ImGui::GetIO().IniFilename = nullptr;
        render::UiRenderer ui(*device);
        const glm::vec3 centre = scene.bounds.center();
        bool open = true, paused = false;
        double animationSeconds = 0.0;
        float angle = 0, degreesPerFrame = 360.0f / float(frames), frameMs = 0;
        for (uint32_t f = 0; open && (untilClosed || f < frames); ++f) {
            const auto t0 = std::chrono::steady_clock::now();
            if (!scene.animations.empty() && !paused) {
                assets::poseScene(scene,
                                  {.animation = 0, .seconds = animationSeconds, .loop = true});
                renderer.updatePose();
                animationSeconds += 1.0 / 30.0;
            }
            renderer.setCamera(scene.camera->orbited(centre, angle * 0.0174532925f));
            renderer.renderFrame();
            renderer.passTimings();  // waits for the frame, so the time below is the frame's
            frameMs =
                std::chrono::duration<float, std::milli>(std::chrono::steady_clock::now() - t0)
                    .count();
            // The panel, fed by the window's input: only in a window.
            if (window) {
                const gdi::InputState in = device->input();
                ImGuiIO& io = ImGui::GetIO();
                io.DisplaySize = ImVec2(float(settings.width), float(settings.height));
                io.DeltaTime = std::max(frameMs, 0.1f) / 1000.0f;
                io.MousePos = ImVec2(in.mouseX, in.mouseY);
                for (int b = 0; b < 3; ++b) io.MouseDown[b] = in.mouse[b];
                ImGui::NewFrame();
                ImGui::SetNextWindowPos(ImVec2(6, 6), ImGuiCond_FirstUseEver);
                ImGui::Begin("turntable", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
                ImGui::Text("%s, %s", device->info().backend.c_str(), settings.technique.c_str());
                ImGui::Text("%.1f ms a frame", frameMs);
                ImGui::Checkbox("pause", &paused);
                ImGui::SliderFloat("deg/frame", &degreesPerFrame, 0.0f, 10.0f, "%.1f");
                ImGui::End();
                ImGui::Render();
                ui.render(*ImGui::GetDrawData(), renderer.displayTexture());
            }
            if (!paused) angle += degreesPerFrame;
            if (window) open = device->present(renderer.displayTexture());
        }
        gdi::writePng(device->readTexture(renderer.displayTexture()), out);
        if (device->validationErrorCount()) {
            std::fprintf(stderr, "fe_example_turntable: %u validation error(s)\n",
                         unsigned(device->validationErrorCount()));
            return 1;
        }
        std::printf("%s: %s with %s, %u frame(s)%s, wrote %s\n", device->info().backend.c_str(),
                    model.c_str(), settings.technique.c_str(), frames,
                    scene.animations.empty()
                        ? ""
                        : (", animation '" + scene.animations[0].name + "' played").c_str(),
                    out.c_str());
        return 0;
    } catch (const assets::AssetError& e) {
        std::fprintf(stderr, "fe_example_turntable: %s\n", e.what());
        return 3;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fe_example_turntable: %s\n", e.what());
        return 1;
    }
}

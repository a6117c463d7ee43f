// Example (b): a glTF model turning, lit and textured, written once against the engine
// (fe::renderer) and run unchanged on every backend: the backend is only a startup argument.
//   fe_example_turntable [MODEL.gltf|.glb|builtin:NAME] [--backend NAME] [--technique NAME]
//                        [--frames N] [--size WxH] [--out FILE.png] [--window] [--validation]
// Headless it renders N frames of one turn about the model and writes the last; with --window
// it shows the turn until the window is closed.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "assets/AssetError.h"
#include "assets/BuiltinScenes.h"
#include "fe/gdi/Backend.h"
#include "integration/SceneRenderer.h"

using namespace fe;

int main(int argc, char** argv) {
    std::string model = "builtin:shadows", backend = "auto", out = "turntable.png";
    render::RenderSettings settings{.technique = "deferred-tiled", .width = 320, .height = 240};
    settings.tonemap = shading::Tonemap::PbrNeutral;  // a display image, not a measurement
    settings.antiAliasing = render::AntiAliasing::Fxaa;
    settings.displayImage = true;
    uint32_t frames = 24;
    bool window = false, validation = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const bool value = i + 1 < argc;
        if (a == "--backend" && value) backend = argv[++i];
        else if (a == "--technique" && value) settings.technique = argv[++i];
        else if (a == "--frames" && value) frames = uint32_t(std::strtoul(argv[++i], nullptr, 10));
        else if (a == "--size" && value && std::sscanf(argv[++i], "%ux%u", &settings.width, &settings.height) == 2) continue;
        else if (a == "--out" && value) out = argv[++i];
        else if (a == "--window") window = true;
        else if (a == "--validation") validation = true;  // tests: Khronos layer / GL debug output on, errors fail
        else if (a[0] != '-') model = a;
        else {
            std::fprintf(stderr, "usage: %s [MODEL] [--backend NAME] [--technique NAME] [--frames N] [--size WxH] "
                                 "[--out FILE.png] [--window] [--validation]\n", argv[0]);
            return 2;
        }
    }
    if (frames == 0) frames = 1;
    try {
        const assets::Scene scene = assets::loadScene(model);
        auto device = gdi::createDevice({.backend = backend, .validation = validation, .window = window});
        render::SceneRenderer renderer(*device, scene, settings);
        const glm::vec3 centre = scene.bounds.center();
        bool open = true;
        for (uint32_t f = 0; open && (window || f < frames); ++f) {
            renderer.setCamera(scene.camera->orbited(centre, 6.2831853f * float(f % frames) / float(frames)));
            renderer.renderFrame();
            if (window) open = device->present(renderer.displayTexture());
        }
        gdi::writePng(renderer.readDisplay(), out);
        if (device->validationErrorCount()) {
            std::fprintf(stderr, "fe_example_turntable: %u validation error(s)\n", unsigned(device->validationErrorCount()));
            return 1;
        }
        std::printf("%s: %s with %s, %u frame(s), wrote %s\n", device->info().backend.c_str(), model.c_str(),
                    settings.technique.c_str(), frames, out.c_str());
        return 0;
    } catch (const assets::AssetError& e) {
        std::fprintf(stderr, "fe_example_turntable: %s\n", e.what());
        return 3;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fe_example_turntable: %s\n", e.what());
        return 1;
    }
}

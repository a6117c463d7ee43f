// Example (e): a material built in code the way a glTF exporter writes one: vertex colours
// (COLOR_0), a texture on the second uv set (TEXCOORD_1) through a KHR_texture_transform, and
// both BRDFs (glTF 2.0's, the default, and the seeds' separable one). Two threads render at
// once, each on a device of its own; then two mistakes are made on purpose. Everything printed
// is the same on every backend (CI diffs it). Last, the quad as a user's model without lights:
// the default look (the sky and a sun) on a transparent background, and the frame's warnings;
// and a pane of glass (KHR_materials_transmission) in front of the quad, which passes what the
// dielectric does not reflect.
//   fe_example_materials [--backend NAME] [--validation]
#include <atomic>
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <thread>

#include <glm/glm.hpp>

#include "fe/gdi/Backend.h"
#include "integration/FrameWarnings.h"
#include "integration/SceneRenderer.h"

using namespace fe;

namespace {

// A unit quad facing +Z: white, red, green and blue corners; uv1 = uv0.
assets::Scene quadScene() {
    assets::Scene scene;
    scene.name = "materials example";
    assets::Primitive quad;
    const glm::vec3 corners[4] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    const glm::vec4 colours[4] = {{1, 1, 1, 1}, {1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}};
    for (int i = 0; i < 4; ++i) {
        assets::Vertex v;
        v.position = corners[i];
        v.normal = {0, 0, 1};
        v.uv0 = v.uv1 = {(corners[i].x + 1) * 0.5f, (1 - corners[i].y) * 0.5f};
        v.color = colours[i];
        quad.vertices.push_back(v);
    }
    quad.indices = {0, 1, 2, 0, 2, 3};
    scene.meshes.push_back({.name = "quad", .primitives = {quad}});
    // A 2x2 texture: the left column white, the right one black (nearest, clamped). Rotated a
    // quarter turn by its transform, the halves become top and bottom.
    assets::TextureImage halves{
        .name = "halves",
        .width = 2,
        .height = 2,
        .pixels = {255, 255, 255, 255, 0, 0, 0, 255, 255, 255, 255, 255, 0, 0, 0, 255}};
    halves.sampler = {.minFilter = assets::Filter::Nearest,
                      .magFilter = assets::Filter::Nearest,
                      .mipFilter = assets::MipFilter::None,
                      .wrapS = assets::Wrap::ClampToEdge,
                      .wrapT = assets::Wrap::ClampToEdge,
                      .mipmaps = false};
    halves.srgb = true;
    scene.textures.push_back(halves);
    assets::Material m;
    m.name = "vertex colours x rotated halves";
    m.metallic = 0.0f;
    m.roughness = 0.5f;
    m.baseColorTexture = {.index = 0, .texCoord = 1};
    // A quarter turn: (u, v) -> (v, 1 - u), so the white left column lands on the top half.
    m.baseColorTexture.transform = {
        .offset = {0.0f, 1.0f}, .rotation = 1.5707963f, .scale = {1.0f, 1.0f}};
    scene.materials.push_back(m);
    scene.instances.push_back({.meshIndex = 0, .name = "quad"});
    scene.lights.push_back({.name = "sun",
                            .type = assets::LightType::Directional,
                            .intensity = 3.0f,
                            .direction = glm::normalize(glm::vec3(0.3f, -0.4f, -1.0f))});
    scene.camera = assets::Camera::lookAlong({0, 0, 3}, {0, 0, -1}, {0, 1, 0}, 0.9f, 0.1f, 100.0f);
    assets::finalizeScene(scene, false, false);
    return scene;
}

// The mean of the image over a region.
glm::dvec3 mean(const gdi::Image& img, uint32_t x0, uint32_t y0, uint32_t x1, uint32_t y1) {
    glm::dvec3 sum(0.0);
    for (uint32_t y = y0; y < y1; ++y)
        for (uint32_t x = x0; x < x1; ++x)
            sum += glm::dvec3(img.texel(x, y)[0], img.texel(x, y)[1], img.texel(x, y)[2]);
    return sum / double((x1 - x0) * (y1 - y0));
}

// Its dominant channel, as a word.
std::string dominant(const glm::dvec3& c) {
    const double total = c.r + c.g + c.b;
    for (int k = 0; k < 3; ++k)
        if (c[k] > 0.5 * total) return k == 0 ? "red" : k == 1 ? "green" : "blue";
    return "mixed";
}

}  // namespace

int main(int argc, char** argv) {
    std::string backend = "auto";
    bool validation = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--backend" && i + 1 < argc)
            backend = argv[++i];
        else if (a == "--validation")
            validation = true;
        else {
            std::fprintf(stderr, "usage: %s [--backend NAME] [--validation]\n", argv[0]);
            return 2;
        }
    }
    try {
        const assets::Scene scene = quadScene();
        // Two threads at once, a device each: the glTF BRDF and the separable one.
        gdi::Image images[2];
        std::string errors[2];
        std::atomic<uint32_t> validationErrors{0};
        auto render = [&](int k) {
            try {
                auto device = gdi::createDevice({.backend = backend, .validation = validation});
                render::RenderSettings s{.technique = "forward", .width = 64, .height = 64};
                s.shadingModel =
                    k == 0 ? render::ShadingModel::Gltf : render::ShadingModel::Separable;
                render::SceneRenderer r(*device, scene, s);
                r.renderFrame();
                images[k] = r.readOutput();
                validationErrors += uint32_t(device->validationErrorCount());
            } catch (const std::exception& e) {
                errors[k] = e.what();
            }
        };
        std::thread other(render, 1);
        render(0);
        other.join();
        for (const std::string& e : errors)
            if (!e.empty()) throw std::runtime_error(e);
        // The quad covers the middle of the image; the texture's white half is on top after its
        // quarter turn, so the top corners show their vertex colours and the bottom, black but
        // for the dielectric's specular reflection, is far darker.
        const gdi::Image& img = images[0];
        const glm::dvec3 topLeft = mean(img, 14, 14, 20, 20), topRight = mean(img, 44, 14, 50, 20),
                         bottom = mean(img, 20, 44, 44, 50);
        const double topBrightness =
            (topLeft.r + topLeft.g + topLeft.b + topRight.r + topRight.g + topRight.b) / 2.0;
        std::printf("top left %s, top right %s, bottom %s\n", dominant(topLeft).c_str(),
                    dominant(topRight).c_str(),
                    bottom.r + bottom.g + bottom.b < 0.1 * topBrightness ? "dark" : "bright");
        double differ = 0;
        for (uint32_t y = 0; y < 64; ++y)
            for (uint32_t x = 0; x < 64; ++x)
                differ = std::max(
                    differ, double(std::abs(images[0].texel(x, y)[2] - images[1].texel(x, y)[2])));
        std::printf("the glTF and separable BRDFs differ: %s\n", differ > 1e-3 ? "yes" : "no");
        auto device = gdi::createDevice({.backend = backend, .validation = validation});
        // The quad as a model whose file has no lights: the loader's rig, replaced by the default
        // look; a transparent background leaves the corners clear and the quad opaque.
        {
            assets::Scene unlit = scene;
            unlit.lights.clear();
            assets::addDefaultLights(unlit, *unlit.camera);
            const bool look = assets::useDefaultSkyAndSun(unlit);
            render::RenderSettings s{
                .technique = "forward", .width = 64, .height = 64, .iblPrefiltered = true};
            s.shadows.enabled = unlit.showsShadows;
            s.tonemap = shading::Tonemap::PbrNeutral;
            s.background.kind = render::Background::Kind::Transparent;
            s.displayImage = true;
            render::SceneRenderer r(*device, unlit, s);
            r.renderFrame();
            const gdi::Image display = r.readDisplay();
            std::printf(
                "default look: %s, %zu light(s), the sky %s, corner %s, quad %s, %zu warning(s)\n",
                look ? "yes" : "no", unlit.lights.size(),
                unlit.environment ? "lights it" : "missing",
                display.texel(0, 0)[3] == 0.0f ? "transparent" : "opaque",
                display.texel(32, 32)[3] == 1.0f ? "opaque" : "transparent",
                render::frameWarnings(unlit, *unlit.camera, s, display).size());
        }
        // A clear pane (transmission 1, smooth, white) over the quad's left half: the quad is seen
        // through it, darkened only by the light the pane reflects (F0 0.04 at normal incidence).
        {
            assets::Scene glass = scene;
            assets::Material pane;
            pane.name = "glass";
            pane.metallic = 0.0f;
            pane.roughness = 0.0f;
            pane.transmission = 1.0f;
            glass.materials.push_back(pane);
            assets::Primitive quad = glass.meshes[0].primitives[0];
            quad.material = 1;
            for (assets::Vertex& v : quad.vertices) {
                v.position = glm::vec3(v.position.x * 0.5f - 0.5f, v.position.y, 0.5f);
                v.color =
                    glm::vec4(1.0f);  // COLOR_0 would tint the glass as it tints a base colour
            }
            glass.meshes.push_back({.name = "pane", .primitives = {quad}});
            glass.instances.push_back({.meshIndex = 1, .name = "pane"});
            glass.lights.clear();  // no light on the pane's front: what it shows is the quad's
            assets::Scene dark = scene;
            dark.lights.clear();
            dark.materials[0].emissiveFactor =
                glm::vec3(1.0f);  // the quad glows, so there is something behind
            glass.materials[0].emissiveFactor = glm::vec3(1.0f);
            assets::finalizeScene(glass, false, false);
            render::SceneRenderer lit(*device, glass,
                                      {.technique = "forward", .width = 64, .height = 64});
            render::SceneRenderer bare(*device, dark,
                                       {.technique = "forward", .width = 64, .height = 64});
            lit.renderFrame();
            bare.renderFrame();
            const double through = mean(lit.readOutput(), 16, 14, 22, 20).r,
                         behind = mean(bare.readOutput(), 16, 14, 22, 20).r;
            std::printf("the glass passes %ld %% of the light behind it\n",
                        std::lround(100.0 * through / behind));
        }
        // Mistakes, made on purpose: each the same gdi::Error everywhere, before any native call.
        try {
            render::RenderSettings s{.technique = "redeferred", .width = 64, .height = 64};
            s.shadingModel = render::ShadingModel::Gltf;
            render::SceneRenderer r(*device, scene, s);
            std::printf("mistake 1 accepted\n");
        } catch (const gdi::Error& e) {
            std::printf("mistake 1: %s\n", e.what());
        }
        try {
            assets::Scene broken = scene;
            broken.meshes[0].primitives[0].vertices[2].color.g = NAN;
            render::SceneRenderer r(*device, broken,
                                    {.technique = "forward", .width = 64, .height = 64});
            std::printf("mistake 2 accepted\n");
        } catch (const gdi::Error& e) {
            std::printf("mistake 2: %s\n", e.what());
        }
        try {
            render::RenderSettings s{.technique = "forward", .width = 64, .height = 64};
            s.background.kind = render::Background::Kind::Environment;  // the quad's scene has none
            render::SceneRenderer r(*device, scene, s);
            std::printf("mistake 3 accepted\n");
        } catch (const gdi::Error& e) {
            std::printf("mistake 3: %s\n", e.what());
        }
        try {
            assets::Scene broken = scene;
            broken.materials[0].transmission = 1.5f;  // a fraction
            render::SceneRenderer r(*device, broken,
                                    {.technique = "forward", .width = 64, .height = 64});
            std::printf("mistake 4 accepted\n");
        } catch (const gdi::Error& e) {
            std::printf("mistake 4: %s\n", e.what());
        }
        if (validationErrors + device->validationErrorCount()) {
            std::fprintf(stderr, "fe_example_materials: validation errors\n");
            return 1;
        }
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fe_example_materials: %s\n", e.what());
        return 1;
    }
}

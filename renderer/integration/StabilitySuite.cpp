#include "integration/StabilitySuite.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

#include "assets/BuiltinScenes.h"
#include "integration/RenderDirector.h"
#include "integration/SceneRenderer.h"

namespace fe::render {

namespace {
assets::Scene spheres(uint32_t grid = 4) {
    return assets::makeBuiltinScene("spheres", {.sphereGrid = grid});
}

assets::Light point(glm::vec3 p, float cd, float range = 0.0f) {
    assets::Light l;
    l.type = assets::LightType::Point;
    l.position = p;
    l.intensity = cd;
    l.range = range;
    l.name = "test";
    return l;
}

}  // namespace

std::vector<StabilityCase> stabilityCases() {
    std::vector<StabilityCase> c;
    c.push_back({"roughness 0 to 1 (below the clamp)", [] { return spheres(); }});
    c.push_back({"grazing angles",
                 [] {
                     assets::Scene s = assets::makeBuiltinScene("plane");
                     // The eye just above the plane's surface: n.v falls to 0 towards the far edge.
                     s.camera =
                         assets::Camera::lookAlong({0.0f, -1.6f, 0.08f}, {0.0f, 1.0f, -0.04f},
                                                   {0, 0, 1}, 0.9f, 0.01f, 100.0f);
                     s.lights.push_back(point({0.0f, 0.5f, 0.3f}, 2.0f));
                     return s;
                 },
                 1.5});
    c.push_back({"light at the eye", [] {
                     assets::Scene s = spheres();
                     s.lights = {point(s.camera->eye(), 30.0f)};
                     return s;
                 }});
    c.push_back({"light inside a sphere", [] {
                     assets::Scene s = spheres();
                     s.lights.push_back(point(glm::vec3(s.instances[5].world[3]), 50.0f));
                     return s;
                 }});
    c.push_back({"light range ending on the surface", [] {
                     assets::Scene s = assets::makeBuiltinScene("plane");
                     s.lights = {point({0.0f, 0.0f, 1.0f}, 1.0f,
                                       1.0f)};  // the range window is 0 at the plane's centre
                     return s;
                 }});
    c.push_back({"lights of 1e4 and 1e7 cd",
                 [] {
                     assets::Scene s = spheres();
                     s.lights.push_back(point({1.0f, 1.0f, 3.0f}, 1e4f));
                     s.lights.push_back(point({-1.0f, -1.0f, 2.0f}, 1e7f));
                     return s;
                 },
                 2.0});
    c.push_back({"no light", [] {
                     assets::Scene s = spheres();
                     s.lights.clear();
                     return s;
                 }});
    c.push_back({"one light", [] {
                     assets::Scene s = spheres();
                     s.lights.resize(1);
                     return s;
                 }});
    c.push_back(
        {"4096 lights", [] { return assets::makeBuiltinScene("lights", {.lights = 4096}); }, 1.0});
    c.push_back({"65536 lights",
                 [] { return assets::makeBuiltinScene("lights", {.lights = 65536}); }, 1.0, "", 6});
    c.push_back({"1e5 from the origin",
                 [] {
                     assets::Scene s = spheres();
                     const glm::vec3 offset(1e5f, 0.0f, 1e5f);
                     for (auto& i : s.instances)
                         i.world = glm::translate(glm::mat4(1.0f), offset) * i.world;
                     for (auto& l : s.lights) l.position += offset;
                     s.camera->worldFromView =
                         glm::translate(glm::mat4(1.0f), offset) * s.camera->worldFromView;
                     s.bounds = assets::computeWorldBounds(s);
                     return s;
                 },
                 1.0});
    c.push_back({"denormal positions and factors", [] {
                     assets::Scene s = assets::makeBuiltinScene("plane");
                     s.meshes[0].primitives[0].vertices[0].uv0 = glm::vec2(1e-40f);
                     s.materials[0].metallic = 1e-40f;
                     s.meshes[0].primitives[0].vertices[0].position.z = 1e-40f;
                     return s;
                 }});
    c.push_back({"degenerate and zero-area triangles", [] {
                     assets::Scene s = assets::makeBuiltinScene("plane");
                     auto& prim = s.meshes[0].primitives[0];
                     prim.indices.insert(prim.indices.end(),
                                         {0, 0, 0, 0, 1, 1, 1, 2, 1});  // points and a line
                     return s;
                 }});
    c.push_back({"translucent materials",
                 [] {
                     assets::Scene s = spheres();
                     for (size_t i = 0; i < s.materials.size(); i += 2) {
                         s.materials[i].alphaMode = assets::AlphaMode::Blend;
                         s.materials[i].baseColorFactor.a = 0.5f;
                     }
                     return s;
                 },
                 1.0});
    // Non-finite data is refused by every technique, with what and where.
    auto broken = [](const char* what, std::function<void(assets::Scene&)> breakIt,
                     const char* message) {
        return StabilityCase{what,
                             [breakIt] {
                                 assets::Scene s = assets::makeBuiltinScene("plane");
                                 breakIt(s);
                                 return s;
                             },
                             0.0, message};
    };
    c.push_back(broken(
        "NaN position",
        [](assets::Scene& s) { s.meshes[0].primitives[0].vertices[2].position.x = NAN; },
        "mesh 'quad' primitive 0 vertex 2: its position is not finite"));
    c.push_back(broken(
        "infinite normal",
        [](assets::Scene& s) { s.meshes[0].primitives[0].vertices[1].normal.y = INFINITY; },
        "vertex 1: its normal is not finite"));
    c.push_back(broken(
        "NaN uv", [](assets::Scene& s) { s.meshes[0].primitives[0].vertices[0].uv0.x = NAN; },
        "vertex 0: its uv is not finite"));
    c.push_back(broken(
        "NaN roughness", [](assets::Scene& s) { s.materials[0].roughness = NAN; },
        "material 'grey': metallic or roughness is not finite"));
    c.push_back(broken(
        "infinite light intensity", [](assets::Scene& s) { s.lights[0].intensity = INFINITY; },
        "light 'point' is not finite"));
    return c;
}

std::vector<StabilityCase> stabilityCases(const std::string& names) {
    std::vector<StabilityCase> all = stabilityCases();
    if (names.empty()) return all;
    std::vector<std::string> parts;
    for (size_t begin = 0; begin <= names.size();) {
        const size_t end = std::min(names.find(',', begin), names.size());
        parts.push_back(names.substr(begin, end - begin));
        begin = end + 1;
    }
    std::vector<StabilityCase> chosen;
    for (const std::string& part : parts) {
        const auto named = [&](const StabilityCase& c) {
            return !part.empty() && c.name.find(part) != std::string::npos;
        };
        if (std::none_of(all.begin(), all.end(), named)) {
            std::string list;
            for (const StabilityCase& c : all) list += (list.empty() ? "" : "; ") + c.name;
            throw gdi::Error("no stability case's name contains '" + part +
                             "' (the cases: " + list + ")");
        }
    }
    for (StabilityCase& c : all) {
        const auto inName = [&](const std::string& part) {
            return !part.empty() && c.name.find(part) != std::string::npos;
        };
        if (std::any_of(parts.begin(), parts.end(), inName)) chosen.push_back(std::move(c));
    }
    return chosen;
}

StabilityOutcome runStabilityCase(gdi::Device& device, const assets::Scene& scene,
                                  const std::string& technique, uint32_t width, uint32_t height,
                                  const std::vector<glm::dvec3>& reference) {
    StabilityOutcome o;
    try {
        SceneRenderer r(device, scene, {.technique = technique, .width = width, .height = height});
        r.renderFrame();
        const gdi::Image img = r.readOutput();
        for (uint32_t y = 0; y < height; ++y)
            for (uint32_t x = 0; x < width; ++x) {
                const auto v = img.texel(x, y);
                for (int k = 0; k < 4; ++k) o.nonFinite += !std::isfinite(v[k]);
            }
        if (!reference.empty()) {
            std::vector<std::array<float, 4>> texels;
            for (const glm::dvec3& v : reference)
                texels.push_back({float(v.x), float(v.y), float(v.z), 1.0f});
            o.percentOver5 = percentPixelsOver5Of255(
                img, gdi::Image::fromTexels(width, height, gdi::Format::RGBA32F, texels), 1.0f);
        }
    } catch (const gdi::Error& e) {
        o.refused = true;
        o.message = e.what();
    }
    return o;
}

}  // namespace fe::render

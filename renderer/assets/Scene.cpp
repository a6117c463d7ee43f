#include "assets/Scene.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "assets/AssetError.h"

namespace fe::assets {

namespace {
// The numbers below are the ones documented under "Defaults" in GltfLoader.h; keep in step.
constexpr float kDefaultYfov = 0.78539816339f;  // 45 degrees
const glm::vec3 kDefaultViewFrom =
    glm::normalize(glm::vec3(0.5f, 0.45f, 1.0f));  // bounds centre to the eye

glm::vec3 toWorld(const Camera& cam, const glm::vec3& viewDir) {
    return glm::normalize(glm::mat3(cam.worldFromView) * glm::normalize(viewDir));
}
}  // namespace

AABB AABB::transformed(const glm::mat4& m) const {
    AABB out;
    if (empty()) return out;
    for (int i = 0; i < 8; ++i) {
        glm::vec3 c((i & 1) ? max.x : min.x, (i & 2) ? max.y : min.y, (i & 4) ? max.z : min.z);
        out.extend(glm::vec3(m * glm::vec4(c, 1.0f)));
    }
    return out;
}

// The rotation inverted on its own: a 4x4 inverse mixes the translation into every cofactor, and
// 1e5 from the origin that cost the rotation 3 decimal places (the stability case).
glm::mat4 Camera::viewFromWorld() const {
    const glm::mat3 rotation = glm::inverse(glm::mat3(worldFromView));
    glm::mat4 v(rotation);
    v[3] = glm::vec4(-(rotation * glm::vec3(worldFromView[3])), 1.0f);
    return v;
}

Camera Camera::lookAlong(const glm::vec3& eye, const glm::vec3& forward, const glm::vec3& up,
                         float yfov, float znear, float zfar) {
    glm::vec3 back = -glm::normalize(forward);
    glm::vec3 right = glm::normalize(glm::cross(up, back));
    glm::vec3 trueUp = glm::cross(back, right);
    Camera c;
    c.worldFromView = glm::mat4(glm::vec4(right, 0.0f), glm::vec4(trueUp, 0.0f),
                                glm::vec4(back, 0.0f), glm::vec4(eye, 1.0f));
    c.yfov = yfov;
    c.znear = znear;
    c.zfar = zfar;
    return c;
}

Camera Camera::orbited(const glm::vec3& center, float radians) const {
    const glm::mat4 r = glm::rotate(glm::mat4(1.0f), radians, glm::vec3(0.0f, 1.0f, 0.0f));
    Camera c = *this;
    c.worldFromView = glm::translate(glm::mat4(1.0f), center) * r *
                      glm::translate(glm::mat4(1.0f), -center) * worldFromView;
    return c;
}

glm::mat4 Node::localTransform() const {
    if (matrix) return *matrix;
    return glm::translate(glm::mat4(1.0f), translation) * glm::mat4_cast(rotation) *
           glm::scale(glm::mat4(1.0f), scale);
}

AABB computeWorldBounds(const Scene& scene) {
    AABB b;
    for (const auto& inst : scene.instances) {
        if (inst.meshIndex >= scene.meshes.size()) continue;
        const AABB& local =
            inst.posedBounds.empty() ? scene.meshes[inst.meshIndex].bounds : inst.posedBounds;
        b.extend(local.transformed(inst.world));
    }
    return b;
}

Camera makeDefaultCamera(const AABB& bounds) {
    glm::vec3 center = bounds.center();
    float radius = 0.5f * glm::length(bounds.size());
    if (!(radius > 1e-6f) || !std::isfinite(radius)) radius = 1.0f;  // empty or a single point
    // Distance at which the bounding sphere touches the top and bottom of the view.
    float dist = radius / std::sin(kDefaultYfov * 0.5f);
    // From the front (+Z), above and to the right: a flat model lying in any axis plane (a
    // ground, TwoSidedPlane's XZ quad) is never seen edge-on, and a box shows three faces.
    const glm::vec3 toEye = kDefaultViewFrom;
    Camera c = Camera::lookAlong(center + toEye * dist, -toEye, glm::vec3(0, 1, 0), kDefaultYfov,
                                 0.5f * (dist - radius), dist + 2.0f * radius);
    c.name = "default";
    return c;
}

void addDefaultLights(Scene& scene, const Camera& cam) {
    Light key;
    key.name = "default key";
    key.type = LightType::Directional;
    key.color = glm::vec3(1.0f, 0.956f, 0.898f);
    key.intensity = 2.5f;
    key.direction = toWorld(cam, glm::vec3(0.5f, -1.0f, -1.0f));  // from the viewer's upper left

    Light fill;
    fill.name = "default fill";
    fill.type = LightType::Directional;
    fill.color = glm::vec3(0.85f, 0.9f, 1.0f);
    fill.intensity = 0.8f;
    fill.direction = toWorld(cam, glm::vec3(-0.7f, 0.2f, -1.0f));  // from the right, slightly below

    Light head;
    head.name = "default headlight";
    head.type = LightType::Point;
    head.color = glm::vec3(1.0f);
    head.position = cam.eye();
    float d = glm::length(scene.bounds.center() - cam.eye());
    if (!(d > 1e-3f) || !std::isfinite(d)) d = 1.0f;
    head.intensity = 0.7f * d * d;  // 0.7 lux at the centre of the bounds
    head.range = 0.0f;

    scene.lights.push_back(key);
    scene.lights.push_back(fill);
    scene.lights.push_back(head);
    scene.hasDefaultLights = true;
}

bool useDefaultSkyAndSun(Scene& scene) {
    if (!scene.hasDefaultLights) return false;
    const Camera cam = scene.camera ? *scene.camera : makeDefaultCamera(scene.bounds);
    // Where the key light of the rig came from (the viewer's upper left, behind the viewer), raised
    // to at least kDefaultSunMinElevation above the horizon: a sun, whatever the camera's tilt.
    glm::vec3 d = glm::normalize(toWorld(cam, glm::vec3(0.8f, -1.0f, -0.6f)));
    if (d.y > -kDefaultSunMinElevation) {
        glm::vec2 h(d.x, d.z);
        h = glm::length(h) > 1e-6f ? glm::normalize(h) : glm::vec2(0.0f, -1.0f);
        const float c = std::sqrt(1.0f - kDefaultSunMinElevation * kDefaultSunMinElevation);
        d = glm::vec3(h.x * c, -kDefaultSunMinElevation, h.y * c);
    }
    Light sun;
    sun.name = "default sun";
    sun.type = LightType::Directional;
    sun.color = glm::vec3(1.0f, 0.956f, 0.898f);
    sun.intensity = kDefaultSunIlluminance;
    sun.direction = d;
    scene.lights.clear();
    scene.lights.push_back(sun);
    Environment sky = loadEnvironment("builtin:sky");
    sky.sky.sunDirection = -glm::dvec3(d);
    sky.sky.sunRadiance = glm::dvec3(0.0);
    scene.environment = std::move(sky);
    scene.showsShadows = true;
    return true;
}

namespace {
template <int N>
bool finite(const glm::vec<N, float>& v) {
    for (int i = 0; i < N; ++i)
        if (!std::isfinite(v[i])) return false;
    return true;
}
bool finite(float v) { return std::isfinite(v); }
bool finite(const glm::mat4& m) {
    return finite(m[0]) && finite(m[1]) && finite(m[2]) && finite(m[3]);
}
}  // namespace

void checkFinite(const Scene& scene) {
    auto fail = [](const std::string& what) {
        throw AssetError(what + " is not finite (NaN or infinity)");
    };
    for (size_t m = 0; m < scene.meshes.size(); ++m)
        for (size_t p = 0; p < scene.meshes[m].primitives.size(); ++p) {
            const Primitive& prim = scene.meshes[m].primitives[p];
            for (size_t v = 0; v < prim.vertices.size(); ++v) {
                const Vertex& x = prim.vertices[v];
                // The vertex's name is spelled only for the error (every vertex of every scene
                // passes through here).
                auto failAt = [&](const char* what) {
                    fail("mesh '" + scene.meshes[m].name + "' primitive " + std::to_string(p) +
                         " vertex " + std::to_string(v) + ": " + what);
                };
                if (!finite(x.position)) failAt("its position");
                if (!finite(x.normal)) failAt("its normal");
                if (!finite(x.tangent)) failAt("its tangent");
                if (!finite(x.uv0)) failAt("its uv");
                if (!finite(x.uv1)) failAt("its second uv set");
                if (!finite(x.color)) failAt("its colour");
            }
        }
    for (const Material& m : scene.materials) {
        const std::string where = "material '" + m.name + "': ";
        if (!finite(m.baseColorFactor)) fail(where + "baseColorFactor");
        if (!finite(m.metallic) || !finite(m.roughness)) fail(where + "metallic or roughness");
        if (!finite(m.emissiveFactor)) fail(where + "emissiveFactor");
        if (!finite(m.normalScale) || !finite(m.occlusionStrength) || !finite(m.alphaCutoff))
            fail(where + "normalScale, occlusionStrength or alphaCutoff");
        for (const TextureRef* r :
             {&m.baseColorTexture, &m.metallicRoughnessTexture, &m.normalTexture,
              &m.emissiveTexture, &m.occlusionTexture, &m.specularTexture, &m.specularColorTexture,
              &m.clearcoatTexture, &m.clearcoatRoughnessTexture, &m.clearcoatNormalTexture,
              &m.transmissionTexture, &m.thicknessTexture, &m.sheenColorTexture,
              &m.sheenRoughnessTexture})
            if (!finite(r->transform.offset) || !finite(r->transform.rotation) ||
                !finite(r->transform.scale))
                fail(where + "a texture transform");
        // The extensions' factors (an infinite ior and attenuation distance are meaningful), in
        // the ranges the loader enforces, so a material built in code is refused as a file is.
        if (!finite(m.specular) || !finite(m.specularColor) || !finite(m.clearcoat) ||
            !finite(m.clearcoatRoughness) || !finite(m.clearcoatNormalScale) ||
            !finite(m.transmission) || !finite(m.thickness) || !finite(m.attenuationColor) ||
            !finite(m.sheenColor) || !finite(m.sheenRoughness) || std::isnan(m.ior) ||
            std::isnan(m.attenuationDistance))
            fail(
                where +
                "a factor of KHR_materials_ior, specular, clearcoat, transmission, volume or sheen");
        auto unit = [&](float v, const char* name) {
            if (!(v >= 0.0f && v <= 1.0f)) throw AssetError(where + name + " must lie in [0, 1]");
        };
        unit(m.specular, "specular");
        unit(m.clearcoat, "clearcoat");
        unit(m.clearcoatRoughness, "clearcoatRoughness");
        unit(m.transmission, "transmission");
        unit(m.sheenRoughness, "sheenRoughness");
        for (int c = 0; c < 3; ++c) {
            unit(m.sheenColor[c], "sheenColor");
            unit(m.attenuationColor[c], "attenuationColor");
        }
        if (!(m.ior >= 1.0f))
            throw AssetError(where + "ior must be at least 1 (infinite for a perfect mirror)");
        if (!(m.thickness >= 0.0f)) throw AssetError(where + "thickness must not be negative");
        if (!(m.attenuationDistance > 0.0f))
            throw AssetError(where + "attenuationDistance must be positive (infinite: none)");
        if (!glm::all(glm::greaterThanEqual(m.specularColor, glm::vec3(0.0f))))
            throw AssetError(where + "specularColor must not be negative");
    }
    for (const MeshInstance& i : scene.instances)
        if (!finite(i.world)) fail("node '" + i.name + "': its transform");
    for (const Light& l : scene.lights)
        if (!finite(l.color) || !finite(l.intensity) || !finite(l.range) || !finite(l.position) ||
            !finite(l.direction) || !finite(l.innerConeAngle) || !finite(l.outerConeAngle))
            fail("light '" + l.name + "'");
    if (scene.camera) checkCamera(*scene.camera);
    for (const Node& n : scene.nodes)
        if (!finite(n.translation) ||
            !finite(glm::vec4(n.rotation.x, n.rotation.y, n.rotation.z, n.rotation.w)) ||
            !finite(n.scale) || (n.matrix && !finite(*n.matrix)))
            fail("node '" + n.name + "': its transform");
    for (const Animation& a : scene.animations)
        for (const AnimationSampler& sm : a.samplers)
            for (float v : sm.values)
                if (!finite(v)) fail("animation '" + a.name + "': a key value");
}

void checkCamera(const Camera& c) {
    const std::string what = "camera '" + c.name + "': ";
    if (!finite(c.worldFromView) || !finite(c.yfov) || !finite(c.znear))
        throw AssetError(what + "not finite (NaN or infinity)");
    // The view matrix is inverted every frame: a singular one gives a NaN view, not a picture.
    if (!(std::abs(glm::determinant(glm::mat3(c.worldFromView))) > 1e-12f))
        throw AssetError(what + "its transform is singular (no view can be made from it)");
    if (c.orthographic) {
        if (!(c.orthographic->x != 0.0f && c.orthographic->y != 0.0f && finite(*c.orthographic)))
            throw AssetError(what + "orthographic xmag and ymag must be finite and not zero");
        if (!(c.znear >= 0.0f))
            throw AssetError(what + "znear " + std::to_string(c.znear) + " is negative");
        if (!(c.zfar > c.znear && std::isfinite(c.zfar)))
            throw AssetError(what + "an orthographic camera needs a finite zfar beyond znear");
        return;
    }
    if (!(c.yfov > 0.0f && c.yfov < 3.14159265f))
        throw AssetError(what + "yfov " + std::to_string(c.yfov) + " is not in (0, pi) radians");
    if (!(c.znear > 0.0f))
        throw AssetError(what + "znear " + std::to_string(c.znear) + " is not positive");
    if (!(c.zfar > c.znear))
        throw AssetError(what + "zfar " + std::to_string(c.zfar) + " is not beyond znear");
    if (c.aspectRatio && !(*c.aspectRatio > 0.0f && std::isfinite(*c.aspectRatio)))
        throw AssetError(what + "aspectRatio " + std::to_string(*c.aspectRatio) +
                         " is not a positive number");
}

void finalizeScene(Scene& scene, bool addCamera, bool addLights) {
    checkFinite(scene);
    scene.bounds = computeWorldBounds(scene);
    if (!scene.camera && addCamera) {
        scene.camera = makeDefaultCamera(scene.bounds);
        scene.hasDefaultCamera = true;
    }
    if (scene.lights.empty() && addLights) {
        addDefaultLights(scene, scene.camera ? *scene.camera : makeDefaultCamera(scene.bounds));
    }
}

}  // namespace fe::assets

#include "render/ShadowPlan.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "reference/CameraMath.h"

namespace fe::render {

namespace {

std::array<glm::vec3, 8> corners(const assets::AABB& b) {
    std::array<glm::vec3, 8> c;
    for (int i = 0; i < 8; ++i)
        c[i] = glm::vec3(i & 1 ? b.max.x : b.min.x, i & 2 ? b.max.y : b.min.y,
                         i & 4 ? b.max.z : b.min.z);
    return c;
}

// How far along the view the scene reaches (the cascades and the importance ray end there).
float viewExtent(const assets::Camera& camera, const assets::AABB& bounds) {
    const float zfar = camera.infiniteFar() ? 1e30f : camera.zfar;
    if (bounds.empty()) return std::min(zfar, camera.znear * 1000.0f);
    float far = 0.0f;
    for (const glm::vec3& c : corners(bounds))
        far = std::max(far, glm::dot(c - camera.eye(), camera.forward()));
    return std::clamp(far, camera.znear * 1.01f, zfar);
}

// A unit vector perpendicular to d.
glm::vec3 perpendicular(const glm::vec3& d) {
    const glm::vec3 up = std::abs(d.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    return glm::normalize(glm::cross(up, d));
}

// Distance from the light to the farthest corner of the scene: how deep a perspective map must see.
float perspectiveFar(const assets::Light& light, const assets::AABB& bounds) {
    if (light.range > 0.0f) return light.range;
    if (bounds.empty()) return 100.0f;
    float far = 0.0f;
    for (const glm::vec3& c : corners(bounds))
        far = std::max(far, glm::distance(c, light.position));
    return std::max(far * 1.01f, 1e-3f);
}

glm::mat4 fromRows(const glm::vec4& r0, const glm::vec4& r1, const glm::vec4& r2,
                   const glm::vec4& r3) {
    return glm::transpose(glm::mat4(r0, r1, r2, r3));
}

}  // namespace

std::vector<bool> ShadowPlan::castsShadow() const {
    std::vector<bool> casts(order.size(), false);
    for (const ShadowedLight& s : shadowed) casts[s.light] = true;
    return casts;
}

double shadowImportance(const assets::Light& light, const assets::Camera& camera,
                        const assets::AABB& bounds) {
    const glm::dvec3 color(light.color);
    const double luminance = 0.2126 * color.r + 0.7152 * color.g + 0.0722 * color.b;
    if (light.type == assets::LightType::Directional) return light.intensity * luminance;
    const double length = viewExtent(camera, bounds);
    const glm::dvec3 eye(camera.eye()), f(camera.forward()), p(light.position);
    const double t = std::clamp(glm::dot(p - eye, f), 0.0, length);
    const double d = std::max(glm::distance(p, eye + f * t), 0.01 * length);
    double window = 1.0;
    if (light.range > 0.0f) {
        const double q = d / light.range;
        window = std::pow(std::clamp(1.0 - q * q * q * q, 0.0, 1.0), 2.0);
    }
    return light.intensity * luminance * window / (d * d);
}

ShadowPlan planShadows(const std::vector<assets::Light>& lights, const assets::Camera& camera,
                       const assets::AABB& bounds, const ShadowSettings& s) {
    ShadowPlan plan;
    const uint32_t n = uint32_t(lights.size());
    std::vector<bool> shadowed(n, false);
    if (s.enabled) {
        std::vector<uint32_t> points;
        for (uint32_t i = 0; i < n; ++i)
            if (lights[i].type == assets::LightType::Point)
                points.push_back(i);
            else
                shadowed[i] = true;
        std::vector<double> importance(n, 0.0);
        for (uint32_t i : points) importance[i] = shadowImportance(lights[i], camera, bounds);
        // Most important first; ties keep the scene's order, so the choice is deterministic.
        std::stable_sort(points.begin(), points.end(),
                         [&](uint32_t a, uint32_t b) { return importance[a] > importance[b]; });
        for (size_t k = 0; k < points.size() && k < s.pointBudget; ++k) shadowed[points[k]] = true;
    }
    for (uint32_t i = 0; i < n; ++i)
        if (!shadowed[i]) plan.order.push_back(i);
    plan.unshadowedCount = uint32_t(plan.order.size());
    for (uint32_t i = 0; i < n; ++i) {
        if (!shadowed[i]) continue;
        plan.order.push_back(i);
        const assets::LightType t = lights[i].type;
        plan.shadowed.push_back({.light = i,
                                 .kind = t == assets::LightType::Directional ? ShadowKind::Cascades
                                         : t == assets::LightType::Spot      ? ShadowKind::Spot
                                                                             : ShadowKind::Cube,
                                 .layers = t == assets::LightType::Directional
                                               ? std::clamp(s.cascades, 1u, 4u)
                                           : t == assets::LightType::Spot ? 1u
                                                                          : 6u});
    }
    return plan;
}

glm::mat4 cubeFaceProjection(uint32_t face, const glm::vec3& light, float n, float f) {
    // Face f sees d = P - light with major axis m; its texel (s, t) has (2s - 1, 2t - 1) =
    // (a.d, b.d) / m.d, the inverse of the face selection (fe_environment.glsl's table).
    static const glm::vec3 m[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                   {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
    static const glm::vec3 a[6] = {{0, 0, -1}, {0, 0, 1}, {1, 0, 0},
                                   {1, 0, 0},  {1, 0, 0}, {-1, 0, 0}};
    static const glm::vec3 b[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1},
                                   {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
    const float A = f / (f - n), B = -n * f / (f - n);  // depth A + B / w: 0 at w = n, 1 at w = f
    return fromRows(glm::vec4(a[face], -glm::dot(a[face], light)),
                    glm::vec4(b[face], -glm::dot(b[face], light)),
                    glm::vec4(A * m[face], -A * glm::dot(m[face], light) + B),
                    glm::vec4(m[face], -glm::dot(m[face], light)));
}

ShadowProjection shadowProjection(const assets::Light& light, ShadowKind kind, uint32_t layers,
                                  const assets::Camera& camera, float aspect,
                                  const assets::AABB& bounds, uint32_t mapSize) {
    ShadowProjection p;
    p.layers = layers;
    const float size = float(mapSize);
    if (kind == ShadowKind::Cascades) {
        const glm::vec3 L = glm::normalize(light.direction);
        const glm::vec3 lx = perpendicular(L), ly = glm::cross(L, lx);
        const glm::vec3 eye = camera.eye(), f = camera.forward();
        const glm::vec3 r = glm::normalize(glm::cross(f, camera.up())), u = glm::cross(r, f);
        const float tanY = std::tan(camera.yfov * 0.5f), tanX = tanY * aspect;
        const float n = camera.znear, far = viewExtent(camera, bounds);
        float tMinScene = 1e30f, tMaxScene = -1e30f;
        for (const glm::vec3& c : corners(bounds)) {
            tMinScene = std::min(tMinScene, glm::dot(c, L));
            tMaxScene = std::max(tMaxScene, glm::dot(c, L));
        }
        float begin = n;
        for (uint32_t i = 0; i < layers; ++i) {
            // Half-way between logarithmic and uniform splits: near cascades stay sharp without
            // the far ones growing coarse.
            const float x = float(i + 1) / float(layers);
            const float end = 0.5f * (n * std::pow(far / n, x) + n + (far - n) * x);
            glm::vec3 c[8];
            glm::vec3 center(0.0f);
            for (int k = 0; k < 8; ++k) {
                const float z = k & 4 ? end : begin;
                c[k] = eye + f * z + r * (k & 1 ? 1.0f : -1.0f) * z * tanX +
                       u * (k & 2 ? 1.0f : -1.0f) * z * tanY;
                center += c[k] * 0.125f;
            }
            float radius = 0.0f;
            for (const glm::vec3& ck : c) radius = std::max(radius, glm::distance(ck, center));
            radius *= 1.0f + 4.0f / size;  // room for the filter's footprint at the sphere's edge
            // Snapped to whole texels, a cascade slides over the scene without its texels shimmering.
            const float texel = 2.0f * radius / size;
            const float cx = std::floor(glm::dot(center, lx) / texel) * texel;
            const float cy = std::floor(glm::dot(center, ly) / texel) * texel;
            const float tc = glm::dot(center, L);
            // Depth covers every caster of the scene, not only the slice: a caster outside the
            // slice still shades it.
            float t0 = std::min(tMinScene, tc - radius), t1 = std::max(tMaxScene, tc + radius);
            const float pad = 0.01f * (t1 - t0) + 1e-4f;
            t0 -= pad;
            t1 += pad;
            p.viewProj[i] =
                fromRows(glm::vec4(lx / radius, -cx / radius), glm::vec4(ly / radius, -cy / radius),
                         glm::vec4(L / (t1 - t0), -t0 / (t1 - t0)), glm::vec4(0, 0, 0, 1));
            p.cascadeEnds[int(i)] = end;
            p.texelWorld[int(i)] = texel;
            begin = end;
        }
        for (uint32_t i = layers; i < 4; ++i) p.cascadeEnds[int(i)] = 1e30f;
        return p;
    }
    p.farPlane = perspectiveFar(light, bounds);
    p.nearPlane = p.farPlane * 0.002f;
    if (kind == ShadowKind::Spot) {
        const glm::vec3 d = glm::normalize(light.direction);
        // The outer cone plus the filter's footprint, below 170 degrees (a wider spot's map would
        // spend its texels on the edges).
        const float half = std::min(light.outerConeAngle + 2.0f / size, glm::radians(85.0f));
        const glm::vec3 x = perpendicular(d), y = glm::cross(d, x);
        // View space looks along -Z: rows x, y, -d.
        const glm::mat4 view = fromRows(
            glm::vec4(x, -glm::dot(x, light.position)), glm::vec4(y, -glm::dot(y, light.position)),
            glm::vec4(-d, glm::dot(d, light.position)), glm::vec4(0, 0, 0, 1));
        p.viewProj[0] = projection(2.0f * half, 1.0f, p.nearPlane, p.farPlane) * view;
        p.texelWorld.x = 2.0f * std::tan(half) / size;
        return p;
    }
    for (uint32_t face = 0; face < 6; ++face)
        p.viewProj[face] = cubeFaceProjection(face, light.position, p.nearPlane, p.farPlane);
    p.texelWorld.x = 2.0f / size;  // a 90-degree face: tan(45) = 1
    return p;
}

}  // namespace fe::render

#include "render/LightVolumes.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "fe/gdi/ShaderRegistry.h"
#include "render/ShaderSlots.h"

namespace fe::render {

namespace {

// Outer angles beyond this make cones wider than their bounding sphere is useful for.
constexpr float kMaxConeAngle = 1.2f;

// Icosphere (one subdivision, 80 faces) scaled so the polytope contains the unit sphere.
std::vector<glm::vec3> icosphere() {
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    std::vector<glm::vec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (auto& p : v) p = glm::normalize(p);
    std::vector<glm::uvec3> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
    auto midpoint = [&](uint32_t a, uint32_t b) {
        auto key = std::minmax(a, b);
        auto it = mid.find(key);
        if (it != mid.end()) return it->second;
        v.push_back(glm::normalize(v[a] + v[b]));
        return mid[key] = uint32_t(v.size() - 1);
    };
    std::vector<glm::uvec3> f2;
    for (auto& tri : f) {
        uint32_t a = midpoint(tri.x, tri.y), b = midpoint(tri.y, tri.z), c = midpoint(tri.z, tri.x);
        f2.push_back({tri.x, a, c});
        f2.push_back({tri.y, b, a});
        f2.push_back({tri.z, c, b});
        f2.push_back({a, b, c});
    }
    float inradius = 1.0f;
    for (auto& tri : f2) {
        glm::vec3 n = glm::normalize(glm::cross(v[tri.y] - v[tri.x], v[tri.z] - v[tri.x]));
        inradius = std::min(inradius, std::abs(glm::dot(n, v[tri.x])));
    }
    std::vector<glm::vec3> out;
    for (auto& tri : f2)  // counter-clockwise seen from outside
        for (uint32_t i : {tri.x, tri.y, tri.z}) out.push_back(v[i] / inradius);
    return out;
}

// Cone along +Z: apex at the origin, base circle of radius 1 (circumscribed) at z = 1, closed.
std::vector<glm::vec3> cone() {
    const int n = 24;
    const float r = 1.0f / std::cos(3.14159265f / n);
    std::vector<glm::vec3> out;
    for (int i = 0; i < n; ++i) {
        float a0 = 2.0f * 3.14159265f * i / n, a1 = 2.0f * 3.14159265f * (i + 1) / n;
        glm::vec3 p0(r * std::cos(a0), r * std::sin(a0), 1.0f),
            p1(r * std::cos(a1), r * std::sin(a1), 1.0f);
        out.insert(out.end(), {glm::vec3(0.0f), p1, p0});              // side, facing outwards
        out.insert(out.end(), {glm::vec3(0.0f, 0.0f, 1.0f), p0, p1});  // cap, facing +Z
    }
    return out;
}

enum Shape : uint32_t { FullScreen = 0, Sphere = 1, Cone = 2 };

Shape shapeOf(const assets::Light& l) {
    if (l.type == assets::LightType::Directional || !(l.range > 0.0f)) return FullScreen;
    if (l.type == assets::LightType::Spot && l.outerConeAngle <= kMaxConeAngle) return Cone;
    return Sphere;
}

// As shapeOf, seen from `camera`: a volume the far plane would clip (its back faces cut away),
// or whose surface passes within the near plane's reach of the eye, is drawn full screen; the
// fragment shader's range window keeps that exact.
Shape shapeSeenFrom(const assets::Light& l, const assets::Camera* camera) {
    const Shape shape = shapeOf(l);
    if (shape == FullScreen || !camera) return shape;
    const float d = glm::distance(camera->eye(), l.position);
    // A cone reaches past its range sphere: its cap's rim lies range / cos(outer) away.
    const float extent = shape == Cone ? l.range / std::cos(l.outerConeAngle) : l.range;
    const bool farClips = !camera->infiniteFar() && d + extent > camera->zfar;
    const bool nearClips = std::abs(d - l.range) < 4.0f * camera->znear;
    return farClips || nearClips ? FullScreen : shape;
}

}  // namespace

// (The margin covers float rounding far from the origin.)
bool lightOutOfView(const assets::Light& l, const FrameConstants& seen) {
    if (l.type == assets::LightType::Directional || !(l.range > 0.0f)) return false;
    const glm::mat4& m = seen.viewProjFromEye;
    const glm::vec3 centre = l.position - glm::vec3(seen.cameraPosition);
    const glm::vec4 rowX(m[0][0], m[1][0], m[2][0], m[3][0]),
        rowY(m[0][1], m[1][1], m[2][1], m[3][1]), rowW(m[0][3], m[1][3], m[2][3], m[3][3]);
    for (const glm::vec4& p : {rowW + rowX, rowW - rowX, rowW + rowY, rowW - rowY}) {
        const float length = glm::length(glm::vec3(p));
        if (!(length > 0.0f)) return false;
        const float distance = (glm::dot(glm::vec3(p), centre) + p.w) / length;
        if (distance < -(l.range * 1.001f + 1e-3f * (1.0f + glm::length(centre)))) return true;
    }
    return false;
}

LightVolumes::Counts LightVolumes::classify(const std::vector<assets::Light>& lights) {
    Counts c;
    for (const auto& l : lights) {
        Shape s = shapeOf(l);
        (s == Sphere ? c.spheres : s == Cone ? c.cones : c.fullscreen)++;
    }
    return c;
}

LightVolumes::LightVolumes(gdi::Device& device, const std::string& fragmentShader,
                           std::vector<gdi::Format> targets)
    : objects_(device) {
    std::vector<glm::vec3> verts = {{-1, -1, 0}, {3, -1, 0}, {-1, 3, 0}};  // full-screen triangle
    sphereFirst_ = uint32_t(verts.size());
    auto s = icosphere();
    verts.insert(verts.end(), s.begin(), s.end());
    sphereCount_ = uint32_t(s.size());
    coneFirst_ = uint32_t(verts.size());
    auto c = cone();
    verts.insert(verts.end(), c.begin(), c.end());
    coneCount_ = uint32_t(c.size());
    mesh_ = objects_.add(device.createBuffer({.size = verts.size() * sizeof(glm::vec3),
                                              .usage = gdi::BufferUsage::Vertex,
                                              .debugName = "light volume meshes"},
                                             gdi::bytesOf(verts)));

    vs_ = objects_.add(device.createShader(
        {.stage = gdi::ShaderStage::Vertex, .binary = shaders::find("scene/light_volume.vert")}));
    fs_ = objects_.add(device.createShader(
        {.stage = gdi::ShaderStage::Fragment, .binary = shaders::find(fragmentShader)}));
    std::vector<gdi::BlendTargetState> blend(targets.size(), gdi::BlendTargetState{
                                                                 .enable = true,
                                                                 .srcColor = gdi::BlendFactor::One,
                                                                 .dstColor = gdi::BlendFactor::One,
                                                                 .srcAlpha = gdi::BlendFactor::One,
                                                                 .dstAlpha = gdi::BlendFactor::One,
                                                             });
    gdi::GraphicsPipelineDesc d{
        .vertexShader = vs_,
        .fragmentShader = fs_,
        .vertexBuffers = {{.stride = 12, .attributes = {{0, gdi::VertexFormat::Float3, 0}}},
                          {.stride = 8,
                           .perInstance = true,
                           .attributes = {{1, gdi::VertexFormat::UInt32, 0},
                                          {2, gdi::VertexFormat::UInt32, 4}}}},
        // Back faces only: each covered pixel is shaded once, also with the eye inside a volume.
        .raster = {.cullMode = gdi::CullMode::Front},
        .blend = blend,
        .colorFormats = targets,
        .debugName = "light volumes",
    };
    volumePipeline_ = objects_.add(device.createGraphicsPipeline(d));
    d.raster.cullMode = gdi::CullMode::None;
    d.debugName = "full-screen lights";
    fullscreenPipeline_ = objects_.add(device.createGraphicsPipeline(d));
}

void LightVolumes::draw(gdi::CommandList& cmd, CommandQueue& queue, const GpuScene& scene,
                        const UploadAllocation& frame, const FrameConstants& seen) {
    drawRange(cmd, queue, scene, frame, seen, 0, scene.unshadowedLightCount());
}

void LightVolumes::drawRange(gdi::CommandList& cmd, CommandQueue& queue, const GpuScene& scene,
                             const UploadAllocation& frame, const FrameConstants& seen,
                             uint32_t first, uint32_t count) {
    const auto& lights = scene.lights();
    const uint32_t end =
        std::min<uint32_t>({first + count, scene.lightCount(), uint32_t(lights.size())});
    if (first >= end) return;
    const assets::Camera* camera = scene.scene().camera ? &*scene.scene().camera : nullptr;
    // Instances grouped by shape: spheres, cones, full screen; the lights out of view left out
    // (with many lights most of a volume pass's work is vertices and triangles, whatever the
    // image's size: 65,536 icospheres took 2.6 s a frame on lavapipe at 8x6 pixels).
    std::vector<glm::uvec2> instances;
    std::vector<Shape> shapes(end - first);
    Counts n;
    for (uint32_t i = first; i < end; ++i)
        shapes[i - first] =
            lightOutOfView(lights[i], seen) ? Shape(~0u) : shapeSeenFrom(lights[i], camera);
    for (Shape shape : {Sphere, Cone, FullScreen})
        for (uint32_t i = first; i < end; ++i)
            if (shapes[i - first] == shape) {
                instances.push_back({i, uint32_t(shape)});
                (shape == Sphere ? n.spheres : shape == Cone ? n.cones : n.fullscreen)++;
            }
    if (instances.empty()) return;
    UploadAllocation inst = queue.upload(gdi::bytesOf(instances));

    cmd.setUniformBuffer(kSlotFrame, frame.buffer, frame.offset, frame.size);
    cmd.setStorageBuffer(kSlotLights, scene.lightBuffer());
    cmd.setVertexBuffer(0, mesh_);
    cmd.setVertexBuffer(1, inst.buffer, inst.offset);
    if (n.spheres + n.cones) {
        cmd.setPipeline(volumePipeline_);
        if (n.spheres) cmd.draw(sphereCount_, n.spheres, sphereFirst_, 0);
        if (n.cones) cmd.draw(coneCount_, n.cones, coneFirst_, n.spheres);
    }
    if (n.fullscreen) {
        cmd.setPipeline(fullscreenPipeline_);
        cmd.draw(3, n.fullscreen, 0, n.spheres + n.cones);
    }
}

}  // namespace fe::render

#include "assets/BuiltinScenes.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

#include "assets/Animation.h"
#include "assets/Geometry.h"

namespace fe::assets {

namespace {

constexpr double kPi = 3.14159265358979323846;

float radians(float degrees) { return degrees * float(kPi / 180.0); }

// Integer mixer (multiply / xor-shift rounds): any fixed bijection with good avalanche works;
// what matters is that light i gets the same numbers on every machine and every run.
uint32_t mix(uint32_t x) {
    x ^= x >> 15;
    x *= 0x2c1b3c6dU;
    x ^= x >> 12;
    x *= 0x297a2d39U;
    x ^= x >> 15;
    return x;
}

// Uniform in [0, 1) from light index and a per-quantity stream number.
float unit(uint32_t light, uint32_t stream) {
    uint32_t h = mix(mix(light * 0x9E3779B1U + 0x5EED1234U) ^ (stream * 0x85EBCA77U));
    return float(h >> 8) * (1.0f / 16777216.0f);
}

glm::vec3 hsv(float h, float s, float v) {
    float h6 = h * 6.0f;
    int i = int(h6) % 6;
    float f = h6 - std::floor(h6);
    float p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
    switch (i) {
        case 0:
            return {v, t, p};
        case 1:
            return {q, v, p};
        case 2:
            return {p, v, t};
        case 3:
            return {p, q, v};
        case 4:
            return {t, p, v};
        default:
            return {v, p, q};
    }
}

Material makeMaterial(const std::string& name, const glm::vec4& base, float metallic,
                      float roughness) {
    Material m;
    m.name = name;
    m.baseColorFactor = base;
    m.metallic = metallic;
    m.roughness = roughness;
    return m;
}

void addInstance(Scene& s, uint32_t mesh, const glm::mat4& world, std::string name) {
    MeshInstance i;
    i.meshIndex = mesh;
    i.world = world;
    i.mirrored = glm::determinant(glm::mat3(world)) < 0.0f;
    i.name = std::move(name);
    s.instances.push_back(std::move(i));
}

// A mesh of one primitive, its bounds computed; returns its index.
uint32_t addMesh(Scene& s, const char* name, Primitive p) {
    Mesh out;
    out.name = name;
    out.primitives.push_back(std::move(p));
    computeBounds(out);
    s.meshes.push_back(std::move(out));
    return uint32_t(s.meshes.size() - 1);
}

Light directional(const std::string& name, const glm::vec3& travel, const glm::vec3& color,
                  float lux) {
    Light l;
    l.name = name;
    l.type = LightType::Directional;
    l.direction = glm::normalize(travel);
    l.color = color;
    l.intensity = lux;
    return l;
}

Light point(const std::string& name, const glm::vec3& pos, const glm::vec3& color, float cd,
            float range) {
    Light l;
    l.name = name;
    l.type = LightType::Point;
    l.position = pos;
    l.color = color;
    l.intensity = cd;
    l.range = range;
    return l;
}

Scene makeSpheres(const BuiltinOptions& o) {
    const uint32_t n = std::clamp(o.sphereGrid, 2u, 16u);
    const float spacing = 1.0f, radius = 0.4f;
    const float half = float(n - 1) * 0.5f;
    Scene s;
    s.name = "spheres";
    const Primitive sphere = makeUVSphere(radius, 48, 24, 0);
    for (uint32_t row = 0; row < n; ++row) {
        for (uint32_t col = 0; col < n; ++col) {
            float roughness = float(col) / float(n - 1);
            float metallic = float(row) / float(n - 1);
            uint32_t mat = uint32_t(s.materials.size());
            s.materials.push_back(
                makeMaterial("m" + std::to_string(row) + "_r" + std::to_string(col),
                             glm::vec4(0.9f, 0.3f, 0.1f, 1.0f), metallic, roughness));
            Mesh mesh;
            mesh.name = "sphere_" + std::to_string(row) + "_" + std::to_string(col);
            mesh.primitives.push_back(sphere);
            mesh.primitives.back().material = mat;
            computeBounds(mesh);
            uint32_t mi = uint32_t(s.meshes.size());
            s.meshes.push_back(std::move(mesh));
            glm::vec3 pos((float(col) - half) * spacing, (half - float(row)) * spacing, 0.0f);
            addInstance(s, mi, glm::translate(glm::mat4(1.0f), pos), s.meshes[mi].name);
        }
    }
    s.lights.push_back(directional("key", {0.5f, -0.6f, -1.0f}, glm::vec3(1.0f), 2.0f));
    s.lights.push_back(directional("fill", {-0.6f, -0.2f, -1.0f}, {0.8f, 0.9f, 1.0f}, 0.5f));
    s.lights.push_back(point("point", {2.0f, 3.0f, 4.0f}, glm::vec3(1.0f), 30.0f, 0.0f));
    const float yfov = radians(45.0f);
    // The sphere fronts (z = radius) are the closest points: fit the grid's half extent plus a
    // 10% margin there.
    const float dist = radius + (half * spacing + radius) * 1.1f / std::tan(yfov * 0.5f);
    s.camera = Camera::lookAlong({0.0f, 0.0f, dist}, {0, 0, -1}, {0, 1, 0}, yfov, 0.1f, 100.0f);
    s.camera->name = "spheres";
    return s;
}

Scene makeLights(const BuiltinOptions& o) {
    Scene s;
    s.name = "lights";
    s.materials.push_back(makeMaterial("grey", glm::vec4(0.8f, 0.8f, 0.8f, 1.0f), 0.0f, 0.5f));
    Mesh cube;
    cube.name = "cube";
    cube.primitives.push_back(makeCube(1.0f, 0));
    computeBounds(cube);
    s.meshes.push_back(std::move(cube));
    for (int iy = 0; iy < 11; ++iy) {
        for (int ix = 0; ix < 11; ++ix) {
            glm::vec3 c(float(-15 + 3 * ix), float(-15 + 3 * iy), 0.0f);
            addInstance(s, 0, glm::translate(glm::mat4(1.0f), c),
                        "cube_" + std::to_string(ix) + "_" + std::to_string(iy));
        }
    }
    s.lights = lightsSceneLights(o.lights, o.frame);
    s.camera =
        Camera::lookAlong({0.0f, 0.0f, -15.0f}, {0, 0, 1}, {0, 1, 0}, radians(60.0f), 0.1f, 100.0f);
    s.camera->name = "lights";
    return s;
}

Scene makePlane() {
    Scene s;
    s.name = "plane";
    s.materials.push_back(makeMaterial("grey", glm::vec4(0.5f, 0.5f, 0.5f, 1.0f), 0.0f, 0.5f));
    Mesh quad;
    quad.name = "quad";
    quad.primitives.push_back(makeQuad(1.0f, 1.0f, 0));
    computeBounds(quad);
    s.meshes.push_back(std::move(quad));
    addInstance(s, 0, glm::mat4(1.0f), "quad");
    s.lights.push_back(point("point", {0.0f, 0.0f, 1.0f}, glm::vec3(1.0f), 1.0f, 0.0f));
    s.camera =
        Camera::lookAlong({0.0f, 0.0f, 3.0f}, {0, 0, -1}, {0, 1, 0}, radians(45.0f), 0.1f, 100.0f);
    s.camera->name = "plane";
    return s;
}

Scene makeTriangle() {
    Scene s;
    s.name = "triangle";
    s.materials.push_back(makeMaterial("white", glm::vec4(1.0f), 0.0f, 1.0f));
    Primitive p;
    p.material = 0;
    const glm::vec3 pos[3] = {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
    for (int i = 0; i < 3; ++i) {
        Vertex v;
        v.position = pos[i];
        v.normal = {0, 0, 1};
        v.uv0 = {(pos[i].x + 1.0f) * 0.5f, (1.0f - pos[i].y) * 0.5f};
        p.vertices.push_back(v);
    }
    p.indices = {0, 1, 2};
    generateTangents(p);
    Mesh m;
    m.name = "triangle";
    m.primitives.push_back(std::move(p));
    computeBounds(m);
    s.meshes.push_back(std::move(m));
    addInstance(s, 0, glm::mat4(1.0f), "triangle");
    s.lights.push_back(directional("sun", {0, 0, -1}, glm::vec3(1.0f), 1.0f));
    s.camera =
        Camera::lookAlong({0.0f, 0.0f, 3.0f}, {0, 0, -1}, {0, 1, 0}, radians(45.0f), 0.1f, 100.0f);
    s.camera->name = "triangle";
    return s;
}

Light spot(const std::string& name, const glm::vec3& pos, const glm::vec3& target,
           const glm::vec3& color, float cd, float innerDegrees, float outerDegrees) {
    Light l = point(name, pos, color, cd, 0.0f);
    l.type = LightType::Spot;
    l.direction = glm::normalize(target - pos);
    l.innerConeAngle = radians(innerDegrees);
    l.outerConeAngle = radians(outerDegrees);
    return l;
}

Scene makeShadows() {
    Scene s;
    s.name = "shadows";
    auto mesh = [&](const char* name, Primitive p, Material m) {
        p.material = uint32_t(s.materials.size());
        s.materials.push_back(std::move(m));
        return addMesh(s, name, std::move(p));
    };
    const uint32_t ground =
        mesh("ground", makeQuad(5.0f, 5.0f, 0),
             makeMaterial("ground", glm::vec4(0.5f, 0.5f, 0.5f, 1.0f), 0.0f, 0.7f));
    addInstance(s, ground, glm::rotate(glm::mat4(1.0f), radians(-90.0f), glm::vec3(1, 0, 0)),
                "ground");
    const uint32_t sphere =
        mesh("sphere", makeUVSphere(0.6f, 48, 24, 0),
             makeMaterial("gold", glm::vec4(1.0f, 0.78f, 0.34f, 1.0f), 1.0f, 0.3f));
    addInstance(s, sphere, glm::translate(glm::mat4(1.0f), {-1.3f, 0.6f, 0.2f}), "sphere");
    const uint32_t cube = mesh("cube", makeCube(0.45f, 0),
                               makeMaterial("red", glm::vec4(0.7f, 0.2f, 0.15f, 1.0f), 0.0f, 0.5f));
    addInstance(s, cube,
                glm::rotate(glm::translate(glm::mat4(1.0f), {1.1f, 0.45f, -0.4f}), radians(30.0f),
                            glm::vec3(0, 1, 0)),
                "cube");
    const uint32_t pole =
        mesh("pole", makeCube(1.0f, 0),
             makeMaterial("white", glm::vec4(0.8f, 0.8f, 0.8f, 1.0f), 0.0f, 0.4f));
    addInstance(
        s, pole,
        glm::scale(glm::translate(glm::mat4(1.0f), {0.2f, 1.0f, 1.3f}), {0.06f, 1.0f, 0.06f}),
        "pole");
    s.lights.push_back(directional("sun", {-0.5f, -1.0f, -0.35f}, {1.0f, 0.95f, 0.85f}, 2.5f));
    s.lights.push_back(spot("spot", {2.6f, 3.2f, 2.4f}, {0.0f, 0.0f, 0.0f}, {0.9f, 0.95f, 1.0f},
                            60.0f, 20.0f, 30.0f));
    s.lights.push_back(point("lamp", {-2.4f, 1.6f, 1.8f}, {1.0f, 0.6f, 0.3f}, 6.0f, 0.0f));
    const glm::vec3 eye(0.0f, 3.0f, 6.0f);
    s.camera = Camera::lookAlong(eye, glm::vec3(0.0f, 1.4f, 0.0f) - eye, {0, 1, 0}, radians(45.0f),
                                 0.1f, 100.0f);
    s.camera->name = "shadows";
    s.showsShadows = true;
    return s;
}

// builtin:particles: builtin:shadows' ground and objects with a fire (additive, emitting) by the
// cube and a column of smoke (alpha-blended, lit, sorted) rising from behind the sphere.
Scene makeParticles() {
    Scene s = makeShadows();
    s.name = "particles";
    ParticleEmitter fire;
    fire.name = "fire";
    fire.position = {0.0f, 0.05f, 0.6f};
    fire.velocity = {0.0f, 1.2f, 0.0f};
    fire.spread = 0.35f;
    fire.rate = 120.0f;
    fire.lifetime = 1.0f;
    fire.gravity = {0.0f, 0.4f, 0.0f};  // buoyant
    fire.sizeStart = 0.12f, fire.sizeEnd = 0.03f;
    fire.colorStart = {6.0f, 2.2f, 0.5f, 1.0f}, fire.colorEnd = {1.5f, 0.2f, 0.05f, 0.0f};
    fire.blend = ParticleEmitter::Blend::Additive;
    ParticleEmitter smoke;
    smoke.name = "smoke";
    smoke.position = {-1.3f, 1.1f, -0.6f};
    smoke.velocity = {0.15f, 0.7f, 0.0f};
    smoke.spread = 0.25f;
    smoke.rate = 60.0f;
    smoke.lifetime = 3.0f;
    smoke.gravity = {0.05f, 0.05f, 0.0f};
    smoke.sizeStart = 0.12f, smoke.sizeEnd = 0.45f;
    smoke.colorStart = {0.55f, 0.55f, 0.55f, 0.7f}, smoke.colorEnd = {0.4f, 0.4f, 0.42f, 0.0f};
    smoke.blend = ParticleEmitter::Blend::Alpha;
    s.emitters = {fire, smoke};
    s.camera->name = "particles";
    return s;
}

// builtin:atrium (BuiltinScenes.h has the layout): a deep two-storey arcade whose near columns
// stand in front of far walls, so a screen tile spans a wide range of depths: what clustered
// shading gains over per-tile lists. Boxes and quads only, so the CPU reference is exact.
Scene makeAtrium(const BuiltinOptions& o) {
    Scene s;
    s.name = "atrium";
    auto material = [&](Material m) {
        s.materials.push_back(std::move(m));
        return uint32_t(s.materials.size() - 1);
    };
    const uint32_t stone =
        material(makeMaterial("stone", glm::vec4(0.62f, 0.6f, 0.56f, 1.0f), 0.0f, 0.8f));
    const uint32_t plaster =
        material(makeMaterial("plaster", glm::vec4(0.78f, 0.72f, 0.62f, 1.0f), 0.0f, 0.9f));
    const uint32_t marble =
        material(makeMaterial("marble", glm::vec4(0.85f, 0.85f, 0.82f, 1.0f), 0.0f, 0.35f));
    const uint32_t box = addMesh(s, "box", makeCube(1.0f, 0));  // scaled per instance: half extents
    const uint32_t quad = addMesh(s, "quad", makeQuad(1.0f, 1.0f, 0));
    auto addBox = [&](uint32_t mat, const glm::vec3& centre, const glm::vec3& half,
                      const std::string& name) {
        // One mesh per material: the primitive's material is the instance's here.
        Mesh m = s.meshes[box];
        m.primitives[0].material = mat;
        m.name = name;
        s.meshes.push_back(std::move(m));
        addInstance(s, uint32_t(s.meshes.size() - 1),
                    glm::scale(glm::translate(glm::mat4(1.0f), centre), half), name);
    };
    constexpr float kHalfWidth = 6.0f, kLength = 60.0f, kStorey = 4.0f, kHeight = 8.0f, kBay = 4.0f;
    addBox(stone, {0.0f, -0.1f, -kLength / 2}, {kHalfWidth, 0.1f, kLength / 2}, "floor");
    addBox(plaster, {-kHalfWidth - 0.1f, kHeight / 2, -kLength / 2},
           {0.1f, kHeight / 2, kLength / 2}, "wall_left");
    addBox(plaster, {kHalfWidth + 0.1f, kHeight / 2, -kLength / 2},
           {0.1f, kHeight / 2, kLength / 2}, "wall_right");
    addBox(plaster, {0.0f, kHeight / 2, -kLength - 0.1f}, {kHalfWidth, kHeight / 2, 0.1f},
           "wall_end");
    for (float side : {-1.0f, 1.0f}) {
        const std::string tag = side < 0 ? "left" : "right";
        // The gallery floor of the upper storey, and the beam along the arcade under it.
        addBox(stone, {side * 4.75f, kStorey, -kLength / 2}, {1.25f, 0.15f, kLength / 2},
               "gallery_" + tag);
        addBox(marble, {side * 3.5f, kStorey - 0.35f, -kLength / 2}, {0.3f, 0.2f, kLength / 2},
               "beam_" + tag);
        for (int bay = 0; bay < int(kLength / kBay) - 1; ++bay) {
            const float z = -kBay * float(bay + 1);
            const std::string at = tag + "_" + std::to_string(bay);
            addBox(marble, {side * 3.5f, (kStorey - 0.55f) / 2, z},
                   {0.3f, (kStorey - 0.55f) / 2, 0.3f}, "column_" + at);
            addBox(marble, {side * 3.5f, kStorey + 0.15f + (kHeight - kStorey - 0.15f) / 2, z},
                   {0.22f, (kHeight - kStorey - 0.15f) / 2, 0.22f}, "upper_column_" + at);
        }
    }
    // Translucent hangings: banners between the upper columns, every other bay, blended and seen
    // from both sides (drawn in the translucent pass, lit with the light clusters' lists).
    if (o.hangings) {
        const uint32_t red = material([] {
            Material m =
                makeMaterial("banner_red", glm::vec4(0.8f, 0.12f, 0.1f, 0.55f), 0.0f, 0.9f);
            m.alphaMode = AlphaMode::Blend;
            m.doubleSided = true;
            return m;
        }());
        const uint32_t blue = material([] {
            Material m =
                makeMaterial("banner_blue", glm::vec4(0.1f, 0.2f, 0.75f, 0.55f), 0.0f, 0.9f);
            m.alphaMode = AlphaMode::Blend;
            m.doubleSided = true;
            return m;
        }());
        for (float side : {-1.0f, 1.0f})
            for (int bay = 0; bay < int(kLength / kBay) - 2; bay += 2) {
                Mesh m = s.meshes[quad];
                m.primitives[0].material = (bay / 2) % 2 ? blue : red;
                m.name = "banner";
                s.meshes.push_back(std::move(m));
                // The quad faces +Z; turned to face the axis, 1.2 m wide and 2.4 m tall.
                const glm::mat4 world = glm::scale(
                    glm::rotate(
                        glm::translate(glm::mat4(1.0f), {side * 3.3f, 6.2f, -kBay * (bay + 1.5f)}),
                        radians(-90.0f * side), glm::vec3(0, 1, 0)),
                    {1.6f, 1.2f, 1.0f});
                addInstance(s, uint32_t(s.meshes.size() - 1), world,
                            "banner_" + std::to_string(bay) + (side < 0 ? "_left" : "_right"));
            }
    }
    s.lights = atriumLights(o.lights);
    s.camera = Camera::lookAlong({0.0f, 1.7f, 1.5f}, {0.0f, -0.05f, -1.0f}, {0, 1, 0},
                                 radians(60.0f), 0.1f, 100.0f);
    s.camera->name = "atrium";
    return s;
}

// "crowd": skinned, morphed reeds swaying (the mesh deformation's stress case; BuiltinScenes.h).
constexpr uint32_t kReedRings = 32, kReedSegments = 16, kReedJoints = 4;
constexpr float kReedHeight = 2.0f, kReedRadius = 0.08f;

Primitive makeReed(uint32_t material) {
    Primitive p;
    p.material = material;
    MorphTarget bulge;
    for (uint32_t r = 0; r <= kReedRings; ++r) {
        const float v = float(r) / kReedRings, y = v * kReedHeight;
        // Linear blend between the two joints around this height (joints every height / kReedJoints).
        const float j = std::min(y / (kReedHeight / kReedJoints), float(kReedJoints - 1) - 1e-4f);
        const uint32_t j0 = uint32_t(j);
        const float w1 = j - float(j0);
        for (uint32_t k = 0; k <= kReedSegments; ++k) {
            const float a = 2.0f * float(kPi) * float(k) / kReedSegments;
            const glm::vec3 n(std::cos(a), 0.0f, std::sin(a));
            Vertex vx;
            vx.position = n * kReedRadius * (1.0f - 0.5f * v) + glm::vec3(0.0f, y, 0.0f);
            vx.normal = n;
            vx.tangent = glm::vec4(-n.z, 0.0f, n.x, 1.0f);
            vx.uv0 = glm::vec2(float(k) / kReedSegments, 1.0f - v);
            p.vertices.push_back(vx);
            SkinInfluences inf;
            inf.joints[0] = glm::uvec4(j0, j0 + 1, 0, 0);
            inf.weights[0] = glm::vec4(1.0f - w1, w1, 0.0f, 0.0f);
            p.skin.push_back(inf);
            bulge.position.push_back(
                n * (kReedRadius * std::sin(float(kPi) * v)));  // fattest halfway up
        }
    }
    for (uint32_t r = 0; r < kReedRings; ++r)
        for (uint32_t k = 0; k < kReedSegments; ++k) {
            const uint32_t a = r * (kReedSegments + 1) + k, b = a + kReedSegments + 1;
            p.indices.insert(p.indices.end(), {a, b, a + 1, a + 1, b, b + 1});
        }
    p.targets.push_back(std::move(bulge));
    computeBounds(p);
    return p;
}

Scene makeCrowd(const BuiltinOptions& o) {
    Scene s;
    s.name = "crowd";
    const uint32_t n = std::max(1u, o.crowd), side = uint32_t(std::ceil(std::sqrt(double(n))));
    const float spacing = 0.5f, extent = spacing * float(side - 1);
    s.materials.push_back(makeMaterial("reed", glm::vec4(0.35f, 0.6f, 0.2f, 1.0f), 0.0f, 0.6f));
    Mesh mesh;
    mesh.name = "reed";
    mesh.primitives.push_back(makeReed(0));
    computeBounds(mesh);
    mesh.weights = {0.0f};
    s.meshes.push_back(std::move(mesh));
    Animation sway;
    sway.name = "sway";
    constexpr uint32_t kKeys = 9;
    constexpr float kPeriod = 2.0f;
    for (uint32_t i = 0; i < n; ++i) {
        const float phase = 2.0f * float(kPi) * unit(i, 20);
        const uint32_t root = uint32_t(s.nodes.size());
        Node r;
        r.name = "reed " + std::to_string(i);
        r.translation =
            glm::vec3(float(i % side) * spacing - 0.5f * extent, 0.0f, -float(i / side) * spacing);
        s.nodes.push_back(r);
        Skin skin;
        for (uint32_t j = 0; j < kReedJoints; ++j) {
            Node joint;
            joint.name = r.name + " joint " + std::to_string(j);
            joint.parent = int32_t(j == 0 ? root : s.nodes.size() - 1);
            joint.translation = glm::vec3(0.0f, j == 0 ? 0.0f : kReedHeight / kReedJoints, 0.0f);
            skin.joints.push_back(uint32_t(s.nodes.size()));
            skin.inverseBindMatrices.push_back(glm::translate(
                glm::mat4(1.0f), glm::vec3(0.0f, -float(j) * kReedHeight / kReedJoints, 0.0f)));
            // Each joint bends about Z and X by up to 0.25 rad, out of phase up the chain.
            AnimationSampler bend{.interpolation = Interpolation::Linear, .width = 4};
            for (uint32_t k = 0; k < kKeys; ++k) {
                const float t = kPeriod * float(k) / float(kKeys - 1),
                            a = phase + 2.0f * float(kPi) * t / kPeriod + 0.6f * float(j);
                const glm::quat q = glm::angleAxis(0.25f * std::sin(a), glm::vec3(0, 0, 1)) *
                                    glm::angleAxis(0.12f * std::cos(a), glm::vec3(1, 0, 0));
                bend.times.push_back(t);
                bend.values.insert(bend.values.end(), {q.x, q.y, q.z, q.w});
            }
            sway.channels.push_back({.sampler = uint32_t(sway.samplers.size()),
                                     .node = skin.joints.back(),
                                     .path = AnimationPath::Rotation});
            sway.samplers.push_back(std::move(bend));
            s.nodes.push_back(joint);
        }
        s.skins.push_back(std::move(skin));
        Node body;
        body.name = r.name + " mesh";
        body.parent = int32_t(root);
        s.nodes.push_back(body);
        // The bulge breathes once a period.
        AnimationSampler breathe{.interpolation = Interpolation::Linear, .width = 1};
        for (uint32_t k = 0; k < kKeys; ++k) {
            const float t = kPeriod * float(k) / float(kKeys - 1);
            breathe.times.push_back(t);
            breathe.values.push_back(0.5f +
                                     0.5f * std::sin(phase + 2.0f * float(kPi) * t / kPeriod));
        }
        sway.channels.push_back({.sampler = uint32_t(sway.samplers.size()),
                                 .node = uint32_t(s.nodes.size() - 1),
                                 .path = AnimationPath::Weights});
        sway.samplers.push_back(std::move(breathe));
        MeshInstance inst;
        inst.meshIndex = 0;
        inst.node = int32_t(s.nodes.size() - 1);
        inst.skin = int32_t(s.skins.size() - 1);
        inst.name = body.name;
        s.instances.push_back(inst);
    }
    sway.duration = kPeriod;
    s.animations.push_back(std::move(sway));
    Mesh ground;
    ground.name = "ground";
    Primitive quad = makeQuad(0.5f * extent + 1.0f, 0.5f * float(side) * spacing + 1.0f, 1);
    for (Vertex& v : quad.vertices)
        v.position = glm::vec3(v.position.x, 0.0f, -v.position.y - 0.5f * extent);
    for (Vertex& v : quad.vertices)
        v.normal = glm::vec3(0, 1, 0), v.tangent = glm::vec4(1, 0, 0, 1);
    ground.primitives.push_back(quad);
    computeBounds(ground);
    s.meshes.push_back(std::move(ground));
    s.materials.push_back(makeMaterial("soil", glm::vec4(0.3f, 0.25f, 0.2f, 1.0f), 0.0f, 0.9f));
    s.instances.push_back({.meshIndex = 1, .name = "ground"});
    Light sun;
    sun.name = "sun";
    sun.type = LightType::Directional;
    sun.intensity = 2.5f;
    sun.direction = glm::normalize(glm::vec3(-0.4f, -1.0f, -0.5f));
    s.lights.push_back(sun);
    s.lights.push_back(
        point("fill", glm::vec3(0.0f, 4.0f, 3.0f), glm::vec3(0.8f, 0.9f, 1.0f), 8.0f, 0.0f));
    const float d = 0.5f * extent + 2.0f;
    s.camera = Camera::lookAlong({0.0f, 1.2f + 0.5f * d, d + 1.0f}, {0.0f, -0.45f, -1.0f},
                                 {0, 1, 0}, radians(50.0f), 0.1f, 200.0f);
    s.camera->name = "crowd";
    poseScene(s, {});
    return s;
}

}  // namespace

std::vector<Light> atriumLights(uint32_t count) {
    std::vector<Light> out;
    out.reserve(count);
    for (uint32_t i = 0; i < count; ++i) {
        // Spread through the whole hall: across, up both storeys, and along its depth.
        const glm::vec3 pos(-5.5f + 11.0f * unit(i, 10), 0.3f + 7.2f * unit(i, 11),
                            -1.0f - 57.0f * unit(i, 12));
        out.push_back(
            point("light" + std::to_string(i), pos, hsv(unit(i, 13), 0.6f, 1.0f), 3.0f, 2.5f));
    }
    return out;
}

const std::vector<std::string>& builtinSceneNames() {
    static const std::vector<std::string> names = {"spheres", "lights",    "plane",  "triangle",
                                                   "shadows", "particles", "atrium", "crowd"};
    return names;
}

std::vector<Light> lightsSceneLights(uint32_t count, uint32_t frame) {
    std::vector<Light> out;
    out.reserve(count);
    const double baseSpeed = 2.0 * kPi / 600.0;
    for (uint32_t i = 0; i < count; ++i) {
        float cx = -14.0f + 28.0f * unit(i, 0);
        float cy = -14.0f + 28.0f * unit(i, 1);
        float z = -2.0f + 4.0f * unit(i, 2);
        double phase = 2.0 * kPi * unit(i, 3);
        double speed = baseSpeed * (0.5 + unit(i, 4)) * (unit(i, 5) < 0.5f ? -1.0 : 1.0);
        // fmod keeps the angle small, so precision does not decay with the frame number.
        double angle = std::fmod(phase + speed * double(frame), 2.0 * kPi);
        glm::vec3 pos(cx + float(std::cos(angle)), cy + float(std::sin(angle)), z);
        out.push_back(
            point("light" + std::to_string(i), pos, hsv(unit(i, 6), 0.7f, 1.0f), 4.0f, 2.0f));
    }
    return out;
}

Scene makeBuiltinScene(std::string_view name, const BuiltinOptions& options) {
    Scene s;
    if (name == "spheres") {
        s = makeSpheres(options);
    } else if (name == "lights") {
        s = makeLights(options);
    } else if (name == "plane") {
        s = makePlane();
    } else if (name == "triangle") {
        s = makeTriangle();
    } else if (name == "shadows") {
        s = makeShadows();
    } else if (name == "particles") {
        s = makeParticles();
    } else if (name == "atrium") {
        s = makeAtrium(options);
    } else if (name == "crowd") {
        s = makeCrowd(options);
    } else {
        std::string valid;
        for (const auto& n : builtinSceneNames()) valid += (valid.empty() ? "" : ", ") + n;
        throw AssetError("unknown builtin scene '" + std::string(name) + "' (valid: " + valid +
                         ")");
    }
    // Every builtin brings its own camera and lights; only the bounds are derived.
    finalizeScene(s, false, false);
    return s;
}

Scene loadScene(std::string_view spec, const LoadOptions& load, const BuiltinOptions& builtin) {
    constexpr std::string_view prefix = "builtin:";
    if (spec.substr(0, prefix.size()) == prefix)
        return makeBuiltinScene(spec.substr(prefix.size()), builtin);
    if (spec.empty())
        throw AssetError("empty scene name (expected 'builtin:NAME' or a glTF file path)");
    return loadGltf(std::string(spec), load);
}

}  // namespace fe::assets

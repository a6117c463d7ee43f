#include "assets/Animation.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <functional>

#include "assets/AssetError.h"

namespace fe::assets {

namespace {

// Index of the key interval holding t: times[k] <= t < times[k + 1] (t strictly inside).
size_t keyBefore(const std::vector<float>& times, float t) {
    return size_t(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
}

glm::quat toQuat(const float* v) { return glm::quat(v[3], v[0], v[1], v[2]); }
void fromQuat(const glm::quat& q, float* out) {
    out[0] = q.x;
    out[1] = q.y;
    out[2] = q.z;
    out[3] = q.w;
}

// Spherical linear interpolation along the shorter arc (glTF Appendix C's slerp); nearly
// parallel quaternions are interpolated linearly and normalised, where slerp divides by ~0.
glm::quat slerpShortest(glm::quat a, glm::quat b, float u) {
    float d = glm::dot(a, b);
    if (d < 0.0f) {
        b = -b;
        d = -d;
    }
    if (d > 0.9995f) return glm::normalize(a * (1.0f - u) + b * u);
    const float angle = std::acos(std::min(d, 1.0f));
    const float s = std::sin(angle);
    return a * (std::sin((1.0f - u) * angle) / s) + b * (std::sin(u * angle) / s);
}

std::string listNames(size_t count, const std::function<std::string(size_t)>& name) {
    if (count == 0) return "it has none";
    std::string s = "it has";
    for (size_t i = 0; i < count; ++i)
        s += (i ? ", " : " ") + std::to_string(i) + " '" + name(i) + "'";
    return s;
}

int32_t findByIndexOrName(size_t count, const std::function<std::string(size_t)>& name,
                          const std::string& what, const std::string& key) {
    if (!key.empty() &&
        std::all_of(key.begin(), key.end(), [](char c) { return c >= '0' && c <= '9'; })) {
        if (key.size() < 9 && std::stoul(key) < count) return int32_t(std::stoul(key));
    } else {
        for (size_t i = 0; i < count; ++i)
            if (name(i) == key) return int32_t(i);
    }
    throw AssetError("no " + what + " '" + key + "' in the scene: " + listNames(count, name));
}

// World transforms of every node, parents before children whatever the file's order.
void computeWorlds(Scene& scene, const std::vector<glm::mat4>& locals) {
    std::vector<char> done(scene.nodes.size(), 0);
    std::vector<uint32_t> chain;
    for (size_t i = 0; i < scene.nodes.size(); ++i) {
        for (int32_t n = int32_t(i); n >= 0 && !done[size_t(n)];
             n = scene.nodes[size_t(n)].parent) {
            chain.push_back(uint32_t(n));
            if (chain.size() > scene.nodes.size())
                throw AssetError("poseScene: the node hierarchy has a cycle");
        }
        for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
            const Node& node = scene.nodes[*it];
            const glm::mat4 parent =
                node.parent >= 0 ? scene.nodes[size_t(node.parent)].world : glm::mat4(1.0f);
            scene.nodes[*it].world = parent * locals[*it];
            done[*it] = 1;
        }
        chain.clear();
    }
}

// A camera hung from a node: at the node's origin, looking along its -Z with its +Y up, scale removed.
void poseCamera(Camera& camera, const glm::mat4& world) {
    const glm::vec3 back(world[2]), up(world[1]);
    if (!(glm::length(glm::cross(up, back)) > 1e-12f))
        return;  // degenerate at this instant: keep the last pose
    const Camera moved =
        Camera::lookAlong(glm::vec3(world[3]), -back, up, camera.yfov, camera.znear, camera.zfar);
    camera.worldFromView = moved.worldFromView;
}

bool sameCamera(const Camera& a, const Camera& b) {
    return a.worldFromView == b.worldFromView && a.yfov == b.yfov && a.znear == b.znear &&
           a.zfar == b.zfar && a.aspectRatio == b.aspectRatio && a.orthographic == b.orthographic &&
           a.node == b.node;
}

}  // namespace

int32_t findAnimation(const Scene& scene, const std::string& key) {
    if (key == "all" && std::none_of(scene.animations.begin(), scene.animations.end(),
                                     [](const Animation& a) { return a.name == "all"; }))
        return kAllAnimations;
    return findByIndexOrName(
        scene.animations.size(), [&](size_t i) { return scene.animations[i].name; }, "animation",
        key);
}

int32_t findCamera(const Scene& scene, const std::string& key) {
    return findByIndexOrName(
        scene.cameras.size(), [&](size_t i) { return scene.cameras[i].name; }, "camera", key);
}

void sampleAnimation(const AnimationSampler& s, float t, bool rotation, float* out) {
    const uint32_t w = s.width;
    const size_t keys = s.times.size();
    const bool cubic = s.interpolation == Interpolation::CubicSpline;
    // Element k of the key list: a CUBICSPLINE key stores (in-tangent, value, out-tangent).
    auto value = [&](size_t k) { return &s.values[(cubic ? 3 * k + 1 : k) * w]; };
    if (keys == 0) return;
    if (!(t > s.times.front())) return void(std::copy_n(value(0), w, out));
    if (!(t < s.times.back())) return void(std::copy_n(value(keys - 1), w, out));
    const size_t k = keyBefore(s.times, t);
    const float t0 = s.times[k], t1 = s.times[k + 1], dt = t1 - t0;
    if (!(dt > 0.0f))
        return void(std::copy_n(value(k + 1), w, out));  // repeated key times: the later key
    const float u = (t - t0) / dt;
    if (s.interpolation == Interpolation::Step) return void(std::copy_n(value(k), w, out));
    if (!cubic) {
        if (rotation)
            return fromQuat(slerpShortest(toQuat(value(k)), toQuat(value(k + 1)), u), out);
        for (uint32_t c = 0; c < w; ++c) out[c] = value(k)[c] * (1.0f - u) + value(k + 1)[c] * u;
        return;
    }
    // Hermite basis; b_k the out-tangent of key k, a_(k+1) the in-tangent of key k + 1, both times dt.
    const float u2 = u * u, u3 = u2 * u;
    const float h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2,
                h11 = u3 - u2;
    const float* outTangent = &s.values[(3 * k + 2) * w];
    const float* inTangent = &s.values[(3 * (k + 1)) * w];
    for (uint32_t c = 0; c < w; ++c)
        out[c] = h00 * value(k)[c] + h10 * dt * outTangent[c] + h01 * value(k + 1)[c] +
                 h11 * dt * inTangent[c];
    if (rotation) fromQuat(glm::normalize(toQuat(out)), out);
}

AABB deformedBounds(const Primitive& prim, const MeshInstance& inst) {
    AABB box = prim.bounds;
    // Morph targets: each weighted target moves every vertex by at most its deltas' extremes.
    for (size_t t = 0; t < prim.targets.size() && t < inst.weights.size(); ++t) {
        const std::vector<glm::vec3>& d = prim.targets[t].position;
        if (d.empty() || inst.weights[t] == 0.0f) continue;
        glm::vec3 lo(0.0f), hi(0.0f);
        for (const glm::vec3& v : d) {
            lo = glm::min(lo, v);
            hi = glm::max(hi, v);
        }
        const float w = inst.weights[t];
        box.min += w > 0.0f ? w * lo : w * hi;
        box.max += w > 0.0f ? w * hi : w * lo;
    }
    if (inst.skin < 0 || prim.skin.empty()) return box;
    // A skinned vertex is a weighted sum of the joints' images of it: with weights summing to 1
    // it lies in the hull of the boxes each joint matrix makes of the box. Weights summing to
    // less (as stored, not renormalised) pull it towards the origin: the union holds it too.
    AABB skinned;
    for (const glm::mat4& j : inst.joints) skinned.extend(box.transformed(j));
    if (skinned.empty()) return box;
    skinned.extend(glm::vec3(0.0f));
    return skinned;
}

void poseScene(Scene& scene, const PoseTime& time) {
    if (time.animation >= int32_t(scene.animations.size()) || time.animation < kAllAnimations)
        throw AssetError("poseScene: animation " + std::to_string(time.animation) +
                         " does not exist (the scene has " +
                         std::to_string(scene.animations.size()) + ")");
    if (!std::isfinite(time.seconds)) throw AssetError("poseScene: the time is not finite");
    for (size_t i = 0; i < scene.nodes.size(); ++i)
        if (scene.nodes[i].parent >= int32_t(scene.nodes.size()) ||
            scene.nodes[i].parent == int32_t(i))
            throw AssetError("poseScene: node '" + scene.nodes[i].name +
                             "' has a parent the scene lacks");
    std::vector<glm::vec3> translation(scene.nodes.size()), scale(scene.nodes.size());
    std::vector<glm::quat> rotation(scene.nodes.size());
    std::vector<std::vector<float>> weights(scene.nodes.size());
    std::vector<char> animatedWeights(scene.nodes.size(), 0);
    for (size_t i = 0; i < scene.nodes.size(); ++i) {
        translation[i] = scene.nodes[i].translation;
        rotation[i] = scene.nodes[i].rotation;
        scale[i] = scene.nodes[i].scale;
    }
    const size_t first = time.animation == kAllAnimations ? 0 : size_t(std::max(time.animation, 0));
    const size_t end = time.animation == kAllAnimations ? scene.animations.size()
                       : time.animation < 0             ? 0
                                                        : first + 1;
    for (size_t index = first; index < end; ++index) {
        const Animation& a = scene.animations[index];
        double t = time.seconds;
        if (time.loop && a.duration > 0.0f) {
            t = std::fmod(t, double(a.duration));
            if (t < 0.0) t += a.duration;
        }
        std::vector<float> v;
        for (const AnimationChannel& c : a.channels) {
            if (c.sampler >= a.samplers.size() || c.node >= scene.nodes.size())
                throw AssetError("poseScene: animation '" + a.name +
                                 "' has a channel naming a sampler or node it lacks");
            const AnimationSampler& s = a.samplers[c.sampler];
            const size_t elements =
                s.times.size() * (s.interpolation == Interpolation::CubicSpline ? 3 : 1);
            if (s.times.empty() || s.values.size() != elements * s.width ||
                (c.path == AnimationPath::Rotation
                     ? s.width != 4
                     : c.path != AnimationPath::Weights && s.width != 3))
                throw AssetError("poseScene: animation '" + a.name +
                                 "' has a sampler whose keys and values do not fit");
            v.assign(s.width, 0.0f);
            sampleAnimation(s, float(t), c.path == AnimationPath::Rotation, v.data());
            switch (c.path) {
                case AnimationPath::Translation:
                    translation[c.node] = glm::vec3(v[0], v[1], v[2]);
                    break;
                case AnimationPath::Rotation:
                    rotation[c.node] = glm::normalize(toQuat(v.data()));
                    break;
                case AnimationPath::Scale:
                    scale[c.node] = glm::vec3(v[0], v[1], v[2]);
                    break;
                case AnimationPath::Weights:
                    weights[c.node] = v;
                    animatedWeights[c.node] = 1;
                    break;
            }
        }
    }
    std::vector<glm::mat4> locals(scene.nodes.size());
    for (size_t i = 0; i < scene.nodes.size(); ++i) {
        const Node& n = scene.nodes[i];
        locals[i] = n.matrix
                        ? *n.matrix
                        : glm::translate(glm::mat4(1.0f), translation[i]) *
                              glm::mat4_cast(rotation[i]) * glm::scale(glm::mat4(1.0f), scale[i]);
    }
    computeWorlds(scene, locals);

    for (MeshInstance& inst : scene.instances) {
        if (inst.node < 0 || size_t(inst.node) >= scene.nodes.size()) continue;
        const Node& node = scene.nodes[size_t(inst.node)];
        inst.world = node.world * inst.local;
        inst.mirrored = glm::determinant(glm::mat3(inst.world)) < 0.0f;
        const Mesh& mesh = scene.meshes[inst.meshIndex];
        size_t targets = 0;
        for (const Primitive& p : mesh.primitives) targets = std::max(targets, p.targets.size());
        if (targets) {
            const std::vector<float>& w = animatedWeights[size_t(inst.node)]
                                              ? weights[size_t(inst.node)]
                                          : !node.weights.empty() ? node.weights
                                                                  : mesh.weights;
            inst.weights.assign(targets, 0.0f);
            std::copy_n(w.begin(), std::min(w.size(), targets), inst.weights.begin());
        }
        if (inst.skin >= 0 && size_t(inst.skin) < scene.skins.size()) {
            const Skin& skin = scene.skins[size_t(inst.skin)];
            if (skin.inverseBindMatrices.size() != skin.joints.size() ||
                std::any_of(skin.joints.begin(), skin.joints.end(),
                            [&](uint32_t j) { return j >= scene.nodes.size(); }))
                throw AssetError(
                    "poseScene: skin '" + skin.name + "' names a node the scene lacks or has " +
                    std::to_string(skin.inverseBindMatrices.size()) +
                    " inverse bind matrices for " + std::to_string(skin.joints.size()) + " joints");
            // inverse(world of the mesh's node): a singular one (scale 0) leaves the joints in world space.
            const bool invertible = std::abs(glm::determinant(glm::mat3(node.world))) > 1e-30f;
            const glm::mat4 toNode = invertible ? glm::inverse(node.world) : glm::mat4(1.0f);
            if (!invertible) inst.world = glm::mat4(1.0f);
            inst.joints.resize(skin.joints.size());
            for (size_t j = 0; j < skin.joints.size(); ++j)
                inst.joints[j] =
                    toNode * scene.nodes[skin.joints[j]].world * skin.inverseBindMatrices[j];
        }
        inst.posedBounds = AABB{};
        if (inst.deformed())
            for (const Primitive& p : mesh.primitives)
                inst.posedBounds.extend(deformedBounds(p, inst));
    }
    for (Light& l : scene.lights) {
        if (l.node < 0 || size_t(l.node) >= scene.nodes.size()) continue;
        const glm::mat4& w = scene.nodes[size_t(l.node)].world;
        l.position = glm::vec3(w[3]);
        const glm::vec3 d = -glm::vec3(w[2]);
        if (glm::length(d) > 1e-12f) l.direction = glm::normalize(d);
    }
    // Scene::camera follows the file's camera it was taken from; one a caller put there instead
    // (another transform or projection) stays.
    const bool follows = scene.cameraIndex >= 0 &&
                         size_t(scene.cameraIndex) < scene.cameras.size() && scene.camera &&
                         sameCamera(*scene.camera, scene.cameras[size_t(scene.cameraIndex)]);
    for (Camera& c : scene.cameras)
        if (c.node >= 0 && size_t(c.node) < scene.nodes.size())
            poseCamera(c, scene.nodes[size_t(c.node)].world);
    if (follows) scene.camera = scene.cameras[size_t(scene.cameraIndex)];
    scene.bounds = computeWorldBounds(scene);
}

}  // namespace fe::assets

#include "reference/AnimationReference.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>

namespace fe::render {

namespace {

using glm::dquat;

dquat quatAt(const std::vector<double>& v, size_t at) {
    return dquat(v[at + 3], v[at], v[at + 1], v[at + 2]);
}

// glTF 2.0 Appendix C's slerp, in double: the shorter arc; a lerp where the arc vanishes.
dquat slerp(dquat a, dquat b, double u) {
    double d = glm::dot(a, b);
    if (d < 0.0) b = -b, d = -d;
    if (d > 1.0 - 1e-12) return glm::normalize(a * (1.0 - u) + b * u);
    const double angle = std::acos(std::min(d, 1.0));
    return (a * std::sin((1.0 - u) * angle) + b * std::sin(u * angle)) / std::sin(angle);
}

// The sampler's value at t, as the spec defines it (the caller wraps t when looping).
std::vector<double> sample(const assets::AnimationSampler& s, double t, bool rotation) {
    const size_t w = s.width, keys = s.times.size();
    const bool cubic = s.interpolation == assets::Interpolation::CubicSpline;
    auto element = [&](size_t e) {
        return std::vector<double>(s.values.begin() + long(e * w),
                                   s.values.begin() + long((e + 1) * w));
    };
    auto value = [&](size_t k) { return element(cubic ? 3 * k + 1 : k); };
    if (t <= s.times.front()) return value(0);
    if (t >= s.times.back()) return value(keys - 1);
    size_t k = 0;
    while (!(s.times[k + 1] > t)) ++k;
    const double dt = double(s.times[k + 1]) - double(s.times[k]);
    if (!(dt > 0.0)) return value(k + 1);
    const double u = (t - s.times[k]) / dt;
    const std::vector<double> v0 = value(k), v1 = value(k + 1);
    std::vector<double> out(w);
    if (s.interpolation == assets::Interpolation::Step) return v0;
    if (!cubic) {
        if (rotation) {
            const dquat q = slerp(quatAt(v0, 0), quatAt(v1, 0), u);
            return {q.x, q.y, q.z, q.w};
        }
        for (size_t c = 0; c < w; ++c) out[c] = v0[c] + (v1[c] - v0[c]) * u;
        return out;
    }
    const std::vector<double> b0 = element(3 * k + 2), a1 = element(3 * (k + 1));
    const double u2 = u * u, u3 = u2 * u;
    for (size_t c = 0; c < w; ++c)
        out[c] = (2 * u3 - 3 * u2 + 1) * v0[c] + dt * (u3 - 2 * u2 + u) * b0[c] +
                 (-2 * u3 + 3 * u2) * v1[c] + dt * (u3 - u2) * a1[c];
    if (rotation) {
        const dquat q = glm::normalize(quatAt(out, 0));
        return {q.x, q.y, q.z, q.w};
    }
    return out;
}

glm::dmat4 cofactorNormalMatrix(const glm::dmat4& m) {
    return glm::dmat4(glm::transpose(glm::inverse(glm::dmat3(m))));
}

}  // namespace

ReferencePose evaluatePose(const assets::Scene& scene, const assets::PoseTime& time) {
    const size_t n = scene.nodes.size();
    std::vector<glm::dvec3> translation(n), scale(n);
    std::vector<dquat> rotation(n);
    std::vector<std::vector<double>> nodeWeights(n);
    std::vector<char> animated(n, 0);
    for (size_t i = 0; i < n; ++i) {
        translation[i] = scene.nodes[i].translation;
        scale[i] = scene.nodes[i].scale;
        rotation[i] = dquat(scene.nodes[i].rotation);
    }
    std::vector<size_t> played;
    if (time.animation == assets::kAllAnimations)
        for (size_t i = 0; i < scene.animations.size(); ++i) played.push_back(i);
    else if (time.animation >= 0)
        played.push_back(size_t(time.animation));
    for (size_t index : played) {
        const assets::Animation& a = scene.animations.at(index);
        double t = time.seconds;
        if (time.loop && a.duration > 0.0f) t -= std::floor(t / a.duration) * a.duration;
        for (const assets::AnimationChannel& c : a.channels) {
            const std::vector<double> v =
                sample(a.samplers[c.sampler], t, c.path == assets::AnimationPath::Rotation);
            if (c.path == assets::AnimationPath::Translation)
                translation[c.node] = {v[0], v[1], v[2]};
            if (c.path == assets::AnimationPath::Scale) scale[c.node] = {v[0], v[1], v[2]};
            if (c.path == assets::AnimationPath::Rotation)
                rotation[c.node] = glm::normalize(quatAt(v, 0));
            if (c.path == assets::AnimationPath::Weights)
                nodeWeights[c.node] = v, animated[c.node] = 1;
        }
    }
    ReferencePose pose;
    pose.nodeWorld.assign(n, glm::dmat4(1.0));
    // Recursion-free: a node's world once its parent's is known (the hierarchy is a forest).
    std::vector<char> done(n, 0);
    for (size_t pass = 0, remaining = n; remaining && pass <= n; ++pass)
        for (size_t i = 0; i < n; ++i) {
            const int32_t p = scene.nodes[i].parent;
            if (done[i] || (p >= 0 && !done[size_t(p)])) continue;
            const glm::dmat4 local = scene.nodes[i].matrix
                                         ? glm::dmat4(*scene.nodes[i].matrix)
                                         : glm::translate(glm::dmat4(1.0), translation[i]) *
                                               glm::mat4_cast(rotation[i]) *
                                               glm::scale(glm::dmat4(1.0), scale[i]);
            pose.nodeWorld[i] = (p >= 0 ? pose.nodeWorld[size_t(p)] : glm::dmat4(1.0)) * local;
            done[i] = 1, --remaining;
        }
    for (const assets::MeshInstance& inst : scene.instances) {
        std::vector<glm::dmat4> joints;
        std::vector<double> weights;
        glm::dmat4 world(inst.world);
        if (inst.node >= 0) {
            const glm::dmat4& nodeWorld = pose.nodeWorld[size_t(inst.node)];
            world = nodeWorld * glm::dmat4(inst.local);
            const assets::Mesh& mesh = scene.meshes[inst.meshIndex];
            size_t targets = 0;
            for (const assets::Primitive& p : mesh.primitives)
                targets = std::max(targets, p.targets.size());
            if (targets) {
                const assets::Node& node = scene.nodes[size_t(inst.node)];
                std::vector<double> given =
                    animated[size_t(inst.node)] ? nodeWeights[size_t(inst.node)]
                    : !node.weights.empty()
                        ? std::vector<double>(node.weights.begin(), node.weights.end())
                        : std::vector<double>(mesh.weights.begin(), mesh.weights.end());
                given.resize(targets, 0.0);
                weights = given;
            }
            if (inst.skin >= 0) {
                const assets::Skin& skin = scene.skins[size_t(inst.skin)];
                for (size_t j = 0; j < skin.joints.size(); ++j)
                    joints.push_back(glm::inverse(nodeWorld) * pose.nodeWorld[skin.joints[j]] *
                                     glm::dmat4(skin.inverseBindMatrices[j]));
            }
        }
        pose.instanceWorld.push_back(world);
        pose.joints.push_back(std::move(joints));
        pose.weights.push_back(std::move(weights));
    }
    return pose;
}

std::vector<DeformedVertex> deformVertices(const assets::Primitive& prim,
                                           const std::vector<glm::dmat4>& joints,
                                           const std::vector<double>& weights) {
    std::vector<DeformedVertex> out(prim.vertices.size());
    for (size_t i = 0; i < prim.vertices.size(); ++i) {
        const assets::Vertex& v = prim.vertices[i];
        glm::dvec3 p(v.position), nrm(v.normal), tan(v.tangent);
        for (size_t t = 0; t < prim.targets.size() && t < weights.size(); ++t) {
            const assets::MorphTarget& target = prim.targets[t];
            if (!target.position.empty()) p += weights[t] * glm::dvec3(target.position[i]);
            if (!target.normal.empty()) nrm += weights[t] * glm::dvec3(target.normal[i]);
            if (!target.tangent.empty()) tan += weights[t] * glm::dvec3(target.tangent[i]);
        }
        if (!joints.empty() && !prim.skin.empty()) {
            glm::dmat4 m(0.0);
            for (int set = 0; set < 2; ++set)
                for (int k = 0; k < 4; ++k)
                    if (prim.skin[i].weights[set][k] != 0.0f)
                        m += double(prim.skin[i].weights[set][k]) *
                             joints.at(prim.skin[i].joints[set][k]);
            p = glm::dvec3(m * glm::dvec4(p, 1.0));
            nrm = glm::dmat3(cofactorNormalMatrix(m)) * nrm;
            tan = glm::dmat3(m) * tan;
        }
        out[i].position = p;
        out[i].normal = glm::length(nrm) > 0.0 ? glm::normalize(nrm) : glm::dvec3(v.normal);
        tan -= out[i].normal * glm::dot(out[i].normal, tan);
        out[i].tangent = glm::dvec4(
            glm::length(tan) > 1e-12 ? glm::normalize(tan) : glm::dvec3(v.tangent), v.tangent.w);
    }
    if (prim.flatNormals)
        for (size_t t = 0; t + 2 < out.size(); t += 3) {
            const glm::dvec3 f = glm::cross(out[t + 1].position - out[t].position,
                                            out[t + 2].position - out[t].position);
            if (!(glm::length(f) > 0.0)) continue;
            for (size_t k = 0; k < 3; ++k) {
                out[t + k].normal = glm::normalize(f);
                glm::dvec3 tan =
                    glm::dvec3(out[t + k].tangent) -
                    out[t + k].normal * glm::dot(out[t + k].normal, glm::dvec3(out[t + k].tangent));
                if (glm::length(tan) > 1e-12)
                    out[t + k].tangent = glm::dvec4(glm::normalize(tan), out[t + k].tangent.w);
            }
        }
    return out;
}

std::vector<DeformedVertex> deformVertices(const assets::Primitive& prim,
                                           const assets::MeshInstance& inst) {
    std::vector<glm::dmat4> joints(inst.joints.begin(), inst.joints.end());
    if (inst.skin < 0) joints.clear();
    return deformVertices(prim, joints,
                          std::vector<double>(inst.weights.begin(), inst.weights.end()));
}

}  // namespace fe::render

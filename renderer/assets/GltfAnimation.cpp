// The glTF loader: nodes, skins and animations (assets/Animation.h poses what they hold).
#include "assets/GltfLoaderInternal.h"

namespace fe::assets::gltf {

void Loader::buildNodes() {
    scene_.nodes.resize(model_.nodes.size());
    for (size_t i = 0; i < model_.nodes.size(); ++i) {
        const auto& gn = model_.nodes[i];
        Node& node = scene_.nodes[i];
        node.name = gn.name;
        node.parent = parent_[i];
        node.world = world_[i];
        if (!gn.matrix.empty()) node.matrix = localTransform(int(i));
        if (gn.translation.size() == 3)
            node.translation = glm::vec3(gn.translation[0], gn.translation[1], gn.translation[2]);
        if (gn.scale.size() == 3) node.scale = glm::vec3(gn.scale[0], gn.scale[1], gn.scale[2]);
        if (gn.rotation.size() == 4) {
            glm::dquat q(gn.rotation[3], gn.rotation[0], gn.rotation[1], gn.rotation[2]);
            if (glm::length(q) > 1e-12) node.rotation = glm::quat(q / glm::length(q));
        }
        for (double w : gn.weights) {
            if (!std::isfinite(w)) fail(nodeLabel(int(i)) + ": non-finite morph weight");
            node.weights.push_back(float(w));
        }
    }
}

void Loader::readSkins() {
    for (size_t s = 0; s < model_.skins.size(); ++s) {
        const auto& gs = model_.skins[s];
        const std::string label = "skin " + std::to_string(s);
        Skin skin;
        skin.name = gs.name;
        std::vector<float> ibm;
        if (gs.inverseBindMatrices >= 0) {
            ibm = readAccessor<float>(gs.inverseBindMatrices, "inverseBindMatrices of " + label,
                                      TINYGLTF_TYPE_MAT4, F32);
            if (ibm.size() < gs.joints.size() * 16)
                fail(label + ": fewer inverseBindMatrices than joints");
        }
        for (size_t j = 0; j < gs.joints.size(); ++j) {
            checkIndex(gs.joints[j], model_.nodes, label + ": joint node");
            skin.joints.push_back(uint32_t(gs.joints[j]));
            glm::mat4 inv = ibm.empty() ? glm::mat4(1.0f) : glm::make_mat4(&ibm[j * 16]);
            for (int c = 0; c < 4; ++c)
                if (!std::isfinite(inv[c].x + inv[c].y + inv[c].z + inv[c].w))
                    fail(label + ": non-finite inverse bind matrix");
            skin.inverseBindMatrices.push_back(inv);
        }
        scene_.skins.push_back(std::move(skin));
    }
}

void Loader::readAnimations() {
    for (size_t a = 0; a < model_.animations.size(); ++a) {
        const auto& ga = model_.animations[a];
        Animation anim;
        anim.name = ga.name;
        std::map<std::tuple<int, int, int>, uint32_t> samplers;
        for (const auto& c : ga.channels) readChannel(int(a), c, anim, samplers);
        for (const AnimationSampler& sm : anim.samplers)
            if (!sm.times.empty()) anim.duration = std::max(anim.duration, sm.times.back());
        scene_.animations.push_back(std::move(anim));
    }
}

void Loader::readChannel(int a, const tinygltf::AnimationChannel& c, Animation& anim,
                         std::map<std::tuple<int, int, int>, uint32_t>& samplers) {
    const auto& ga = model_.animations[size_t(a)];
    const std::string label =
        "animation " + std::to_string(a) + (ga.name.empty() ? "" : " '" + ga.name + "'");
    checkIndex(c.sampler, ga.samplers, label + ": channel sampler");
    if (c.target_node < 0) return;  // glTF: a channel without a target node is ignored
    checkIndex(c.target_node, model_.nodes, label + ": channel target node");
    AnimationPath path;
    if (c.target_path == "translation")
        path = AnimationPath::Translation;
    else if (c.target_path == "rotation")
        path = AnimationPath::Rotation;
    else if (c.target_path == "scale")
        path = AnimationPath::Scale;
    else if (c.target_path == "weights")
        path = AnimationPath::Weights;
    else {
        warn(label + ": channel on '" + c.target_path + "' ignored");
        return;
    }
    if (path != AnimationPath::Weights && !model_.nodes[size_t(c.target_node)].matrix.empty()) {
        warn(label + ": " + nodeLabel(c.target_node) +
             " has a matrix, which glTF does not animate: its " + c.target_path +
             " channel ignored");
        return;
    }
    // A sampler is read once per path it animates (its output's layout depends on the path) and,
    // for weights, per node (the width is its mesh's target count).
    const auto key =
        std::make_tuple(c.sampler, int(path), path == AnimationPath::Weights ? c.target_node : -1);
    auto found = samplers.find(key);
    if (found == samplers.end()) {
        anim.samplers.push_back(readSampler(a, c.sampler, path, c.target_node));
        found = samplers.emplace(key, uint32_t(anim.samplers.size() - 1)).first;
    }
    anim.channels.push_back(
        {.sampler = found->second, .node = uint32_t(c.target_node), .path = path});
}

AnimationSampler Loader::readSampler(int a, int si, AnimationPath path, int node) {
    const auto& gs = model_.animations[size_t(a)].samplers[size_t(si)];
    const std::string label = "animation " + std::to_string(a) + " sampler " + std::to_string(si);
    AnimationSampler s;
    if (gs.interpolation.empty() || gs.interpolation == "LINEAR")
        s.interpolation = Interpolation::Linear;
    else if (gs.interpolation == "STEP")
        s.interpolation = Interpolation::Step;
    else if (gs.interpolation == "CUBICSPLINE")
        s.interpolation = Interpolation::CubicSpline;
    else
        fail(label + ": unknown interpolation '" + gs.interpolation + "'");
    s.times = readAccessor<float>(gs.input, "input of " + label, TINYGLTF_TYPE_SCALAR, F32);
    if (s.times.empty()) fail(label + ": no keys (an input accessor of count 0)");
    for (size_t k = 0; k < s.times.size(); ++k) {
        if (!std::isfinite(s.times[k])) fail(label + ": non-finite key time");
        if (k && s.times[k] < s.times[k - 1])
            fail(label + ": key times decrease (" + std::to_string(s.times[k - 1]) + " then " +
                 std::to_string(s.times[k]) + ")");
    }
    const bool weights = path == AnimationPath::Weights;
    const int type = weights                           ? TINYGLTF_TYPE_SCALAR
                     : path == AnimationPath::Rotation ? TINYGLTF_TYPE_VEC4
                                                       : TINYGLTF_TYPE_VEC3;
    const uint32_t allowed =
        weights || path == AnimationPath::Rotation ? F32 | S8N | U8N | S16N | U16N : F32;
    s.values = readAccessor<float>(gs.output, "output of " + label, type, allowed);
    for (float v : s.values)
        if (!std::isfinite(v)) fail(label + ": non-finite output value");
    const size_t perKey = s.interpolation == Interpolation::CubicSpline ? 3 : 1;
    const size_t elements = s.times.size() * perKey;
    if (weights) {
        // One weight per morph target of the node's mesh, per element.
        if (elements == 0 || s.values.size() % elements != 0)
            fail(label + ": " + std::to_string(s.values.size()) + " output weights for " +
                 std::to_string(s.times.size()) + " keys is not a whole number per key");
        s.width = uint32_t(s.values.size() / elements);
        const int mesh = model_.nodes[size_t(node)].mesh;
        if (mesh >= 0 && mesh < int(model_.meshes.size()))
            for (const auto& p : model_.meshes[size_t(mesh)].primitives)
                if (!p.targets.empty() && p.targets.size() != s.width)
                    fail(label + ": " + std::to_string(s.width) + " weights per key for " +
                         meshLabel(mesh) + "'s " + std::to_string(p.targets.size()) +
                         " morph targets");
    } else {
        s.width = path == AnimationPath::Rotation ? 4 : 3;
        if (s.values.size() != elements * s.width)
            fail(label + ": output count " + std::to_string(s.values.size() / s.width) + " for " +
                 std::to_string(s.times.size()) + " keys (" + std::to_string(perKey) +
                 " per key expected)");
    }
    return s;
}

}  // namespace fe::assets::gltf

// The glTF loader: buffer views, meshes, primitives, morph targets and skin influences.
#include "assets/GltfLoaderInternal.h"

#include "assets/Geometry.h"

namespace fe::assets::gltf {

// ---------------------------------------------------------------------------------------------
// Accessors

const unsigned char* Loader::bufferViewData(int bvIndex, const std::string& ctx, uint64_t& length) {
    checkIndex(bvIndex, model_.bufferViews, ctx + ": bufferView");
    const auto& bv = model_.bufferViews[size_t(bvIndex)];
    checkIndex(bv.buffer, model_.buffers,
               ctx + ": bufferView " + std::to_string(bvIndex) + ": buffer");
    const auto& buf = model_.buffers[size_t(bv.buffer)];
    uint64_t end = 0;
    if (addOverflows(bv.byteOffset, bv.byteLength, end) || end > buf.data.size()) {
        fail("bufferView " + std::to_string(bvIndex) + ": byteOffset+byteLength (" +
             std::to_string(end) + ") exceeds buffer " + std::to_string(bv.buffer) + " length " +
             std::to_string(buf.data.size()));
    }
    length = bv.byteLength;
    return buf.data.data() + bv.byteOffset;
}

// ---------------------------------------------------------------------------------------------
// Meshes

uint32_t Loader::getMesh(int m) {
    auto it = meshMap_.find(m);
    if (it != meshMap_.end()) return it->second;
    const auto& gm = model_.meshes[size_t(m)];
    Mesh mesh;
    mesh.name = gm.name;
    for (size_t p = 0; p < gm.primitives.size(); ++p) {
        Primitive prim;
        if (loadPrimitive(m, int(p), prim)) mesh.primitives.push_back(std::move(prim));
    }
    for (double w : gm.weights) {
        if (!std::isfinite(w)) fail(meshLabel(m) + ": non-finite morph weight");
        mesh.weights.push_back(float(w));
    }
    computeBounds(mesh);
    uint32_t index = uint32_t(scene_.meshes.size());
    scene_.meshes.push_back(std::move(mesh));
    meshMap_[m] = index;
    return index;
}

void Loader::readMorphTargets(int m, int p, size_t n, Primitive& out) {
    const auto& gp = model_.meshes[size_t(m)].primitives[size_t(p)];
    const std::string label = meshLabel(m) + " primitive " + std::to_string(p);
    for (size_t t = 0; t < gp.targets.size(); ++t) {
        MorphTarget target;
        auto read = [&](const char* name, std::vector<glm::vec3>& into) {
            auto it = gp.targets[t].find(name);
            if (it == gp.targets[t].end()) return;
            const std::string what =
                std::string(name) + " of morph target " + std::to_string(t) + " of " + label;
            const std::vector<float> d =
                readAccessor<float>(it->second, what, TINYGLTF_TYPE_VEC3, F32 | S8N | S16N);
            if (d.size() / 3 != n)
                fail(label + ": morph target " + std::to_string(t) + " " + name +
                     " count differs from POSITION");
            into.resize(n);
            for (size_t i = 0; i < n; ++i) {
                into[i] = glm::vec3(d[i * 3], d[i * 3 + 1], d[i * 3 + 2]);
                if (!std::isfinite(into[i].x + into[i].y + into[i].z))
                    fail("non-finite value in " + what);
            }
        };
        read("POSITION", target.position);
        read("NORMAL", target.normal);
        read("TANGENT", target.tangent);
        out.targets.push_back(std::move(target));
    }
}

void Loader::readSkinInfluences(const tinygltf::Primitive& gp, const std::string& label, size_t n,
                                Primitive& out) {
    for (int set = 0; set < 2; ++set) {
        const std::string js = "JOINTS_" + std::to_string(set),
                          ws = "WEIGHTS_" + std::to_string(set);
        auto ja = gp.attributes.find(js), wa = gp.attributes.find(ws);
        if (ja == gp.attributes.end() && wa == gp.attributes.end()) continue;
        if (ja == gp.attributes.end() || wa == gp.attributes.end())
            fail(label + ": " + js + " and " + ws + " come together");
        const std::vector<uint32_t> j =
            readAccessor<uint32_t>(ja->second, js + " of " + label, TINYGLTF_TYPE_VEC4, U8 | U16);
        const std::vector<float> w = readAccessor<float>(wa->second, ws + " of " + label,
                                                         TINYGLTF_TYPE_VEC4, F32 | U8N | U16N);
        if (j.size() != n * 4 || w.size() != n * 4)
            fail(label + ": " + js + "/" + ws + " count differs from POSITION");
        out.skin.resize(n);
        for (size_t i = 0; i < n; ++i)
            for (int k = 0; k < 4; ++k) {
                const float weight = w[i * 4 + size_t(k)];
                if (!std::isfinite(weight)) fail("non-finite " + ws + " value in " + label);
                out.skin[i].joints[set][k] = j[i * 4 + size_t(k)];
                out.skin[i].weights[set][k] = weight;
            }
    }
}

bool Loader::loadPrimitive(int m, int p, Primitive& out) {
    const auto& gm = model_.meshes[size_t(m)];
    const auto& gp = gm.primitives[size_t(p)];
    const std::string label = meshLabel(m) + " primitive " + std::to_string(p);
    const int mode = gp.mode < 0 ? TINYGLTF_MODE_TRIANGLES : gp.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN) {
        static const char* names[] = {"POINTS", "LINES", "LINE_LOOP", "LINE_STRIP"};
        std::string name = mode >= 0 && mode < 4 ? names[mode] : "mode " + std::to_string(mode);
        warn(label + ": " + name + " primitive skipped (only triangles are drawn)");
        return false;
    }
    auto attr = [&](const char* name) {
        auto it = gp.attributes.find(name);
        return it == gp.attributes.end() ? -1 : it->second;
    };
    const int aPos = attr("POSITION");
    if (aPos < 0) {
        warn(label + ": no POSITION attribute; primitive skipped");
        return false;
    }

    const std::vector<float> pos =
        readAccessor<float>(aPos, "POSITION of " + label, TINYGLTF_TYPE_VEC3, F32);
    const size_t n = pos.size() / 3;
    for (size_t i = 0; i < pos.size(); ++i) {
        if (!std::isfinite(pos[i])) {
            fail("non-finite POSITION value (vertex " + std::to_string(i / 3) + ") in " + label +
                 " (accessor " + std::to_string(aPos) + ")");
        }
    }
    auto readMatching = [&](const char* name, int type, uint32_t allowed, size_t comps) {
        std::vector<float> v;
        int a = attr(name);
        if (a < 0) return v;
        v = readAccessor<float>(a, std::string(name) + " of " + label, type, allowed);
        if (v.size() / comps != n) {
            fail("accessor " + std::to_string(a) + " (" + name + " of " + label + "): count " +
                 std::to_string(v.size() / comps) + " differs from POSITION count " +
                 std::to_string(n));
        }
        for (float f : v)
            if (!std::isfinite(f)) fail(std::string("non-finite ") + name + " value in " + label);
        return v;
    };
    const std::vector<float> nrm = readMatching("NORMAL", TINYGLTF_TYPE_VEC3, F32, 3);
    const std::vector<float> tan = readMatching("TANGENT", TINYGLTF_TYPE_VEC4, F32, 4);
    const std::vector<float> uv =
        readMatching("TEXCOORD_0", TINYGLTF_TYPE_VEC2, F32 | U8N | U16N, 2);
    const std::vector<float> uv1 =
        readMatching("TEXCOORD_1", TINYGLTF_TYPE_VEC2, F32 | U8N | U16N, 2);
    // COLOR_0 is VEC3 or VEC4 (alpha 1 when absent), float or normalized unsigned integers.
    std::vector<float> color;
    size_t colorComps = 4;
    if (const int a = attr("COLOR_0"); a >= 0) {
        checkIndex(a, model_.accessors, "COLOR_0 of " + label + ": accessor");
        const int type = model_.accessors[size_t(a)].type;
        colorComps = type == TINYGLTF_TYPE_VEC3 ? 3 : 4;
        color = readMatching("COLOR_0", colorComps == 3 ? TINYGLTF_TYPE_VEC3 : TINYGLTF_TYPE_VEC4,
                             F32 | U8N | U16N, colorComps);
    }

    out.vertices.resize(n);
    for (size_t i = 0; i < n; ++i) {
        Vertex& v = out.vertices[i];
        v.position = glm::vec3(pos[i * 3], pos[i * 3 + 1], pos[i * 3 + 2]);
        if (!nrm.empty()) v.normal = glm::vec3(nrm[i * 3], nrm[i * 3 + 1], nrm[i * 3 + 2]);
        if (!tan.empty())
            v.tangent = glm::vec4(tan[i * 4], tan[i * 4 + 1], tan[i * 4 + 2], tan[i * 4 + 3]);
        if (!uv.empty()) v.uv0 = glm::vec2(uv[i * 2], uv[i * 2 + 1]);
        if (!uv1.empty()) v.uv1 = glm::vec2(uv1[i * 2], uv1[i * 2 + 1]);
        if (!color.empty()) {
            const float* c = &color[i * colorComps];
            v.color = glm::vec4(c[0], c[1], c[2], colorComps == 4 ? c[3] : 1.0f);
        }
    }

    // Indices.
    std::vector<uint32_t> idx;
    if (gp.indices >= 0) {
        idx = readAccessor<uint32_t>(gp.indices, "indices of " + label, TINYGLTF_TYPE_SCALAR,
                                     U8 | U16 | U32);
        for (uint32_t i : idx) {
            if (i >= n)
                fail("index " + std::to_string(i) + " >= vertex count " + std::to_string(n) +
                     " in " + label);
        }
    } else {
        idx.resize(n);
        for (size_t i = 0; i < n; ++i) idx[i] = uint32_t(i);
    }
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) idx = triangleStripToList(idx);
    if (mode == TINYGLTF_MODE_TRIANGLE_FAN) idx = triangleFanToList(idx);
    if (idx.size() % 3 != 0) {
        warn(label + ": index count not a multiple of 3; trailing indices dropped");
        idx.resize(idx.size() - idx.size() % 3);
    }
    out.indices = std::move(idx);

    // Deformation data, kept beside the rest pose (assets/Animation.h).
    readMorphTargets(m, p, n, out);
    readSkinInfluences(gp, label, n, out);

    // Material (needed to know whether tangents must be generated).
    if (gp.material >= 0) {
        checkIndex(gp.material, model_.materials, label + ": material");
        out.material = getMaterial(gp.material);
    } else {
        out.material = defaultMaterial();
    }
    const Material& mat = scene_.materials[out.material];

    // Normals.
    if (nrm.empty()) {
        if (opt_.smoothNormals) {
            generateSmoothNormals(out);
        } else {
            // Unwelded: corner k of triangle t becomes vertex 3t + k; its deformation data follows.
            const std::vector<uint32_t> corners = out.indices;
            generateFlatNormals(out);
            out.flatNormals = true;
            auto remap = [&](auto& list) {
                if (list.empty()) return;
                std::remove_reference_t<decltype(list)> unwelded(corners.size());
                for (size_t k = 0; k < corners.size(); ++k) unwelded[k] = list[corners[k]];
                list = std::move(unwelded);
            };
            remap(out.skin);
            for (MorphTarget& t : out.targets) {
                remap(t.position);
                remap(t.normal);
                remap(t.tangent);
            }
        }
    } else {
        std::vector<glm::vec3> smooth;
        size_t repaired = 0;
        for (size_t i = 0; i < out.vertices.size(); ++i) {
            glm::vec3& nv = out.vertices[i].normal;
            float len = glm::length(nv);
            if (len > 1e-8f && std::isfinite(len)) {
                nv /= len;
                continue;
            }
            if (smooth.empty()) smooth = computeSmoothNormals(out);
            nv = smooth[i];
            ++repaired;
        }
        if (repaired)
            warn(label + ": " + std::to_string(repaired) +
                 " zero-length normal(s) replaced by smooth normals");
    }

    // Tangents.
    if (!tan.empty()) {
        for (auto& v : out.vertices) {
            glm::vec3 t(v.tangent);
            t -= v.normal *
                 glm::dot(v.normal, t);  // an exporter's rounding can bend it off the plane
            float len = glm::length(t);
            glm::vec3 tt = len > 1e-8f ? t / len : anyPerpendicular(v.normal);
            v.tangent = glm::vec4(tt, v.tangent.w < 0.0f ? -1.0f : 1.0f);
        }
    } else if (mat.normalTexture.valid()) {
        const uint32_t set = mat.normalTexture.texCoord;
        if ((set == 0 ? uv : uv1).empty()) {
            warn(label + ": normal map without TEXCOORD_" + std::to_string(set) +
                 "; tangents cannot be generated");
            setFallbackTangents(out);
        } else {
            generateTangents(out, set);
        }
    } else {
        setFallbackTangents(out);
    }
    computeBounds(out);
    return true;
}

}  // namespace fe::assets::gltf

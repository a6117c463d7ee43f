#include "reference/CpuReference.h"
#include "reference/AnimationReference.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "reference/CameraMath.h"
#include "reference/ParallelRows.h"
#include "shading/ShadingModel.h"

namespace fe::render {

namespace {

struct WorldTriangle {
    glm::dvec3 p[3], n[3];
    glm::dvec4 t[3];
    glm::dvec2 uv[3], uv1[3];
    glm::dvec4 color[3];
    uint32_t material;
    int32_t surface;
    bool mirrored;
    glm::dvec3
        meshScale;  // the lengths of the instance's axes: KHR_materials_volume's thickness scale
};

struct SurfaceBox {
    glm::dvec3 min, max;
    size_t first, count;
};

double srgbToLinear(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

double wrapCoord(double u, assets::Wrap w) {
    switch (w) {
        case assets::Wrap::ClampToEdge:
            return std::clamp(u, 0.0, 1.0);
        case assets::Wrap::MirroredRepeat: {
            double f = u - 2.0 * std::floor(u / 2.0);
            return f > 1.0 ? 2.0 - f : f;
        }
        default:
            return u - std::floor(u);
    }
}

// Bilinear sample of mip level 0, decoded to linear for sRGB images.
glm::dvec4 sample(const assets::TextureImage& img, glm::dvec2 uv) {
    auto texel = [&](int x, int y) {
        x = (x % int(img.width) + int(img.width)) % int(img.width);
        y = (y % int(img.height) + int(img.height)) % int(img.height);
        const uint8_t* p = &img.pixels[(size_t(y) * img.width + x) * 4];
        glm::dvec4 v(p[0] / 255.0, p[1] / 255.0, p[2] / 255.0, p[3] / 255.0);
        if (img.srgb)
            for (int c = 0; c < 3; ++c) v[c] = srgbToLinear(v[c]);
        return v;
    };
    double u = wrapCoord(uv.x, img.sampler.wrapS) * img.width - 0.5;
    double v = wrapCoord(uv.y, img.sampler.wrapT) * img.height - 0.5;
    if (img.sampler.magFilter == assets::Filter::Nearest)
        return texel(int(std::floor(u + 0.5)), int(std::floor(v + 0.5)));
    int x0 = int(std::floor(u)), y0 = int(std::floor(v));
    double fx = u - x0, fy = v - y0;
    if (img.sampler.wrapS == assets::Wrap::ClampToEdge)
        x0 = std::clamp(x0, 0, int(img.width) - 2 < 0 ? 0 : int(img.width) - 2);
    if (img.sampler.wrapT == assets::Wrap::ClampToEdge)
        y0 = std::clamp(y0, 0, int(img.height) - 2 < 0 ? 0 : int(img.height) - 2);
    return glm::mix(glm::mix(texel(x0, y0), texel(x0 + 1, y0), fx),
                    glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), fx), fy);
}

// The point a material's texture samples at barycentrics (b1, b2): its texture coordinate set,
// then its KHR_texture_transform, in double.
glm::dvec2 textureCoord(const WorldTriangle& tri, const assets::TextureRef& ref, double b1,
                        double b2) {
    const glm::dvec2* set = ref.texCoord == 1 ? tri.uv1 : tri.uv;
    const glm::dvec2 uv = (1.0 - b1 - b2) * set[0] + b1 * set[1] + b2 * set[2];
    const assets::TextureTransform& x = ref.transform;
    if (x.identity()) return uv;
    const double c = std::cos(double(x.rotation)), s = std::sin(double(x.rotation));
    const glm::dvec2 scaled = uv * glm::dvec2(x.scale);
    return glm::dvec2(c * scaled.x + s * scaled.y, -s * scaled.x + c * scaled.y) +
           glm::dvec2(x.offset);
}

// Base colour alpha times COLOR_0's at barycentrics (b1, b2): what MASK tests and BLEND blends.
double coverageAlpha(const assets::Scene& scene, const WorldTriangle& tri, double b1, double b2) {
    const assets::Material& mat = scene.materials[tri.material];
    double a = mat.baseColorFactor.a *
               ((1.0 - b1 - b2) * tri.color[0].a + b1 * tri.color[1].a + b2 * tri.color[2].a);
    if (mat.baseColorTexture.valid())
        a *= sample(scene.textures[mat.baseColorTexture.index],
                    textureCoord(tri, mat.baseColorTexture, b1, b2))
                 .a;
    return a;
}

// Moller-Trumbore; returns t and barycentrics (b1, b2), or t < 0 for a miss.
double intersect(const WorldTriangle& tri, const glm::dvec3& o, const glm::dvec3& d, double& b1,
                 double& b2) {
    glm::dvec3 e1 = tri.p[1] - tri.p[0], e2 = tri.p[2] - tri.p[0];
    glm::dvec3 pv = glm::cross(d, e2);
    double det = glm::dot(e1, pv);
    if (std::abs(det) < 1e-300) return -1.0;
    double inv = 1.0 / det;
    glm::dvec3 tv = o - tri.p[0];
    b1 = glm::dot(tv, pv) * inv;
    if (b1 < 0.0 || b1 > 1.0) return -1.0;
    glm::dvec3 qv = glm::cross(tv, e1);
    b2 = glm::dot(d, qv) * inv;
    if (b2 < 0.0 || b1 + b2 > 1.0) return -1.0;
    return glm::dot(e2, qv) * inv;
}

bool hitsBox(const SurfaceBox& b, const glm::dvec3& o, const glm::dvec3& invD, double tMax) {
    double t0 = 0.0, t1 = tMax;
    for (int a = 0; a < 3; ++a) {
        double ta = (b.min[a] - o[a]) * invD[a], tb = (b.max[a] - o[a]) * invD[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
        if (t0 > t1) return false;
    }
    return true;
}

}  // namespace

// The opaque scene's copy that transmission samples, as the GPU builds it (render/
// TransmissionPass): level 0 the image, each next level a 2x2 box average of the one above
// (floor sizes, the last row or column of an odd level dropped), read trilinearly with
// clamp-to-edge addressing in the GPU's pixel-centre convention.
class MipChain {
public:
    MipChain(std::vector<glm::dvec3> base, uint32_t width, uint32_t height) {
        levels_.push_back({width, height, std::move(base)});
        while (levels_.back().width > 1 || levels_.back().height > 1) {
            const Level& a = levels_.back();
            Level b{std::max(a.width / 2, 1u), std::max(a.height / 2, 1u), {}};
            b.texels.resize(size_t(b.width) * b.height);
            for (uint32_t y = 0; y < b.height; ++y)
                for (uint32_t x = 0; x < b.width; ++x) {
                    glm::dvec3 sum(0.0);
                    for (uint32_t k = 0; k < 4; ++k)
                        sum += a.at(std::min(2 * x + (k & 1), a.width - 1),
                                    std::min(2 * y + (k >> 1), a.height - 1));
                    b.texels[size_t(y) * b.width + x] = sum / 4.0;
                }
            levels_.push_back(std::move(b));
        }
    }
    // uv in [0, 1] of the image (x right, y down the rows), lod in levels.
    glm::dvec3 sample(glm::dvec2 uv, double lod) const {
        lod = std::clamp(lod, 0.0, double(levels_.size() - 1));
        const size_t l0 = size_t(std::floor(lod)), l1 = std::min(l0 + 1, levels_.size() - 1);
        const double f = lod - double(l0);
        const glm::dvec3 a = levels_[l0].bilinear(uv);
        return f > 0.0 ? a * (1.0 - f) + levels_[l1].bilinear(uv) * f : a;
    }

private:
    struct Level {
        uint32_t width, height;
        std::vector<glm::dvec3> texels;
        const glm::dvec3& at(uint32_t x, uint32_t y) const { return texels[size_t(y) * width + x]; }
        glm::dvec3 bilinear(glm::dvec2 uv) const {
            const double fx = uv.x * width - 0.5, fy = uv.y * height - 0.5;
            const double x0 = std::floor(fx), y0 = std::floor(fy), tx = fx - x0, ty = fy - y0;
            auto texel = [&](double x, double y) {
                return at(uint32_t(std::clamp(x, 0.0, double(width - 1))),
                          uint32_t(std::clamp(y, 0.0, double(height - 1))));
            };
            return (texel(x0, y0) * (1.0 - tx) + texel(x0 + 1, y0) * tx) * (1.0 - ty) +
                   (texel(x0, y0 + 1) * (1.0 - tx) + texel(x0 + 1, y0 + 1) * tx) * ty;
        }
    };
    std::vector<Level> levels_;
};

bool ReferenceImage::nearShadowEdge(uint32_t x, uint32_t y, uint32_t radius) const {
    if (occluded.empty()) return false;
    const uint32_t own = occluded[size_t(y) * width + x];
    const int r = int(radius);
    for (int dy = -r; dy <= r; ++dy)
        for (int dx = -r; dx <= r; ++dx) {
            const int xx = int(x) + dx, yy = int(y) + dy;
            if (xx < 0 || yy < 0 || xx >= int(width) || yy >= int(height)) continue;
            if (occluded[size_t(yy) * width + size_t(xx)] != own) return true;
        }
    return false;
}

bool ReferenceImage::nearEdge(uint32_t x, uint32_t y) const {
    const int32_t s = surface[size_t(y) * width + x];
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            int nx = int(x) + dx, ny = int(y) + dy;
            if (nx < 0 || ny < 0 || nx >= int(width) || ny >= int(height)) continue;
            if (surface[size_t(ny) * width + nx] != s) return true;
        }
    return false;
}

ReferenceImage renderReference(const assets::Scene& scene, const assets::Camera& camera,
                               uint32_t width, uint32_t height, const ReferenceOptions& options) {
    // World-space triangles grouped per (instance, primitive) with a bounding box each.
    std::vector<WorldTriangle> tris;
    std::vector<WorldTriangle> blended;  // BLEND surfaces: composited over the opaque result
    std::vector<WorldTriangle>
        transmissive;  // seen in front of the opaque result, which they see through
    std::vector<SurfaceBox> boxes, transmissiveBoxes;
    {  // reserved: growing these lists copied every triangle again and again (perf: 9 % of a test)
        size_t counts[3] = {};
        for (const assets::MeshInstance& inst : scene.instances)
            for (const assets::Primitive& prim : scene.meshes[inst.meshIndex].primitives) {
                const assets::Material& m = scene.materials[prim.material];
                counts[m.alphaMode == assets::AlphaMode::Blend ? 0
                       : m.transmissive()                      ? 1
                                                               : 2] += prim.indices.size() / 3;
            }
        blended.reserve(counts[0]);
        transmissive.reserve(counts[1]);
        tris.reserve(counts[2]);
    }
    int32_t surfaceId = 0;
    for (const assets::MeshInstance& inst : scene.instances) {
        const glm::dmat4 world(inst.world);
        const glm::dmat3 normalMat = glm::transpose(glm::inverse(glm::dmat3(world)));
        for (const assets::Primitive& prim : scene.meshes[inst.meshIndex].primitives) {
            const int32_t id = surfaceId++;
            // An animated instance's pose (assets::poseScene) deforms the rest pose, in double.
            const std::vector<DeformedVertex> deformed =
                inst.deformed() ? deformVertices(prim, inst) : std::vector<DeformedVertex>{};
            // Triangle i/3 of the primitive in world space.
            auto triangle = [&](size_t i) {
                WorldTriangle t;
                for (int k = 0; k < 3; ++k) {
                    const assets::Vertex& v = prim.vertices[prim.indices[i + k]];
                    const DeformedVertex d =
                        deformed.empty()
                            ? DeformedVertex{glm::dvec3(v.position), glm::dvec3(v.normal),
                                             glm::dvec4(v.tangent)}
                            : deformed[prim.indices[i + k]];
                    t.p[k] = glm::dvec3(world * glm::dvec4(d.position, 1.0));
                    t.n[k] = normalMat * d.normal;
                    t.t[k] = glm::dvec4(glm::dmat3(world) * glm::dvec3(d.tangent), d.tangent.w);
                    t.uv[k] = glm::dvec2(v.uv0);
                    t.uv1[k] = glm::dvec2(v.uv1);
                    t.color[k] = glm::dvec4(v.color);
                }
                t.material = prim.material;
                t.surface = id;
                t.mirrored = inst.mirrored;
                t.meshScale =
                    glm::dvec3(glm::length(world[0]), glm::length(world[1]), glm::length(world[2]));
                return t;
            };
            const assets::Material& primMaterial = scene.materials[prim.material];
            if (primMaterial.alphaMode == assets::AlphaMode::Blend) {
                for (size_t i = 0; i + 2 < prim.indices.size(); i += 3)
                    blended.push_back(triangle(i));
                continue;
            }
            // Opaque and transmissive primitives: their triangles with a bounding box each.
            std::vector<WorldTriangle>& list = primMaterial.transmissive() ? transmissive : tris;
            SurfaceBox box{glm::dvec3(std::numeric_limits<double>::infinity()),
                           glm::dvec3(-std::numeric_limits<double>::infinity()), list.size(), 0};
            for (size_t i = 0; i + 2 < prim.indices.size(); i += 3) {
                const WorldTriangle t = triangle(i);
                for (int k = 0; k < 3; ++k) {
                    box.min = glm::min(box.min, t.p[k]);
                    box.max = glm::max(box.max, t.p[k]);
                }
                list.push_back(t);
            }
            box.count = list.size() - box.first;
            if (box.count) (primMaterial.transmissive() ? transmissiveBoxes : boxes).push_back(box);
        }
    }

    std::vector<shading::PunctualLight> lights;
    for (const assets::Light& l : scene.lights) {
        shading::PunctualLight p;
        p.type = l.type == assets::LightType::Directional ? shading::LightType::Directional
                 : l.type == assets::LightType::Point     ? shading::LightType::Point
                                                          : shading::LightType::Spot;
        p.position = glm::dvec3(l.position);
        p.direction = glm::dvec3(l.direction);
        p.color = glm::dvec3(l.color);
        p.intensity = l.intensity;
        p.range = l.range;
        p.innerConeAngle = l.innerConeAngle;
        p.outerConeAngle = l.outerConeAngle;
        lights.push_back(p);
    }

    // Anything hit on the way to the light, from either side; MASK texels below the cutoff let
    // light through as they let the eye through.
    auto alphaPasses = [&](const WorldTriangle& tri, double b1, double b2) {
        const assets::Material& mat = scene.materials[tri.material];
        if (mat.alphaMode != assets::AlphaMode::Mask) return true;
        return coverageAlpha(scene, tri, b1, b2) >= mat.alphaCutoff;
    };
    auto occluded = [&](const glm::dvec3& o, const glm::dvec3& d, double tMax) {
        const glm::dvec3 invD = 1.0 / d;
        for (const SurfaceBox& box : boxes) {
            if (!hitsBox(box, o, invD, tMax)) continue;
            for (size_t i = box.first; i < box.first + box.count; ++i) {
                double b1, b2;
                const double t = intersect(tris[i], o, d, b1, b2);
                if (t > 0.0 && t < tMax && alphaPasses(tris[i], b1, b2)) return true;
            }
        }
        return false;
    };
    const assets::AABB bounds = assets::computeWorldBounds(scene);
    // Shadow rays start this far off the surface, along its geometric normal: far below a
    // texel of any shadow map, far above double rounding.
    const double rayOffset = 1e-5 * std::max(1e-3, double(glm::length(bounds.size())));
    std::vector<int> casterBit(lights.size(), -1);
    for (size_t i = 0, k = 0; i < lights.size() && i < options.castsShadow.size(); ++i)
        if (options.castsShadow[i]) casterBit[i] = k < 32 ? int(k++) : 32;

    ReferenceImage out;
    out.width = width;
    out.height = height;
    out.radiance.assign(size_t(width) * height, glm::dvec3(0.0));
    out.surface.assign(size_t(width) * height, -1);
    out.textured.assign(size_t(width) * height, 0);
    out.occluded.assign(size_t(width) * height, 0);
    // The camera's aspect ratio when it has one, else the viewport's, as the renderer projects
    // (glTF 2.0 3.10.3: a given aspectRatio is the field of view's).
    const double aspect = projectionAspect(camera, float(width) / float(height));
    // Eye rays from the projection and the view's rotation alone (camera-relative, as the GPU
    // renders): a float view-projection holds the eye's distance from the origin in its
    // translation, which 1e5 from the origin moved these rays by 2 % of a pixel's radiance.
    glm::dmat4 rotation(glm::inverse(glm::dmat3(camera.worldFromView)));
    const glm::dmat4 invProjRotation =
        glm::inverse(glm::dmat4(projection(camera, float(aspect))) * rotation);
    const glm::dvec3 eye(camera.eye());
    // The nearest a hit may be along a ray: half the near plane from the eye, or from the near
    // plane itself for an orthographic camera's rays, which start there.
    const double nearestHit = camera.orthographic ? 0.0 : camera.znear * 0.5;

    // The radiance a surface sends to the eye and its alpha: `shadows` (the opaque surfaces)
    // traces shadow rays for the casting lights, recording occluded ones in *occludedBits;
    // blended surfaces receive no shadows, as on the GPU.
    // A transmissive surface also sees the opaque scene at `exit` (where the light leaves its
    // volume), weighed by `sceneWeight`, through mip level `lod` of its copy.
    struct Shaded {
        glm::dvec3 radiance{0.0};
        double alpha = 1.0;
        bool textured = false;
        glm::dvec3 sceneWeight{0.0};
        glm::dvec3 exit{0.0};
        double lod = 0.0;
    };
    auto shade = [&](const WorldTriangle& tri, double hb1, double hb2, double distance,
                     const glm::dvec3& origin, const glm::dvec3& dir, bool shadows,
                     uint32_t* occludedBits) {
        Shaded out;
        const WorldTriangle* hit = &tri;
        const assets::Material& mat = scene.materials[hit->material];
        const double b0 = 1.0 - hb1 - hb2;
        auto texel = [&](const assets::TextureRef& ref) {
            return sample(scene.textures[ref.index], textureCoord(*hit, ref, hb1, hb2));
        };
        glm::dvec3 n = glm::normalize(b0 * hit->n[0] + hb1 * hit->n[1] + hb2 * hit->n[2]);
        glm::dvec3 ng = glm::cross(hit->p[1] - hit->p[0], hit->p[2] - hit->p[0]);
        const bool front = (glm::dot(ng, dir) < 0.0) != hit->mirrored;
        if (!front) n = -n;  // a double-sided back face shades with the flipped normal
        const glm::dvec3 vertexNormal =
            n;  // the clearcoat's: the base's normal map does not bend it

        glm::dvec4 bc = glm::dvec4(mat.baseColorFactor) *
                        (b0 * hit->color[0] + hb1 * hit->color[1] + hb2 * hit->color[2]);
        double metallic = mat.metallic, roughness = mat.roughness;
        glm::dvec3 emissive(mat.emissiveFactor);
        if (mat.baseColorTexture.valid()) {
            bc *= texel(mat.baseColorTexture);
            out.textured = true;
        }
        if (mat.metallicRoughnessTexture.valid()) {
            glm::dvec4 mr = texel(mat.metallicRoughnessTexture);
            metallic *= mr.b;
            roughness *= mr.g;
            out.textured = true;
        }
        if (mat.emissiveTexture.valid()) {
            emissive *= glm::dvec3(texel(mat.emissiveTexture));
            out.textured = true;
        }
        // A normal map about the vertex normal (the base's, or the clearcoat layer's).
        auto mapNormal = [&](const assets::TextureRef& map, double scale) {
            const glm::dvec4 T = b0 * hit->t[0] + hb1 * hit->t[1] + hb2 * hit->t[2];
            glm::dvec3 t = glm::dvec3(T) - vertexNormal * glm::dot(vertexNormal, glm::dvec3(T));
            if (!(glm::dot(t, t) > 1e-24)) return vertexNormal;
            t = glm::normalize(t);
            const glm::dvec3 b = glm::cross(vertexNormal, t) * (T.w < 0.0 ? -1.0 : 1.0);
            glm::dvec3 tn = glm::dvec3(texel(map)) * 2.0 - 1.0;
            tn.x *= scale;
            tn.y *= scale;
            return glm::normalize(tn.x * t + tn.y * b + tn.z * vertexNormal);
        };
        if (mat.normalTexture.valid()) {
            n = mapNormal(mat.normalTexture, mat.normalScale);
            out.textured = true;
        }
        out.alpha = bc.a;
        double transmission = mat.transmissive() ? mat.transmission : 0.0,
               thickness = mat.thickness;
        if (transmission > 0.0 && mat.transmissionTexture.valid())
            transmission *= texel(mat.transmissionTexture).r;
        if (transmission > 0.0 && mat.thicknessTexture.valid())
            thickness *= texel(mat.thicknessTexture).g;
        if (mat.unlit) {
            out.radiance = glm::dvec3(bc);
            return out;
        }
        shading::SurfacePoint s;
        s.P = origin + dir * distance;
        s.n = n;
        s.wo = -dir;
        s.baseColor = glm::dvec3(bc);
        s.metallic = std::clamp(metallic, 0.0, 1.0);
        s.roughness = roughness;
        // KHR_materials_specular and clearcoat with their textures (1 where there is none).
        for (const assets::TextureRef* t :
             {&mat.specularTexture, &mat.specularColorTexture, &mat.clearcoatTexture,
              &mat.clearcoatRoughnessTexture, &mat.clearcoatNormalTexture})
            out.textured = out.textured || t->valid();
        const glm::dvec3 specularColorTexel = mat.specularColorTexture.valid()
                                                  ? glm::dvec3(texel(mat.specularColorTexture))
                                                  : glm::dvec3(1.0);
        const double specularTexel =
            mat.specularTexture.valid() ? texel(mat.specularTexture).a : 1.0;
        s.dielectricF0 =
            glm::min(glm::dvec3(mat.specularColorF0()) * specularColorTexel, glm::dvec3(1.0)) *
            double(mat.specular) * specularTexel;
        s.dielectricF90 = double(mat.specular) * specularTexel;
        s.clearcoat =
            mat.clearcoat * (mat.clearcoatTexture.valid() ? texel(mat.clearcoatTexture).r : 1.0);
        s.clearcoatRoughness =
            mat.clearcoatRoughness *
            (mat.clearcoatRoughnessTexture.valid() ? texel(mat.clearcoatRoughnessTexture).g : 1.0);
        s.clearcoatNormal = mat.clearcoatNormalTexture.valid()
                                ? mapNormal(mat.clearcoatNormalTexture, mat.clearcoatNormalScale)
                                : vertexNormal;
        s.clearcoatF0 = mat.clearcoatF0();
        s.ior = mat.ior;
        if (mat.hasSheen()) {
            s.sheenColor = glm::dvec3(mat.sheenColor);
            s.sheenRoughness = mat.sheenRoughness;
            if (mat.sheenColorTexture.valid())
                s.sheenColor *= glm::dvec3(texel(mat.sheenColorTexture));
            if (mat.sheenRoughnessTexture.valid())
                s.sheenRoughness *= texel(mat.sheenRoughnessTexture).a;
        }
        // Transmissive surfaces are drawn by the transmission pass under the glTF model, whatever
        // the technique's (render/TransmissionPass.h).
        const shading::Brdf brdf = mat.transmissive() ? shading::Brdf::Gltf : options.brdf;
        if (transmission > 0.0) {
            s.transmission = transmission;
            s.transmissionRay =
                shading::transmissionRay(n, s.wo, thickness, mat.ior, hit->meshScale);
            s.transmittance = shading::volumeTransmittance(glm::dvec3(mat.attenuationColor),
                                                           mat.attenuationDistance,
                                                           glm::length(s.transmissionRay));
            out.sceneWeight = shading::transmittedSceneWeight(s);
            out.exit = s.P + s.transmissionRay;
            out.lod = shading::transmissionLod(roughness, mat.ior, width, height);
        }
        if (mat.clearcoat > 0.0f && brdf == shading::Brdf::Gltf)
            emissive *= 1.0 - s.clearcoat * shading::clearcoatViewFresnel(
                                                s);  // the layer covers emission too
        glm::dvec3 L = emissive;
        // The side of the surface the eye sees, for the shadow rays' start.
        const glm::dvec3 ngEye = glm::normalize(glm::dot(ng, dir) < 0.0 ? ng : -ng);
        for (size_t li = 0; li < lights.size(); ++li) {
            const shading::LightSample ls = shading::evaluateLight(lights[li], s.P);
            if (shadows && casterBit[li] >= 0 && glm::dot(ls.wi, n) > 0.0) {
                const double tMax = lights[li].type == shading::LightType::Directional
                                        ? std::numeric_limits<double>::infinity()
                                        : glm::distance(lights[li].position, s.P);
                if (occluded(s.P + ngEye * rayOffset, ls.wi, tMax - rayOffset)) {
                    if (casterBit[li] < 32) *occludedBits |= 1u << casterBit[li];
                    continue;
                }
            }
            L += shading::shadeLight(s, ls, brdf);
        }
        if (options.iblSamples > 0 && scene.environment) {
            // The occlusion texture darkens indirect light only (glTF 2.0: 1 + strength (ao - 1)).
            const double ao =
                mat.occlusionTexture.valid()
                    ? 1.0 + mat.occlusionStrength * (texel(mat.occlusionTexture).r - 1.0)
                    : 1.0;
            if (mat.occlusionTexture.valid()) out.textured = true;
            L += ao * shading::shadeEnvironment(
                          s, [&](const glm::dvec3& d) { return scene.environment->radiance(d); },
                          options.iblSamples, brdf);
        }
        out.radiance = L;
        return out;
    };
    // Blended surfaces in front of the opaque result, composited far to near (source-over, the
    // GPU's translucent pass, which sorts whole objects: the same wherever they do not interleave).
    auto composite = [&](glm::dvec3 radiance, const glm::dvec3& origin, const glm::dvec3& dir,
                         double limit) {
        struct Layer {
            double t, b1, b2;
            const WorldTriangle* tri;
        };
        std::vector<Layer> layers;
        for (const WorldTriangle& tri : blended) {
            double b1, b2;
            const double t = intersect(tri, origin, dir, b1, b2);
            if (!(t > nearestHit) || t >= limit) continue;
            const glm::dvec3 ng = glm::cross(tri.p[1] - tri.p[0], tri.p[2] - tri.p[0]);
            const bool front = (glm::dot(ng, dir) < 0.0) != tri.mirrored;
            if (!scene.materials[tri.material].doubleSided && !front) continue;
            layers.push_back({t, b1, b2, &tri});
        }
        std::sort(layers.begin(), layers.end(),
                  [](const Layer& a, const Layer& b) { return a.t > b.t; });
        for (const Layer& l : layers) {
            const Shaded s = shade(*l.tri, l.b1, l.b2, l.t, origin, dir, false, nullptr);
            const double a = std::clamp(s.alpha, 0.0, 1.0);
            radiance = s.radiance * a + radiance * (1.0 - a);
        }
        return radiance;
    };

    // The nearest transmissive surface in front of `limit` along the ray, if any.
    struct Hit {
        double t = std::numeric_limits<double>::infinity(), b1 = 0, b2 = 0;
        const WorldTriangle* tri = nullptr;
    };
    auto nearestTransmissive = [&](const glm::dvec3& origin, const glm::dvec3& dir, double limit) {
        Hit best;
        best.t = limit;
        const glm::dvec3 invD = 1.0 / dir;
        for (const SurfaceBox& box : transmissiveBoxes) {
            if (!hitsBox(box, origin, invD, best.t)) continue;
            for (size_t i = box.first; i < box.first + box.count; ++i) {
                const WorldTriangle& tri = transmissive[i];
                double b1, b2;
                const double t = intersect(tri, origin, dir, b1, b2);
                if (!(t > nearestHit) || t >= best.t) continue;
                const glm::dvec3 ng = glm::cross(tri.p[1] - tri.p[0], tri.p[2] - tri.p[0]);
                const bool front = (glm::dot(ng, dir) < 0.0) != tri.mirrored;
                if (!scene.materials[tri.material].doubleSided && !front) continue;
                best = {t, b1, b2, &tri};
            }
        }
        return best;
    };
    const glm::dmat4 projRotation = glm::inverse(invProjRotation);
    // The ray of a pixel centre: from the eye, or for an orthographic camera from the pixel's
    // point on the near plane along the view axis.
    struct Ray {
        glm::dvec3 origin, dir;
    };
    auto pixelRay = [&](uint32_t x, uint32_t y) {
        glm::dvec2 ndc((x + 0.5) / width * 2.0 - 1.0, (y + 0.5) / height * 2.0 - 1.0);
        if (camera.orthographic) {
            const glm::dvec4 nearPoint = invProjRotation * glm::dvec4(ndc, 0.0, 1.0);
            return Ray{eye + glm::dvec3(nearPoint) / nearPoint.w, glm::dvec3(camera.forward())};
        }
        glm::dvec4 farPoint = invProjRotation * glm::dvec4(ndc, 0.5, 1.0);
        return Ray{eye, glm::normalize(glm::dvec3(farPoint) / farPoint.w)};
    };

    // Every pixel is its own ray and writes only its own entries, and everything the rays read is
    // const: rows are shared out among the machine's threads (interleaved, as cost varies by row),
    // with the same result as one thread. 78 s on one thread for the 1280x720 atrium with 1024
    // lights was more than a 15-minute GPU lease could spend on each reference.
    // First the opaque scene; with transmissive surfaces, a second pass sees them in front of it.
    std::vector<double> opaqueDepth(size_t(width) * height,
                                    std::numeric_limits<double>::infinity());
    auto row = [&](uint32_t y) {
        for (uint32_t x = 0; x < width; ++x) {
            const auto [origin, dir] = pixelRay(x, y);
            glm::dvec3 invD = 1.0 / dir;
            double best = std::numeric_limits<double>::infinity();
            const WorldTriangle* hit = nullptr;
            double hb1 = 0, hb2 = 0;
            for (const SurfaceBox& box : boxes) {
                if (!hitsBox(box, origin, invD, best)) continue;
                for (size_t i = box.first; i < box.first + box.count; ++i) {
                    const WorldTriangle& tri = tris[i];
                    double b1, b2;
                    double t = intersect(tri, origin, dir, b1, b2);
                    if (!(t > nearestHit) || t >= best) continue;
                    const assets::Material& mat = scene.materials[tri.material];
                    // Back faces are culled for single-sided materials, as on the GPU.
                    glm::dvec3 ng = glm::cross(tri.p[1] - tri.p[0], tri.p[2] - tri.p[0]);
                    // Counter-clockwise seen from the eye; mirrored instances flip the winding.
                    bool front = (glm::dot(ng, dir) < 0.0) != tri.mirrored;
                    if (!mat.doubleSided && !front) continue;
                    if (mat.alphaMode == assets::AlphaMode::Mask &&
                        coverageAlpha(scene, tri, b1, b2) < mat.alphaCutoff)
                        continue;
                    best = t;
                    hit = &tri;
                    hb1 = b1;
                    hb2 = b2;
                }
            }
            const size_t pixel = size_t(y) * width + x;
            glm::dvec3 radiance(0.0);
            if (!hit) {  // the environment seen along the ray, or black
                if (scene.environment) radiance = scene.environment->radiance(dir);
            } else {
                out.surface[pixel] = hit->surface;
                const Shaded opaque =
                    shade(*hit, hb1, hb2, best, origin, dir, true, &out.occluded[pixel]);
                out.textured[pixel] = opaque.textured;
                radiance = opaque.radiance;
            }
            opaqueDepth[pixel] = best;
            out.radiance[pixel] =
                transmissive.empty() ? composite(radiance, origin, dir, best) : radiance;
        }
    };
    forEachRowInParallel(height, row);
    if (transmissive.empty()) return out;

    const MipChain opaqueScene(out.radiance, width, height);
    auto transmissionRow = [&](uint32_t y) {
        for (uint32_t x = 0; x < width; ++x) {
            const size_t pixel = size_t(y) * width + x;
            const auto [origin, dir] = pixelRay(x, y);
            double limit = opaqueDepth[pixel];
            glm::dvec3 radiance = out.radiance[pixel];
            const Hit h = nearestTransmissive(origin, dir, limit);
            if (h.tri) {
                const Shaded s = shade(*h.tri, h.b1, h.b2, h.t, origin, dir, false, nullptr);
                // Where the light leaves the volume, on the screen (the GPU's pixel-centre convention).
                const glm::dvec4 clip = projRotation * glm::dvec4(s.exit - eye, 1.0);
                const glm::dvec2 uv = glm::dvec2(clip) / clip.w * 0.5 + 0.5;
                radiance = s.radiance + s.sceneWeight * opaqueScene.sample(uv, s.lod);
                limit = h.t;
                out.surface[pixel] = h.tri->surface;
                out.textured[pixel] = s.textured;
            }
            out.radiance[pixel] = composite(radiance, origin, dir, limit);
        }
    };
    forEachRowInParallel(height, transmissionRow);
    return out;
}

}  // namespace fe::render

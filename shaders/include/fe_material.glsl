// Material evaluation for passes that draw scene meshes (forward, G-buffer, transparent).
#ifndef FE_MATERIAL_GLSL
#define FE_MATERIAL_GLSL
// Where the material is sampled and shaded: the KHR_materials_* extensions' textures, and the
// sheen lobe, whose functions in fe_shading.glsl read the albedo table bound with the material's
// textures.
#if !defined(FE_MESH_VERTEX_STAGE) && !defined(FE_VISIBILITY_PASS) && !defined(FE_MATERIAL_EXTENSIONS)
#define FE_MATERIAL_EXTENSIONS
#endif
#include "fe_scene.glsl"

// What scene/mesh.vert (FE_MESH_VERTEX_STAGE, which declares them as outputs) passes every
// mesh-pass fragment shader; each includes this file.
#if !defined(FE_MESH_VERTEX_STAGE) && !defined(FE_VISIBILITY_PASS) && !defined(FE_MATERIAL_FROM_STORAGE)
layout(location = 0) in vec3 vEye;  // camera-relative position: world minus frame.cameraPosition
layout(location = 1) in vec3 vNormal;
layout(location = 2) in vec4 vTangent;
layout(location = 3) in vec4 vUv;     // xy TEXCOORD_0, zw TEXCOORD_1
layout(location = 4) in vec4 vColor;  // COLOR_0 (white without one)
#endif

#ifdef FE_MATERIAL_FROM_STORAGE
// The visibility buffer's resolve (visibility_resolve.comp): a pixel's draw is found from its
// triangle id, so the draw's constants come from the array of every draw, set in `object` before
// sampling; a compute shader has no derivatives, so textures take explicit gradients (feUvDx/Dy).
struct ObjectRecord {
    mat4 world;
    mat4 normalMatrix;
    vec4 baseColorFactor;
    vec4 emissiveNormalScale;
    vec4 params;
    uvec4 flags;
    vec4 uvTransform[28];
    vec4 occlusion;
    vec4 dielectric;
    vec4 transmission;
    vec4 attenuation;
    vec4 sheen;
    vec4 clearcoatNormal;
};
layout(binding = FE_SLOT_DRAWS, std430) readonly buffer DrawBlock {
    ObjectRecord draws[];
};
ObjectRecord object;
vec4 feUvDx, feUvDy;  // both texture coordinate sets' gradients
#else
layout(binding = FE_SLOT_OBJECT, std140) uniform ObjectBlock {
    mat4 world;
    mat4 normalMatrix;
    vec4 baseColorFactor;
    vec4 emissiveNormalScale;
    vec4 params;  // metallic, roughness, alpha cutoff, alpha mode
    uvec4 flags;  // x: bit0 normal map, bit1 unlit, bit2 mirrored, bit3 specular textures, bit4 clearcoat textures,
                  // bit5 clearcoat normal map, bits 8-31 texture set; y, z, w: ObjectConstants
    vec4 uvTransform[28];  // per texture (FE_TEXTURE_*): rows (a, b, c, set) and (d, e, f, 0) of its uv map
    vec4 occlusion;        // x strength (0 without an occlusion texture)
    vec4 dielectric;       // rgb the dielectric's F0 before its clamp, a the specular factor (ObjectConstants::dielectric)
    vec4 transmission;     // x factor, y thickness, z attenuation distance (0: infinite), w ior (0: infinite)
    vec4 attenuation;      // rgb the volume's attenuation colour
    vec4 sheen;            // rgb KHR_materials_sheen's colour (0: none), a its roughness
    vec4 clearcoatNormal;  // x the clearcoat normal texture's scale
} object;
#endif

// What the draw's material uses (a specialization constant, render/ShaderFeatures.h: the
// driver drops the sampling of what it does not; unspecialized, everything). Bit 0 its base
// colour, metallic-roughness, emissive or occlusion texture; 1 a normal map; 2 specular
// textures; 3 clearcoat textures; 4 a clearcoat normal map; 5 a sheen; 6 the MASK alpha mode.
layout(constant_id = 202) const uint FE_MATERIAL_FEATURES = 0xffffffffu;
bool feMaterialUses(uint bit) { return (FE_MATERIAL_FEATURES & bit) != 0u; }

// The textures of a material, in ObjectConstants::uvTransform's order.
const uint FE_TEXTURE_BASECOLOR = 0u;
const uint FE_TEXTURE_METALROUGH = 1u;
const uint FE_TEXTURE_NORMAL = 2u;
const uint FE_TEXTURE_EMISSIVE = 3u;
const uint FE_TEXTURE_OCCLUSION = 4u;
const uint FE_TEXTURE_TRANSMISSION = 5u;
const uint FE_TEXTURE_THICKNESS = 6u;
const uint FE_TEXTURE_SHEEN_COLOR = 7u;
const uint FE_TEXTURE_SHEEN_ROUGHNESS = 8u;
const uint FE_TEXTURE_SPECULAR = 9u;
const uint FE_TEXTURE_SPECULAR_COLOR = 10u;
const uint FE_TEXTURE_CLEARCOAT = 11u;
const uint FE_TEXTURE_CLEARCOAT_ROUGHNESS = 12u;
const uint FE_TEXTURE_CLEARCOAT_NORMAL = 13u;

// Where texture `t` samples: its coordinate set (uvs.xy or .zw), through its KHR_texture_transform.
vec2 feTextureCoord(uint t, vec4 uvs) {
    const vec4 r0 = object.uvTransform[2u * t], r1 = object.uvTransform[2u * t + 1u];
    const vec3 uv = vec3(r0.w != 0.0 ? uvs.zw : uvs.xy, 1.0);
    return vec2(dot(r0.xyz, uv), dot(r1.xyz, uv));
}
#ifdef FE_MATERIAL_FROM_STORAGE
// A compute shader has no derivatives: the set's gradients, through the transform's linear part.
vec4 feSampleTexture(sampler2D tex, uint t, vec4 uvs) {
    const vec4 r0 = object.uvTransform[2u * t], r1 = object.uvTransform[2u * t + 1u];
    const bool second = r0.w != 0.0;
    const vec2 dx = second ? feUvDx.zw : feUvDx.xy, dy = second ? feUvDy.zw : feUvDy.xy;
    return textureGrad(tex, feTextureCoord(t, uvs), vec2(dot(r0.xy, dx), dot(r1.xy, dx)), vec2(dot(r0.xy, dy), dot(r1.xy, dy)));
}
#else
vec4 feSampleTexture(sampler2D tex, uint t, vec4 uvs) { return texture(tex, feTextureCoord(t, uvs)); }
#endif
// A base texture (feMaterialUses(1u)): without one the draw binds white (GpuScene), texel 1.
vec4 feSampleBaseTexture(sampler2D tex, uint t, vec4 uvs) { return feMaterialUses(1u) ? feSampleTexture(tex, t, uvs) : vec4(1.0); }

layout(binding = FE_SLOT_BASECOLOR) uniform sampler2D baseColorTexture;
layout(binding = FE_SLOT_METALROUGH) uniform sampler2D metallicRoughnessTexture;
layout(binding = FE_SLOT_NORMALMAP) uniform sampler2D normalTexture;
layout(binding = FE_SLOT_EMISSIVE) uniform sampler2D emissiveTexture;
layout(binding = FE_SLOT_OCCLUSION) uniform sampler2D occlusionTexture;
#ifdef FE_MATERIAL_EXTENSIONS
layout(binding = FE_SLOT_SHEEN_COLOR) uniform sampler2D sheenColorTexture;
layout(binding = FE_SLOT_SHEEN_ROUGHNESS) uniform sampler2D sheenRoughnessTexture;
layout(binding = FE_SLOT_SPECULAR) uniform sampler2D specularTexture;
layout(binding = FE_SLOT_SPECULAR_COLOR) uniform sampler2D specularColorTexture;
layout(binding = FE_SLOT_CLEARCOAT) uniform sampler2D clearcoatTexture;
layout(binding = FE_SLOT_CLEARCOAT_ROUGHNESS) uniform sampler2D clearcoatRoughnessTexture;
layout(binding = FE_SLOT_CLEARCOAT_NORMAL) uniform sampler2D clearcoatNormalTexture;
#endif
#ifdef FE_TRANSMISSION
layout(binding = FE_SLOT_TRANSMISSION) uniform sampler2D transmissionTexture;
layout(binding = FE_SLOT_THICKNESS) uniform sampler2D thicknessTexture;
#endif

struct MaterialSample {
    vec3 baseColor;
    float alpha;
    float metallic;
    float roughness;
    vec3 emissive;
    vec3 n;
    bool unlit;
    vec3 dielectricF0;  // KHR_materials_ior / KHR_materials_specular (ObjectConstants::dielectric)
    float dielectricF90;
    vec3 clearcoatNormal;  // the vertex normal facing the viewer's side, or the layer's normal map about it
    float clearcoat;       // KHR_materials_clearcoat's factor and roughness, with their textures
    float clearcoatRoughness;
    // KHR_materials_transmission / volume (the transmission pass: FE_TRANSMISSION; 0 elsewhere):
    // the factor and thickness with their textures, and the perceptual roughness unclamped (the
    // mip level rough transmission reads).
    float transmission;
    float thickness;
    float roughnessUnclamped;
    vec3 sheenColor;  // KHR_materials_sheen (0: none) with its textures
    float sheenRoughness;
};

// Base colour alpha times COLOR_0's: what MASK tests and BLEND blends.
float feCoverageAlpha(vec4 uvs, vec4 color) {
    return object.baseColorFactor.a * color.a * feSampleBaseTexture(baseColorTexture, FE_TEXTURE_BASECOLOR, uvs).a;
}

// The factor of indirect light (image-based) at uvs: glTF's 1 + strength (occlusion - 1).
float feOcclusion(vec4 uvs) {
    if (object.occlusion.x == 0.0) return 1.0;
    return 1.0 + object.occlusion.x * (feSampleBaseTexture(occlusionTexture, FE_TEXTURE_OCCLUSION, uvs).r - 1.0);
}

// A tangent-space normal map about the vertex normal n (tangent T from the vertex), its xy scaled.
vec3 feMapNormal(sampler2D map, uint t, float scale, vec3 n, vec4 T, vec4 uvs) {
    vec3 tangent = T.xyz - n * dot(n, T.xyz);
    if (!(dot(tangent, tangent) > 1e-12)) return n;
    tangent = normalize(tangent);
    const vec3 b = cross(n, tangent) * (T.w < 0.0 ? -1.0 : 1.0);
    vec3 tn = feSampleTexture(map, t, uvs).xyz * 2.0 - 1.0;
    tn.xy *= scale;
    return normalize(tn.x * tangent + tn.y * b + tn.z * n);
}

// Sampled textures are decoded by the sampler (sRGB formats), so everything here is linear.
// COLOR_0 multiplies the base colour and its alpha (glTF 2.0).
MaterialSample feSampleMaterial(vec4 uvs, vec4 color, vec3 N, vec4 T, bool frontFacing) {
    MaterialSample m;
    vec4 bc = object.baseColorFactor * color * feSampleBaseTexture(baseColorTexture, FE_TEXTURE_BASECOLOR, uvs);
    m.baseColor = bc.rgb;
    m.alpha = bc.a;
    vec4 mr = feSampleBaseTexture(metallicRoughnessTexture, FE_TEXTURE_METALROUGH, uvs);
    m.metallic = clamp(object.params.x * mr.b, 0.0, 1.0);
    m.roughnessUnclamped = clamp(object.params.y * mr.g, 0.0, 1.0);
    m.roughness = feClampRoughness(m.roughnessUnclamped);
    m.emissive = object.emissiveNormalScale.rgb * feSampleBaseTexture(emissiveTexture, FE_TEXTURE_EMISSIVE, uvs).rgb;
    vec3 n = normalize(N);
    if (!frontFacing) n = -n;  // double-sided: the back face shades with the flipped normal
    m.clearcoatNormal = n;  // KHR_materials_clearcoat: the layer keeps the vertex normal
    m.n = feMaterialUses(2u) && (object.flags.x & 1u) != 0u ? feMapNormal(normalTexture, FE_TEXTURE_NORMAL, object.emissiveNormalScale.a, n, T, uvs) : n;
    m.unlit = (object.flags.x & 2u) != 0u;
    // KHR_materials_ior / specular: F0 = min(ior's F0 x specularColor x colour texel, 1) x specular
    // x texel, F90 = specular x texel; KHR_materials_clearcoat's factor, roughness and normal map.
    vec3 specularColorTexel = vec3(1.0);
    float specularTexel = 1.0;
    m.clearcoat = object.occlusion.y;
    m.clearcoatRoughness = object.occlusion.z;
#ifdef FE_MATERIAL_EXTENSIONS
    if (feMaterialUses(4u) && (object.flags.x & 8u) != 0u) {
        specularColorTexel = feSampleTexture(specularColorTexture, FE_TEXTURE_SPECULAR_COLOR, uvs).rgb;
        specularTexel = feSampleTexture(specularTexture, FE_TEXTURE_SPECULAR, uvs).a;
    }
    if (feMaterialUses(8u) && (object.flags.x & 16u) != 0u) {
        m.clearcoat *= feSampleTexture(clearcoatTexture, FE_TEXTURE_CLEARCOAT, uvs).r;
        m.clearcoatRoughness *= feSampleTexture(clearcoatRoughnessTexture, FE_TEXTURE_CLEARCOAT_ROUGHNESS, uvs).g;
    }
    if (feMaterialUses(16u) && (object.flags.x & 32u) != 0u)
        m.clearcoatNormal = feMapNormal(clearcoatNormalTexture, FE_TEXTURE_CLEARCOAT_NORMAL, object.clearcoatNormal.x, n, T, uvs);
#endif
    m.dielectricF0 = min(object.dielectric.rgb * specularColorTexel, vec3(1.0)) * object.dielectric.a * specularTexel;
    m.dielectricF90 = object.dielectric.a * specularTexel;
    m.transmission = 0.0;
    m.thickness = 0.0;
    m.sheenColor = vec3(0.0);
    m.sheenRoughness = 0.0;
#ifdef FE_MATERIAL_EXTENSIONS
    if (feMaterialUses(32u) && object.sheen.rgb != vec3(0.0)) {
        m.sheenColor = object.sheen.rgb * feSampleTexture(sheenColorTexture, FE_TEXTURE_SHEEN_COLOR, uvs).rgb;
        m.sheenRoughness = object.sheen.a * feSampleTexture(sheenRoughnessTexture, FE_TEXTURE_SHEEN_ROUGHNESS, uvs).a;
    }
#endif
#ifdef FE_TRANSMISSION
    m.transmission = object.transmission.x;  // the draw's: a uniform branch
    if (m.transmission > 0.0) {
        m.transmission *= feSampleTexture(transmissionTexture, FE_TEXTURE_TRANSMISSION, uvs).r;
        m.thickness = object.transmission.y * feSampleTexture(thicknessTexture, FE_TEXTURE_THICKNESS, uvs).g;
    }
#endif
    return m;
}

// MASK: discard below the cutoff; OPAQUE: alpha ignored.
bool feAlphaDiscard(float alpha) { return feMaterialUses(64u) && object.params.w == 1.0 && alpha < object.params.z; }

// The shading inputs of a sampled material at eye-space position Pe, seen from the camera.
SurfacePoint feMaterialSurface(MaterialSample m, vec3 Pe) {
    SurfacePoint s;
    s.P = frame.cameraPosition.xyz + Pe;
    s.Pe = Pe;
    s.n = m.n;
    s.wo = feViewDirection(Pe);
    s.baseColor = m.baseColor;
    s.metallic = m.metallic;
    s.roughness = m.roughness;
    s.dielectricF0 = m.dielectricF0;
    s.dielectricF90 = m.dielectricF90;
    s.clearcoat = m.clearcoat;  // KHR_materials_clearcoat (ObjectConstants::occlusion, its textures)
    s.clearcoatRoughness = m.clearcoatRoughness;
    s.clearcoatNormal = m.clearcoatNormal;
    s.clearcoatF0 = object.occlusion.w;
    s.sheenColor = m.sheenColor;
    s.sheenRoughness = m.sheenRoughness;
    s.transmission = m.transmission;
    s.ior = object.transmission.w;
    s.transmissionRay = vec3(0.0);
    s.transmittance = vec3(1.0);
    if (m.thickness > 0.0) {
        // KHR_materials_volume (shading::transmissionRay): the refracted view ray, thickness x the
        // mesh's axis scales long; Beer-Lambert along it (shading::volumeTransmittance).
        const vec3 refracted = s.ior == 0.0 ? -s.wo : refract(-s.wo, s.n, 1.0 / s.ior);
        const float len = length(refracted);
        const vec3 scale = vec3(length(object.world[0].xyz), length(object.world[1].xyz), length(object.world[2].xyz));
        s.transmissionRay = (len > 0.0 ? refracted / len : -s.wo) * m.thickness * scale;
        if (object.transmission.z > 0.0)
            s.transmittance = pow(object.attenuation.rgb, vec3(length(s.transmissionRay) / object.transmission.z));
    }
    return s;
}

// The emission under the clearcoat: weighed by 1 - c Fc(n_c.v) as the base is (KHR_materials_clearcoat).
vec3 feCoatedEmission(MaterialSample m, vec3 Pe) {
    if (m.clearcoat == 0.0 || frame.shading.x != FE_BRDF_GLTF) return m.emissive;
    return m.emissive * (1.0 - m.clearcoat * feClearcoatViewFresnel(feMaterialSurface(m, Pe)));
}
#endif

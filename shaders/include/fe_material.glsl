// Material evaluation for passes that draw scene meshes (forward, G-buffer, transparent).
#ifndef FE_MATERIAL_GLSL
#define FE_MATERIAL_GLSL
#include "fe_scene.glsl"

// What scene/mesh.vert (FE_MESH_VERTEX_STAGE, which declares them as outputs) passes every
// mesh-pass fragment shader; each includes this file.
#if !defined(FE_MESH_VERTEX_STAGE) && !defined(FE_VISIBILITY_PASS) && !defined(FE_MATERIAL_FROM_STORAGE)
layout(location = 0) in vec3 vEye;  // camera-relative position: world minus frame.cameraPosition
layout(location = 1) in vec3 vNormal;
layout(location = 2) in vec4 vTangent;
layout(location = 3) in vec2 vUv;
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
};
layout(binding = FE_SLOT_DRAWS, std430) readonly buffer DrawBlock {
    ObjectRecord draws[];
};
ObjectRecord object;
vec2 feUvDx, feUvDy;
#define FE_MATERIAL_TEXTURE(t, uv) textureGrad(t, uv, feUvDx, feUvDy)
#else
layout(binding = FE_SLOT_OBJECT, std140) uniform ObjectBlock {
    mat4 world;
    mat4 normalMatrix;
    vec4 baseColorFactor;
    vec4 emissiveNormalScale;
    vec4 params;  // metallic, roughness, alpha cutoff, alpha mode
    uvec4 flags;  // x: bit0 normal map, bit1 unlit, bit2 mirrored, bits 8-31 texture set; y, z, w: ObjectConstants
} object;
#define FE_MATERIAL_TEXTURE(t, uv) texture(t, uv)
#endif

layout(binding = FE_SLOT_BASECOLOR) uniform sampler2D baseColorTexture;
layout(binding = FE_SLOT_METALROUGH) uniform sampler2D metallicRoughnessTexture;
layout(binding = FE_SLOT_NORMALMAP) uniform sampler2D normalTexture;
layout(binding = FE_SLOT_EMISSIVE) uniform sampler2D emissiveTexture;

struct MaterialSample {
    vec3 baseColor;
    float alpha;
    float metallic;
    float roughness;
    vec3 emissive;
    vec3 n;
    bool unlit;
};

// Sampled textures are decoded by the sampler (sRGB formats), so everything here is linear.
MaterialSample feSampleMaterial(vec2 uv, vec3 N, vec4 T, bool frontFacing) {
    MaterialSample m;
    vec4 bc = object.baseColorFactor * FE_MATERIAL_TEXTURE(baseColorTexture, uv);
    m.baseColor = bc.rgb;
    m.alpha = bc.a;
    vec4 mr = FE_MATERIAL_TEXTURE(metallicRoughnessTexture, uv);
    m.metallic = clamp(object.params.x * mr.b, 0.0, 1.0);
    m.roughness = feClampRoughness(object.params.y * mr.g);
    m.emissive = object.emissiveNormalScale.rgb * FE_MATERIAL_TEXTURE(emissiveTexture, uv).rgb;
    vec3 n = normalize(N);
    if (!frontFacing) n = -n;  // double-sided: the back face shades with the flipped normal
    if ((object.flags.x & 1u) != 0u) {
        vec3 t = T.xyz - n * dot(n, T.xyz);
        if (dot(t, t) > 1e-12) {
            t = normalize(t);
            vec3 b = cross(n, t) * (T.w < 0.0 ? -1.0 : 1.0);
            vec3 tn = FE_MATERIAL_TEXTURE(normalTexture, uv).xyz * 2.0 - 1.0;
            tn.xy *= object.emissiveNormalScale.a;
            n = normalize(tn.x * t + tn.y * b + tn.z * n);
        }
    }
    m.n = n;
    m.unlit = (object.flags.x & 2u) != 0u;
    return m;
}

// MASK: discard below the cutoff; OPAQUE: alpha ignored.
bool feAlphaDiscard(float alpha) { return object.params.w == 1.0 && alpha < object.params.z; }

// The shading inputs of a sampled material at eye-space position Pe, seen from the camera.
SurfacePoint feMaterialSurface(MaterialSample m, vec3 Pe) {
    SurfacePoint s;
    s.P = frame.cameraPosition.xyz + Pe;
    s.Pe = Pe;
    s.n = m.n;
    s.wo = normalize(-Pe);
    s.baseColor = m.baseColor;
    s.metallic = m.metallic;
    s.roughness = m.roughness;
    return s;
}
#endif

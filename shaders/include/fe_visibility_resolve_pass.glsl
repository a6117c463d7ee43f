// The body of visibility_resolve*.comp (VisibilityBufferRenderer): a work group per 16x16 screen
// tile; each pixel finds its triangle from the visibility buffer's id, rebuilds the surface the
// ray through its centre meets there (barycentrics of the view ray, not of the depth), samples
// its material with the gradients of the rays through the next pixels, and shades the lights of
// its cluster (ClusterLightGrid), once, writing L_o. A device without bindless textures binds one
// texture set at a time: the renderer dispatches once per set (resolve.pass.x) and a pixel whose
// draw samples another set is left for that dispatch; the first also writes the empty pixels.
#define FE_TILE_LISTS  // the list passes' helpers and uniform lights (fe_tile_culling.glsl)
#define FE_CLUSTER_LISTS
#define FE_MATERIAL_FROM_STORAGE
#define FE_MATERIAL_EXTENSIONS  // their textures and the sheen lobe, as fe_material.glsl defines it: included first here
#include "fe_common.glsl"
#include "fe_tile_culling.glsl"
#include "fe_clusters.glsl"
#include "fe_material.glsl"
#ifdef FE_IBL
#include "fe_ibl.glsl"
#endif
layout(local_size_x = 16, local_size_y = 16) in;
#ifdef FE_MULTISAMPLED
// --msaa: the ids of every sample; the lists are whole (the cluster of the shading's own depth),
// and each dispatch adds its texture set's triangles to what the earlier ones stored.
layout(binding = FE_SLOT_VISIBILITY) uniform usampler2DMS visibility;
layout(binding = FE_SLOT_RADIANCE_OUT, rgba32f) uniform image2D outRadiance;
#else
layout(binding = FE_SLOT_VISIBILITY) uniform usampler2D visibility;
layout(binding = FE_SLOT_DEPTH) uniform sampler2D depthTexture;
layout(binding = FE_SLOT_RADIANCE_OUT, rgba32f) uniform writeonly image2D outRadiance;
#endif
layout(binding = FE_SLOT_VERTICES, std430) readonly buffer VertexBlock {
    float vertexFloats[];  // assets::Vertex: position, normal, tangent, uv0, uv1, colour (18 floats)
};
layout(binding = FE_SLOT_INDICES, std430) readonly buffer IndexBlock {
    uint indices[];
};
FE_CONSTANTS(ResolveConstants) {
    uvec4 pass;  // x: the texture set this dispatch shades, y: 1 when it also writes empty pixels
} resolve;

// The draw holding triangle `id`: the last whose first triangle is at most id (draws are in
// scene order, their ids increasing).
uint feDrawOfTriangle(uint id) {
    uint lo = 0u, hi = uint(draws.length()) - 1u;
    while (lo < hi) {
        const uint mid = (lo + hi + 1u) >> 1;
        if (draws[mid].flags.w <= id) lo = mid;
        else hi = mid - 1u;
    }
    return lo;
}

struct TriangleVertex {
    vec3 eye;  // camera-relative position, as mesh.vert computes it
    vec3 normal;
    vec4 tangent;
    vec4 uv;  // both sets
    vec4 color;
};
TriangleVertex feTriangleVertex(uint index) {
    const uint f = (index + object.flags.z) * 18u;
    TriangleVertex v;
    const vec3 p = vec3(vertexFloats[f], vertexFloats[f + 1u], vertexFloats[f + 2u]);
    v.eye = mat3(object.world) * p + (object.world[3].xyz - frame.cameraPosition.xyz);
    v.normal = vec3(vertexFloats[f + 3u], vertexFloats[f + 4u], vertexFloats[f + 5u]);
    v.tangent = vec4(vertexFloats[f + 6u], vertexFloats[f + 7u], vertexFloats[f + 8u], vertexFloats[f + 9u]);
    v.uv = vec4(vertexFloats[f + 10u], vertexFloats[f + 11u], vertexFloats[f + 12u], vertexFloats[f + 13u]);
    v.color = vec4(vertexFloats[f + 14u], vertexFloats[f + 15u], vertexFloats[f + 16u], vertexFloats[f + 17u]);
    return v;
}

// Barycentrics (of vertices 1 and 2) where the ray from the eye along `dir` meets the plane of
// the triangle (Moller and Trumbore 1997, with the ray's origin at the eye: 0 in eye space).
vec2 feRayBarycentrics(vec3 dir, vec3 p0, vec3 e1, vec3 e2) {
    const vec3 pv = cross(dir, e2);
    const float inv = 1.0 / dot(e1, pv);
    const vec3 tv = -p0;
    return vec2(dot(tv, pv), dot(dir, cross(tv, e1))) * inv;
}

// L_o of triangle `id` (of the draw in `object`) where the ray through pixel p's centre meets it.
vec3 feShadeTriangle(ivec2 p, uint id) {
    const uint first = object.flags.y + 3u * (id - object.flags.w);
    const TriangleVertex v0 = feTriangleVertex(indices[first]), v1 = feTriangleVertex(indices[first + 1u]),
                         v2 = feTriangleVertex(indices[first + 2u]);
    const vec3 e1 = v1.eye - v0.eye, e2 = v2.eye - v0.eye;
    // The rays through this pixel's centre and its neighbours' (the gradients a fragment
    // shader's 2x2 quad would see).
    const vec3 dir = feEyeFromDepth(vec2(p) + 0.5, 0.5);
    const vec2 b = feRayBarycentrics(dir, v0.eye, e1, e2);
    const vec2 bx = feRayBarycentrics(feEyeFromDepth(vec2(p) + vec2(1.5, 0.5), 0.5), v0.eye, e1, e2);
    const vec2 by = feRayBarycentrics(feEyeFromDepth(vec2(p) + vec2(0.5, 1.5), 0.5), v0.eye, e1, e2);
    const vec3 w = vec3(1.0 - b.x - b.y, b);
    const vec4 uv = w.x * v0.uv + w.y * v1.uv + w.z * v2.uv;
    const mat3x4 uvs = mat3x4(v0.uv, v1.uv, v2.uv);
    feUvDx = uvs * vec3(1.0 - bx.x - bx.y, bx) - uv;
    feUvDy = uvs * vec3(1.0 - by.x - by.y, by) - uv;
    const vec3 eye = w.x * v0.eye + w.y * v1.eye + w.z * v2.eye;
    const vec3 N = mat3(object.normalMatrix) * (w.x * v0.normal + w.y * v1.normal + w.z * v2.normal);
    const vec4 T = w.x * v0.tangent + w.y * v1.tangent + w.z * v2.tangent;
    // Counter-clockwise seen from the eye; mirrored instances flip the winding (CpuReference).
    const bool front = (dot(cross(e1, e2), dir) < 0.0) != ((object.flags.x & 4u) != 0u);
    const vec4 color = w.x * v0.color + w.y * v1.color + w.z * v2.color;
    const MaterialSample m = feSampleMaterial(uv, color, N, vec4(mat3(object.world) * T.xyz, T.w), front);
    if (m.unlit) return m.baseColor;
    vec3 radiance = feCoatedEmission(m, eye);
    const SurfacePoint s = feMaterialSurface(m, eye);
    const SurfaceBrdf brdf = fePrepareBrdf(s);
#ifdef FE_MULTISAMPLED
    const vec4 clip = frame.viewProjFromEye * vec4(eye, 1.0);
    feUseClusterList(p, clip.z / clip.w);
    const uint count = feClusterLightCount(frame.counts.x);  // whole: two runs in light order
#else
    feUseClusterList(p, texelFetch(depthTexture, p, 0).r);
    const uint count = feClusterBoundedLightCount(frame.counts.x);
#endif
    for (uint k = 0u; k < count; ++k) {
        const uint i = feClusterLight(k);
        if (i >= frame.counts.x) {  // the shadowed lights, last in a run, have passes of their own
#ifdef FE_MULTISAMPLED
            continue;
#else
            break;
#endif
        }
        const GpuLight L = feLight(i);
        if (!feLightReaches(L, s.P)) continue;  // beyond its range a light adds exactly 0
        radiance += feShadeLight(brdf, feEvaluateLightFromEye(L, s.Pe));
    }
#ifdef FE_IBL
    radiance += feOcclusion(uv) * feShadeEnvironment(s, frame.counts.z);
#endif
    return radiance;
}

#ifdef FE_MULTISAMPLED
// Each triangle the pixel's samples hold is shaded once, at the pixel's centre as a multisampled
// forward pass shades it, weighted by how many samples it covers; empty samples add 0.
void main() {
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, ivec2(frame.viewport.xy)))) return;
    const int n = textureSamples(visibility);
    vec3 sum = vec3(0.0);
    bool shaded = false;
    for (int i = 0; i < n; ++i) {
        const uint id = texelFetch(visibility, p, i).r;
        bool seen = id == 0u;
        for (int j = 0; j < i; ++j) seen = seen || texelFetch(visibility, p, j).r == id;
        if (seen) continue;
        object = draws[feDrawOfTriangle(id)];
        if ((object.flags.x >> 8) != resolve.pass.x) continue;
        int covered = 1;
        for (int j = i + 1; j < n; ++j) covered += texelFetch(visibility, p, j).r == id ? 1 : 0;
        sum += float(covered) * feShadeTriangle(p, id);
        shaded = true;
    }
    if (resolve.pass.y != 0u) imageStore(outRadiance, p, vec4(sum / float(n), 1.0));
    else if (shaded) imageStore(outRadiance, p, vec4(imageLoad(outRadiance, p).rgb + sum / float(n), 1.0));
}
#else
void main() {
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, ivec2(frame.viewport.xy)))) return;
    const uint id = texelFetch(visibility, p, 0).r;
    if (id == 0u) {
        if (resolve.pass.y != 0u) imageStore(outRadiance, p, vec4(0.0, 0.0, 0.0, 1.0));
        return;
    }
    object = draws[feDrawOfTriangle(id)];
    if ((object.flags.x >> 8) != resolve.pass.x) return;
    imageStore(outRadiance, p, vec4(feShadeTriangle(p, id), 1.0));
}
#endif

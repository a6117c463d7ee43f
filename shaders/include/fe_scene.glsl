// Resource layout shared by the scene renderers (renderer/render/*): flat binding slots.
#ifndef FE_SCENE_GLSL
#define FE_SCENE_GLSL
#include "fe_shading.glsl"

#define FE_SLOT_FRAME 0
#define FE_SLOT_OBJECT 1
#define FE_SLOT_LIGHTS 2
#define FE_SLOT_BASECOLOR 3
#define FE_SLOT_METALROUGH 4
#define FE_SLOT_NORMALMAP 5
#define FE_SLOT_EMISSIVE 6
#define FE_SLOT_OCCLUSION 7
#define FE_SLOT_GBUFFER0 8
#define FE_SLOT_GBUFFER1 9
#define FE_SLOT_GBUFFER2 10
#define FE_SLOT_DEPTH 11
#define FE_SLOT_IBUFFER0 12
#define FE_SLOT_IBUFFER1 13
#define FE_SLOT_IBUFFER2 14
#define FE_SLOT_RADIANCE 15
#define FE_SLOT_RADIANCE_OUT 16
#define FE_SLOT_TILE_LIGHTS 17
#define FE_SLOT_TILE_LIGHTS_OUT 18
#define FE_SLOT_ENVIRONMENT 19
#define FE_SLOT_ENVIRONMENT_SOURCE 20
#define FE_SLOT_HISTORY0 25
#define FE_SLOT_HISTORY1 26
#define FE_SLOT_HISTORY2 27
#define FE_SLOT_GBUFFER3 28
#define FE_SLOT_TRANSMISSION 29
#define FE_SLOT_THICKNESS 30
#define FE_SLOT_TRANSMITTED 31
#define FE_SLOT_SHEEN_COLOR 32
#define FE_SLOT_SHEEN_ROUGHNESS 33
// FE_SLOT_SHEEN_ALBEDO 44: fe_shading.glsl
#define FE_SLOT_SPECULAR 45
#define FE_SLOT_SPECULAR_COLOR 46
#define FE_SLOT_CLEARCOAT 47
#define FE_SLOT_CLEARCOAT_ROUGHNESS 48
#define FE_SLOT_CLEARCOAT_NORMAL 49
#define FE_SLOT_TAA 34
#define FE_SLOT_VISIBILITY 36
#define FE_SLOT_DRAWS 37
#define FE_SLOT_VERTICES 38
#define FE_SLOT_INDICES 39

// G-buffer 2's alpha: -1 where nothing was drawn (its clear value), w_o.n in [0, 1] on lit
// surfaces (redeferred consideration A: the material pass need not rebuild it), 2 on unlit ones.
bool feGBufferUnlit(float gb2Alpha) { return gb2Alpha > 1.5; }

layout(binding = FE_SLOT_FRAME, std140) uniform FrameBlock {
    mat4 viewProj;
    mat4 invViewProj;
    vec4 cameraPosition;  // w = exposure
    vec4 viewport;        // w, h, 1/w, 1/h
    vec4 illumViewport;   // I-buffer: w, h, 1/w, 1/h
    uvec4 counts;         // x lights, y illumination scale, z image-based lighting samples, w all lights (shadowed too)
    uvec4 lightRange;     // forward shading: x first light, y light count, z 1 = add emissive/unlit, w 0
    mat4 view;            // view from world (rigid): the light pre-pass packs view-space normals
    vec4 temporal;        // xy representative pixel's offset in its I-buffer block, z history valid, w history cap
    mat4 prevViewProj;    // the previous frame's viewProj
    vec4 clusters;        // the light cluster grid's slicing (fe_clusters.glsl): x near, y (slices - 1) / ln(far / split), z far, w near split
    mat4 viewProjFromEye;     // clip from eye space (world - cameraPosition.xyz): camera-relative rendering
    mat4 invViewProjFromEye;  // and back
    uvec4 shading;            // x: the BRDF (FE_BRDF_GLTF or FE_BRDF_SEPARABLE), w: 1 = an orthographic camera
} frame;

// w_o, towards the viewer from the eye-space position Pe: back to the eye, or along the view axis
// for an orthographic camera (whose rays are parallel).
vec3 feViewDirection(vec3 Pe) {
    return frame.shading.w == 1u ? vec3(frame.view[0][2], frame.view[1][2], frame.view[2][2]) : normalize(-Pe);
}

// The surface's BRDF factors under the frame's shading model.
SurfaceBrdf fePrepareBrdf(SurfacePoint s) { return fePrepareBrdf(s, frame.shading.x); }
vec3 feShadeLight(SurfacePoint s, SurfaceLight l) { return feShadeLight(fePrepareBrdf(s), l); }

// The representative pixel of I-buffer texel q is q * scale + feRepOffset() (clamped to the
// screen): the block's centre, or this frame's jittered position with temporal accumulation.
ivec2 feRepOffset() { return ivec2(frame.temporal.xy); }

// The passes that walk light lists and the forward shaders read the lights from a uniform block
// (FE_LIGHTS_UNIFORM): on lavapipe and llvmpipe a storage buffer load is a loop over the SIMD
// lanes, a uniform one a vector gather, which measured 10 % faster tiled passes and a forward
// shading pass 7x faster (docs/MEASUREMENT_LOG.md). A block holds at most FE_UNIFORM_LIGHTS (64 KiB):
// scenes with more use each such shader's FE_LIGHTS_IN_STORAGE variant (TileLightCulling::shader,
// GeometryRenderer::lightsVariant).
#define FE_UNIFORM_LIGHTS 1024
// The block is declared as plain vec4s, not GpuLight records: Mesa's GL linker makes a program
// resource per member of every array element and grows its lists by realloc, which made each
// link of a 1024-record block take 10 s under AddressSanitizer. feLight(i) reads record i.
#if defined(FE_LIGHTS_UNIFORM) && !defined(FE_LIGHTS_IN_STORAGE)
layout(binding = FE_SLOT_LIGHTS, std140) uniform LightBlock {
    vec4 lightWords[FE_UNIFORM_LIGHTS * 4];
};
GpuLight feLight(uint i) {
    return GpuLight(lightWords[4u * i], lightWords[4u * i + 1u], lightWords[4u * i + 2u], lightWords[4u * i + 3u]);
}
#else
layout(binding = FE_SLOT_LIGHTS, std430) readonly buffer LightBlock {
    GpuLight lights[];
};
GpuLight feLight(uint i) { return lights[i]; }
#endif

// Depth along the view axis from the depth buffer: the w row of the inverse projection (and of
// invViewProj, the view being rigid) depends on depth alone, so no matrix product is needed.
float feViewDepth(float depth) {
    return 1.0 / abs(frame.invViewProj[2][3] * depth + frame.invViewProj[3][3]);
}

// The tiled illumination pass stores, in the I-buffer's alpha channels, what the material
// pass's upsampling filter needs of each texel's representative pixel, so the filter fetches
// no G-buffer texel per tap: L_dg.a its view depth (0: nothing lit there), L_sg1.a its normal's
// octahedral x, L_sg2.a the octahedral y (in [0, 1) after the offset) plus its roughness in
// 1/255 steps as the integer part (float32 keeps 16 bits of the fraction beside them).
vec2 feOctEncode(vec3 n) {
    n /= abs(n.x) + abs(n.y) + abs(n.z);
    vec2 e = n.xy;
    if (n.z < 0.0) e = (1.0 - abs(n.yx)) * vec2(e.x >= 0.0 ? 1.0 : -1.0, e.y >= 0.0 ? 1.0 : -1.0);
    return e;
}
vec3 feOctDecode(vec2 e) {
    vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    return normalize(n);
}
float fePackOctYRoughness(float octY, float roughness) {
    return round(clamp(roughness, 0.0, 1.0) * 255.0) + clamp(octY * 0.5 + 0.5, 0.0, 0.99998);
}
void feUnpackOctYRoughness(float v, out float octY, out float roughness) {
    roughness = floor(v) / 255.0;
    octY = fract(v) * 2.0 - 1.0;
}

// Eye-space offset (world - camera position) of full-resolution pixel `p` from its depth
// (Vulkan clip conventions). Rebuilt relative to the camera: the world-space inverse multiplies
// the position's distance from the origin into every term.
vec3 feEyeFromDepth(vec2 pixelCenter, float depth) {
    vec2 ndc = pixelCenter * frame.viewport.zw * 2.0 - 1.0;
    vec4 e = frame.invViewProjFromEye * vec4(ndc, depth, 1.0);
    return e.xyz / e.w;
}
vec3 feWorldFromDepth(vec2 pixelCenter, float depth) {
    return frame.cameraPosition.xyz + feEyeFromDepth(pixelCenter, depth);
}

// The light at eye-space offset Pe from the camera (feEvaluateLightAt).
SurfaceLight feEvaluateLightFromEye(GpuLight L, vec3 Pe) { return feEvaluateLightAt(L, Pe, frame.cameraPosition.xyz); }

// The surface a G-buffer pixel holds (base colour + metallic in g0, normal + roughness in g1).
SurfacePoint feGBufferSurface(ivec2 p, float depth, vec4 g0, vec4 g1) {
    SurfacePoint s;
    const vec3 eye = feEyeFromDepth(vec2(p) + 0.5, depth);
    s.P = frame.cameraPosition.xyz + eye;
    s.Pe = eye;
    s.n = normalize(g1.xyz);
    s.wo = feViewDirection(eye);
    s.baseColor = g0.rgb;
    s.metallic = g0.a;
    s.roughness = g1.a;
    s.dielectricF0 = vec3(0.04);  // the G-buffer holds no KHR_materials_ior / specular / clearcoat
    s.dielectricF90 = 1.0;
    s.clearcoat = 0.0;
    s.clearcoatRoughness = 0.0;
    s.clearcoatNormal = s.n;
    s.clearcoatF0 = 0.04;
    s.transmission = 0.0;  // transmissive surfaces are drawn by the transmission pass alone
    s.transmissionRay = vec3(0.0);
    s.ior = 1.5;
    s.transmittance = vec3(1.0);
    s.sheenColor = vec3(0.0);
    s.sheenRoughness = 0.0;
    return s;
}
#endif

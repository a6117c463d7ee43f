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

// G-buffer 2's alpha: -1 where nothing was drawn (its clear value), w_o.n in [0, 1] on lit
// surfaces (redeferred consideration A: the material pass need not rebuild it), 2 on unlit ones.
bool feGBufferUnlit(float gb2Alpha) { return gb2Alpha > 1.5; }

layout(binding = FE_SLOT_FRAME, std140) uniform FrameBlock {
    mat4 viewProj;
    mat4 invViewProj;
    vec4 cameraPosition;  // w = exposure
    vec4 viewport;        // w, h, 1/w, 1/h
    vec4 illumViewport;   // I-buffer: w, h, 1/w, 1/h
    uvec4 counts;         // x lights, y illumination scale
    uvec4 lightRange;     // forward shading: x first light, y light count, z 1 = add emissive/unlit
    mat4 view;            // view from world (rigid): the light pre-pass packs view-space normals
} frame;

layout(binding = FE_SLOT_LIGHTS, std430) readonly buffer LightBlock {
    GpuLight lights[];
};

// World position of full-resolution pixel `p` from its depth (Vulkan clip conventions).
vec3 feWorldFromDepth(vec2 pixelCenter, float depth) {
    vec2 ndc = pixelCenter * frame.viewport.zw * 2.0 - 1.0;
    vec4 w = frame.invViewProj * vec4(ndc, depth, 1.0);
    return w.xyz / w.w;
}
#endif

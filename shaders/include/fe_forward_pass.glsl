// The body of forward.frag and forward_ibl.frag.
// The lights come from the uniform block (fe_scene.glsl: on llvmpipe a storage buffer load is a
// loop over the SIMD lanes; measured 794 -> 108 ms for forward-zprepass's shading of
// builtin:lights with 64 lights at 640x360), or with FE_LIGHTS_IN_STORAGE (each forward shader's
// variant) from the storage buffer when they outnumber the block; GeometryRenderer binds either.
#define FE_LIGHTS_UNIFORM
#include "fe_material.glsl"
#ifdef FE_IBL
#include "fe_ibl.glsl"
#endif
#ifdef FE_SHADOWED
#include "fe_shadow.glsl"
#endif
#ifdef FE_TILE_LISTS
#include "fe_tile_culling.glsl"
#endif
#if defined(FE_CLUSTER_LISTS) || defined(FE_MULTISAMPLED)
#include "fe_clusters.glsl"  // forward-plus: the fallback under MSAA
#endif
#ifdef FE_TRANSMISSION
// The transmission pass (render/TransmissionPass.h): the opaque scene behind the surface, from
// its mip-chained copy at the point where the light leaves the volume, rough transmission from
// a coarser level (shading::transmittedSceneWeight, transmissionLod).
layout(binding = FE_SLOT_TRANSMITTED) uniform sampler2D transmittedScene;
vec3 feTransmittedScene(SurfacePoint s, float roughnessUnclamped) {
    if (s.transmission <= 0.0) return vec3(0.0);
    const vec4 clip = frame.viewProjFromEye * vec4(s.Pe + s.transmissionRay, 1.0);
    const vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    const vec2 size = vec2(textureSize(transmittedScene, 0));
    const float iorScale = s.ior == 0.0 ? 1.0 : clamp(2.0 * s.ior - 2.0, 0.0, 1.0);
    const float lod = log2(max(size.x, size.y)) * roughnessUnclamped * iorScale;
    const vec3 F = s.dielectricF0 + (s.dielectricF90 - s.dielectricF0) * feFresnelPower(clamp(dot(s.n, s.wo), 0.0, 1.0));
    const vec3 weight = (1.0 - s.metallic) * s.transmission * s.baseColor * (1.0 - F) * s.transmittance;
    return weight * textureLod(transmittedScene, uv, lod).rgb;
}
#endif
#ifdef FE_DISPLAY_OUT
// forward-plus writing the display image itself where nothing after its shading pass changes L_o
// (SceneRenderer::displayInShading): what the display pass (fe_display_pass.glsl) makes of this
// L_o with background 0, in the same fragment, one full-screen pass fewer.
#include "fe_tonemap.glsl"
layout(constant_id = 205) const uint FE_DISPLAY_TONEMAP = 0u;  // RenderSettings::tonemap
layout(location = 1) out vec4 outDisplay;
#endif
#ifdef FE_TILE_LISTS
// forward-plus's list for a fragment: its tile's; under MSAA (FE_MULTISAMPLED) its cluster's
// where the fragment lies outside the depth bounds its tile was culled for.
bool feInCluster_ = false;
void feUseForwardPlusList(ivec2 pixel, float depth) {
    feUseTileList(pixel);
#ifdef FE_MULTISAMPLED
    feInCluster_ = !feTileListHolds(depth);
    if (feInCluster_) feUseClusterList(pixel, depth);
#endif
}
uint feForwardPlusLightCount(uint end) {
#ifdef FE_MULTISAMPLED
    if (feInCluster_) return feClusterLightCount(end);
#endif
    return feTileLightCount();
}
uint feForwardPlusLight(uint k) {
#ifdef FE_MULTISAMPLED
    if (feInCluster_) return feClusterLight(k);
#endif
    return feTileLight(k);
}
#endif
// Forward: the lights of frame.lightRange in one loop (SHADING.md per-light sum): every light
// for forward and the transparent pass, one per pass for forward-multipass (which adds the
// emissive and unlit terms in its first pass only). forward_ibl.frag adds the environment's
// light by importance sampling (FE_IBL, fe_ibl.glsl). forward_plus*.frag (FE_TILE_LISTS) loop over
// their tile's list instead, forward_clustered*.frag (FE_CLUSTER_LISTS) over their cluster's.
layout(location = 0) out vec4 outRadiance;
void main() {
    MaterialSample m = feSampleMaterial(vUv, vColor, vNormal, vTangent, gl_FrontFacing);
    if (feAlphaDiscard(m.alpha)) discard;
    const bool first = frame.lightRange.z != 0u;
    vec3 L = first ? feCoatedEmission(m, vEye) : vec3(0.0);
    if (m.unlit) {
        L = first ? m.baseColor : vec3(0.0);
    } else {
        const SurfacePoint s = feMaterialSurface(m, vEye);
        const SurfaceBrdf brdf = fePrepareBrdf(s);
#ifdef FE_TILE_LISTS
        // forward-plus: the lights of this pixel's tile list (light-culling pass). Under MSAA a
        // fragment's centre may lie outside the slice its tile was culled for (an edge pixel,
        // culled for sample 0's depths); such a fragment walks its cluster's list instead (the
        // grid every technique's translucent pass reads, culled without depth): exact, and short.
        // (It walked every light until 2026-11-28: 4x MSAA Forward+ then cost 0.30x
        // forward-zprepass's frame on lavapipe, 0.95x on an H200.) At one sample a fragment that
        // passes the EQUAL depth test stands on the depth culled for, whatever its gl_FragCoord.z
        // reads, so the plain variant has no check (two texel fetches and a branch): on lavapipe
        // it cost 97.7 -> 62.2 ms in builtin:atrium at 1024 lights, with no fragment falling back.
        feUseForwardPlusList(ivec2(gl_FragCoord.xy), gl_FragCoord.z);
        const uint end = frame.lightRange.x + frame.lightRange.y;
        const uint count = feForwardPlusLightCount(end);
        for (uint k = 0u; k < count; ++k) {
            const uint i = feForwardPlusLight(k);
            if (i >= end) continue;  // a cluster's whole list is two runs in light order
#elif defined(FE_CLUSTER_LISTS)
        // clustered: the lights of the fragment's cluster (ClusterLightGrid), those of this
        // pass's range (the shadowed lights have passes of their own). An opaque fragment stands
        // on the depth the grid was bounded by (the pre-pass's, EQUAL test; at one sample) and
        // walks the bounded part; a blended one lies in front of it and walks the whole list.
        feUseClusterList(ivec2(gl_FragCoord.xy), gl_FragCoord.z);
        const uint end = frame.lightRange.x + frame.lightRange.y;
#ifdef FE_MULTISAMPLED
        const bool whole = true;
#else
        const bool whole = object.params.w == 2.0;
#endif
        const uint count = whole ? feClusterLightCount(end) : feClusterBoundedLightCount(end);
        for (uint k = 0u; k < count; ++k) {
            const uint i = feClusterLight(k);
            if (i >= end) continue;
#else
        const uint end = frame.lightRange.x + frame.lightRange.y;
        for (uint i = frame.lightRange.x; i < end; ++i) {
#endif
            SurfaceLight l = feEvaluateLightFromEye(feLight(i), vEye);
#ifdef FE_SHADOWED
            l.E *= feShadowVisibility(s.P, s.n);  // forward_shadowed*.frag: one light per pass
#endif
            L += feShadeLight(brdf, l);
        }
#ifdef FE_IBL
        // The environment's light, with the emissive term in the first pass (frame.counts.z samples).
        if (first) L += feOcclusion(vUv) * feShadeEnvironment(s, frame.counts.z);
#endif
#ifdef FE_TRANSMISSION
        L += feTransmittedScene(s, m.roughnessUnclamped);
#endif
    }
    // Alpha only matters for BLEND draws (source-over); opaque targets ignore it.
    outRadiance = vec4(L, object.params.w == 2.0 ? m.alpha : 1.0);
#ifdef FE_DISPLAY_OUT
    outDisplay = vec4(feDisplayedBy(frame.cameraPosition.w * L, FE_DISPLAY_TONEMAP), 1.0);
#endif
}

// The body of material*.frag, the redeferred material pass at full resolution: L_o = emissive
// + L_d + L_s from the I-buffer. One shader per path, chosen when the pipeline is made: on
// llvmpipe a path present but not taken measured as costly as running it (35 ms of a 53 ms pass
// at 1280x720), so no path is a run-time branch.
//   material.frag                 scale 1, w_o.n read from G-buffer 2 (consideration A)
//   material_rebuild_nov.frag     scale 1, w_o.n rebuilt from depth and the normal (FE_REBUILD_NOV)
//   material_upsample.frag        reduced rate (FE_UPSAMPLE): the sums upsampled with a
//                                 G-buffer-guided filter: the bilinear weights of the 4 nearest
//                                 I-buffer texels times depth, normal and roughness similarity
//                                 between this pixel and each texel's representative pixel
//   material_upsample_split.frag  reduced rate, only L_dg upsampled (FE_SPLIT, --illum-split)
layout(binding = FE_SLOT_GBUFFER0) uniform sampler2D gb0;
layout(binding = FE_SLOT_GBUFFER1) uniform sampler2D gb1;
layout(binding = FE_SLOT_GBUFFER2) uniform sampler2D gb2;
layout(binding = FE_SLOT_DEPTH) uniform sampler2D depthTexture;
layout(binding = FE_SLOT_IBUFFER0) uniform sampler2D iLdg;
layout(binding = FE_SLOT_IBUFFER1) uniform sampler2D iLsg1;
layout(binding = FE_SLOT_IBUFFER2) uniform sampler2D iLsg2;
layout(location = 0) out vec4 outRadiance;

// Depth along the view axis, from the depth buffer: the w row of the inverse projection (and of
// invViewProj, the view being rigid) depends on depth alone, so no matrix product is needed.
float viewDepth(float depth) {
    return 1.0 / abs(frame.invViewProj[2][3] * depth + frame.invViewProj[3][3]);
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 g2 = texelFetch(gb2, p, 0);
    if (g2.a < 0.0) discard;  // nothing drawn here (G-buffer 2's clear value)
    if (feGBufferUnlit(g2.a)) { outRadiance = vec4(g2.rgb, 1.0); return; }
    vec4 g0 = texelFetch(gb0, p, 0);
    vec4 g1 = texelFetch(gb1, p, 0);
    IlluminationSums acc;
#if !defined(FE_UPSAMPLE) && !defined(FE_REBUILD_NOV)
    // Consideration A: w_o.n from the geometry pass; no depth, position or normal needed.
    acc.Ldg = texelFetch(iLdg, p, 0).rgb;
    acc.Lsg1 = texelFetch(iLsg1, p, 0).rgb;
    acc.Lsg2 = texelFetch(iLsg2, p, 0).rgb;
    outRadiance = vec4(g2.rgb + feResolveMaterialNoV(acc, g2.a, g0.rgb, g0.a, g1.a), 1.0);
#else
    float depth = texelFetch(depthTexture, p, 0).r;
    vec3 P = feWorldFromDepth(vec2(p) + 0.5, depth);
    vec3 n = normalize(g1.xyz);
    vec3 wo = normalize(frame.cameraPosition.xyz - P);
#ifndef FE_UPSAMPLE
    acc.Ldg = texelFetch(iLdg, p, 0).rgb;
    acc.Lsg1 = texelFetch(iLsg1, p, 0).rgb;
    acc.Lsg2 = texelFetch(iLsg2, p, 0).rgb;
#else
    {
        // With the split I-buffer (FE_SPLIT) the specular sums are at full resolution: only
        // L_dg is upsampled.
#ifdef FE_SPLIT
        const bool split = true;
#else
        const bool split = false;
#endif
        const int scale = int(frame.counts.y);
        ivec2 isize = ivec2(frame.illumViewport.xy);
        // Texel qi holds the sums of its representative pixel qi * scale + scale / 2 (the
        // illumination passes' choice), so that pixel, not the block's centre, is where texel qi
        // lies in the bilinear footprint.
        vec2 q = (vec2(p) - float(scale / 2)) / float(scale);
        ivec2 q0 = ivec2(floor(q));
        vec2 f = q - vec2(q0);
        float zp = viewDepth(depth);
        acc.Ldg = vec3(0.0);
        acc.Lsg1 = vec3(0.0);
        acc.Lsg2 = vec3(0.0);
        float wsum = 0.0;
        IlluminationSums nearest = acc;
        float best = -1.0;
        for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 2; ++i) {
                ivec2 qi = clamp(q0 + ivec2(i, j), ivec2(0), isize - 1);
                ivec2 rep = min(qi * scale + scale / 2, ivec2(frame.viewport.xy) - 1);
                float dr = texelFetch(depthTexture, rep, 0).r;
                vec4 r1 = texelFetch(gb1, rep, 0);
                float bil = (i == 0 ? 1.0 - f.x : f.x) * (j == 0 ? 1.0 - f.y : f.y);
                float wz = dr >= 1.0 ? 0.0 : exp(-abs(viewDepth(dr) - zp) / (0.02 * zp));
                float wn = pow(max(dot(normalize(r1.xyz), n), 0.0), 32.0);
                float wr = exp(-abs(r1.a - g1.a) / 0.05);
                float w = bil * wz * wn * wr;
                vec3 a = texelFetch(iLdg, qi, 0).rgb;
                vec3 b = split ? vec3(0.0) : texelFetch(iLsg1, qi, 0).rgb;
                vec3 c = split ? vec3(0.0) : texelFetch(iLsg2, qi, 0).rgb;
                acc.Ldg += w * a;
                acc.Lsg1 += w * b;
                acc.Lsg2 += w * c;
                wsum += w;
                float sim = wz * wn * wr;
                if (sim > best) { best = sim; nearest.Ldg = a; nearest.Lsg1 = b; nearest.Lsg2 = c; }
            }
        if (wsum > 1e-6) {
            acc.Ldg /= wsum;
            acc.Lsg1 /= wsum;
            acc.Lsg2 /= wsum;
        } else {
            acc = nearest;  // no similar neighbour: take the most similar one
        }
        if (split) {
            acc.Lsg1 = texelFetch(iLsg1, p, 0).rgb;
            acc.Lsg2 = texelFetch(iLsg2, p, 0).rgb;
        }
    }
#endif  // FE_UPSAMPLE
    outRadiance = vec4(g2.rgb + feResolveMaterial(acc, n, wo, g0.rgb, g0.a, g1.a), 1.0);
#endif
}

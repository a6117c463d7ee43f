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
//   material_upsample_tiled.frag  the same, each texel's representative pixel data read from the
//                                 I-buffer's alpha channels (FE_REP_IN_IBUFFER; fe_scene.glsl)
//   material_upsample_split.frag  reduced rate, only L_dg upsampled (FE_SPLIT, --illum-split)
layout(binding = FE_SLOT_GBUFFER0) uniform sampler2D gb0;
layout(binding = FE_SLOT_GBUFFER1) uniform sampler2D gb1;
layout(binding = FE_SLOT_GBUFFER2) uniform sampler2D gb2;
layout(binding = FE_SLOT_DEPTH) uniform sampler2D depthTexture;
layout(binding = FE_SLOT_IBUFFER0) uniform sampler2D iLdg;
layout(binding = FE_SLOT_IBUFFER1) uniform sampler2D iLsg1;
layout(binding = FE_SLOT_IBUFFER2) uniform sampler2D iLsg2;
layout(location = 0) out vec4 outRadiance;

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
        float zp = feViewDepth(depth);
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
                const vec4 ta = texelFetch(iLdg, qi, 0);
                const vec4 tb = split ? vec4(0.0) : texelFetch(iLsg1, qi, 0);
                const vec4 tc = split ? vec4(0.0) : texelFetch(iLsg2, qi, 0);
                vec3 a = ta.rgb, b = tb.rgb, c = tc.rgb;
                // The representative pixel's view depth, normal and roughness: from the I-buffer's
                // alpha channels where the tiled pass stored them (FE_REP_IN_IBUFFER, and the
                // depth alone with FE_SPLIT), else from the G-buffer.
#if defined(FE_REP_IN_IBUFFER) || defined(FE_SPLIT)
                const float zr = ta.a;
#else
                const float dr = texelFetch(depthTexture, rep, 0).r;
                const float zr = dr >= 1.0 ? 0.0 : feViewDepth(dr);
#endif
#ifdef FE_REP_IN_IBUFFER
                float octY, rr;
                feUnpackOctYRoughness(tc.a, octY, rr);
                const vec4 r1 = vec4(feOctDecode(vec2(tb.a, octY)), rr);
#else
                const vec4 r1 = texelFetch(gb1, rep, 0);
#endif
                float bil = (i == 0 ? 1.0 - f.x : f.x) * (j == 0 ? 1.0 - f.y : f.y);
                float wz = zr <= 0.0 ? 0.0 : exp(-abs(zr - zp) / (0.02 * zp));
                float wn = pow(max(dot(normalize(r1.xyz), n), 0.0), 32.0);
                float wr = exp(-abs(r1.a - g1.a) / 0.05);
                float w = bil * wz * wn * wr;
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

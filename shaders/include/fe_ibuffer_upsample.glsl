// The G-buffer-guided upsampling of reduced-rate I-buffer sums to full-resolution pixel p
// (depth, unit normal n, G-buffer 1 texel g1): the bilinear weights of the 4 nearest I-buffer
// texels times depth, normal and roughness similarity between p and each texel's representative
// pixel. Reads the includer's iLdg, iLsg1, iLsg2, gb1 and depthTexture at the scale and I-buffer
// size of frame.counts.y and frame.illumViewport. Used by the material pass (material_upsample*)
// and by the per-source rates' upsampling passes (ibuffer_upsample.frag).
#ifndef FE_IBUFFER_UPSAMPLE_GLSL
#define FE_IBUFFER_UPSAMPLE_GLSL
IlluminationSums feUpsampleIBuffer(ivec2 p, float depth, vec3 n, vec4 g1) {
    IlluminationSums acc;
    // With the split I-buffer (FE_SPLIT) the specular sums are at full resolution: only
    // L_dg is upsampled.
#ifdef FE_SPLIT
    const bool split = true;
#else
    const bool split = false;
#endif
    const int scale = int(frame.counts.y);
    ivec2 isize = ivec2(frame.illumViewport.xy);
    // Texel qi holds the sums of its representative pixel qi * scale + feRepOffset() (the
    // illumination passes' choice), so that pixel, not the block's centre, is where texel qi
    // lies in the bilinear footprint.
    vec2 q = (vec2(p) - vec2(feRepOffset())) / float(scale);
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
            ivec2 rep = min(qi * scale + feRepOffset(), ivec2(frame.viewport.xy) - 1);
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
            vec4 r1 = texelFetch(gb1, rep, 0);
            r1.xyz = normalize(r1.xyz);
#endif
            float bil = (i == 0 ? 1.0 - f.x : f.x) * (j == 0 ? 1.0 - f.y : f.y);
            // One exp for depth and roughness together, and cos^32 by five squarings: on
            // lavapipe pow() is exp2(32 log2 x), and the two exps and pow per tap measured a
            // large part of the reduced-rate material pass (docs/MEASUREMENT_LOG.md).
            float wzr = zr <= 0.0 ? 0.0 : exp(-abs(zr - zp) / (0.02 * zp) - abs(r1.a - g1.a) / 0.05);
            float cn = max(dot(r1.xyz, n), 0.0);  // r1.xyz is unit (feOctDecode, or normalized above)
            cn *= cn;
            cn *= cn;
            cn *= cn;
            cn *= cn;
            float wn = cn * cn;
            float w = bil * wzr * wn;
            acc.Ldg += w * a;
            acc.Lsg1 += w * b;
            acc.Lsg2 += w * c;
            wsum += w;
            float sim = wzr * wn;
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
        return acc;
}
#endif

// The direction that addresses texture coordinate (s, t) of cube face `face` (+X, -X, +Y, -Y,
// +Z, -Z), inverting the major-axis table both APIs share. Band f of six across the target is
// face f; each band's left/right half is s = 0.25/0.75, the top/bottom half t = 0.25/0.75.
vec3 cubeDirection(vec2 fragCoord, out int face) {
    float u = fragCoord.x * 6.0 / 64.0;
    face = int(floor(u));
    float sc = fract(u) < 0.5 ? -0.5 : 0.5;
    float tc = fragCoord.y < 32.0 ? -0.5 : 0.5;
    if (face == 0) return vec3(1.0, -tc, -sc);
    if (face == 1) return vec3(-1.0, -tc, sc);
    if (face == 2) return vec3(sc, 1.0, tc);
    if (face == 3) return vec3(sc, -1.0, -tc);
    if (face == 4) return vec3(sc, -tc, 1.0);
    return vec3(-sc, -tc, -1.0);
}

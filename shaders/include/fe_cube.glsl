// Cube map faces: the direction of a face texel.
#ifndef FE_CUBE_GLSL
#define FE_CUBE_GLSL
// The direction through point (s, t) in [0, 1]^2 of cube face `face`, inverting the cube map
// face selection of the Vulkan and OpenGL specifications (sc, tc = 2 s - 1, 2 t - 1).
vec3 feCubeFaceDirection(int face, vec2 st) {
    const vec2 c = st * 2.0 - 1.0;
    vec3 d;
    if (face == 0) d = vec3(1.0, -c.y, -c.x);
    else if (face == 1) d = vec3(-1.0, -c.y, c.x);
    else if (face == 2) d = vec3(c.x, 1.0, c.y);
    else if (face == 3) d = vec3(c.x, -1.0, -c.y);
    else if (face == 4) d = vec3(c.x, -c.y, 1.0);
    else d = vec3(-c.x, -c.y, -1.0);
    return normalize(d);
}
#endif

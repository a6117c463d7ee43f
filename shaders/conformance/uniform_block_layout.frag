#version 450
// conformance/uniform_block_layout: a std140 block of every kind of member whose offsets a
// C++ struct would have to pad by hand, written by name (gdi::UniformBlock). Each column of 8
// pixels checks a group of members against the values the case writes: green where they hold,
// red where not.
struct Light {
    vec3 colour;
    float weight;
    vec2 direction;
};
layout(binding = 0, std140) uniform Material {
    float scale;              // 0
    vec3 tint;                // 16
    vec2 offsets[3];          // 32, stride 16
    mat3 rotation;            // 80, columns 16 apart
    int mode;                 // 128
    uint flags;               // 132
    bool enabled;             // 136
    Light lights[2];          // 144, stride 32
    layout(row_major) mat2x3 skew;  // 208: 3 rows of 2, 16 apart
    ivec2 counts;             // 256
} m;
layout(location = 0) out vec4 outColor;

bool near(float a, float b) { return abs(a - b) < 1e-6; }
bool near3(vec3 a, vec3 b) { return all(lessThan(abs(a - b), vec3(1e-6))); }

void main() {
    const int column = int(gl_FragCoord.x) / 8;
    bool ok = false;
    if (column == 0) ok = near(m.scale, 0.25) && near3(m.tint, vec3(0.5, 0.75, 1.0));
    if (column == 1)
        ok = near(m.offsets[0].x, 1.0) && near(m.offsets[1].y, -2.0) && near(m.offsets[2].x, 3.5);
    if (column == 2)  // column-major: rotation[c] is column c
        ok = near3(m.rotation[0], vec3(1, 2, 3)) && near3(m.rotation[1], vec3(4, 5, 6)) &&
             near3(m.rotation[2], vec3(7, 8, 9));
    if (column == 3) ok = m.mode == -7 && m.flags == 0x80000001u && m.enabled;
    if (column == 4)
        ok = near3(m.lights[0].colour, vec3(0.1, 0.2, 0.3)) && near(m.lights[0].weight, 0.5) &&
             near3(m.lights[1].colour, vec3(0.9, 0.8, 0.7)) && near(m.lights[1].direction.y, -1.0);
    if (column == 5)  // skew[c][r]: column c, row r, whatever the memory order
        ok = near(m.skew[0][0], 1.0) && near(m.skew[1][0], 2.0) && near(m.skew[0][2], 5.0) &&
             near(m.skew[1][2], 6.0);
    if (column == 6) ok = m.counts == ivec2(3, -4);
    if (column == 7) ok = true;
    outColor = ok ? vec4(0, 1, 0, 1) : vec4(1, 0, 0, 1);
}

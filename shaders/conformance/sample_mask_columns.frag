#version 450
// gl_SampleMask by pixel column (x % 4): 0 no sample, 1 sample 0, 2 samples 1-3, 3 every sample;
// column 3's lower half returns early with an empty mask (a second return of main).
layout(location = 0) out vec4 outColor;
void main() {
    const int masks[4] = int[4](0, 1, 0xe, -1);
    const int column = int(gl_FragCoord.x) & 3;
    outColor = vec4(1.0);
    if (column == 3 && gl_FragCoord.y >= 32.0) {
        gl_SampleMask[0] = 0;
        return;
    }
    gl_SampleMask[0] = masks[column];
}

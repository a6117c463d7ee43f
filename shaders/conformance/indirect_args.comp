#version 450
// Writes indirect argument records the way a GPU-driven renderer would (layout in
// StateCases.cpp): four quad draws, a draw count of 2, one indexed draw, a dispatch of 8x8x1.
layout(local_size_x = 1) in;
layout(binding = 0, std430) buffer Args { uint words[]; };
void main() {
    // drawIndirect records at byte 0: {vertexCount, instanceCount, firstVertex, firstInstance}
    words[0] = 6u; words[1] = 1u; words[2] = 0u; words[3] = 0u;
    words[4] = 6u; words[5] = 1u; words[6] = 6u; words[7] = 1u;
    words[8] = 6u; words[9] = 1u; words[10] = 0u; words[11] = 2u;
    words[12] = 6u; words[13] = 1u; words[14] = 6u; words[15] = 3u;
    words[16] = 2u;  // the draw count, at byte 64
    // drawIndexedIndirect record at byte 128: {indexCount, instanceCount, firstIndex, baseVertex, firstInstance}
    words[32] = 6u; words[33] = 2u; words[34] = 0u; words[35] = 12u; words[36] = 4u;
    // dispatchIndirect record at byte 192
    words[48] = 8u; words[49] = 8u; words[50] = 1u;
}

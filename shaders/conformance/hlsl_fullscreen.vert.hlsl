// A triangle over the whole target from SV_VertexID, in the engine's clip space (Vulkan's: y
// down, so uv = pixel / 64); uv for hlsl_tint.frag.hlsl. The conformance case hlsl_shaders.
// fe-entry: VSMain
struct VSOut {
    float4 position : SV_Position;
    float2 uv : TEXCOORD0;
};
VSOut VSMain(uint id : SV_VertexID) {
    VSOut o;
    const float2 p = float2((id << 1) & 2, id & 2);
    o.position = float4(p * 2.0 - 1.0, 0.0, 1.0);
    o.uv = p;
    return o;
}

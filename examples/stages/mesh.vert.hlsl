// The mesh in HLSL, as a Direct3D program would write it: a register's number is its slot, and
// the view-projection matrix, written from glm, is the M of mul(M, v) (docs/PORTING.md).
// fe-entry: VSMain
cbuffer Frame : register(b0) {
    float4x4 viewProj;
    float4 lightDir;
};
struct VSIn {
    float3 position : POSITION;
    float3 normal : NORMAL;
};
struct VSOut {
    float4 position : SV_Position;
    float3 normal : NORMAL;
};
VSOut VSMain(VSIn i) {
    VSOut o;
    o.position = mul(viewProj, float4(i.position, 1.0));
    o.normal = i.normal;
    return o;
}

// A 2x2 texture (t1, sampled through s1) at uv, times mul(transform, tint) (b0): a register's
// number is its slot, whatever its letter, and a float4x4 written from glm (column-major) is the
// matrix mul(M, v) multiplies by. The conformance case hlsl_shaders.
// fe-entry: PSMain
cbuffer Params : register(b0) {
    float4x4 transform;
    float4 tint;
};
Texture2D<float4> quadrants : register(t1);
SamplerState nearest : register(s1);
float4 PSMain(float4 position : SV_Position, float2 uv : TEXCOORD0) : SV_Target0 {
    return quadrants.Sample(nearest, uv) * mul(transform, tint);
}

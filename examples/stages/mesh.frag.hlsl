// Lambert in a warm red, so the mesh's pixels are told apart from the normals' and the terrain's.
// fe-entry: PSMain
cbuffer Frame : register(b0) {
    float4x4 viewProj;
    float4 lightDir;
};
float4 PSMain(float4 position : SV_Position, float3 normal : NORMAL) : SV_Target0 {
    const float lit = saturate(dot(normalize(normal), lightDir.xyz));
    return float4(float3(1.0, 0.3, 0.2) * (0.25 + 0.75 * lit), 1.0);
}

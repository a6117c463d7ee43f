// Binding slots of the scene shaders; must match shaders/include/fe_scene.glsl.
#pragma once
#include <cstdint>

namespace fe::render {
constexpr uint32_t kSlotFrame = 0;
constexpr uint32_t kSlotObject = 1;
constexpr uint32_t kSlotLights = 2;
constexpr uint32_t kSlotBaseColor = 3;
constexpr uint32_t kSlotMetalRough = 4;
constexpr uint32_t kSlotNormalMap = 5;
constexpr uint32_t kSlotEmissive = 6;
constexpr uint32_t kSlotOcclusion = 7;
constexpr uint32_t kSlotGBuffer0 = 8;
constexpr uint32_t kSlotGBuffer1 = 9;
constexpr uint32_t kSlotGBuffer2 = 10;
constexpr uint32_t kSlotDepth = 11;
constexpr uint32_t kSlotIBuffer0 = 12;
constexpr uint32_t kSlotIBuffer1 = 13;
constexpr uint32_t kSlotIBuffer2 = 14;
constexpr uint32_t kSlotRadiance = 15;
constexpr uint32_t kSlotRadianceOut = 16;        // storage image: compute passes writing L_o
constexpr uint32_t kSlotTileLights = 17;         // per-tile light lists (TileLightCulling), sampled
constexpr uint32_t kSlotTileLightsOut = 18;      // ... and written, by the light-culling pass
constexpr uint32_t kSlotEnvironment = 19;        // the environment cube map (EnvironmentMap)
constexpr uint32_t kSlotEnvironmentSource = 20;  // its source: the equirectangular image
constexpr uint32_t kSlotShadow = 21;             // a shadowed light's ShadowMaps::Constants
constexpr uint32_t kSlotShadowMap = 22;  // ... and its map (2D array or cube, comparison sampler)
constexpr uint32_t kSlotIblSh = 23;      // image-based lighting's fast path: irradiance SH
constexpr uint32_t kSlotIblLut = 24;     // ... and its split-sum table (PrefilteredEnvironment)
constexpr uint32_t kSlotHistory0 = 25;   // redeferred temporal accumulation: last frame's sums
constexpr uint32_t kSlotHistory1 = 26;
constexpr uint32_t kSlotHistory2 = 27;
constexpr uint32_t kSlotGBuffer3 = 28;      // the G-buffer's occlusion (GBuffer::gb3), or 1x1 white
constexpr uint32_t kSlotTransmission = 29;  // KHR_materials_transmission's texture (R)
constexpr uint32_t kSlotThickness = 30;     // KHR_materials_volume's thickness texture (G)
constexpr uint32_t kSlotTransmitted =
    31;  // the opaque scene's mip-chained copy the transmission pass samples
constexpr uint32_t kSlotSheenColor = 32;      // KHR_materials_sheen's colour texture (RGB, sRGB)
constexpr uint32_t kSlotSheenRoughness = 33;  // ... and its roughness texture (A)
constexpr uint32_t kSlotTaa = 34;             // temporal antialiasing's constants (PostProcess)
constexpr uint32_t kSlotClusterLights =
    35;  // the light cluster grid's lists (ClusterLightGrid), storage buffer
constexpr uint32_t kSlotVisibility = 36;  // the visibility buffer's triangle ids (R32U, sampled)
constexpr uint32_t kSlotDraws = 37;       // every draw's ObjectConstants (storage buffer)
constexpr uint32_t kSlotVertices = 38;  // the scene's vertices, pulled by shaders (storage buffer)
constexpr uint32_t kSlotIndices = 39;   // ... and its indices
constexpr uint32_t kSlotClusterColumns =
    40;  // the cluster light assignment's lights per tile column (storage buffer)
constexpr uint32_t kSlotClusterIndices =
    41;  // the light cluster grid's list entries (R32U texture), sampled
constexpr uint32_t kSlotClusterIndicesOut = 42;  // ... and written, by the light assignment
constexpr uint32_t kSlotSheenAlbedo =
    44;  // the sheen's albedo table (shading::sheenAlbedoTable, R32F), with every texture set
constexpr uint32_t kSlotSpecular = 45;            // KHR_materials_specular's textures: specular (A)
constexpr uint32_t kSlotSpecularColor = 46;       // ... and specular colour (RGB, sRGB)
constexpr uint32_t kSlotClearcoat = 47;           // KHR_materials_clearcoat's textures: factor (R)
constexpr uint32_t kSlotClearcoatRoughness = 48;  // ... roughness (G)
constexpr uint32_t kSlotClearcoatNormal = 49;     // ... and the layer's normal map
constexpr uint32_t kSlotClusterBounds =
    43;  // the opaque depths each light cluster holds (storage buffer)
constexpr uint32_t kSlotSkin =
    50;  // mesh deformation: the skinned primitives' influences (storage buffer)
constexpr uint32_t kSlotMorphTargets = 51;  // ... the morph targets' deltas
constexpr uint32_t kSlotPose = 52;          // ... the frame's joint matrices and morph weights
constexpr uint32_t kSlotDeformations = 53;  // ... what each deformed primitive reads and writes
constexpr uint32_t kSlotDeformGroups = 54;  // ... and which of them each work group deforms
constexpr uint32_t kSlotVisibleLights =
    55;  // the lights the light-culling pass walks (TileLightCulling::lightsInView)
}  // namespace fe::render

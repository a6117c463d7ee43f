// Included by every shader: hides the few differences between Vulkan and OpenGL SPIR-V.
#ifndef FE_COMMON_GLSL
#define FE_COMMON_GLSL
// FE_VERTEX_ID counts from firstVertex (plus baseVertex), FE_INSTANCE_ID from firstInstance,
// on both: GL's gl_InstanceID starts at 0 whatever the base instance, so the base is added
// (ARB_shader_draw_parameters, SPIR-V DrawParameters).
#if defined(FE_VULKAN)
#define FE_VERTEX_ID gl_VertexIndex
#define FE_INSTANCE_ID gl_InstanceIndex
#else
#extension GL_ARB_shader_draw_parameters : enable
#define FE_VERTEX_ID gl_VertexID
#define FE_INSTANCE_ID (gl_InstanceID + gl_BaseInstanceARB)
#endif
// Per-draw constants (CommandList::setConstants, at most 128 bytes, one block per shader):
//   FE_CONSTANTS(DrawConstants) { mat4 model; vec4 tint; } draw;
// A push-constant block on Vulkan; on GL, which has no push constants, a uniform block at the
// binding the device reserves for them (64, past the 0..63 slots). std140 on both, so the
// bytes written land on the same members everywhere.
#if defined(FE_VULKAN)
#define FE_CONSTANTS(Name) layout(push_constant, std140) uniform Name
#else
#define FE_CONSTANTS(Name) layout(std140, binding = 64) uniform Name
#endif
#endif

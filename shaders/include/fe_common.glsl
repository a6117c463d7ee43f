// Included by every shader: hides the few differences between Vulkan and OpenGL SPIR-V.
#ifndef FE_COMMON_GLSL
#define FE_COMMON_GLSL
#if defined(FE_VULKAN)
#define FE_VERTEX_ID gl_VertexIndex
#define FE_INSTANCE_ID gl_InstanceIndex  // draws use firstInstance 0, where the two agree
#else
#define FE_VERTEX_ID gl_VertexID
#define FE_INSTANCE_ID gl_InstanceID
#endif
#endif

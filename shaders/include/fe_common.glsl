// Included by every shader: hides the few differences between Vulkan and OpenGL SPIR-V.
#ifndef FE_COMMON_GLSL
#define FE_COMMON_GLSL
#if defined(FE_VULKAN)
#define FE_VERTEX_ID gl_VertexIndex
#else
#define FE_VERTEX_ID gl_VertexID
#endif
#endif

#version 450
// A vertex shader a Vulkan sample would write: gl_VertexIndex is not GL's name. The GL compile
// fails, and fe_add_shaders' wrapper says to write FE_VERTEX_ID (test shader_error_names_portable_macro).
void main() { gl_Position = vec4(float(gl_VertexIndex), 0.0, 0.0, 1.0); }

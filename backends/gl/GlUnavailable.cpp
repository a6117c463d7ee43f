#include "gl/GlBackend.h"

namespace fe::gl {
std::unique_ptr<gdi::Device> createGlDevice(PlatformKind platform, bool) {
    const char* name = platform == PlatformKind::Egl ? "gl-egl" : platform == PlatformKind::OSMesa ? "gl-osmesa" : "gl-glfw";
    throw gdi::Error(std::string(name) + ": the OpenGL backend is not built in this version (backends/gl is a placeholder)");
}
}  // namespace fe::gl

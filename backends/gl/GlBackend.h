// Entry point of the OpenGL 4.5 backend; the only GL symbol visible outside backends/gl.
#pragma once
#include <memory>

#include "fe/gdi/Device.h"

namespace fe::gl {
enum class PlatformKind { Egl, OSMesa, Glfw };
// Throws gdi::Error saying why the platform could not give a GL 4.5 core context
// (library missing, no EGL device, no display, ...).
// `vsync`: the window platform (Glfw) swaps on the display's refresh; ignored by headless ones.
std::unique_ptr<gdi::Device> createGlDevice(PlatformKind platform, bool validation, bool vsync = true);
}  // namespace fe::gl

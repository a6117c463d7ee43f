// Entry point of the OpenGL 4.5 backend; the only GL symbol visible outside backends/gl.
#pragma once
#include <functional>
#include <memory>

#include "fe/gdi/Device.h"

namespace fe::gl {
enum class PlatformKind { Egl, OSMesa, Glfw };
// Throws gdi::Error saying why the platform could not give a GL 4.5 core context
// (library missing, no EGL device, no display, ...).
// `vsync`: the window platform (Glfw) swaps on the display's refresh; ignored by headless ones.
std::unique_ptr<gdi::Device> createGlDevice(PlatformKind platform, bool validation,
                                            bool vsync = true);
// Runs `task` on the thread that owns the device's GL context, after the work queued before
// it (interop, and bench/ measuring direct GL calls). Throws Error when `device` is not GL.
void runOnContextThread(gdi::Device& device, const std::function<void()>& task);
}  // namespace fe::gl

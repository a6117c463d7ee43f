// Where a GL context comes from, apart from the driver (Filament's Platform idea): EGL
// (surfaceless, headless), OSMesa (offscreen), GLFW (a window; not built in this version).
// Libraries are opened at run time so a missing one is a reason, not a link failure.
#pragma once
#include <memory>
#include <string>

#include "gl/GlBackend.h"

namespace fe::gl {

class GlPlatform {
public:
    virtual ~GlPlatform() = default;
    virtual const char* name() const = 0;
    virtual void* getProcAddress(const char* name) = 0;
    virtual void makeCurrent() = 0;
};

// Creates a 4.5 core context (debug context when `debug`); throws gdi::Error saying why not.
std::unique_ptr<GlPlatform> createPlatform(PlatformKind kind, bool debug);

}  // namespace fe::gl

#include "platform/DynamicLibrary.h"

#include <dlfcn.h>

#include "fe/gdi/Device.h"

namespace fe::platform {

void* openLibrary(const char* const* names, const char* package) {
    for (const char* const* n = names; *n; ++n)
        if (void* h = dlopen(*n, RTLD_NOW | RTLD_LOCAL)) return h;
    throw gdi::Error(std::string(names[0]) + " not found (apt-get install " + package + ")");
}

void* librarySymbol(void* library, const char* name) {
    void* p = dlsym(library, name);
    if (!p) throw gdi::Error(std::string("symbol ") + name + " missing from its library");
    return p;
}

}  // namespace fe::platform

// Sanitizer builds only (cmake/FeSanitize.cmake): dlclose does nothing, so the driver modules the
// Vulkan loader and the GL platform load stay mapped until the process exits and LeakSanitizer
// can attribute what they leak to them by name (tools/sanitizers/lsan.supp). Being defined in
// the executable, this dlclose takes precedence over libc's for every library in the process.
// Unloading is only ever an optimisation, so keeping modules loaded changes no behaviour.
#include <dlfcn.h>

int dlclose(void* handle) {
    (void)handle;
    return 0;
}

#include "fe/gdi/Backend.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace fe::gdi {

// mallopt rather than GLIBC_TUNABLES: the tunables are read once, when the process starts, so
// only its parent could set them (the test suite does: cmake/FeTestEnvironment.cmake).
void keepFreedMemory() {
#if defined(__GLIBC__)
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, -1);  // (unsigned) the largest: never trim
    mallopt(M_TOP_PAD, 64 << 20);
#endif
}

}  // namespace fe::gdi

// Libraries opened at run time (dlopen), shared by the backends' platforms: a missing library is
// a reason a backend cannot start, not a link error that stops every backend.
#pragma once
#include <string>

namespace fe::platform {

// Opens the first of `names` (null-terminated list) that loads; throws gdi::Error naming the
// Debian `package` that provides it.
void* openLibrary(const char* const* names, const char* package);
// A symbol of an opened library; throws gdi::Error when it is missing.
void* librarySymbol(void* library, const char* name);

template <class T>
T symbol(void* library, const char* name) {
    return reinterpret_cast<T>(librarySymbol(library, name));
}

}  // namespace fe::platform

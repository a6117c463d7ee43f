// Sanitizer builds only (cmake/FeSanitize.cmake): the AddressSanitizer options every program of
// the build starts with; ASAN_OPTIONS in the environment still overrides each of them.
//
// intercept_tls_get_addr=0: GCC 12's and clang 14's runtimes (LLVM 16 and older) intercept
// __tls_get_addr and take a dynamic TLS block that happens to start 16 bytes past a page boundary
// for a glibc-2.19 block whose header holds its real start and size. Since glibc 2.25 there is no
// such header, so those two words are whatever malloc left there, and LeakSanitizer's tracer
// later scans that "range" and dies ("Tracer caught signal 11", no leak named). Mesa's drivers
// use dynamic TLS in their threads, so any test can draw it: seen once in three full sanitized
// runs (NativeFaults/gl_osmesa, 2026-11-24; 15 reruns of that test passed). Without the interceptor the blocks are ordinary heap
// blocks reachable from the thread's DTV, so leak checking loses nothing.
const char* __asan_default_options(void) { return "intercept_tls_get_addr=0"; }

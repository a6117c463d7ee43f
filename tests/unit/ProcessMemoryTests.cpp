// gdi::keepFreedMemory (Backend.h): after it, a large block comes from the heap (not a mapping
// of its own) and stays with the process once freed, so the next frame's allocation of it does
// not fault its pages in again. The test suite sets the same policy through GLIBC_TUNABLES
// (cmake/FeTestEnvironment.cmake), so the check runs in a child started again without them.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "fe/gdi/Backend.h"

#if defined(__GLIBC__)
#include <malloc.h>

namespace {

// 0 when a 16 MiB block came from the heap and its memory was kept after free, else 1 or 2.
int allocateAndFree() {
    fe::gdi::keepFreedMemory();
    constexpr size_t kBlock = size_t(16) << 20;
    const size_t mappedBefore = mallinfo2().hblkhd;
    void* block = std::malloc(kBlock);
    static_cast<volatile char*>(block)[kBlock - 1] = 1;
    const bool fromHeap = mallinfo2().hblkhd == mappedBefore;
    std::free(block);
    const bool kept = mallinfo2().fordblks >= kBlock;
    return fromHeap ? (kept ? 0 : 2) : 1;
}

}  // namespace

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define FE_ALLOCATOR_REPLACED 1  // the sanitizer's allocator stands in for glibc's
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || \
    __has_feature(memory_sanitizer)
#define FE_ALLOCATOR_REPLACED 1
#endif
#endif

TEST(ProcessMemory, KeepFreedMemoryKeepsLargeBlocksInTheHeap) {
#ifdef FE_ALLOCATOR_REPLACED
    GTEST_SKIP() << "a sanitizer's allocator replaces glibc's malloc, which mallopt tunes";
#endif
    // The "threadsafe" style starts the binary again, with the environment as it is now.
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    const char* tunables = std::getenv("GLIBC_TUNABLES");
    const std::string kept = tunables ? tunables : "";
    unsetenv("GLIBC_TUNABLES");
    EXPECT_EXIT(std::exit(allocateAndFree()), ::testing::ExitedWithCode(0), "");
    if (tunables) setenv("GLIBC_TUNABLES", kept.c_str(), 1);  // for the processes tests start
}
#endif

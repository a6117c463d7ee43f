// gdi::keepFreedMemory (Backend.h): after it, a large block comes from the heap (not a mapping
// of its own) and stays with the process once freed, so the next frame's allocation of it does
// not fault its pages in again. The test suite sets the same policy through GLIBC_TUNABLES
// (cmake/FeTestEnvironment.cmake), so the check runs in a child started again without them.
#include <gtest/gtest.h>

#include <cstdlib>

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

TEST(ProcessMemory, KeepFreedMemoryKeepsLargeBlocksInTheHeap) {
    // The "threadsafe" style starts the binary again, with the environment as it is now.
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    unsetenv("GLIBC_TUNABLES");
    EXPECT_EXIT(std::exit(allocateAndFree()), ::testing::ExitedWithCode(0), "");
}
#endif

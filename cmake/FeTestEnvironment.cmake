# The environment every test process runs in (issue 53: the suite's time).
#
# The suite runs on software rasterizers: llvmpipe zero-fills every texture it allocates, and
# lavapipe's device memory and our staging buffers are malloc'd, so a test process touches
# 100-900 MB that it frees and allocates again case after case. glibc returns large blocks to
# the kernel (mmap'd above its threshold, trimmed off the heap's top), and each page comes back
# as a fault: 4.3 million faults in a third of the suite, and on the virtual machines this
# project tests on (2 cores, paravirtual page tables) a fault is expensive, the more so with
# two tests faulting at once. These glibc tunables (read from the environment at process start)
# keep freed memory in the process and back the heap with transparent huge pages where the
# kernel allows them (madvise mode): one fault per 2 MiB. Measured on that subset, ctest -j2:
# 4.3 M to 0.9 M faults, 131 s to 108 s; the tests' code paths are the same.
# (No effect on sanitized builds' own allocators; harmless where the kernel has no THP.)
#
# LP_NUM_THREADS=0: llvmpipe and lavapipe rasterize on the thread that flushes instead of
# handing each draw's bins to a pool of one thread per core. ctest -j$(nproc) already gives
# every core a test process, so the pool only adds threads that wait for a core and for each
# other. Measured on a 2-core Xeon, warm shader caches: the suite 205.7 s -> 188.3 s (user +
# system 381 -> 359 s); RenderAccuracy on gl-osmesa alone 12.46 s with the pool, 12.47 s
# without, so a single test run by hand loses nothing. Only the software drivers read it.
set(FE_TEST_MALLOC_ENVIRONMENT
    "GLIBC_TUNABLES=glibc.malloc.hugetlb=1:glibc.malloc.mmap_threshold=33554432:glibc.malloc.trim_threshold=4294967295:glibc.malloc.top_pad=67108864")
set(FE_TEST_ENVIRONMENT "${FE_TEST_MALLOC_ENVIRONMENT}" "LP_NUM_THREADS=0")

# Appends FE_TEST_ENVIRONMENT to every test this directory has added so far: call it last.
function(fe_apply_test_environment)
  get_property(tests DIRECTORY PROPERTY TESTS)
  if(tests)
    set_property(TEST ${tests} APPEND PROPERTY ENVIRONMENT "${FE_TEST_ENVIRONMENT}")
  endif()
endfunction()

#!/usr/bin/env bash
# The test suite under AddressSanitizer (leak checking on) and UndefinedBehaviorSanitizer, in
# build-sanitize/ (clang; tools/sanitized-build.sh, shared with the fuzzers). Any report fails
# the test that caused it. CI runs this after the suite.
# Suppressions are limited to the Mesa / Khronos driver modules; see tools/sanitizers/lsan.supp.
#   tools/run-sanitized-tests.sh [--all] [CTEST ARGS...]
# Sanitized, a test runs about three times slower, and the whole suite took 40 minutes of CI on a
# 2-core machine. So by default each piece of the engine's code runs once, not once per
# configuration that only changes the pixels: every test but
#  - the gtest cases on gl-osmesa: the GL backend's code is the same as on gl-egl (osmesa's own
#    platform code still runs: conformance_gl-osmesa, capture_cli_gl-osmesa, the examples);
#  - the cross-backend image agreements (every technique x sample x backend: *BackendsAgree,
#    *EveryBackendPair, *OnEveryBackendAgrees), whose code the per-backend tests run;
#  - the fault sweeps through a window (the same device code as without one) and on gl-osmesa;
#  - capture bisection on gl-egl (53 s sanitized): its search is the same code on every backend,
#    and GL's replay runs in CaptureConformanceRun/gl_egl;
#  - of the visibility buffer against forward on the glTF samples, the three whose difference
#    from the others is in the shaders alone, which the sanitizers do not see (lights, untextured
#    spheres, normal maps): the textured, interleaved, mirrored, alpha and multi-mesh ones stay;
#  - the labels report (the bench report in Chromium) and package (an install and a consumer build);
#  - of the stability suite's cases, the broken data (NaN, infinities, denormals, degenerate
#    triangles) and one light: the heavy light counts are the same code with more lights.
# --all runs every test.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/install-deps.sh
tools/sanitized-build.sh
here="$(pwd)"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:halt_on_error=1:detect_stack_use_after_return=0:strict_string_checks=1"
export LSAN_OPTIONS="suppressions=$here/tools/sanitizers/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:suppressions=$here/tools/sanitizers/ubsan.supp"
select=(-E '/gl_osmesa|BackendsAgree|EveryBackendPair|OnEveryBackendAgrees|^fault_sweep_(gl-osmesa|vulkan-glfw|gl-glfw)$|CaptureBisect.*/gl_egl|VisibilityBufferMatchesForward/(LightsPunctualLamp|MetalRoughSpheresNoTextures|NormalTangentTest)'
        -LE '^(report|package)$')
export FE_STABILITY_CASES="NaN,infinite,denormal,degenerate,one light"
if [ "${1:-}" = "--all" ]; then
  shift
  select=()
  unset FE_STABILITY_CASES
fi
cd build-sanitize
ctest --output-on-failure -j"$(nproc)" "${select[@]}" "$@"  # -j nproc+1 measured slower here (RELIABILITY)

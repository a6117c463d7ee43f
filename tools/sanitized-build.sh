#!/usr/bin/env bash
# Configures and builds build-sanitize/, the one sanitized build that the sanitized suite
# (tools/run-sanitized-tests.sh) and the libFuzzer harnesses (tools/fuzz/run.sh) share: clang,
# AddressSanitizer and UndefinedBehaviorSanitizer, every object instrumented for libFuzzer's
# coverage as well (-DFE_FUZZ=ON: fuzzer-no-link). One build instead of two saves CI the second
# compile of the engine (about 9 minutes on 2 cores); the programs that are not fuzzers link the
# sanitizer runtime's no-op coverage hooks. Both callers must configure identically, or each
# would rebuild the tree: hence this one script.
#   tools/sanitized-build.sh [TARGET...]     no target: everything (tests, examples, harnesses)
set -euo pipefail
cd "$(dirname "$0")/.."
# clang: it compiles the sanitized build about twice as fast as gcc (a test file: 56 s against
# 109 s), and libFuzzer comes with it.
CC=clang CXX=clang++ cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DFE_SANITIZE=address,undefined -DFE_FUZZ=ON >/dev/null
targets=()
for t in "$@"; do targets+=(--target "$t"); done
cmake --build build-sanitize -j"$(nproc)" "${targets[@]}"

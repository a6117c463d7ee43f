#!/usr/bin/env bash
# Configures and builds into build/ (Release with line tables). Used by the quick-start scripts.
set -euo pipefail
cd "$(dirname "$0")/.."
"$(dirname "$0")/install-deps.sh"
# Line tables (-g1), not full debug info: stack traces and profiles keep functions, files and
# lines, and the build is about 30 % faster (a test file: 29.7 s with -g, 21.3 s with -g1).
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" >/dev/null
cmake --build build -j"$(nproc)"

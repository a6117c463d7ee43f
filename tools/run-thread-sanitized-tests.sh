#!/usr/bin/env bash
# The threaded execution-model cases (lists recorded on 4 threads, objects created and destroyed
# on another while lists record and submit) under ThreadSanitizer, in build-tsan/. Only the one
# small test program is built, to keep CI's run short. Any report fails it. CI runs this.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/install-deps.sh
cmake -S . -B build-tsan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFE_SANITIZE=thread >/dev/null
cmake --build build-tsan -j"$(nproc)" --target fe_execution_tests
here="$(pwd)"
# Reports inside the Mesa drivers' own worker threads are theirs, not ours: tsan.supp names them.
export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:suppressions=$here/tools/sanitizers/tsan.supp"
build-tsan/tests/fe_execution_tests "$@"

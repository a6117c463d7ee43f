#!/usr/bin/env bash
# The house style (.clang-format, clang-format 14 from Debian 12) on the C++ sources a change
# touches: every tracked .cpp/.h changed since BASE (a commit), or with --all every one. Prints
# each file that differs with the first lines of its difference and exits 1; fix with
#   clang-format -i FILE...
# The tree was formatted once as a whole, so CI (.ci/run) checks --all: about a minute.
#
# usage: tools/check-format.sh [BASE | --all]   (default BASE: HEAD~1, or --all without history)
set -euo pipefail
cd "$(dirname "$0")/.."
command -v clang-format >/dev/null || tools/install-deps.sh
if [ "${1:-}" = "--all" ] || ! git rev-parse -q --verify "${1:-HEAD~1}^{commit}" >/dev/null; then
  mapfile -t files < <(git ls-files '*.cpp' '*.h')
else
  mapfile -t files < <(git diff --name-only --diff-filter=ACMR "${1:-HEAD~1}" -- '*.cpp' '*.h')
fi
bad=0
for f in "${files[@]}"; do
  [ -f "$f" ] || continue
  if ! clang-format --style=file "$f" | diff -q "$f" - >/dev/null; then
    echo "check-format: $f is not in the house style (clang-format -i $f):"
    clang-format --style=file "$f" | diff "$f" - | head -8 || true
    bad=1
  fi
done
echo "check-format: ${#files[@]} file(s) checked"
exit $bad

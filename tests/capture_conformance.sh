#!/usr/bin/env bash
# A program captured without a change to it (FE_CAPTURE), then run as a conformance case on every
# backend: fe conformance --capture replays it on each and compares the images across backends.
# Usage: capture_conformance.sh FE OUT_DIR NAME -- PROGRAM [ARGS...]
set -euo pipefail
fe=$1 out=$2 name=$3
shift 3
[ "$1" = "--" ] && shift
mkdir -p "$out"
file="$out/$name.fecap"
rm -f "$file"
FE_CAPTURE="$file" "$@" >"$out/$name.program.log" 2>&1 || { echo "the program failed:"; cat "$out/$name.program.log"; exit 1; }
[ -s "$file" ] || { echo "no capture written"; cat "$out/$name.program.log"; exit 1; }
"$fe" conformance --capture "$file" --report "$out/$name.json" 2>&1 | grep -v "SPIR-V WARNING\|Decoration not allowed\|bytes into the SPIR-V"

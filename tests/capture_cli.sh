#!/usr/bin/env bash
# fe capture and fe replay end to end, as a user runs them: fe render captured on BACKEND without
# a change to it, replayed on every backend (validation on). Replayed on BACKEND, the image is
# the live one byte for byte; elsewhere the replay must succeed with validation silent (the
# in-process CaptureReplay test checks those images against each backend's live render).
# A damaged file is exit code 1 with the record or offset named.
# Usage: capture_cli.sh FE BACKEND OUT_DIR
set -euo pipefail
fe=$1
backend=$2
out=$3/capture_cli_$backend
rm -rf "$out"
mkdir -p "$out"
"$fe" capture --out "$out/render.fecap" -- "$fe" render builtin:spheres --backend "$backend" --size 64x48 \
  --technique deferred --out "$out/live.png" >"$out/capture.log" 2>&1 || { cat "$out/capture.log"; exit 1; }
grep -q "captured on $backend" "$out/capture.log" || { echo "no summary:"; cat "$out/capture.log"; exit 1; }
for to in vulkan gl-egl gl-osmesa; do
  if ! "$fe" info --backend "$to" --json >/dev/null 2>&1; then continue; fi
  "$fe" replay "$out/render.fecap" --backend "$to" --out "$out/$to" --validation >"$out/replay_$to.log" 2>&1 ||
    { echo "replay on $to failed:"; cat "$out/replay_$to.log"; exit 1; }
  grep -q "captured on $backend, replayed on $to: 1 frame(s)" "$out/replay_$to.log" ||
    { echo "unexpected replay summary:"; cat "$out/replay_$to.log"; exit 1; }
  # The name is the texture's first debug name: GL reuses whole textures between graph resources.
  if [ "$to" = "$backend" ]; then
    cmp "$out/live.png" "$out/$to"/frame1_1_*.png || { echo "replay on $to differs from the live image"; exit 1; }
  fi
done
# Damage one byte in the middle and cut the end: both refused, exit code 1, the place named.
python3 - "$out/render.fecap" "$out/cut.fecap" <<'PY'
import sys
data = open(sys.argv[1], 'rb').read()
open(sys.argv[2], 'wb').write(data[: len(data) // 2])
PY
if "$fe" replay "$out/cut.fecap" --backend "$backend" >"$out/cut.log" 2>&1; then echo "a truncated capture replayed"; exit 1; fi
status=$("$fe" replay "$out/cut.fecap" --backend "$backend" >/dev/null 2>&1; echo $?) || true
[ "$status" = 1 ] || { echo "exit code $status for a truncated capture, 1 expected"; exit 1; }
grep -q "capture: .*offset [0-9]" "$out/cut.log" || { echo "no offset named:"; cat "$out/cut.log"; exit 1; }
echo "capture on $backend: replayed on every backend, exact on $backend; damage refused"

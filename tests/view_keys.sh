#!/usr/bin/env bash
# fe view's keys and drops, scripted (--input-script) under a virtual display: two F12 taps
# write fe-view-001.png and fe-view-002.png (numbered, none overwritten, each path printed), a
# dropped .obj is refused with a message and the scene kept, a dropped glTF opens, Esc quits
# long before --frames.
#   view_keys.sh FE BACKEND OUT_DIR [MODEL.gltf]
set -u
fe=$1 backend=$2 out=$3 model=${4:-}
rm -rf "$out" && mkdir -p "$out" && cd "$out" || exit 1
echo "v 0 0 0" >thing.obj
script="1:F12,2:F12,3:drop=$out/thing.obj,6:Esc"
[ -n "$model" ] && [ -f "$model" ] && script="1:F12,2:F12,3:drop=$out/thing.obj,4:drop=$model,6:Esc"
"$fe" view builtin:spheres --backend "$backend" --size 320x240 --frames 1000 --validation \
  --input-script "$script" >view.out 2>view.err
rc=$?
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
[ $rc = 0 ] || fail "fe view exited $rc: $(cat view.err)"
grep -q "^wrote fe-view-001.png" view.out || fail "F12 did not write fe-view-001.png: $(cat view.out)"
grep -q "^wrote fe-view-002.png" view.out || fail "a second F12 did not write fe-view-002.png"
[ -s fe-view-001.png ] && [ -s fe-view-002.png ] || fail "the screenshots are not there"
grep -q "cannot open $out/thing.obj: .*unsupported format" view.err || fail "the dropped .obj: $(cat view.err)"
if [ -n "$model" ] && [ -f "$model" ]; then grep -q "^opened $model" view.out || fail "the dropped glTF did not open"; fi
grep -q "^fe view: Esc: quit after 6 frame(s)" view.out || fail "Esc did not quit at frame 6: $(tail -2 view.out)"
cat view.out
if [ $failures = 0 ]; then echo "fe view keys and drops work ($backend)"; else exit 1; fi

#!/bin/sh
# fe render's animation, camera and frame-sequence options (issue 48), on one backend:
#   cli_animation.sh FE ASSETS OUTDIR BACKEND
set -u
fe=$1 assets=$2 out=$3 backend=$4
fox=$assets/Fox/glTF-Binary/Fox.glb box=$assets/BoxAnimated/glTF/BoxAnimated.gltf cams=$assets/Cameras/glTF/Cameras.gltf
common="--backend $backend --size 64x48 --technique forward --shadows off"
rm -rf "$out" && mkdir -p "$out"
fail() { echo "FAIL: $*"; exit 1; }
# expect CODE PATTERN -- ARGS: fe exits with CODE and prints PATTERN
expect() {
    code=$1 pattern=$2; shift 3
    text=$("$fe" "$@" 2>&1); rc=$?
    [ "$rc" = "$code" ] || fail "fe $* exited $rc, not $code: $text"
    echo "$text" | grep -q -- "$pattern" || fail "fe $* did not say '$pattern': $text"
}

# A sequence: every frame written under a directory fe creates, each a different pose.
expect 0 "wrote 3 frame(s)" -- render "$fox" $common --animation Walk --time 0.2 --frames 3 --fps 10 --out "$out/seq/fox_{frame:02}.png"
for k in 00 01 02; do [ -s "$out/seq/fox_$k.png" ] || fail "frame $k missing"; done
cmp -s "$out/seq/fox_00.png" "$out/seq/fox_01.png" && fail "frames 0 and 1 are the same pose"
# Frame 1 of that sequence is the instant 0.3 s rendered on its own.
expect 0 "wrote" -- render "$fox" $common --animation 1 --time 0.3 --out "$out/fox_0.3.png"
cmp -s "$out/seq/fox_01.png" "$out/fox_0.3.png" || fail "frame 1 at 0.2 + 1/10 s is not the pose at 0.3 s"
# After the last key the last value; --loop wraps instead.
expect 0 "wrote" -- render "$box" $common --time 3.709 --out "$out/box_end.png"
expect 0 "wrote" -- render "$box" $common --time 100 --out "$out/box_late.png"
cmp -s "$out/box_end.png" "$out/box_late.png" || fail "past the end is not the last key's pose"
expect 0 "wrote" -- render "$box" $common --time 0.5 --out "$out/box_half.png"
expect 0 "wrote" -- render "$box" $common --time 4.208329916 --loop --out "$out/box_loop.png"
cmp -s "$out/box_half.png" "$out/box_loop.png" || fail "--loop at duration + 0.5 s is not the pose at 0.5 s"
cmp -s "$out/box_half.png" "$out/box_end.png" && fail "0.5 s and the end are the same pose"
# Cameras: the file's second (orthographic) camera, and one of the command line's.
expect 0 "wrote" -- render "$cams" $common --camera 1 --out "$out/cams_ortho.png"
expect 0 "wrote" -- render "$cams" $common --camera-position 0.5,0.5,2 --camera-target 0.5,0.5,0 --fov 60 --out "$out/cams_own.png"
expect 0 "wrote" -- render "$fox" $common --azimuth 90 --elevation 30 --out "$out/fox_turned.png"
cmp -s "$out/cams_ortho.png" "$out/cams_own.png" && fail "the cameras give the same image"
# The deformation survives capture and replay: the capture of an animated render replays on
# every backend to that backend's live image (byte for byte where it was captured). Once, from
# the first backend available: each capture is replayed on all of them anyway.
first=
for b in vulkan gl-egl gl-osmesa; do "$fe" info --backend "$b" --json >/dev/null 2>&1 && { first=$b; break; }; done
if [ "$backend" = "$first" ]; then
expect 0 "captured on $backend" -- capture --out "$out/fox.fecap" -- "$fe" render "$fox" $common --animation Run --time 0.25 \
    --out "$out/fox_live.png"
for to in vulkan gl-egl gl-osmesa; do
    "$fe" info --backend "$to" --json >/dev/null 2>&1 || continue
    expect 0 "replayed on $to" -- replay "$out/fox.fecap" --backend "$to" --out "$out/replay_$to" --validation
    if [ "$to" = "$backend" ]; then
        cmp -s "$out/fox_live.png" "$out/replay_$to"/frame1_1_*.png || fail "the replay on $to differs from the live image"
    else
        expect 0 "wrote" -- render "$fox" --backend "$to" --size 64x48 --technique forward --shadows off --animation Run \
            --time 0.25 --out "$out/fox_live_$to.png"
        python3 "$(dirname "$0")/check_png.py" "$out/fox_live_$to.png" --like "$out/replay_$to"/frame1_1_*.png 0.01 ||
            fail "the replay on $to differs from $to's live image"
    fi
done
fi
# Mistakes: exit 2 saying what is wrong, before anything is rendered.
expect 2 "no animation 'Jump' in the scene: it has 0 'Survey', 1 'Walk', 2 'Run'" -- render "$fox" $common --animation Jump
expect 2 "has no animation" -- render "$cams" $common --time 1
expect 2 "no camera '5' in the scene" -- render "$cams" $common --camera 5
expect 2 "give one or the other" -- render "$cams" $common --camera 0 --fov 40
expect 2 "{frame} or {frame:0N}" -- render "$fox" $common --frames 2 --out "$out/f_{frames}.png"
expect 2 "--camera-position takes X,Y,Z" -- render "$fox" $common --camera-position 1,2
expect 2 "--fps takes a number" -- render "$fox" $common --animation 0 --fps 0
expect 1 "cannot create the directory /proc/fe_no/such" -- render "$fox" $common --out /proc/fe_no/such/f.png
echo "all animation CLI checks passed"

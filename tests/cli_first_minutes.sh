#!/usr/bin/env bash
# What a new user meets first in fe's command line (issue 51): usage errors are one line and a
# pointer to help (exit 2), --help shows what a command takes, outputs create their
# directories and are checked before rendering, options a technique does not use are one
# warning of one form, and a run prints a short summary, nothing (--quiet) or one JSON document.
# Usage: cli_first_minutes.sh FE OUTDIR BACKEND
set -u
fe=$1 out=$2 backend=$3
rm -rf "$out" && mkdir -p "$out"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
# run NAME EXPECTED_EXIT ARGS...: stdout in $out/NAME.out, stderr in $out/NAME.err
run() {
  local name=$1 expected=$2; shift 2
  "$fe" "$@" >"$out/$name.out" 2>"$out/$name.err"
  local rc=$?
  [ "$rc" = "$expected" ] || fail "$name: fe $* exited $rc, expected $expected; stderr: $(head -c 400 "$out/$name.err")"
}
has() { grep -q -- "$2" "$out/$1" || fail "$1 lacks '$2': $(head -c 600 "$out/$1")"; }
lacks() { ! grep -q -- "$2" "$out/$1" || fail "$1 has '$2'"; }
small=(--backend "$backend" --size 64x48)
# Debian's interpreter, whose python3-matplotlib it is (a python3 earlier on PATH may lack it).
python=/usr/bin/python3
[ -x "$python" ] || python=python3

# Usage errors: the message, then where help is; nothing else, exit 2.
run bogus 2 render --bogus
[ "$(wc -l <"$out/bogus.err")" = 2 ] || fail "fe render --bogus printed $(wc -l <"$out/bogus.err") lines on stderr, expected 2"
has bogus.err "--bogus"
has bogus.err "see 'fe render --help'"
run technique 2 render --technique nope "${small[@]}"
has technique.err "see 'fe render --help'"
run backend 2 render --backend nope --size 64x48
run scene 2 render builtin:nope "${small[@]}"
has scene.err "unknown scene 'builtin:nope' (builtin scenes: builtin:spheres"
run command 2 frobnicate
has command.err "see 'fe --help'"
run info_positional 2 info extra
run conformance_positional 2 conformance extra

# --help: only the positionals a command takes; render lists scenes and techniques.
run info_help 0 info --help
lacks info_help.out "Positionals"
run render_help 0 render --help
has render_help.out "SCENE"
has render_help.out "builtin scenes: builtin:spheres"
has render_help.out "deferred-tiled"
run replay_help 0 replay --help
has replay_help.out "FILE"

# A file fe does not read: "unsupported format", naming those it does (an asset error, exit 3).
echo "v 0 0 0" >"$out/model.obj"
run obj 3 render "$out/model.obj" "${small[@]}"
has obj.err "unsupported format '.obj': scenes are glTF 2.0 files (.gltf, .glb) or builtin:NAME"

# Outputs: directories created; a path that cannot be written fails before any rendering.
run outdir 0 render builtin:triangle "${small[@]}" --out "$out/new/dir/q.png" --dump-graph "$out/graphs/g.dot"
[ -s "$out/new/dir/q.png" ] || fail "--out did not create its directory"
[ -s "$out/graphs/g.dot" ] || fail "--dump-graph did not create its directory"
run unwritable 1 render builtin:triangle "${small[@]}" --out /proc/version/q.png
has unwritable.err "cannot create the directory /proc/version for --out"
lacks unwritable.out "backend"
run report 0 conformance --backend "$backend" --case clear_and_readback --report "$out/reports/r.json"
[ -s "$out/reports/r.json" ] || fail "conformance --report did not create its directory"
run capture 0 capture --out "$out/captures/c.fecap" -- "$fe" render builtin:triangle "${small[@]}" --out "$out/c.png"
[ -s "$out/captures/c.fecap" ] || fail "capture --out did not create its directory"

run replay_list 0 replay "$out/captures/c.fecap" --backend "$backend" --list
grep -q -E "^  pass 0 '.+': [0-9]+ draw\(s\), 0 to [0-9]+" "$out/replay_list.out" || fail "replay --list: $(cat "$out/replay_list.out")"

# fe bisect: a draw left out on one side is found; its heat map is scaled to the largest
# difference (white) and says so; the report command named is one that exists.
run bisect 1 bisect "$out/captures/c.fecap" --backends "$backend,$backend" --perturb "$backend:1" --out "$out/bisect"
has bisect.out "first divergent draw 1"
has bisect.out "heat map (white: a difference of "
# Passing runs print no alarms: the engine's own shaders draw no validation message, and the
# conformance case that damages a pipeline cache on purpose prints nothing about it.
lacks bisect.err "validation"
run cache_case 0 conformance --backend "$backend" --case pipeline_cache_roundtrip
lacks cache_case.err "ignored"
lacks cache_case.out "ignored"
report_script=$(sed -n "s/^report: .* '\([^']*report.py\)' .*/\1/p" "$out/bisect.out")
[ -f "$report_script" ] || fail "bisect names a report script that is not there: $(grep '^report:' "$out/bisect.out")"
heat=$(sed -n 's/^    heat map (white: [^)]*): //p' "$out/bisect.out" | head -1)
"$python" - "$heat" <<'EOF2' || fail "the heat map $heat is not scaled to its largest difference"
import sys
import matplotlib.image as mpimg
image = mpimg.imread(sys.argv[1])
assert image[..., :3].max() > 0.99, image[..., :3].max()
EOF2

# fe info in vulkaninfo's terms: the driver by name, the device type, sample counts as lists;
# --json also the extensions (and on Vulkan the memory heaps).
run info 0 info --backend "$backend"
grep -q -E "^  driver: (llvmpipe|Mesa|NVIDIA|AMD|Intel)" "$out/info.out" || fail "fe info: no driver name: $(head -6 "$out/info.out")"
grep -q -E "^  device: .*\((cpu|gpu|integrated-gpu|discrete-gpu|virtual-gpu|other)" "$out/info.out" || fail "fe info: no device type"
grep -q -E "colorSampleCounts 1(,[248])*," "$out/info.out" || fail "fe info: sample counts not a list"
lacks info.out "driver version"
run info_json 0 info --backend "$backend" --json
"$python" - "$out/info_json.out" "$backend" <<'EOF2' || fail "fe info --json: $(head -c 300 "$out/info_json.out")"
import json, sys
d = json.load(open(sys.argv[1]))["backends"][0]["device"]
assert d["driverName"] and d["deviceType"], d
assert len(d["extensions"]) > 10 and all(isinstance(e, str) for e in d["extensions"])
assert d["limits"]["colorSampleCounts"][0] == 1
if sys.argv[2] == "vulkan":
    assert d["memoryHeaps"] and d["memoryHeaps"][0]["bytes"] > 0 and d["conformanceVersion"]
EOF2

# An option the technique does not use: one warning, one form, and the render goes on.
for case in "forward --illum-scale 2" "redeferred --msaa 4" "deferred --one-pass-culling" "forward --temporal" "forward --rates punctual=2"; do
  set -- $case
  name=unused_${2#--}
  run "$name" 0 render builtin:triangle "${small[@]}" --out "$out/$name.png" --technique "$@"
  has "$name.err" "fe warning: $2 has no effect on technique $1 (it applies to "
  has "$name.err" "): ignored"
done
# Image-based light without --environment: the builtin sky, as the quick start draws.
run prefiltered 0 render builtin:spheres "${small[@]}" --out "$out/prefiltered.png" --ibl-prefiltered
has prefiltered.out "environment light prefiltered"

# What a run prints: a short summary; --verbose adds passes and memory (KiB/MiB); --quiet
# nothing; --json one document.
run summary 0 render builtin:spheres "${small[@]}" --technique deferred --out "$out/s.png"
lacks summary.out "pass times"
lacks summary.out "transient memory"
has summary.out "frame time"
has summary.out "wrote $out/s.png"
[ "$(wc -l <"$out/summary.out")" -le 5 ] || fail "the default summary has $(wc -l <"$out/summary.out") lines"
run verbose 0 render builtin:spheres "${small[@]}" --technique deferred --out "$out/v.png" --verbose
has verbose.out "pass times"
grep -q -E "transient memory: [0-9.]+ (B|KiB|MiB|GiB) with aliasing" "$out/verbose.out" || fail "no transient memory in KiB/MiB: $(cat "$out/verbose.out")"
run quiet 0 render builtin:spheres "${small[@]}" --out "$out/q.png" --quiet
[ ! -s "$out/quiet.out" ] || fail "--quiet printed: $(cat "$out/quiet.out")"
[ -s "$out/q.png" ] || fail "--quiet wrote no image"
run json 0 render builtin:spheres "${small[@]}" --technique forward --msaa 4 --illum-scale 2 --out "$out/j.png" --json
"$python" - "$out/json.out" <<'EOF' || fail "--json: $(head -c 600 "$out/json.out")"
import json, sys
doc = json.load(open(sys.argv[1]))
for key in ("device", "technique", "frameTimeMs", "passTimes", "memory", "warnings", "outputs"):
    assert key in doc, key
assert doc["frameTimeMs"]["median"] > 0
assert doc["passTimes"]["passes"], "no passes"
assert any("--illum-scale has no effect" in w for w in doc["warnings"]), doc["warnings"]
assert doc["outputs"][-1].endswith("j.png")
EOF

# Progress: a run that takes more than a second says how far it is (on stderr).
start=$(date +%s%N)
run progress 0 render builtin:shadows --backend "$backend" --size 320x240 --frames 30 --out "$out/p.png"
elapsed_ms=$((($(date +%s%N) - start) / 1000000))
if [ "$elapsed_ms" -ge 1500 ]; then
  has progress.err "fe render: frame [0-9]*/31"
else
  echo "note: 30 frames took $elapsed_ms ms here: too quick for a progress line"
fi

if [ "$failures" = 0 ]; then echo "all first-minutes CLI checks passed ($backend)"; else echo "$failures failure(s)"; exit 1; fi

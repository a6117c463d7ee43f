#!/usr/bin/env bash
# fe view --post-shader: the shader over the image is compiled again whenever its file changes.
# A version that keeps only red is written and the viewer started; once it says "compiled", a
# version that does not compile is written (the error, with file:line, is printed and the red one
# stays), then one painting every pixel green; once that compiled, Ctrl-C (SIGINT) ends the
# viewer, which writes its screenshot: green. LANG glsl or hlsl (a .frag or a .frag.hlsl file).
# Each wait is bounded (60 s).
#   view_post_shader.sh FE BACKEND LANG OUT_DIR CHECK_PNG
set -u
fe=$1 backend=$2 lang=$3 out=$4 check_png=$5
rm -rf "$out" && mkdir -p "$out" && cd "$out" || exit 1
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
waitFor() {  # waitFor COUNT TEXT: until view.out holds TEXT at least COUNT times
  for _ in $(seq 600); do
    [ "$(grep -cF "$2" view.out 2>/dev/null)" -ge "$1" ] && return 0
    kill -0 "$pid" 2>/dev/null || return 1
    sleep 0.1
  done
  return 1
}
if [ "$lang" = hlsl ]; then
  file=post.frag.hlsl
  red='Texture2D frame : register(t0);
SamplerState nearest : register(s0);
float4 main(float4 p : SV_Position) : SV_Target0 { return float4(frame.Load(int3(p.xy, 0)).r, 0, 0, 1); }'
  broken='float4 main(float4 p : SV_Position) : SV_Target0 {
  return nope;
}'
  green='// fe-entry: PSMain
float4 PSMain(float4 p : SV_Position) : SV_Target0 { return float4(0, 1, 0, 1); }'
  error="$file:2: 'nope' : unknown variable"
else
  file=post.frag
  red='#version 450
layout(binding = 0) uniform sampler2D frame;
layout(location = 0) out vec4 color;
void main() { color = vec4(texelFetch(frame, ivec2(gl_FragCoord.xy), 0).r, 0.0, 0.0, 1.0); }'
  broken='#version 450
layout(location = 0) out vec4 color;
void main() { color = nope; }'
  green='#version 450
layout(location = 0) out vec4 color;
void main() { color = vec4(0.0, 1.0, 0.0, 1.0); }'
  error="$file:3: 'nope' : undeclared identifier"
fi
printf '%s\n' "$red" >"$file"
"$fe" view builtin:spheres --backend "$backend" --size 96x64 --no-ui --validation \
  --post-shader "$file" --screenshot shot.png >view.out 2>view.err &
pid=$!
waitFor 1 "post shader $file: compiled" || fail "the first version did not compile: $(cat view.out view.err)"
sleep 1.1  # a new modification time on any file system
printf '%s\n' "$broken" >"$file"
waitFor 1 "the previous version stays" || fail "the broken version was not reported: $(cat view.out)"
grep -qF "$error" view.out || fail "no '$error' in the report: $(cat view.out)"
sleep 1.1
printf '%s\n' "$green" >"$file"
waitFor 2 "post shader $file: compiled" || fail "the green version did not compile: $(cat view.out)"
kill -INT "$pid"
wait "$pid"
rc=$?
[ $rc = 0 ] || fail "fe view exited $rc after Ctrl-C: $(cat view.err)"
grep -q "^fe view: interrupted after" view.out || fail "Ctrl-C did not end the loop: $(tail -2 view.out)"
/usr/bin/python3 "$check_png" shot.png --pixel 48,32=0,255,0 --pixel 5,5=0,255,0 ||
  fail "the screenshot is not the green version's"
cat view.out
if [ $failures = 0 ]; then echo "fe view reloads its post shader ($backend, $lang)"; else exit 1; fi

#!/usr/bin/env bash
# Runs every fe command of README.md's code blocks, as a new user would copy them, in a temporary
# directory: a command that fails fails the test, and so does a README output line (a block's
# lines after a "$ " command) that the command no longer prints.
#   readme_commands.sh FE SOURCE_DIR WORK_DIR [ASSETS_DIR]
# Made small to run in seconds, and said here so the test hides nothing: images at 64x48 (64x64
# in a window; a --size given is replaced), --frames at most 3, the conformance suite filtered to one case,
# `bench --quick` (minutes per backend) replaced by a one-case sweep, window commands under
# xvfb-run with --frames 2. The README's model paths become the sample assets (ASSETS_DIR), or
# builtin:spheres without them; RenderDoc lines run only where librenderdoc is installed.
set -u
fe=$1 src=$2 work=$3 assets=${4:-}
rm -rf "$work" && mkdir -p "$work/out"
cd "$work" || exit 1
cat >tiny-sweep.json <<'EOF'
{"description": "one small case (readme_commands.sh)",
 "cases": [{"scene": "builtin:spheres", "size": "48x36", "technique": "forward"}]}
EOF
model=builtin:spheres fox=builtin:crowd cameras=builtin:spheres
if [ -n "$assets" ] && [ -f "$assets/Box/glTF/Box.gltf" ]; then
  model=$assets/Box/glTF/Box.gltf fox=$assets/Fox/glTF-Binary/Fox.glb cameras=$assets/Cameras/glTF/Cameras.gltf
fi
xvfb=$(command -v xvfb-run || true)
failures=0 ran=0 skipped=0

# The sh and plain blocks' lines, one command per line; "$ " lines keep the output lines after them.
awk '/^```/ { if (inside) inside = 0; else inside = ($0 == "```sh" || $0 == "```"); next } inside { print }' \
  "$src/README.md" >commands.txt

adapt() {  # one README line -> the command run here (stdout), or nothing to skip it
  local line=$1
  line=${line#\$ }
  line=$(printf '%s' "$line" | sed -E 's/[[:space:]]{2,}#.*$//; s/[[:space:]]+$//')
  case "$line" in
    build/tools/fe* | "xvfb-run -a build/tools/fe"*) ;;
    *) return ;;
  esac
  case "$line" in *--renderdoc-capture*) [ -e /usr/lib/librenderdoc.so ] || { echo SKIP; return; } ;; esac
  line=${line//build\/tools\/fe/$fe}
  line=${line//path\/to\/model.gltf/$model}
  line=${line//scene.gltf/$model}
  line=${line//model.glb/$model}
  line=${line//Fox.glb/$fox}
  line=${line//Cameras.gltf/$cameras}
  line=${line//my-sweep.json/tiny-sweep.json}
  if [ "$fox" = builtin:crowd ]; then  # no Fox here: the builtin crowd's animation instead
    line=${line//--animation Walk/--animation sway}
    line=${line//--animation Run/--animation sway}
  fi
  line=${line//bench --quick/bench --sweep tiny-sweep.json --stability-cases NaN}
  line=$(printf '%s' "$line" | sed -E 's/--frames ([4-9]|[1-9][0-9]+)/--frames 3/')
  case "$line" in
    *" conformance "*) case "$line" in *--capture*) ;; *) line="$line --case clear_and_readback" ;; esac ;;
  esac
  local size=64x48
  case "$line" in *" view"*) size=64x64 ;; esac  # a window is at least 64 high
  case "$line" in
    *" render"* | *" view"*)
      if printf '%s' "$line" | grep -q -- '--size'; then
        line=$(printf '%s' "$line" | sed -E "s/--size [0-9]+x[0-9]+/--size $size/")
      else
        line="$line --size $size"
      fi ;;
  esac
  case "$line" in
    *" view"* | *--window*)
      [ -n "$xvfb" ] || { echo SKIP; return; }
      case "$line" in xvfb-run*) ;; *) line="xvfb-run -a $line" ;; esac
      case "$line" in *--frames*) ;; *) line="$line --frames 2" ;; esac ;;
  esac
  printf '%s\n' "$line"
}

expect=""  # output lines the README shows for the last "$ " command
last=""
check_expected() {
  [ -n "$last" ] || return 0
  while IFS= read -r want; do
    [ -z "$want" ] && continue
    case "$want" in *...*) continue ;; esac
    # d.fecap's statistics: the README's words, whatever the path the capture was written to.
    grep -qF -- "$want" "$last.out" || { echo "FAIL: README shows '$want' after '$lastcmd'; it printed:"; sed 's/^/    /' "$last.out"; failures=$((failures + 1)); }
  done <<<"$expect"
  expect=""
}

n=0
while IFS= read -r raw; do
  case "$raw" in
    '$ '*) ;;
    build/tools/fe* | xvfb-run*) ;;
    *)  # an output line of the "$ " command before it
      [ -n "$last" ] && case "$raw" in '  '* | [a-z]*) expect="$expect$raw"$'\n' ;; esac
      continue ;;
  esac
  check_expected
  last=""
  cmd=$(adapt "$raw")
  [ -z "$cmd" ] && continue
  if [ "$cmd" = SKIP ]; then skipped=$((skipped + 1)); echo "skip: $raw"; continue; fi
  n=$((n + 1)) ran=$((ran + 1))
  eval "$cmd" >"cmd$n.out" 2>"cmd$n.err"
  rc=$?
  # bisect exits 1 when the backends differ, as the README's example shows they do.
  ok=0
  [ $rc = 0 ] && ok=1
  case "$cmd" in *" bisect "*) [ $rc = 1 ] && grep -q "first divergent" "cmd$n.out" && ok=1 ;; esac
  if [ $ok = 1 ]; then echo "ok: $raw"; else
    echo "FAIL (exit $rc): $cmd"; sed 's/^/    /' "cmd$n.err" | tail -5; failures=$((failures + 1))
  fi
  case "$raw" in '$ '*) last="cmd$n" lastcmd=$raw ;; esac
done <commands.txt
check_expected
# The figures README states in its text: the conformance suite's size.
said=$(sed -n 's/^The suite has \([0-9]*\) cases per backend.*/\1/p' "$src/README.md")
has=$("$fe" conformance --list | tail -1 | cut -d' ' -f1)
[ "$said" = "$has" ] || { echo "FAIL: README says the suite has '$said' cases per backend; fe conformance --list counts $has"; failures=$((failures + 1)); }
echo "$ran README command(s) run, $skipped skipped"
if [ "$failures" = 0 ]; then echo "every README command works"; else echo "$failures failure(s)"; exit 1; fi

#!/usr/bin/env bash
# fe render --renderdoc-capture on BACKEND, then the capture opened with Debian's python3-renderdoc
# (/usr/bin/python3): the render graph's passes must be markers and its textures named resources.
#   capture_test.sh FE BACKEND OUTDIR
# GL backends are captured only with librenderdoc preloaded (RenderDoc hooks GL by interposition).
set -euo pipefail
fe="$1" backend="$2" out="$3"
here="$(cd "$(dirname "$0")" && pwd)"
rm -rf "$out" && mkdir -p "$out"
preload=()
case "$backend" in gl-*) preload=(env LD_PRELOAD=/usr/lib/librenderdoc.so) ;; esac
# In a sanitizer build ASan's runtime comes first (gcc: libasan first in the preload list; clang:
# linked into fe), and then its dlopen interceptor, not RenderDoc's, wins symbol lookup:
# RenderDoc cannot hook GL there. Skipped (77) in that suite only; the plain suite runs it.
# (grep without -q after ldd: under pipefail, ldd killed by SIGPIPE when grep quits early reads
# as "no"; clang's static runtime is found by its symbol in the file itself.)
asan() { ldd "$fe" | grep libasan >/dev/null || grep -q __asan_init "$fe"; }
if [ ${#preload[@]} -gt 0 ] && asan; then
  echo "skipped: RenderDoc cannot hook GL in an AddressSanitizer build (ASan's dlopen comes first)"
  exit 77
fi
log="$("${preload[@]}" "$fe" render builtin:spheres --backend "$backend" --size 64x48 --out "$out/frame.png" \
       --renderdoc-capture "$out/frame")"
echo "$log"
rdc="$(sed -n 's/^RenderDoc capture of frame 0: //p' <<<"$log")"
[ -f "$rdc" ] || { echo "no capture file reported"; exit 1; }
/usr/bin/python3 "$here/inspect_capture.py" "$rdc" --expect-marker forward --expect-marker display \
  --expect-resource "output L_o" --expect-resource "display sRGB" --expect-resource "scene vertices"

#!/usr/bin/env bash
# Cost of the abstraction in instructions, not seconds: runs the abstraction benchmark's
# --count-instructions mode under callgrind, which counts every instruction the recording
# thread (and, on GL, the context thread that replays) executes while recording (and recording
# + submitting) 10,000 draws, for the abstract
# and the direct path on every backend. Counts are repeatable on a busy machine where CPU time
# is not (docs/BENCHMARKS.md). Each count is split by where the instructions ran: the program's
# own code (application loop + engine; the only part the abstraction changes) and the libraries
# under it (Vulkan/GL driver, libc).
#
# usage: tools/bench-abstraction-instructions.sh [FRAMES]   (default 5; build first: tools/build.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
frames="${1:-5}"
bin=build/bench/fe_bench_abstraction
[ -x "$bin" ] || { echo "build first: tools/build.sh" >&2; exit 2; }
if ! command -v valgrind >/dev/null || ! command -v callgrind_annotate >/dev/null; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get install -y -q --no-install-recommends valgrind >/dev/null
fi

out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
# --separate-threads: the driver's own threads (lavapipe's queue executes submitted frames)
# would otherwise be summed in whenever the scheduler runs them inside a counted window;
# only the threads that dump a frame's profile (below) are counted.
if ! valgrind --tool=callgrind --collect-atstart=no --separate-threads=yes --callgrind-out-file="$out/cg.%p" \
     "$bin" --count-instructions "$frames" >"$out/stdout" 2>"$out/log"; then
  echo "callgrind run failed:" >&2; tail -20 "$out/log" >&2; exit 1
fi
draws=$(awk '/^frames/ {print $4}' "$out/stdout")  # per frame

# name total own  (one line per dump, in dump order)
# Self cost per ELF object, read from the profile itself: "ob=" names the object of the
# functions that follow (an id's name may first appear in a "cob=" line); a cost line right after "calls=" is a call's inclusive cost, skipped.
own_cost() {
  awk -v own="$(basename "$bin")" '
    /^cob=/ { id = $0; sub(/^cob=/, "", id); name = id; sub(/^\([0-9]+\) */, "", name); key = id; sub(/ .*/, "", key)
              if (name != "" && name != key) names[key] = name; next }
    /^ob=/ { id = $0; sub(/^ob=/, "", id); name = id; sub(/^\([0-9]+\) */, "", name); key = id; sub(/ .*/, "", key)
             if (name != "" && name != key) names[key] = name; cur = (key in names) ? names[key] : name; next }
    /^calls=/ { skip = 1; next }
    /^[0-9+*-]/ { if (skip) { skip = 0; next } if (cur ~ ("/" own "$")) s += $NF; next }
    END { print s + 0 }' "$1"
}
# A frame's profiles: the recording thread's and, on GL, the context thread's, which replays
# the recorded lists and makes the direct path's GL calls (backends/gl/GlContextThread.h); the
# benchmark names each frame's dumps alike ("... #N"). Other threads (llvmpipe's rasterizer,
# lavapipe's queue: the "GPU") are never dumped inside a frame.
for f in $(cd "$out" && ls cg.*.*-* | sort -t. -k3 -n); do
  name=$(sed -n 's/^desc: Trigger: Client Request: //p' "$out/$f" | head -1)
  total=$(sed -n 's/^\(summary\|totals\): *//p' "$out/$f" | head -1)
  echo "$name|$total|$(own_cost "$out/$f")"
done | awk -F'|' '{ if (!($1 in t)) order[++m] = $1; t[$1] += $2; o[$1] += $3 }
  END { for (i = 1; i <= m; ++i) { n = order[i]; sub(/ #[0-9]+$/, "", n); print n "|" t[order[i]] "|" o[order[i]] } }' >"$out/frames"
# One row per path and phase: the median frame's total and own counts (the driver's allocator
# now and then does extra work in one frame; the median is what a frame costs).
awk -F'|' '
  function median(list,   v, n, i, j, t) {
    n = split(list, v, " ")
    for (i = 2; i <= n; ++i) for (j = i; j > 1 && v[j - 1] + 0 > v[j] + 0; --j) { t = v[j]; v[j] = v[j - 1]; v[j - 1] = t }
    return n % 2 ? v[(n + 1) / 2] : (v[n / 2] + v[n / 2 + 1]) / 2
  }
  { if (!($1 in tot)) order[++m] = $1; tot[$1] = tot[$1] " " $2; own[$1] = own[$1] " " $3 }
  END { for (i = 1; i <= m; ++i) print order[i] "|" median(tot[order[i]]) "|" median(own[order[i]]) }' "$out/frames" >"$out/rows"

echo "instructions per draw (median of $frames frames of $draws draws per path and phase, callgrind; software rasterizer drivers)"
printf '%-10s %-9s %-14s %10s %10s %10s\n' backend path phase total own driver
awk -F'|' -v n="$draws" '{split($1, k, " "); printf "%-10s %-9s %-14s %10.1f %10.1f %10.1f\n", k[1], k[2], k[3], $2 / n, $3 / n, ($2 - $3) / n}' "$out/rows"
echo
echo "abstract / direct (record+submit): total ratio; instructions the abstraction adds in the program's own code, as a share of the direct path's total"
awk -F'|' -v n="$draws" '{split($1, k, " "); if (k[3] != "record+submit") next; t[k[1] " " k[2]] = $2; o[k[1] " " k[2]] = $3; if (!(k[1] in seen)) {seen[k[1]] = 1; order[++m] = k[1]}}
  END {for (i = 1; i <= m; ++i) {b = order[i]; ta = t[b " abstract"]; td = t[b " direct"]; if (!td) continue;
       printf "  %-10s total %.3f; own code adds %.1f instructions/draw = %.1f%% of direct\n", b, ta / td, (o[b " abstract"] - o[b " direct"]) / n, 100 * (o[b " abstract"] - o[b " direct"]) / td}}' "$out/rows"

#!/bin/sh
# The full sweep: the quick sweep and every sweep of bench/sweeps/ on every backend, spliced into docs/BENCHMARKS.md
# (tools/bench/update_benchmarks.py). Run from the repository root after tools/build.sh; the
# machine should be otherwise idle (the figures are CPU rasterization on a machine without a GPU).
#   tools/bench/regenerate-benchmarks.sh [OUT_DIR]
set -eu
fe=${FE:-build/tools/fe}
out=${1:-/tmp/fe-bench-full}
python=/usr/bin/python3
[ -x "$python" ] || python=python3
start=$(date +%s)
"$fe" bench --quick --backend all --out "$out/quick"
"$fe" bench --sweep bench/sweeps/techniques-720p.json --backend all --frames 5 --out "$out/techniques-720p"
"$fe" bench --sweep bench/sweeps/tiled-720p.json --backend all --frames 21 --out "$out/tiled-720p"
"$fe" bench --sweep bench/sweeps/light-scaling.json --backend all --frames 5 --out "$out/light-scaling"
"$fe" bench --sweep bench/sweeps/shadows.json --backend all --frames 5 --out "$out/shadows"
"$fe" bench --sweep bench/sweeps/post.json --backend all --frames 5 --out "$out/post"
"$fe" bench --sweep bench/sweeps/many-lights.json --backend all --frames 5 --out "$out/many-lights"
"$fe" bench --sweep bench/sweeps/cluster-bounds.json --backend all --frames 5 --interleave --out "$out/cluster-bounds"
"$fe" bench --sweep bench/sweeps/director-crossovers.json --backend vulkan,gl-egl --frames 5 --out "$out/director-crossovers"
"$fe" bench --sweep bench/sweeps/deferred-msaa.json --backend all --frames 5 --out "$out/deferred-msaa"
"$fe" bench --sweep bench/sweeps/async-compute.json --backend all --frames 9 --interleave --out "$out/async-compute"
"$python" tools/bench/update_benchmarks.py docs/BENCHMARKS.md quick="$out/quick" \
    techniques-720p="$out/techniques-720p" tiled-720p="$out/tiled-720p" light-scaling="$out/light-scaling" shadows="$out/shadows" post="$out/post" \
    many-lights="$out/many-lights" cluster-bounds="$out/cluster-bounds" director-crossovers="$out/director-crossovers" \
    deferred-msaa="$out/deferred-msaa" async-compute="$out/async-compute"
echo "the full sweep took $(( $(date +%s) - start )) s; results in $out"

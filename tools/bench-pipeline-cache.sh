#!/usr/bin/env bash
# Start-up with and without the engine's pipeline cache (issue 26): fe render's quick-start scene,
# cold (no cache file) and warm (the file the cold run saved), per backend, with Mesa's own shader
# cache off (MESA_SHADER_CACHE_DISABLE=true) so the engine's cache is what is measured, and on.
# Prints fe render's "start-up:" line figures as medians of RUNS runs (default 5).
#   tools/bench-pipeline-cache.sh [FE] [RUNS]
set -euo pipefail
fe="${1:-build/tools/fe}"
runs="${2:-5}"
dir="$(mktemp -d)"
trap 'rm -rf "$dir"' EXIT
median() { sort -n | awk '{v[NR]=$1} END {print (NR % 2) ? v[(NR+1)/2] : (v[NR/2] + v[NR/2+1]) / 2}'; }
echo "| backend | Mesa shader cache | cold device ms | cold renderer ms | warm device ms | warm renderer ms | cache file bytes | warm hits / compiled |"
echo "|---|---|---|---|---|---|---|---|"
for backend in vulkan gl-egl gl-osmesa; do
  for mesa in off on; do
    env=()
    [ "$mesa" = off ] && env=(MESA_SHADER_CACHE_DISABLE=true)
    for phase in cold warm; do : > "$dir/$phase"; done
    for ((i = 0; i < runs; i++)); do
      cache="$dir/$backend-$mesa-$i.bin"
      for phase in cold warm; do
        [ "$phase" = cold ] && rm -f "$cache"
        line="$(env "${env[@]}" "$fe" render --backend "$backend" --size 320x240 --out "$dir/x.png" --pipeline-cache "$cache" 2>/dev/null |
                grep '^start-up:')"
        echo "$line" >> "$dir/$phase"
      done
    done
    field() { sed -E "s/.*$1 ([0-9.]+) ms.*/\1/" "$dir/$2" | median; }
    hits="$(tail -1 "$dir/warm" | sed -E 's/.*, ([0-9]+) hit\(s\), ([0-9]+) compiled/\1 \/ \2/')"
    bytes="$(stat -c %s "$dir/$backend-$mesa-0.bin" 2>/dev/null || echo 0)"
    echo "| $backend | $mesa | $(field device cold) | $(field "pipelines and resources\)" cold) | $(field device warm) | $(field "pipelines and resources\)" warm) | $bytes | $hits |"
  done
done

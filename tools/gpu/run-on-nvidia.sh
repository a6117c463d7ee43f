#!/usr/bin/env bash
# Runs on a lent NVIDIA machine (the device tool; docs/BENCHMARKS.md, "On NVIDIA"), from the
# repository root with .gl/ and .gpubundle/ carried (tools/gpu/make-bundle.sh): the test
# binaries in parallel, then the benchmarks one at a time. Everything it writes goes
# to $OUT. Each step has its own time limit so that one slow step still leaves the others' files.
#   bash tools/gpu/run-on-nvidia.sh [QUICK_S SWEEP_S MICRO_S TESTS_S]   (a step given 0 s is left out)
# SWEEP_FRAMES and SWEEP_WARMUP_MS (default 20 and 1000) size the sweep to the time left;
# SWEEP_BACKENDS (default vulkan,gl-egl) picks its backends (one a run left unmeasured, say).
set -u
out=${OUT:-/tmp/gpu-out}; mkdir -p "$out"
quick_s=${1:-100} sweep_s=${2:-120} micro_s=${3:-60} tests_s=${4:-150}
for f in .gl/*.deb; do dpkg -x "$f" /; done; ldconfig
tar -xzf .gpubundle/bundle.tar.gz
export LD_LIBRARY_PATH=$PWD/gpu-libs VK_LAYER_PATH=$PWD/gpu-libs/layers
# The binaries name their data by the path they were built at.
if [ ! -e /work/main ]; then mkdir -p /work && ln -s "$PWD" /work/main
elif [ "$(realpath /work/main)" != "$(realpath .)" ]; then echo "/work/main is another checkout: the binaries would read its files" >&2; exit 2; fi
[ -e /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json ] && export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
[ -e /usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json ] && export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
fe=build/tools/fe
{ date -u; pwd; nproc; nvidia-smi -L; nvidia-smi --query-gpu=driver_version,clocks.sm,clocks.mem --format=csv; $fe info --backend all; } >"$out/info.txt" 2>&1
backends=vulkan,gl-egl
step() { local name=$1 limit=$2; shift 2; [ "$limit" -gt 0 ] || return 0; local t0=$SECONDS; timeout "$limit" "$@" >"$out/$name.log" 2>&1; echo "$name: exit $? after $((SECONDS - t0)) s" | tee -a "$out/info.txt"; }
# Tests first (what a change must not break), the unit tests in 12 shards; osmesa is not there.
if [ "$tests_s" -gt 0 ]; then
  t0=$SECONDS
  for i in $(seq 0 11); do
    (GTEST_TOTAL_SHARDS=12 GTEST_SHARD_INDEX=$i timeout "$tests_s" build/tests/fe_unit_tests --gtest_brief=1 >"/tmp/unit$i.log" 2>&1
     echo "exit $?" >>"/tmp/unit$i.log") &
  done
  for t in execution stability tool; do (timeout "$tests_s" build/tests/fe_${t}_tests --gtest_brief=1 >"/tmp/$t.log" 2>&1; echo "exit $?" >>"/tmp/$t.log") & done
  wait
  logs=(/tmp/unit*.log /tmp/execution.log /tmp/stability.log /tmp/tool.log)
  cat "${logs[@]}" >"$out/tests.log"
  echo "tests: $((SECONDS - t0)) s; $(grep -c '^\[  FAILED  \]' "$out/tests.log") failed lines, $(grep -h '^\[  PASSED  \]' "${logs[@]}" | awk '{s+=$4} END {print s}') passed; binaries' exits: $(grep -h '^exit ' "${logs[@]}" | sort | uniq -c | tr '\n' ' ')" | tee -a "$out/info.txt"
fi
# Then the benchmarks, on an otherwise idle GPU.
# The sweep's measurements so far reach $OUT every few seconds, so a time limit keeps them.
( while sleep 3; do cp /tmp/sweep/results.partial.json "$out/sweep.partial.json" 2>/dev/null; done ) & copier=$!
step sweep "$sweep_s" $fe bench --sweep bench/sweeps/many-lights-gpu.json --backend ${SWEEP_BACKENDS:-$backends} --frames ${SWEEP_FRAMES:-20} \
  --warmup-ms ${SWEEP_WARMUP_MS:-1000} --out /tmp/sweep
kill $copier 2>/dev/null
cp /tmp/sweep/results.json /tmp/sweep/results.csv "$out/" 2>/dev/null
step quick "$quick_s" $fe bench --quick --backend $backends --out /tmp/quick
# The GL recording ratio once more without NVIDIA's threaded optimisations (its driver thread
# may share the recording threads' CPUs).
step micro "$micro_s" bash -c 'build/bench/fe_bench_execution --rounds 21 && build/bench/fe_bench_abstraction --paired 300 &&
  __GL_THREADED_OPTIMIZATIONS=0 build/bench/fe_bench_execution --backend gl-egl --rounds 21'
# Results only: 28 cases' 720p images and FLIP maps are past what the device tool brings back.
tar -C /tmp -czf "$out/bench.tar.gz" --exclude='*.pfm' --exclude='*.png' --exclude=images quick sweep 2>/dev/null

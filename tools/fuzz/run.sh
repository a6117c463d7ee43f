#!/usr/bin/env bash
# Builds the libFuzzer harnesses with clang in build-sanitize/ and runs each for SECONDS (default 60)
# on its corpus: the hand-made seeds (tests/fuzz/seeds/), the glTF sample models of
# ../shared/assets when present, and what earlier runs kept (build-sanitize/fuzz/corpus/). A crash, a
# leak, a timeout or a sanitizer report stops the harness, leaves the input in
# build-sanitize/fuzz/findings/ and makes this script fail. CI runs it with a short SECONDS.
#   tools/fuzz/run.sh [SECONDS] [HARNESS...]     HARNESS: GltfLoaderFuzzer GltfUploadFuzzer CliFuzzer
#                                                PipelineCacheFuzzer CaptureStreamFuzzer CaptureFileFuzzer
#                                                ShaderSourceFuzzer
set -euo pipefail
cd "$(dirname "$0")/../.."
root="$(pwd)"
tools/install-deps.sh
seconds="${1:-60}"
shift || true
harnesses=("$@")
[ ${#harnesses[@]} -gt 0 ] || harnesses=(GltfLoaderFuzzer GltfUploadFuzzer CliFuzzer PipelineCacheFuzzer CaptureStreamFuzzer CaptureFileFuzzer ShaderSourceFuzzer)

# The sanitized suite's build (tools/sanitized-build.sh): after that suite, nothing is left to compile.
tools/sanitized-build.sh "${harnesses[@]}"

# Driver modules stay loaded for leak attribution, as in the sanitizer suite (lsan.supp).
export LSAN_OPTIONS="suppressions=$root/tools/sanitizers/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
mkdir -p build-sanitize/fuzz/findings
status=0
for h in "${harnesses[@]}"; do
  corpus="build-sanitize/fuzz/corpus/$h"
  mkdir -p "$corpus"
  case "$h" in
    CliFuzzer) seeds=(tests/fuzz/seeds/cli) ;;
    PipelineCacheFuzzer) seeds=(tests/fuzz/seeds/pipeline_cache) ;;
    CaptureStreamFuzzer) seeds=(tests/fuzz/seeds/capture_stream) ;;
    CaptureFileFuzzer) seeds=(tests/fuzz/seeds/capture_file) ;;
    ShaderSourceFuzzer) seeds=(tests/fuzz/seeds/shader_source) ;;
    *) seeds=(tests/fuzz/seeds/gltf)
       if [ -d ../shared/assets ]; then
         mkdir -p build-sanitize/fuzz/samples
         find ../shared/assets \( -name '*.gltf' -o -name '*.glb' \) -size -2M -exec cp -t build-sanitize/fuzz/samples {} + 2>/dev/null || true
         seeds+=(build-sanitize/fuzz/samples)
       fi ;;
  esac
  # The upload harness keeps one device for the whole run; the driver's own allocations are
  # not per input, so libFuzzer's per-input leak check is off there (objects are checked
  # per input with Device::liveObjects, and process leaks by the sanitizer suite).
  leaks=1
  [ "$h" = GltfUploadFuzzer ] || [ "$h" = CaptureFileFuzzer ] && leaks=0
  log="build-sanitize/fuzz/$h.log"
  echo "fuzz: $h for ${seconds} s"
  if ! "build-sanitize/tests/fuzz/$h" "$corpus" "${seeds[@]}" -max_total_time="$seconds" -timeout=30 -rss_limit_mb=8000 \
       -detect_leaks="$leaks" -print_final_stats=1 -artifact_prefix="build-sanitize/fuzz/findings/$h-" >"$log" 2>&1; then
    echo "fuzz: $h FOUND A PROBLEM (input in build-sanitize/fuzz/findings/, log $log):"
    grep -E "ERROR|SUMMARY|Test unit written|deadly signal|timeout" "$log" | head -20
    status=1
  fi
  grep -E "^stat::number_of_executed_units|^stat::peak_rss_mb|#[0-9]+ +DONE" "$log" | sed "s/^/  $h: /" || true
  grep -E "INITED|DONE" "$log" | tail -2 | sed "s/^/  $h: /" || true
done
exit $status

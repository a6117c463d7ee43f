#!/usr/bin/env bash
# fe bench's report in a browser: a small sweep on every backend, then the page opened in
# headless Chromium (Debian's chromium): every image and chart must load, no script or console
# error may occur, the stability table and conformance triplets must be there, and a screenshot of the page is kept
# beside it (report.png).
# Usage: report_in_chromium.sh FE SWEEP.json OUT_DIR
set -euo pipefail
fe=$1 sweep=$2 out=$3
rm -rf "$out"
"$fe" bench --sweep "$sweep" --stability --conformance --backend all --frames 2 --out "$out"
for f in results.json results.csv report.html; do
  test -s "$out/$f" || { echo "missing $out/$f"; exit 1; }
done
grep -q '<h2>Stability</h2>' "$out/report.html" || { echo "no stability table in the report"; exit 1; }
grep -q '<h2>Conformance</h2>' "$out/report.html" || { echo "no conformance section in the report"; exit 1; }
charts=$(ls "$out"/charts/*.png | wc -l)
svgs=$(ls "$out"/charts/*.svg | wc -l)
[ "$charts" -ge 4 ] && [ "$charts" -eq "$svgs" ] || { echo "expected 4 or more charts as PNG and SVG, got $charts / $svgs"; exit 1; }
url="file://$(realpath "$out")/report.html"
browse() { timeout 120 chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --virtual-time-budget=10000 "$@" "$url" 2>/dev/null; }
body=$(browse --dump-dom | grep -o '<body[^>]*>' || true)
echo "report body: $body"
[[ $body =~ data-images=\"([0-9]+)\" ]] || { echo "the page's check did not run"; exit 1; }
images=${BASH_REMATCH[1]}
[[ $body == *'data-broken="0"'* ]] || { echo "images that did not load: $body"; exit 1; }
[[ $body == *'data-errors="0"'* ]] || { echo "script or console errors: $body"; exit 1; }
[ "$images" -gt "$charts" ] || { echo "only $images images on the page"; exit 1; }
browse --window-size=1400,2400 --screenshot="$(realpath "$out")/report.png" >/dev/null
test -s "$out/report.png" || { echo "no screenshot"; exit 1; }
echo "report: $images images loaded, no errors; screenshot $out/report.png"

#!/usr/bin/env bash
# fe bench's report in a browser: a small sweep on every backend, then the page opened in
# headless Chromium (Debian's chromium): every image and chart must load, no script or console
# error may occur, the stability table and conformance triplets must be there, and a screenshot of the page is kept
# beside it (report.png). The charts: each has a legend, the heaviest cases' chart (light count x
# pixels) opens the page, and report.py still draws a sweep of one backend, technique and light count.
# Usage: report_in_chromium.sh FE SWEEP.json OUT_DIR
set -euo pipefail
fe=$1 sweep=$2 out=$3
rm -rf "$out"
# The stability table from two of its cases (a measured one and a refusal), the conformance
# section from two of its cases: the whole suites are tests of their own (the stability label's,
# conformance_*), and here they took most of this test's time.
"$fe" bench --sweep "$sweep" --stability-cases "one light,NaN uv" --conformance-cases "triangle,texture_sampling" \
  --backend all --frames 2 --out "$out"
for f in results.json results.csv report.html; do
  test -s "$out/$f" || { echo "missing $out/$f"; exit 1; }
done
grep -q '<h2>Stability</h2>' "$out/report.html" || { echo "no stability table in the report"; exit 1; }
grep -q '<h2>Conformance</h2>' "$out/report.html" || { echo "no conformance section in the report"; exit 1; }
charts=$(ls "$out"/charts/*.png | wc -l)
svgs=$(ls "$out"/charts/*.svg | wc -l)
[ "$charts" -ge 4 ] && [ "$charts" -eq "$svgs" ] || { echo "expected 4 or more charts as PNG and SVG, got $charts / $svgs"; exit 1; }
# Every chart names its techniques (or bars) in a legend, not in text at the points.
for svg in "$out"/charts/*.svg; do
  grep -q 'id="legend_1"' "$svg" || { echo "no legend in $svg"; exit 1; }
done
# report.py as fe runs it (Debian's interpreter, whose python3-matplotlib it is), from this source tree.
python=/usr/bin/python3; [ -x "$python" ] || python=python3
report="$(cd "$(dirname "$0")/.." && pwd)/tools/bench/report.py"
"$python" - "$out" <<'PY'
import json, os, re, sys
out = sys.argv[1]
doc = json.load(open(os.path.join(out, "results.json")))
done = [r for r in doc["results"] if "refused" not in r]
# The page opens with the heaviest cases' chart (light count x pixels): when those cases have
# lights, with scaling_lights, before the charts of the cases without lights.
def weight(r):
    s = r["settings"]
    return max(s["lights"], 1) * s["width"] * s["height"]
lit = max((weight(r) for r in done if r["settings"]["lights"]), default=0)
unlit = max((weight(r) for r in done if not r["settings"]["lights"]), default=0)
first = re.search(r'src="charts/([^"]+)\.png"', open(os.path.join(out, "report.html")).read())
if lit > unlit and (not first or first.group(1) != "scaling_lights"):
    sys.exit(f"the report opens with {first and first.group(1)}, not scaling_lights (the heaviest cases)")
# One backend, one technique, one light count: the results cut down to one case with lights.
one = next((r for r in done if r["settings"]["lights"]), None)
if one is None:
    sys.exit("the sweep has no case with lights")
doc["results"] = [one]
doc["backends"] = [b for b in doc["backends"] if b["name"] == one["backend"]]
doc.pop("conformance", None)
# A stability case rendered at a size of its own (as the 65536 lights are) is labelled with it.
for r in doc.get("stability", []):
    if r["case"] == "NaN uv":
        r["width"], r["height"] = 16, 12
os.makedirs(os.path.join(out, "one-case"), exist_ok=True)
json.dump(doc, open(os.path.join(out, "one-case", "results.json"), "w"))
PY
"$python" "$report" "$out/one-case/results.json" >/dev/null || { echo "report.py failed on one backend, technique and light count"; exit 1; }
for f in scaling_lights.png scaling_lights.svg; do
  test -s "$out/one-case/charts/$f" || { echo "no $f for one backend, technique and light count"; exit 1; }
done
grep -q 'id="legend_1"' "$out/one-case/charts/scaling_lights.svg" || { echo "no legend for one technique"; exit 1; }
grep -q '| NaN uv at 16x12 \['  "$out/one-case/summary.md" || { echo "a stability case at its own size is not labelled with it"; exit 1; }
grep -q '| one light \['  "$out/one-case/summary.md" || { echo "a stability case at the suite's size is labelled"; exit 1; }
url="file://$(realpath "$out")/report.html"
browse() { timeout 120 chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --virtual-time-budget=10000 "$@" "$url" 2>/dev/null; }
# One launch both dumps the DOM and takes the screenshot, after the same virtual time (the
# screenshot is byte for byte the one a second launch took; a launch costs about 7 s here).
body=$(browse --dump-dom --window-size=1400,2400 --screenshot="$(realpath "$out")/report.png" | grep -o '<body[^>]*>' || true)
echo "report body: $body"
[[ $body =~ data-images=\"([0-9]+)\" ]] || { echo "the page's check did not run"; exit 1; }
images=${BASH_REMATCH[1]}
[[ $body == *'data-broken="0"'* ]] || { echo "images that did not load: $body"; exit 1; }
[[ $body == *'data-errors="0"'* ]] || { echo "script or console errors: $body"; exit 1; }
[ "$images" -gt "$charts" ] || { echo "only $images images on the page"; exit 1; }
test -s "$out/report.png" || { echo "no screenshot"; exit 1; }
echo "report: $images images loaded, no errors; screenshot $out/report.png"

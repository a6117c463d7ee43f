#!/usr/bin/env python3
"""tools/bench/peer_side_by_side.py on a canned harness log (tests/data/peer_side_by_side.log):
ratios within each round on the same API, the noisy round left out, a failed run (fe's, or
bgfx's) giving no ratio, the best exact technique and the target. Exits non-zero on a mismatch."""
import json
import os
import subprocess
import sys
import tempfile

root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "../..")
with tempfile.TemporaryDirectory() as out:
    subprocess.run([sys.executable, os.path.join(root, "tools/bench/peer_side_by_side.py"), "parse",
                    os.path.join(root, "tests/data/peer_side_by_side.log"), "--out", out],
                   check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(out, "results.json")) as f:
        r = json.load(f)
    with open(os.path.join(out, "summary.md")) as f:
        summary = f.read()


def near(a, b):
    return all(abs(x - y) < 1e-9 for x, y in zip(a, b)) and len(a) == len(b)


checks = [
    (r["quietRounds"] == [1, 3], f"quiet rounds {r['quietRounds']}, expected [1, 3] (round 2's load 3.1)"),
    (near(r["ratios"]["gl-egl"]["forward-plus"], [0.5, 0.5]), f"gl forward-plus {r['ratios']['gl-egl']['forward-plus']}"),
    (near(r["ratios"]["gl-egl"]["deferred"], [2.0]), f"gl deferred {r['ratios']['gl-egl']['deferred']} (round 3 failed)"),
    (near(r["ratios"]["vulkan"]["forward-plus"], [0.5]), f"vulkan forward-plus {r['ratios']['vulkan']['forward-plus']} (round 3: no bgfx time)"),
    (r["bestExact"]["gl-egl"] == {"technique": "forward-plus", "ratio": 0.5}, f"best gl {r['bestExact']['gl-egl']}"),
    (r["bestExact"]["vulkan"]["technique"] == "visibility-buffer" and abs(r["bestExact"]["vulkan"]["ratio"] - 0.38) < 1e-9,
     f"best vulkan {r['bestExact']['vulkan']}"),
    ("visibility-buffer, 0.38x bgfx's frame time (meets the 0.4x target)" in summary, "the vulkan target line"),
    ("forward-plus, 0.50x bgfx's frame time (misses the 0.4x target)" in summary, "the gl target line"),
    ("left out: round(s) 2" in summary, "the noisy round named"),
]
failed = [what for ok, what in checks if not ok]
for what in failed:
    print("FAIL:", what)
sys.exit(1 if failed else 0)

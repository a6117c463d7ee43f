#!/usr/bin/env bash
# fe view's default (no scene: the quick start's) under a virtual display: a screenshot with the
# panel, and one without it in a window as wide as the scene's part of the first; then the
# pixels checked (tests/check_view_screenshot.py): the panel's column is dark with light text,
# and beside it is the whole scene, unobstructed: the same image as the second shot.
#   view_screenshot.sh FE BACKEND OUT_DIR
set -euo pipefail
fe=$1 backend=$2 out=$3
mkdir -p "$out"
# 640 wide: the panel takes its 300-pixel column, the scene the other 340.
"$fe" view --backend "$backend" --frames 4 --size 640x320 --validation --screenshot "$out/view_$backend.png"
"$fe" view --backend "$backend" --frames 4 --size 340x320 --validation --no-ui --screenshot "$out/view_${backend}_noui.png"
python=/usr/bin/python3
[ -x "$python" ] || python=python3
"$python" "$(dirname "$0")/check_view_screenshot.py" "$out/view_$backend.png" "$out/view_${backend}_noui.png" 300

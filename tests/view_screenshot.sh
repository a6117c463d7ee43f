#!/usr/bin/env bash
# fe view under a virtual display: a screenshot with the UI and one without, then the UI's
# pixels checked (tests/check_view_screenshot.py): the panel is there, dark with light text,
# and the scene beside it is the same in both shots.
#   view_screenshot.sh FE BACKEND OUT_DIR
set -euo pipefail
fe=$1 backend=$2 out=$3
mkdir -p "$out"
"$fe" view builtin:spheres --backend "$backend" --frames 4 --size 480x320 --validation --screenshot "$out/view_$backend.png"
"$fe" view builtin:spheres --backend "$backend" --frames 4 --size 480x320 --validation --no-ui --screenshot "$out/view_${backend}_noui.png"
python=/usr/bin/python3
[ -x "$python" ] || python=python3
"$python" "$(dirname "$0")/check_view_screenshot.py" "$out/view_$backend.png" "$out/view_${backend}_noui.png"

#!/usr/bin/env python3
"""Checks an fe view screenshot's UI against the same frame without it (view_screenshot.sh).

usage: check_view_screenshot.py WITH_UI.png WITHOUT_UI.png
The panel (ImGui's window at 8,8, 300 pixels wide) must cover its corner of the frame with its
dark background and light text; right of it the two shots must be the same image, and that
image must be a scene (not one flat colour)."""
import sys

import matplotlib.image as mpimg
import numpy as np


def main(ui_path, plain_path):
    ui = mpimg.imread(ui_path)[..., :3].astype(float)
    plain = mpimg.imread(plain_path)[..., :3].astype(float)
    if ui.shape != plain.shape:
        sys.exit(f"sizes differ: {ui.shape} and {plain.shape}")
    h, w, _ = ui.shape
    failures = []
    panel = ui[40:min(h, 200), 14:300]
    luma = panel @ np.array([0.2126, 0.7152, 0.0722])
    dark = float(np.mean(luma < 0.2))
    text = int(np.sum(luma > 0.75))
    changed = float(np.mean(np.abs(ui[40:200, 14:300] - plain[40:200, 14:300]).max(axis=2) > 0.02))
    if dark < 0.5:
        failures.append(f"the panel's area is not mostly dark ({dark:.0%} dark pixels)")
    if text < 100:
        failures.append(f"the panel shows no text ({text} light pixels)")
    if changed < 0.5:
        failures.append(f"the panel's area is the scene's ({changed:.0%} of pixels differ from the shot without UI)")
    right = (slice(0, h), slice(340, w))
    diff = float(np.abs(ui[right] - plain[right]).max())
    if diff > 2.0 / 255.0:
        failures.append(f"beside the panel the shots differ by {diff * 255:.0f}/255: the UI drew over the scene")
    if float(plain[right].std()) < 0.02:
        failures.append("beside the panel the frame is flat: no scene was drawn")
    print(f"{ui_path}: panel {dark:.0%} dark, {text} text pixels, {changed:.0%} changed; scene beside it identical "
          f"(max {diff * 255:.1f}/255)")
    if failures:
        sys.exit("; ".join(failures))


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])

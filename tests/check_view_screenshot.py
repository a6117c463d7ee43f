#!/usr/bin/env python3
"""Checks an fe view screenshot: the panel beside the scene, not over it (view_screenshot.sh).

usage: check_view_screenshot.py WITH_UI.png SCENE_ALONE.png PANEL_WIDTH
WITH_UI is the window with its panel, a column PANEL_WIDTH pixels wide at the left; SCENE_ALONE
the same scene in a window as wide as the rest (--no-ui). The column must be the panel (dark
background, light text); right of it must be exactly SCENE_ALONE, and that a scene (not one flat
colour): the whole view, none of it under the panel."""
import sys

import matplotlib.image as mpimg
import numpy as np


def main(ui_path, plain_path, panel_width):
    ui = mpimg.imread(ui_path)[..., :3].astype(float)
    plain = mpimg.imread(plain_path)[..., :3].astype(float)
    h, w, _ = ui.shape
    if plain.shape != (h, w - panel_width, 3):
        sys.exit(f"the scene alone is {plain.shape[1]}x{plain.shape[0]}, expected {w - panel_width}x{h}")
    failures = []
    luma = ui[:, :panel_width] @ np.array([0.2126, 0.7152, 0.0722])
    dark = float(np.mean(luma < 0.2))
    text = int(np.sum(luma > 0.75))
    if dark < 0.5:
        failures.append(f"the panel's column is not mostly dark ({dark:.0%} dark pixels)")
    if text < 100:
        failures.append(f"the panel shows no text ({text} light pixels)")
    scene = ui[:, panel_width:]
    diff = float(np.abs(scene - plain).max())
    if diff > 2.0 / 255.0:
        over = float(np.mean(np.abs(scene - plain).max(axis=2) > 2.0 / 255.0))
        failures.append(f"beside the panel the scene differs from the scene alone by up to {diff * 255:.0f}/255 "
                        f"({over:.1%} of its pixels): the panel covers it or it is not drawn there")
    if float(plain.std()) < 0.02:
        failures.append("the scene is flat: nothing was drawn")
    print(f"{ui_path}: panel {dark:.0%} dark, {text} text pixels; the scene beside it is the scene alone "
          f"(max difference {diff * 255:.1f}/255)")
    if failures:
        sys.exit("; ".join(failures))


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], int(sys.argv[3]))

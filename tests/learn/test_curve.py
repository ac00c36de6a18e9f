"""The learning-curve picture (``roboracer_arena.learn.curve``)."""

import numpy as np
from PIL import Image

from roboracer_arena.learn.curve import plot_curve


def test_plot_curve_writes_a_png_with_both_series(tmp_path):
    curve = [{"env_steps": 1000.0 * g, "mean_return": float(g), "max_return": float(2 * g)} for g in range(1, 6)]
    path = tmp_path / "curve.png"
    plot_curve(curve, path, "test", size=(400, 300))
    img = np.asarray(Image.open(path).convert("RGB"))
    assert img.shape == (300, 400, 3)
    blue = np.all(img == (31, 94, 200), axis=-1).sum()
    grey = np.all(img == (150, 150, 150), axis=-1).sum()
    assert blue > 50 and grey > 50  # the mean and best lines are drawn
    assert not list(tmp_path.glob("*.tmp*"))  # written atomically, no leftovers

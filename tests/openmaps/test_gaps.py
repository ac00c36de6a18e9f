"""Gap closing, shown: a thin-line ring whose outer wall has a 0.5 m opening leaks; closing
openings up to 0.8 m makes it a track again, and the gap is reported and drawn."""

from __future__ import annotations

import numpy as np
import pytest
from PIL import Image

from roboracer_arena.errors import CorridorError, InvalidArgumentError
from roboracer_arena.maps.corridor import extract_corridor
from roboracer_arena.maps.gaps import close_gaps
from roboracer_arena.maps.occupancy import load_map


def _leaking_ring(tmp_path):
    n = 140
    yy, xx = np.mgrid[0:n, 0:n]
    r = np.hypot(xx - n / 2, yy - n / 2)
    img = np.full((n, n), 255, np.uint8)
    img[(np.abs(r - 20) < 1.5) | (np.abs(r - 48) < 1.5)] = 0
    img[65:75, 110:125] = 255  # a 10-cell (0.5 m) doorway through the outer wall, on the right
    Image.fromarray(img).save(tmp_path / "leak.png")
    y = tmp_path / "leak.yaml"
    y.write_text(
        "image: leak.png\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"
    )
    return y


def test_closing_a_doorway_makes_a_leaking_loop_a_track(tmp_path):
    y = _leaking_ring(tmp_path)
    with pytest.raises(CorridorError, match="leak"):
        extract_corridor(y)
    geo = extract_corridor(y, close_gaps_m=0.8)
    assert geo.kind == "track" and geo.centreline_length > 8.0
    (gap,) = geo.closed_gaps  # exactly the doorway: never a silent change elsewhere
    assert abs(gap.x - 117 * 0.05) < 0.3 and abs(gap.y - 70 * 0.05) < 0.3
    assert 0.3 < gap.width_m < 0.8
    # Too narrow a width closes nothing and says so (an empty list), the map still leaks.
    m, gaps = close_gaps(load_map(y), 0.3)
    assert gaps == [] and np.array_equal(m.data, load_map(y).data)
    with pytest.raises(InvalidArgumentError):
        close_gaps(load_map(y), -1.0)


def test_preview_and_build_show_every_closed_gap(tmp_path):
    from roboracer_arena.builder import build_environment
    from roboracer_arena.render.preview import preview_map

    y = _leaking_ring(tmp_path)
    s = preview_map(y, tmp_path / "p.png", close_gaps_m=0.8)
    assert "closed gaps" in s.drawn and [f for f in s.features if "closed_gap" in f]
    rep = build_environment(y, tmp_path / "leak.usdc", close_gaps_m=0.8)
    assert rep.map_kind == "track" and len(rep.closed_gaps) == 1 and "closed gap at" in rep.summary()


def test_close_gaps_flag_is_range_checked(tmp_path, capsys):
    from roboracer_arena.cli import main

    y = _leaking_ring(tmp_path)
    for bad in ("nan", "-1", "50"):
        assert main(["build", str(y), "-o", str(tmp_path / "x.usdc"), "--close-gaps", bad]) == 2
        assert "--close-gaps" in capsys.readouterr().err
    assert not (tmp_path / "x.usdc").exists()

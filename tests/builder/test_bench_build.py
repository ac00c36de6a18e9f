"""The build benchmark's plumbing (no timing assertions: performance lives in the bench)."""

from __future__ import annotations

import pytest

from benchmarks import build as bench
from roboracer_arena import load_map
from roboracer_arena.bench.output import json_text
from shared_data import sources_dir  # tests/ is on sys.path (rootdir conftest)


def test_paper_table_and_interpolation():
    assert [p[0] for p in bench.PAPER][-1] == "Spa-Francorchamps"
    assert bench.paper_at(0.13) == (1.18, 7.8)
    assert bench.paper_at(10.77) == (2.48, 65.9)
    assert bench.paper_at(0.05) == (1.18, 7.8)  # clamped below the table
    s, mb = bench.paper_at(5.0)
    assert 1.75 < s < 2.16 and 40.6 < mb < 55.4


def test_resampled_map_keeps_extent(tmp_path):
    src = sources_dir() / "f1tenth-simulator/maps/columbia.yaml"
    m = load_map(src)
    for target in (0.05, 0.6):
        out = load_map(bench.resampled_map(src, target, tmp_path))
        assert out.megapixels == pytest.approx(target, rel=0.02)
        assert out.shape[1] * out.resolution == pytest.approx(m.shape[1] * m.resolution, rel=1e-9)
        assert out.origin == m.origin


@pytest.mark.slow
def test_one_size_runs_in_a_single_threaded_subprocess():
    result = bench.run(["generated 3h1c"], repeat=1, textures=False, progress=False)
    (row,) = result.rows
    assert isinstance(row, bench.BuildRow), row
    assert row.iou >= 0.97 and row.usd_bytes > 0 and row.peak_rss_gb > 0
    assert {"load", "geometry", "usd_author", "usd_write", "total"} <= set(row.stages)
    assert row.paper_seconds == bench.paper_at(row.raster_mp)[0] and row.speedup == row.paper_seconds / row.seconds
    text = json_text(result)
    assert json_text(bench.BuildResult.model_validate_json(text)) == text
    assert "generated 3h1c" in bench.format_table(result)
    assert bench.format_markdown(result).startswith("| map | raster MP |")

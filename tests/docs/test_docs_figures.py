"""The figures README.md and BENCHMARKS.md quote come from the current build: each doc
block equals the rendering of its data file (docs/learning/*.json, docs/figures/*.json),
and rerunning the deterministic part of each figure that takes seconds (``ci="rerun"``;
``make docs-figures`` runs the same functions) reproduces that data. Wall and CPU times
are measurements and are not compared; "long" figures (minutes) are rerun only by
``make docs-figures``."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _figures():
    spec = importlib.util.spec_from_file_location("docs_figures", ROOT / "scripts" / "docs_figures.py")
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_doc_blocks_match_their_data():
    assert _figures().check() == []


def _approx(x):
    """Exact for ints, bools and strings; floats to 1e-9 relative (printing round-trips)."""
    if isinstance(x, dict):
        return {k: _approx(v) for k, v in x.items()}
    if isinstance(x, list):
        return [_approx(v) for v in x]
    if isinstance(x, float):
        return pytest.approx(x, rel=1e-9, abs=1e-12)
    return x


def test_every_figure_is_listed_with_its_ci_rule():
    figs = _figures()
    for key, fig in figs.FIGURES.items():
        assert fig["ci"] in ("rerun", "long", "measured"), key
        assert (fig["deterministic"] is None) == (fig["ci"] == "measured"), key


LEARNING_RUNS = {"es", "generalisation"}  # about a minute and several minutes
RERUN = [
    pytest.param(k, marks=pytest.mark.slow) if k in LEARNING_RUNS else k
    for k, f in _figures().FIGURES.items()
    if f["ci"] == "rerun"
]


@pytest.mark.parametrize("key", RERUN)
def test_rerun_reproduces_the_documented_figures(key, sources):
    figs = _figures()
    fig = figs.FIGURES[key]
    committed = fig["deterministic"](figs.read_data(key))
    fresh = fig["deterministic"](fig["run"]("test rerun"))
    assert fresh == _approx(committed)

"""``roboracer-arena bench library`` end to end: the JSON is its model's dump (the figures
live in BENCHMARKS.md; the circuit build itself is tested in tests/circuits)."""

from __future__ import annotations

import pytest

from benchmarks.__main__ import main
from benchmarks.library import LibraryResult
from roboracer_arena.bench.output import json_text


@pytest.mark.slow
def test_bench_library_cli_writes_its_model(sources, tmp_path, capsys):
    out = tmp_path / "library.json"
    assert main(["library", "--sources", str(sources), "--jobs", "2", "--json", str(out)]) == 0
    assert "length error mean (%)" in capsys.readouterr().out
    text = out.read_text()
    res = LibraryResult.model_validate_json(text)
    assert json_text(res) == text
    assert res.built == sum(r.raster is not None for r in res.per_circuit) and res.circuits == len(res.per_circuit)

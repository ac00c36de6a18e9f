"""``tracks verify`` on a sample of each kind (load, ring, USD, pure-pursuit lap)."""

from __future__ import annotations

import json

import pytest

from roboracer_arena.catalog import load_catalog
from roboracer_arena.cli import main
from roboracer_arena.library.verify import verify
from roboracer_arena.physx import available as physx_available


def test_verify_one_track_of_each_kind():
    cat = load_catalog()
    picks = [cat.get("norisring"), cat.select("generated")[0], cat.get("gym-berlin")]
    s = verify(cat, picks, jobs=1)
    assert s.tracks == 3 and s.passed == 3, s.failed
    for r in s.results:
        assert {k: v.status for k, v in r.checks.items()} == {
            "load": "pass",
            "ring": "pass",
            "usd": "pass",
            "physx": "pass" if physx_available() else "not run",  # the PhysX check, with the extra
            "drive": "pass",
        }, r


def test_verify_catches_a_tampered_map(tmp_path):
    cat = load_catalog()
    e = cat.select("generated")[0].with_fields(sha256="0" * 64)
    s = verify(cat, [e], jobs=1, usd=False, drive=False)
    assert s.failed == [e.id]
    assert "checksum" in s.results[0].checks["load"].detail


@pytest.mark.slow
def test_cli_verify_subset(capsys):
    rc = main(["tracks", "verify", "--limit", "1", "--no-drive", "--jobs", "1", "--json"])
    out = json.loads(capsys.readouterr().out)
    assert rc == 0 and out["tracks"] == 3 and out["passed"] == 3
    assert out["per_check"]["drive"]["not run"] == 3


def test_sheet(tmp_path):
    out = tmp_path / "sheet.png"
    assert main(["tracks", "sheet", "-o", str(out), "--limit", "2", "--columns", "3"]) == 0
    from PIL import Image

    with Image.open(out) as im:
        assert im.size[0] == 3 * 180 and im.size[1] >= 2 * 178


def test_prune_moves_failed_recorded_maps_only():
    from roboracer_arena.library.verify import prune_catalog
    from roboracer_arena.library.verify_report import Check, TrackResult, VerifySummary

    cat = load_catalog()
    rec, gen = cat.select("recorded")[0], cat.select("generated")[0]
    bad = Check(status="FAIL", detail="lap not completed")
    ok = Check(status="pass", detail="fine")
    results = [
        TrackResult(id=e.id, kind=e.kind, passed=False, seconds=0.0, checks={"load": ok, "drive": bad})
        for e in (rec, gen)
    ]
    n = len(cat.entries)
    assert prune_catalog(cat, VerifySummary.tally(results, 0.0, 1)) == [rec.id]
    assert len(cat.entries) == n - 1 and cat.left_out[-1].id == rec.id
    assert "drive: lap not completed" in cat.left_out[-1].reason
    assert cat.get(gen.id).verified == {**(gen.verified or {}), "load": "pass", "drive": "FAIL"}
    assert cat.meta.counts == cat.counts()


def test_a_partial_run_adds_its_column_and_keeps_the_others():
    """``verify --no-drive --update-catalog`` records the checks it made (a new physx column)
    and keeps the lap and its text from the earlier full run."""
    from roboracer_arena.library.verify import prune_catalog
    from roboracer_arena.library.verify_report import Check, TrackResult, VerifySummary

    cat = load_catalog()
    gen = cat.select("generated")[0]
    assert gen.verified and gen.verified["drive"] == "pass" and gen.drive
    checks = {
        "load": Check(status="pass", detail=""),
        "physx": Check(status="pass", detail="1081/1081 beams"),
        "drive": Check(status="not run", detail="not run: --no-drive"),
    }
    result = TrackResult(id=gen.id, kind=gen.kind, passed=True, seconds=0.0, checks=checks)
    assert prune_catalog(cat, VerifySummary.tally([result], 0.0, 1)) == []
    after = cat.get(gen.id)
    assert after.verified == {**gen.verified, "physx": "pass"}
    assert after.drive == gen.drive

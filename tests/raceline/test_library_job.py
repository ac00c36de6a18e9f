"""The catalog raceline job: staged records, skipped on a rerun, verified by planning again."""

from __future__ import annotations

from roboracer_arena.library.racelines import build_racelines, load_index, verify_record

SMALL = "gen-l040-w12-h2c1s1-clo-s0"


def test_job_records_skips_and_verifies(tmp_path):
    path = tmp_path / "racelines.json"
    seen = []
    index = build_racelines([SMALL], path=path, drive=False, progress=seen.append)
    rec = index.get(SMALL)
    assert rec is not None and rec.error is None and rec.lap_time_s > 0 and len(seen) == 1
    assert load_index(path) == index
    build_racelines([SMALL], path=path, drive=False, progress=seen.append)
    assert len(seen) == 1  # recorded already: skipped
    assert verify_record(SMALL, index) == []
    bad = index.with_fields(records=[rec.with_fields(lap_time_s=rec.lap_time_s + 1).to_json_dict()])
    assert "planned lap" in verify_record(SMALL, bad)[0]
    assert "no raceline recorded" in verify_record("monaco", index)[0]


def test_a_failing_track_is_recorded_not_raised(tmp_path):
    index = build_racelines(["no-such-track-id"], path=tmp_path / "r.json", drive=False)
    assert index.records[0].error

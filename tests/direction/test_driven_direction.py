"""Every track is driven in its real direction: the sign of the area the driven path
encloses equals the sign of the area of the *source* centreline (in its point order),
and ``reverse=True`` flips it. The source signs are read from the source files here, not
from anything the package wrote."""

from __future__ import annotations

import json

import pytest
from drive_path import driven_lap
from source_sense import shoelace, source_sign

from roboracer_arena.catalog import load_catalog
from roboracer_arena.foundation.paths import tracks_dir
from roboracer_arena.maps.direction import COUNTERCLOCKWISE


def _clockwise_generated():
    """A 40 m clockwise track with one hairpin, generated afresh (seed 0)."""
    from roboracer_arena import TrackSpec
    from roboracer_arena.generate import generate_track

    spec = TrackSpec(
        name="cw",
        lap_length_m=40.0,
        corridor_width_m=1.2,
        hall_x_m=20.0,
        hall_y_m=15.0,
        direction="clockwise",
        hairpins=1,
        chicanes=0,
        sweepers=0,
    )
    return generate_track(spec, seed=0)


def _sign(path) -> int:
    return 1 if shoelace(path) > 0 else -1


def _circuit_source(sources, track_id: str):
    e = load_catalog().get(track_id)
    assert e.kind == "circuit"
    return sources / e.source.path


@pytest.mark.parametrize("track_id,real", [("monza", -1), ("sao-paulo", 1)])
def test_circuit_lap_runs_the_source_direction(sources, track_id, real):
    src = _circuit_source(sources, track_id)
    assert source_sign(src) == real  # Monza runs clockwise, Interlagos counter-clockwise
    path = driven_lap(track_id)
    assert _sign(path) == source_sign(src), f"{track_id} driven the wrong way round"


def test_reverse_drives_the_other_way(sources):
    src = _circuit_source(sources, "norisring")
    assert _sign(driven_lap("norisring", reverse=True)) == -source_sign(src)


def test_clockwise_generated_track_is_driven_clockwise():
    track_id = "gen-l040-w12-h2c1s1-clo-s0"
    spec = json.loads((tracks_dir() / "generated" / track_id / "spec.json").read_text())
    assert spec["direction"] == "clockwise"  # the request
    assert _sign(driven_lap(track_id)) == -1
    assert _sign(driven_lap(track_id, reverse=True)) == 1


def test_generated_map_path_outside_the_catalog_keeps_the_requested_direction(tmp_path):
    """A freshly generated clockwise track, driven from its folder (not the catalog)."""
    from roboracer_arena.generate import Acceptance, write_outputs
    from roboracer_arena.track.drivable import track_from_map_path

    out = _clockwise_generated()
    assert isinstance(out, Acceptance)
    paths = write_outputs(out, tmp_path)
    t = track_from_map_path(paths["map_yaml"])
    assert t.direction == "clockwise"
    assert t.reversed().direction == COUNTERCLOCKWISE


@pytest.mark.slow
def test_every_catalog_circuit_is_driven_in_its_source_direction(sources):
    """46 laps (no lidar): each circuit's driven area has the sign of its source centreline."""
    wrong = []
    for e in load_catalog().select("circuits"):
        src = sources / e.source.path
        if _sign(driven_lap(e.id)) != source_sign(src):
            wrong.append(e.id)
    assert not wrong, f"driven against the source direction: {wrong}"


def test_catalog_records_every_circuit_in_its_source_direction(sources):
    cat = load_catalog()
    for e in cat.select("circuits"):
        want = source_sign(sources / e.source.path)
        assert (1 if e.direction == COUNTERCLOCKWISE else -1) == want, e.id
        assert e.direction_source and "point order" in e.direction_source
    for e in cat.select("generated"):
        assert e.spec is not None
        spec = json.loads((tracks_dir() / e.spec).read_text())
        assert e.direction == spec["direction"], e.id


def test_generated_outcome_and_its_map_plug_in_everywhere(tmp_path):
    """One map type: ``generate_track(...).map`` is an ``OccupancyMap`` that the env, the
    builder and the corridor take as they take ``load_map``'s; the Acceptance itself drives
    in the requested direction."""
    import gymnasium as gym

    from roboracer_arena import build_environment, extract_corridor, load_map

    out = _clockwise_generated()
    m = out.map
    assert type(m) is type(load_map(m.save(tmp_path / "cw.yaml")))
    assert extract_corridor(m).walls
    assert build_environment(m, tmp_path / "cw.usda").iou > 0.99
    assert gym.make("RoboRacerArena-v0", track=m).unwrapped.tracks[0].name == "map"
    assert _sign(driven_lap(out)) == -1  # the Acceptance keeps the requested clockwise sense

"""generate_track → written artefacts: determinism per seed, direction, feature order,
the report's checks, and the map loading back."""

import json

import numpy as np
import pytest

from roboracer_arena import TrackSpec
from roboracer_arena.generate import Acceptance, generate_track, validate_map, write_outputs
from roboracer_arena.maps.occupancy import load_map

SMALL = TrackSpec(name="small", lap_length_m=40, hall_x_m=15, hall_y_m=12, hairpins=1, chicanes=1)


def _accept(spec: TrackSpec, seed: int = 0) -> Acceptance:
    out = generate_track(spec, seed=seed)
    assert isinstance(out, Acceptance), out.summary()
    return out


def _signed_area(xy: np.ndarray) -> float:
    x, y = xy[:, 0], xy[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def test_same_seed_gives_identical_files(tmp_path):
    a = write_outputs(_accept(SMALL, 5), tmp_path / "a")
    b = write_outputs(_accept(SMALL, 5), tmp_path / "b")
    for key in ("map_png", "map_yaml", "centreline_csv", "spec_json"):
        assert a[key].read_bytes() == b[key].read_bytes(), key


def test_different_seeds_explore_different_candidates():
    maps = {_accept(SMALL, s).map.data.tobytes() for s in range(4)}
    assert len(maps) > 1


@pytest.mark.parametrize("direction, sign", [("counterclockwise", 1), ("clockwise", -1)])
def test_direction_is_honoured(tmp_path, direction, sign):
    spec = SMALL.model_copy(update={"direction": direction})
    acc = _accept(spec)
    assert np.sign(_signed_area(acc.centreline)) == sign
    paths = write_outputs(acc, tmp_path)
    csv = np.loadtxt(paths["centreline_csv"], delimiter=",", comments="#")
    assert csv.shape[1] == 4 and np.allclose(csv[:, 2:], spec.corridor_width_m / 2)
    assert np.sign(_signed_area(csv[:, :2])) == sign


@pytest.mark.parametrize("direction", ["counterclockwise", "clockwise"])
def test_feature_order_is_honoured_in_the_driving_direction(direction):
    order = ["hairpin", "hairpin", "chicane", "sweeper"]
    spec = TrackSpec(lap_length_m=60, hairpins=2, chicanes=1, sweepers=1, feature_order=order, direction=direction)
    got = [f.kind for f in _accept(spec).report.features]
    rotations = [order[i:] + order[:i] for i in range(len(order))]
    assert got in rotations


def test_every_check_reports_measured_bound_and_verdict(tmp_path):
    acc = _accept(SMALL)
    paths = write_outputs(acc, tmp_path)
    report = json.loads(paths["report_json"].read_text())
    names = {c["name"] for c in report["checks"]}
    assert {
        "corridor",
        "infield",
        "lap_length",
        "width",
        "min_radius",
        "hairpins",
        "chicanes",
        "sweepers",
        "self_clearance",
        "hall_fit",
    } <= names
    for c in report["checks"]:
        assert c["measured"] and c["bound"] and c["passed"] is True
    assert json.loads(paths["spec_json"].read_text()) == SMALL.model_dump(mode="json")
    # The written map loads back and re-validates to the same verdict.
    again, _ = validate_map(load_map(paths["map_yaml"]), SMALL)
    assert again.valid and [c.measured for c in again.checks] == [c["measured"] for c in report["checks"]]


def test_validator_fails_a_map_against_the_wrong_spec():
    acc = _accept(SMALL)
    report, _ = validate_map(acc.map, SMALL.model_copy(update={"lap_length_m": 50.0, "hairpins": 2}))
    failed = {c.name for c in report.failed()}
    assert not report.valid and {"lap_length", "hairpins"} <= failed


@pytest.mark.parametrize("resolution", [0.025, 0.1])
def test_resolution_is_configurable(resolution):
    from roboracer_arena.config.constructor import ConstructorConfig

    out = generate_track(SMALL, config=ConstructorConfig(resolution_m=resolution))
    assert isinstance(out, Acceptance) and out.map.resolution == resolution
    h, w = out.map.shape
    assert w * resolution == pytest.approx(SMALL.hall_x_m - 1, abs=3)  # map spans the hall, not the cell count

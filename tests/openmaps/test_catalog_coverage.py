"""Every recorded source map is in the catalog as a track, an open map, a duplicate or
broken, with its reason; at least the paper's 74 are usable (tracks or open maps)."""

from __future__ import annotations

import csv
import json

from roboracer_arena.catalog.catalog_file import load_catalog
from roboracer_arena.library.open_maps import map_kinds


def test_every_source_map_has_a_kind_and_74_are_usable(sources):
    cat = load_catalog()
    kinds = map_kinds(cat)
    paths = {e.map: e.id for e in cat.entries if e.kind == "recorded"}
    paths.update({lo.source_path: lo.id for lo in cat.left_out})
    with open(sources / "map-inventory.csv", newline="") as f:
        inventory = [row["yaml"] for row in csv.DictReader(f)]
    assert len(inventory) == 92
    missing = [y for y in inventory if y not in paths]
    assert missing == []
    assert set(kinds.values()) <= {"track", "open", "duplicate", "broken"}
    assert sum(k in ("track", "open") for k in kinds.values()) >= 74
    reasons = {lo.id: lo.reason for lo in cat.left_out}
    assert all(reasons[o.id] == o.reason and o.reason for o in cat.open_maps)
    narrow = [o for o in cat.open_maps if o.reason.startswith("verify failed")]
    assert narrow and all(o.narrowest_gap_m is not None and "narrowest gap" in o.reason for o in narrow)


def test_tracks_list_kind_open(capsys):
    from roboracer_arena.cli import main

    assert main(["tracks", "list", "--kind", "open", "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)
    assert "gym-ros-levine" in {r["id"] for r in rows}
    assert main(["tracks", "list", "--kind", "open"]) == 0
    assert "open maps" in capsys.readouterr().out


def test_an_open_map_catalog_id_is_a_track_argument():
    import gymnasium as gym

    import roboracer_arena  # noqa: F401

    env = gym.make("RoboRacerArena-v0", track="gym-ros-levine")
    _, info = env.reset(seed=0)
    assert info["open_map"] is True and info["track"] == "gym-ros-levine"
    assert env.unwrapped.tracks[0].start_pose == (0.0, 0.0, 0.0)
    env.close()

"""The committed catalog: contents, round trip, resolve() and the CLI listing."""

from __future__ import annotations

import json

import pytest

from roboracer_arena.catalog import Catalog, load_catalog, resolve, resolve_tracks
from roboracer_arena.catalog.catalog_file import sha256_file
from roboracer_arena.cli import main
from roboracer_arena.errors import InvalidArgumentError

REQUIRED = (
    "id",
    "name",
    "kind",
    "source",
    "scale",
    "resolution_m",
    "lap_length_m",
    "width_mean_m",
    "width_min_m",
    "min_radius_m",
    "raster",
    "sha256",
    "map",
    "notes",
)


@pytest.fixture(scope="module")
def cat() -> Catalog:
    return load_catalog()


def test_catalog_has_every_kind_and_at_least_130_tracks(cat):
    kinds = cat.counts()
    assert len(cat.entries) >= 130
    assert kinds["circuit"] >= 44 and kinds["generated"] >= 50 and kinds["recorded"] > 0
    assert len({e.id for e in cat.entries}) == len(cat.entries)
    for e in cat.entries:
        missing = [k for k in REQUIRED if k not in e.model_fields_set]
        assert not missing, (e.id, missing)
        assert e.source.licence and e.source.repository
    ids = {e.id for e in cat.entries}
    assert {"monaco", "baku", "suzuka"} <= ids
    assert cat.get("suzuka").grade_separated is True
    assert any("grade-separated" in n for n in cat.get("suzuka").notes)


def test_left_out_maps_carry_a_reason(cat):
    assert cat.left_out
    assert all(lo.reason and lo.source_path for lo in cat.left_out)
    assert any("porto.yaml" in lo.source_path for lo in cat.left_out)  # names a missing image


def test_round_trip(cat, tmp_path):
    p = tmp_path / "catalog.json"
    p.write_text(cat.to_json())
    again = load_catalog(p)
    assert again.entries == cat.entries and again.left_out == cat.left_out


def test_project_maps_match_their_checksums(cat):
    for e in cat.select("circuits")[:5] + cat.select("generated")[:5]:
        png = cat.map_path(e).with_suffix(".png")
        assert sha256_file(png) == e.sha256, e.id


def test_recorded_maps_are_referenced_not_copied(cat, sources):
    for e in cat.select("recorded"):
        assert not e.map.startswith("/") and (sources / e.map).is_file(), e.id
    assert not (cat.path.parent / "recorded").exists()


def test_resolve_ids_and_selections(cat, sources):
    assert resolve("monaco", cat)[0].name == "map.yaml" and resolve("monaco", cat)[0].is_file()
    assert len(resolve("circuits", cat)) == cat.counts()["circuit"]
    assert len(resolve("all", cat, sources=sources)) == len(cat.entries)
    assert len(resolve(["monaco", "generated"], cat)) == 1 + len(cat.select("generated"))
    tracks = resolve_tracks(["monaco", "suzuka"], cat)
    assert [t.name for t in tracks] == ["monaco", "suzuka"]
    # Suzuka is grade-separated: the env laps its own figure-8 centreline, not one lobe.
    assert tracks[1].length > 550  # the full lap (580.7 m), not one lobe (~343 m)
    with pytest.raises(InvalidArgumentError, match="unknown track id"):
        resolve("no-such-track", cat)


def test_cli_list_and_show(capsys):
    assert main(["tracks", "list", "--kind", "circuit", "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)
    assert all(r["kind"] == "circuit" for r in rows) and len(rows) >= 44
    assert main(["tracks", "show", "monaco", "--json"]) == 0
    e = json.loads(capsys.readouterr().out)
    assert e["id"] == "monaco" and e["map_path"].endswith("map.yaml")
    assert main(["tracks", "show", "nope"]) == 2

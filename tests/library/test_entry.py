"""The catalog's typed models: the shipped catalog loads into them and writes back byte for
byte; a key the model does not know, or a value of the wrong kind, is refused with the
file, the entry and the field named."""

from __future__ import annotations

import json
import re

import pytest
from pydantic import ValidationError

from roboracer_arena.catalog import load_catalog
from roboracer_arena.catalog.entry import LeftOut, TrackEntry
from roboracer_arena.errors import MapIOError


def test_shipped_catalog_loads_typed_and_round_trips_byte_for_byte():
    cat = load_catalog()
    assert cat.path is not None
    assert all(isinstance(e, TrackEntry) for e in cat.entries)
    assert all(isinstance(lo, LeftOut) for lo in cat.left_out)
    assert cat.to_json() == cat.path.read_text(encoding="utf-8")


def test_entries_are_frozen_and_copies_are_validated():
    e = load_catalog().get("monaco")
    with pytest.raises(ValidationError):
        e.lap_length_m = 1.0  # type: ignore[misc]
    assert e.with_fields(drive="lap ok").drive == "lap ok"
    with pytest.raises(ValidationError, match="direction"):
        e.with_fields(direction="sideways")


def _tamper(tmp_path, change) -> str:
    doc = json.loads(load_catalog().to_json())
    change(doc)
    p = tmp_path / "catalog.json"
    p.write_text(json.dumps(doc))
    return str(p)


def test_unknown_key_is_refused_naming_the_entry(tmp_path):
    p = _tamper(tmp_path, lambda d: d["tracks"][0].update(lap_lenght_m=3.0))
    with pytest.raises(MapIOError, match=r"catalog.json: tracks\['austin'\]\.lap_lenght_m: Extra inputs"):
        load_catalog(p)


def test_wrong_kind_and_bad_left_out_are_refused(tmp_path):
    with pytest.raises(MapIOError, match=r"tracks\['austin'\]\.kind"):
        load_catalog(_tamper(tmp_path, lambda d: d["tracks"][0].update(kind="oval")))
    with pytest.raises(MapIOError, match=r"left_out\[.*\]\.reason: Field required"):
        load_catalog(_tamper(tmp_path, lambda d: d["left_out"][0].pop("reason")))


def test_catalog_header_is_typed_and_checked(tmp_path):
    meta = load_catalog().meta
    assert meta.catalog_schema == "roboracer-arena track catalog v1" and sum(meta.counts.values()) > 100
    with pytest.raises(MapIOError, match=r"catalog.json: header\.schem: Extra inputs"):
        load_catalog(_tamper(tmp_path, lambda d: d.update(schem="v2")))
    with pytest.raises(MapIOError, match=r"header\.counts\.oval\.\[key\]: Input should be .recorded"):
        load_catalog(_tamper(tmp_path, lambda d: d["counts"].update(oval=1)))


@pytest.mark.slow
def test_catalog_builder_reproduces_every_shipped_entry(tmp_path, sources):
    """``build_catalog`` (typed end to end) writes each shipped entry as shipped, field for
    field and in the same key order; only ``tracks verify --update-catalog``'s results
    (``verified``, ``drive``, and the recorded maps it moved to ``left_out``) are not its."""
    from roboracer_arena.foundation.paths import tracks_dir
    from roboracer_arena.library.index import build_catalog

    for part in ("circuits", "generated"):
        (tmp_path / part).symlink_to(tracks_dir() / part)
    build_catalog(sources, tmp_path, jobs=2)
    built = {e["id"]: e for e in json.loads((tmp_path / "catalog.json").read_text())["tracks"]}
    shipped = json.loads(load_catalog().to_json())
    for e in shipped["tracks"]:
        want = {k: v for k, v in e.items() if k not in ("verified", "drive")}
        assert list(built[e["id"]].items()) == list(want.items()), e["id"]
    assessed = [lo for lo in shipped["left_out"] if not lo["reason"].startswith("verify failed")]
    assert all(lo in json.loads((tmp_path / "catalog.json").read_text())["left_out"] for lo in assessed)


def test_shipped_catalog_names_no_absolute_path():
    """Entries name maps relative to the sources folder: a builder's own paths (its sources
    or output folder) must not leak into the shipped catalog (they did into left_out reasons)."""
    from roboracer_arena.foundation.paths import tracks_dir

    text = (tracks_dir() / "catalog.json").read_text()
    leaks = re.findall(r"(?<![\w:/.])/(?:[\w.+-]+/)+[\w.+-]+\.(?:yaml|pgm|png|json|csv)", text)
    assert leaks == []

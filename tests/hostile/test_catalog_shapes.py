"""Issue 38, class C for catalogs: a catalog of the wrong shape (``tracks`` a number, a
top-level list, ``open_maps`` a number, entries that are not objects, nesting thousands
deep) is one line and exit 2 naming the file and the field, never a TypeError or an
AttributeError; a seeded fuzz of 3000 mutated catalogs (structure and text) sees nothing
but the typed error."""

from __future__ import annotations

import copy
import json
import random
import time
from pathlib import Path

import pytest

from roboracer_arena.catalog import load_catalog
from roboracer_arena.cli import main
from roboracer_arena.errors import ArenaError, InternalError, MapIOError
from roboracer_arena.foundation.paths import PACKAGE_DIR

SHIPPED = json.loads((PACKAGE_DIR / "tracks" / "catalog.json").read_text(encoding="utf-8"))


def _small() -> dict:
    doc = copy.deepcopy(SHIPPED)
    doc["tracks"] = doc["tracks"][:3]
    doc["left_out"] = doc["left_out"][:3]
    doc["open_maps"] = doc["open_maps"][:3]
    return doc


SHAPES = {
    "tracks a number": ({**_small(), "tracks": 5}, "tracks"),
    "top-level list": ([_small()], "must be a JSON object, not an array"),
    "top-level number": (7, "must be a JSON object, not a number"),
    "open_maps a number": ({**_small(), "open_maps": 3}, "open_maps"),
    "left_out a string": ({**_small(), "left_out": "x"}, "left_out"),
    "an entry a list": ({**_small(), "tracks": [[1, 2]]}, "tracks.0"),
    "an entry a number": ({**_small(), "open_maps": [1]}, "open_maps.0"),
    "counts a list": ({**_small(), "counts": [1]}, "counts"),
    "lap a string": (
        {**_small(), "tracks": [{**SHIPPED["tracks"][0], "lap_length_m": "40"}]},
        "lap_length_m: must be a number",
    ),
    "deep nesting": ({**_small(), "x": json.loads("[" * 500 + "]" * 500)}, "nested too deeply"),
}


@pytest.mark.parametrize("case", sorted(SHAPES))
def test_a_catalog_of_the_wrong_shape_is_one_line_exit_2(tmp_path, capsys, case):
    doc, words = SHAPES[case]
    path = tmp_path / "catalog.json"
    path.write_text(json.dumps(doc))
    with pytest.raises(MapIOError) as e:
        load_catalog(path)
    assert "catalog.json" in str(e.value) and words in str(e.value), e.value
    for argv in (["tracks", "list"], ["tracks", "verify", "--no-usd", "--no-drive"], ["tracks", "show", "x"]):
        assert main([*argv, "--catalog", str(path)]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "catalog.json" in err and "Traceback" not in err, err


def _hostile(rng: random.Random):
    return rng.choice(
        [
            None,
            True,
            0,
            -1,
            2**70,
            1e308,
            "",
            "x" * 300,
            "../../etc/passwd",
            [],
            {},
            [1, "a"],
            {"id": "z"},
            "9" * 50,
            json.loads("[" * 80 + "]" * 80),
        ]
    )


def _mutate(node, rng: random.Random, depth: int = 0):
    """A copy of ``node`` with one random place (deeper with some chance) replaced,
    dropped, or duplicated."""
    if isinstance(node, dict) and node and (depth < 4 and rng.random() < 0.7):
        node = dict(node)
        key = rng.choice(list(node))
        op = rng.random()
        if op < 0.6:
            node[key] = _mutate(node[key], rng, depth + 1)
        elif op < 0.8:
            del node[key]
        else:
            node[rng.choice([key + "_x", "schema", "count", "sweep"])] = _hostile(rng)
        return node
    if isinstance(node, list) and node and (depth < 4 and rng.random() < 0.7):
        node = list(node)
        k = rng.randrange(len(node))
        op = rng.random()
        if op < 0.7:
            node[k] = _mutate(node[k], rng, depth + 1)
        elif op < 0.85:
            del node[k]
        else:
            node.append(copy.deepcopy(node[k]))
        return node
    return _hostile(rng)


def test_fuzz_catalogs_see_only_the_typed_error(tmp_path):
    """3000 seeded mutations of a small real catalog: 2000 structural (a value anywhere
    replaced by a hostile one, a key or item dropped, an item duplicated), 1000 textual
    (bytes cut, flipped or inserted in the JSON text). Each load gives a catalog or a
    one-line MapIOError, in well under a second per case."""
    rng = random.Random(38)
    base = _small()
    text = json.dumps(base, indent=1)
    path = tmp_path / "catalog.json"
    outcomes = {"ok": 0, "typed": 0}
    t0 = time.perf_counter()
    for k in range(3000):
        if k < 2000:
            doc = base
            for _ in range(rng.randint(1, 3)):
                doc = _mutate(doc, rng)
            path.write_text(json.dumps(doc))
        else:
            data = bytearray(text.encode())
            for _ in range(rng.randint(1, 4)):
                i = rng.randrange(len(data))
                op = rng.random()
                if op < 0.3:
                    del data[i : i + rng.randint(1, 50)]
                elif op < 0.6:
                    data[i] = rng.randrange(256)
                else:
                    data[i:i] = rng.choice([b"[", b"{", b"9" * 5000, b'"', b"\xff", b",", b"null"])
            path.write_bytes(bytes(data))
        try:
            load_catalog(path)
            outcomes["ok"] += 1
        except InternalError as e:  # pragma: no cover - what this test exists to catch
            pytest.fail(f"case {k}: internal error {e}")
        except ArenaError as e:
            assert "\n" not in str(e) and "catalog.json" in str(e) and len(str(e)) < 2000, str(e)[:300]
            outcomes["typed"] += 1
    assert outcomes["typed"] > 2000, outcomes
    assert time.perf_counter() - t0 < 60, outcomes


def test_a_5000_digit_integer_and_a_bom_in_a_catalog(tmp_path: Path):
    path = tmp_path / "catalog.json"
    path.write_text('{"tracks": [], "count": ' + "9" * 5000 + "}")
    with pytest.raises(MapIOError, match="catalog.json.*digit"):
        load_catalog(path)

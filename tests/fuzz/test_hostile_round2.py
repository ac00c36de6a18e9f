"""Round 2 (issue 25): hostile sweep files, catalog files and env arguments (kwargs,
reset options, actions), drawn by hypothesis (derandomized) and run in the capped worker
of ``harness.py`` like round 1's suites: every case succeeds or is refused with a typed
one-line error (exit 2; 4 for a sweep whose budget runs out), never a traceback."""

from __future__ import annotations

import base64
import json

from hypothesis import strategies as st

from roboracer_arena.catalog.catalog_file import default_tracks_dir

from .harness import check_all
from .test_hostile import JSON_HOSTILE, draw_cases, numbered

SPEC_FIELDS = ["lap_length_m", "corridor_width_m", "hall_x_m", "hall_y_m", "hairpins", "chicanes", "sweepers"]
TEXT_HOSTILE = st.sampled_from(
    ["", "a\nb", "\x1b[31mred", "../up", "/abs", "a" * 300, "ok-id", "sp ace", "é", "\x00", "x" * 121]
)
BIG_INT = st.sampled_from([2**64, -(2**63), 10**30]).map(str)

# -- sweep files -----------------------------------------------------------------------


@st.composite
def hostile_sweep(draw) -> dict:
    fields = draw(st.lists(st.sampled_from(SPEC_FIELDS + ["direction", "feature_order", "bogus"]), max_size=4))
    ranges = {
        f: draw(
            st.one_of(
                st.tuples(JSON_HOSTILE, JSON_HOSTILE).map(list),
                st.just({"choice": draw(st.lists(JSON_HOSTILE, max_size=3))}),
                JSON_HOSTILE,
            )
        )
        for f in fields
    }
    doc = {
        "name": draw(st.one_of(st.just("fz"), TEXT_HOSTILE)),
        "base_seed": draw(st.one_of(st.just(0), JSON_HOSTILE)),
        "decimals": draw(st.one_of(st.just(1), JSON_HOSTILE)),
        "ranges": ranges,
        "fixed": draw(st.dictionaries(st.sampled_from(SPEC_FIELDS), JSON_HOSTILE, max_size=2)),
    }
    text = json.dumps(doc, allow_nan=True)
    if draw(st.booleans()):  # a huge integer literal somewhere (JSON has no digit limit)
        text = text.replace(
            '"base_seed": ', '"base_seed": ' + "9" * draw(st.sampled_from([20, 4301, 5000])) + ', "x": ', 1
        )
    return {
        "files": {"s.json": {"text": text}},
        "argv": [
            "tracks",
            "generate",
            "--sweep",
            "s.json",
            "--count",
            "1",
            "-o",
            "out",
            "--max-requests",
            "1",
            "--jobs",
            "1",
        ],
        "codes": [0, 2, 4],
        "one_line": True,
    }


def test_hostile_sweep_files():
    check_all(numbered("sweep", draw_cases(hostile_sweep(), 40)), timeout_s=240)


# -- catalog files ---------------------------------------------------------------------


def _base_catalog() -> tuple[dict, dict]:
    """One shipped generated track: the catalog document and its files (worker format)."""
    tracks = default_tracks_dir()
    doc = json.loads((tracks / "catalog.json").read_text())
    e = next(t for t in doc["tracks"] if t["kind"] == "generated")
    folder = tracks / e["map"].rsplit("/", 1)[0]
    files = {
        f"{e['map'].rsplit('/', 1)[0]}/{p.name}": {"b64": base64.b64encode(p.read_bytes()).decode()}
        for p in folder.iterdir()
        if p.is_file()
    }
    doc.update(tracks=[e], left_out=[], count=1)
    return doc, files


ENTRY_FIELDS = [
    "id",
    "sha256",
    "lap_length_m",
    "resolution_m",
    "width_mean_m",
    "width_min_m",
    "min_radius_m",
    "scale",
    "map",
    "centreline",
    "raster",
    "start",
    "direction",
    "kind",
]


@st.composite
def hostile_catalog(draw, doc: dict, files: dict) -> dict:
    d = json.loads(json.dumps(doc))
    e = d["tracks"][0]
    for f in draw(st.lists(st.sampled_from(ENTRY_FIELDS), min_size=1, max_size=3, unique=True)):
        if f == "raster":
            e["raster"] = {"width_px": draw(JSON_HOSTILE), "height_px": e["raster"]["height_px"]}
        else:
            e[f] = draw(st.one_of(JSON_HOSTILE, TEXT_HOSTILE))
    command = draw(st.sampled_from(["list", "show", "verify"]))
    argv = ["tracks", command, "--catalog", "c.json"]
    if command == "show":
        argv.insert(2, str(e.get("id")) if isinstance(e.get("id"), str) and e.get("id") else "x")
    if command == "verify":
        argv += ["--no-usd", "--no-drive", "--jobs", "1"]
    return {
        "files": {**files, "c.json": {"text": json.dumps(d, allow_nan=True)}},
        "argv": argv,
        "codes": [0, 2],
        "one_line": command != "verify",  # verify prints its table before the verdict
    }


def test_hostile_catalog_files():
    doc, files = _base_catalog()
    check_all(numbered("catalog", draw_cases(hostile_catalog(doc, files), 40)), timeout_s=240)


# -- env kwargs, reset options, actions ------------------------------------------------

ACTION = st.one_of(
    st.lists(st.one_of(JSON_HOSTILE, st.none(), st.text(max_size=2)), max_size=4),
    JSON_HOSTILE,
    st.none(),
)
KWARG = st.sampled_from(
    [
        ("num_envs", None),
        ("vehicles_per_env", st.one_of(st.integers(-2, 70), JSON_HOSTILE)),
        ("control_rate_hz", JSON_HOSTILE),
        ("time_limit_s", JSON_HOSTILE),
        ("observation", st.fixed_dictionaries({"frame_stack": st.one_of(st.integers(-1, 100), JSON_HOSTILE)})),
        ("sim", st.fixed_dictionaries({"physics": st.fixed_dictionaries({"dt": JSON_HOSTILE})})),
        ("sim", st.fixed_dictionaries({"lidar": st.fixed_dictionaries({"num_beams": JSON_HOSTILE})})),
        ("reset_poses", st.one_of(TEXT_HOSTILE, JSON_HOSTILE)),
        ("action_mode", st.one_of(TEXT_HOSTILE, st.just("normalised"))),
        ("bogus", JSON_HOSTILE),
    ]
)
OPTIONS = st.one_of(
    st.none(),
    st.dictionaries(
        st.sampled_from(["track_id", "track_ids", "poses", "speeds", "reset_mask"]),
        st.one_of(JSON_HOSTILE, TEXT_HOSTILE, st.lists(st.one_of(st.booleans(), JSON_HOSTILE), max_size=3)),
        max_size=2,
    ),
)


@st.composite
def hostile_env(draw) -> dict:
    kwargs = {}
    for name, values in draw(st.lists(KWARG, max_size=2)):
        if name != "num_envs":
            kwargs[name] = draw(values)
    vector = draw(st.sampled_from([0, 0, 2, 3]))
    if vector and draw(st.booleans()):
        vector = draw(st.sampled_from([10**6, 50_000]))  # over the size budget
    args = {"kwargs": kwargs, "options": draw(OPTIONS), "actions": draw(st.lists(ACTION, max_size=3)), "vector": vector}
    return {"api": "env", "args": json.loads(json.dumps(args, default=str, allow_nan=True)), "codes": [0, 2]}


def test_hostile_env_arguments():
    check_all(numbered("env", draw_cases(hostile_env(), 60)), timeout_s=240)

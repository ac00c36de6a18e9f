"""Hostile maps (YAML fields, image headers, image bytes), specs, build configs and CLI
numbers drawn by hypothesis (derandomized: the same cases on every run), each batch run
in one worker process under a memory cap and a time limit (see ``harness.py``)."""

from __future__ import annotations

import io
import json

from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st
from PIL import Image

from builder.ringmap import ring_raster

from .cases import b64, build_case, map_yaml, pgm_declaring, png_declaring, ring_map, ring_png, text
from .corpus import SPEC_OK
from .harness import check_all

# -- value palettes -------------------------------------------------------------------

YAML_SCALARS = st.sampled_from(
    [
        ".nan",
        ".inf",
        "-.inf",
        "1e300",
        "-1e300",
        "1e-300",
        "1e6",
        "1000",
        "0",
        "-0.05",
        "0.05",
        "0.1",
        "1",
        "true",
        "null",
        "[]",
        "{}",
        "''",
        "abc",
        "0x10",
        "5e-324",
        "1.0e+308",
    ]
)
JSON_HOSTILE = st.one_of(
    st.floats(0, 3),
    st.integers(0, 30),  # plausible values too, so some runs go all the way
    st.booleans(),
    st.none(),
    st.text(max_size=8),
    st.just(float("nan")),
    st.just(float("inf")),
    st.sampled_from([1e308, -1e308, 1e-300, -5, 0, 2**70, -(2**70), 1e12]),
    st.lists(st.integers(), max_size=3),
    st.dictionaries(st.text(max_size=3), st.integers(), max_size=2),
    st.floats(allow_nan=True, allow_infinity=True),
)
NUM_TEXT = st.one_of(
    st.sampled_from(["nan", "inf", "-inf", "0", "-1", "1e308", "1e-308", str(2**64), str(-(2**63)), "1e400"]),
    st.floats(allow_nan=True, allow_infinity=True).map(repr),
    st.integers(min_value=-(2**70), max_value=2**70).map(str),
)


def draw_cases(strategy: st.SearchStrategy, n: int) -> list:
    """``n`` deterministic examples of ``strategy`` (derandomized, no database, no shrinking:
    a failing case is reported whole by the worker)."""
    out: list = []

    @settings(
        max_examples=n,
        derandomize=True,
        database=None,
        deadline=None,
        phases=[Phase.generate],
        suppress_health_check=list(HealthCheck),
    )
    @given(strategy)
    def collect(case):
        out.append(case)

    collect()
    return out[:n]


def numbered(prefix: str, cases: list[dict]) -> list[dict]:
    return [{**c, "id": f"{prefix}-{i}"} for i, c in enumerate(cases)]


# -- strategies -----------------------------------------------------------------------


@st.composite
def hostile_map(draw) -> dict:
    """A build of a map whose YAML fields, image header or image bytes are hostile."""
    kind = draw(st.sampled_from(["yaml", "pgm", "png", "bytes"]))
    if kind == "yaml":  # hostile fields over a valid image
        origin = draw(
            st.one_of(
                st.lists(YAML_SCALARS, min_size=0, max_size=5).map(lambda xs: "[" + ", ".join(xs) + "]"), YAML_SCALARS
            )
        )
        resolution = draw(st.one_of(YAML_SCALARS, st.floats(0.0005, 2.0).map(repr)))
        return build_case(
            "", {"ring.png": b64(ring_png()), "ring.yaml": text(map_yaml("ring.png", resolution, origin))}
        )
    if kind == "pgm":
        size = st.one_of(st.integers(0, 2**64 + 5), st.integers(0, 300))
        img = pgm_declaring(
            draw(size),
            draw(size),
            draw(st.sampled_from([0, 1, 255, 256, 65535, 65536, 2**40])),
            ascii=draw(st.booleans()),
        )
    elif kind == "png":
        size = st.one_of(st.integers(0, 2**32 - 1), st.integers(0, 300))
        img = png_declaring(draw(size), draw(size))
    else:
        img = draw(st.sampled_from([b"\x89PNG\r\n\x1a\n", b"P5 ", b"P2\n", b""])) + draw(st.binary(max_size=64))
    return build_case("", {"img": b64(img), "ring.yaml": text(map_yaml("img"))})  # valid fields, hostile image


@st.composite
def random_raster(draw) -> dict:
    """A build of a small random map: blobs, noise and rings of free, occupied and unknown
    cells at a valid resolution (real corridors sometimes, degenerate ones mostly)."""
    import numpy as np

    h, w = draw(st.integers(1, 48)), draw(st.integers(1, 48))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    img = rng.choice(np.array([0, 254, 205, 128], np.uint8), size=(h, w), p=[0.3, 0.55, 0.1, 0.05])
    if draw(st.booleans()):  # a ring corridor under the noise
        img = np.where(rng.random((h, w)) < 0.9, ring_raster(max(h, w))[:h, :w], img).astype(np.uint8)
    buf = io.BytesIO()
    Image.fromarray(img, mode="L").save(buf, format="PNG")
    start = draw(
        st.none() | st.tuples(st.floats(-5.1, -2.5), st.floats(-5.1, -2.5)).map(lambda p: f"--start={p[0]},{p[1]}")
    )
    return build_case("", {"ring.png": b64(buf.getvalue()), "ring.yaml": text(map_yaml())}, *([start] if start else []))


@st.composite
def hostile_spec(draw) -> dict:
    """``validate`` of a valid ring map against a spec with 1–3 hostile fields."""
    spec = dict(SPEC_OK)
    fields = [
        "lap_length_m",
        "corridor_width_m",
        "hall_x_m",
        "hall_y_m",
        "hairpins",
        "chicanes",
        "sweepers",
        "min_radius_m",
        "longest_straight_m",
        "name",
        "direction",
        "feature_order",
        "extra_key",
    ]
    for k in draw(st.lists(st.sampled_from(fields), min_size=1, max_size=3, unique=True)):
        spec[k] = draw(JSON_HOSTILE)
    return {
        "files": {**ring_map(), "spec.json": text(json.dumps(spec))},
        "argv": ["validate", "ring.yaml", "--spec", "spec.json"],
    }


@st.composite
def hostile_config(draw) -> dict:
    """A build with a config whose geometry/materials/physics fields are hostile."""
    fields = {
        "geometry": [
            "wall_height_m",
            "wall_offset_m",
            "tube_diameter_m",
            "tube_segments",
            "ring_spacing_m",
            "ring_width_m",
            "ring_scale",
            "simplify_tolerance_m",
            "smoothing_iterations",
            "centreline_spacing_m",
            "floor_margin_m",
        ],
        "physics": ["static_friction", "gravity"],
        "materials": ["texture_size_px"],
    }
    group = draw(st.sampled_from(sorted(fields)))
    cfg = {group: {draw(st.sampled_from(fields[group])): draw(JSON_HOSTILE)}}
    return build_case("", {**ring_map(), "c.json": text(json.dumps(cfg))}, "--config", "c.json")


def _plausible(s: str) -> bool:
    try:
        v = float(s)
    except ValueError:
        return False
    return 0 <= v <= 1e4


@st.composite
def hostile_flags(draw) -> dict:
    """A CLI call with at least one hostile number (so nothing long runs)."""
    cmd = draw(st.sampled_from(["drive", "preview", "generate", "circuits"]))
    bad = draw(NUM_TEXT)
    if cmd in ("drive", "generate") and _plausible(bad):
        bad = "nan"  # a plausible value would really drive or generate: not this suite's job
    if cmd == "drive":
        flag = draw(st.sampled_from(["--fps", "--max-time", "--laps", "--max-speed"]))
        argv = ["drive", "ring.yaml", flag, bad]
        codes = [0, 2, 3, 4, 5]
    elif cmd == "preview":
        argv = ["preview", "ring.yaml", "-o", "p.png", "--max-px", bad]
        codes = [0, 2]
    elif cmd == "generate":
        argv = ["generate", "--spec", "spec.json", "--seed", bad, "-o", "gen"]
        codes = [0, 2, 3, 4]
    else:
        argv = ["circuits", "--resolution", bad, "--jobs", "1", "--only", "none", "-o", "c"]
        codes = [0, 2]
    return {"files": {**ring_map(), "spec.json": text(json.dumps(SPEC_OK))}, "argv": argv, "codes": codes}


# -- tests ----------------------------------------------------------------------------


def test_hostile_maps():
    check_all(numbered("map", draw_cases(hostile_map(), 60)))


def test_random_rasters():
    check_all(numbered("raster", draw_cases(random_raster(), 80)))


def test_hostile_specs():
    check_all(numbered("spec", draw_cases(hostile_spec(), 40)))


def test_hostile_configs():
    check_all(numbered("config", draw_cases(hostile_config(), 40)))


def test_hostile_cli_numbers():
    check_all(numbered("flags", draw_cases(hostile_flags(), 60)))


def test_hostile_parse_requests():
    reqs = ["a 6e1 m lap", "a -5 m lap", "a 1e308 m lap", "lap " * 5_000, "a nan m lap", "\x00\xff lap"]
    check_all([{"id": f"parse-{i}", "argv": ["parse", r], "codes": [0, 2]} for i, r in enumerate(reqs)], timeout_s=30)

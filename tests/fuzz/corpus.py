"""Regression corpus: every concrete hostile input of issue 10 that the map builder, the
CLI's inputs/outputs and the core's door own, as worker cases (see ``worker.py``).
Generation and parsing cases live with the fuzz tests, marked for their owners."""

from __future__ import annotations

import json

from .cases import b64, build_case, map_yaml, pgm_declaring, png_declaring, ring_map, ring_png, text

NAN_USDA = """#usda 1.0
def Xform "World" {
    def Xform "Track" {
        def Mesh "Walls" {
            point3f[] points = [(nan, 0, 0), (1, 0, 0), (0, 1, 0)]
            int[] faceVertexCounts = [3]
            int[] faceVertexIndices = [0, 1, 2]
        }
    }
}
"""
BAD_INDEX_USDA = NAN_USDA.replace("(nan, 0, 0)", "(0, 0, 0)").replace("[0, 1, 2]", "[0, 1, 7]")
SPEC_OK = {"lap_length_m": 40.0, "hall_x_m": 16.0, "hall_y_m": 12.0}


def _spec_case(cid: str, spec_file: dict, **kw) -> dict:
    return {
        "id": cid,
        "files": {"spec.json": spec_file},
        "argv": ["generate", "--spec", "spec.json", "-o", "gen"],
        "target": "gen",
        "codes": [2],
        **kw,
    }


def _cfg(geometry: dict) -> dict:
    return text(json.dumps({"geometry": geometry}))


CORPUS: list[dict] = [
    # allocation bombs: refused from the header, before decoding
    build_case(
        "p2-150000-squared",
        {"ring.yaml": text(map_yaml("b.pgm")), "b.pgm": b64(pgm_declaring(150000, 150000))},
        codes=[2],
        says=["pixel budget"],
        one_line=True,
    ),
    build_case(
        "p5-16bit-overflowing-header",
        {"ring.yaml": text(map_yaml("b.pgm")), "b.pgm": b64(pgm_declaring(2**62, 2**62, 65535, ascii=False))},
        codes=[2],
    ),
    build_case(
        "png-2^31-1-squared",
        {"ring.yaml": text(map_yaml("b.png")), "b.png": b64(png_declaring(2**31 - 1, 2**31 - 1))},
        codes=[2],
        one_line=True,
    ),
    # the pixel budget is configurable: a 120² map is over a 10 kP budget, and a bad budget is named
    build_case(
        "pixel-budget-env",
        ring_map(),
        codes=[2],
        env={"ROBORACER_ARENA_MAX_PIXELS": "10000"},
        says=["ROBORACER_ARENA_MAX_PIXELS"],
        one_line=True,
    ),
    build_case(
        "pixel-budget-env-garbage",
        ring_map(),
        codes=[2],
        env={"ROBORACER_ARENA_MAX_PIXELS": "lots"},
        says=["ROBORACER_ARENA_MAX_PIXELS"],
        one_line=True,
    ),
    build_case("pixel-budget-env-raised", ring_map(), codes=[0], env={"ROBORACER_ARENA_MAX_PIXELS": "20000"}),
    # implausible resolutions and origins: refused with the allowed range
    *(
        build_case(f"resolution-{r}", ring_map(resolution=r), codes=[2], says=["resolution"], one_line=True)
        for r in ("1e6", "1e300", "1e-300", "1000", ".nan", "-0.05")
    ),
    build_case("origin-1e300", ring_map(origin="[1e300, -1e300, 0]"), codes=[2], says=["origin"], one_line=True),
    build_case("origin-4-elements", ring_map(origin="[1, 2, 3, 4]"), codes=[2], says=["origin"], one_line=True),
    # build configs whose counts would explode, or whose offset leaves no walls
    build_case(
        "centreline-spacing-1e-7",
        {**ring_map(), "c.json": _cfg({"centreline_spacing_m": 1e-7})},
        "--config",
        "c.json",
        codes=[2],
        says=["centreline_spacing_m"],
    ),
    build_case(
        "ring-spacing-1e-7",
        {**ring_map(), "c.json": _cfg({"ring_spacing_m": 1e-7})},
        "--config",
        "c.json",
        codes=[2],
        says=["ring_spacing_m"],
    ),
    build_case(
        "wall-offset--5", {**ring_map(), "c.json": _cfg({"wall_offset_m": -5})}, "--config", "c.json", codes=[2]
    ),
    build_case(
        "config-utf16",
        {**ring_map(), "c.json": text('{"geometry": {}}', "utf-16")},
        "--config",
        "c.json",
        codes=[2],
        says=["UTF-8"],
        one_line=True,
    ),
    build_case(
        "config-deep-json",
        {**ring_map(), "c.json": text("[" * 100000 + "]" * 100000)},
        "--config",
        "c.json",
        codes=[2],
        one_line=True,
    ),
    build_case(
        "config-bool-number", {**ring_map(), "c.json": _cfg({"wall_height_m": True})}, "--config", "c.json", codes=[2]
    ),
    # inputs must be regular files
    {
        "id": "map-is-fifo",
        "files": {"m.yaml": {"fifo": True}},
        "argv": ["build", "m.yaml", "-o", "o.usdc"],
        "codes": [2],
        "says": ["FIFO"],
        "target": "o.usdc",
    },
    {
        "id": "image-is-dev-zero",
        "files": {"m.yaml": text(map_yaml("/dev/zero"))},
        "argv": ["build", "m.yaml", "-o", "o.usdc"],
        "codes": [2],
        "says": ["device"],
        "target": "o.usdc",
    },
    {
        "id": "image-is-fifo",
        "files": {"m.yaml": text(map_yaml("p.png")), "p.png": {"fifo": True}},
        "argv": ["build", "m.yaml", "-o", "o.usdc"],
        "codes": [2],
        "says": ["FIFO"],
        "target": "o.usdc",
    },
    {
        "id": "map-is-directory",
        "files": {"m.yaml": {"dir": True}},
        "argv": ["build", "m.yaml", "-o", "o.usdc"],
        "codes": [2],
        "says": ["directory"],
    },
    {
        "id": "map-is-symlink-loop",
        "files": {"m.yaml": {"symlink": "m.yaml"}},
        "argv": ["build", "m.yaml", "-o", "o.usdc"],
        "codes": [2],
        "says": ["symlink loop"],
    },
    {"id": "load-map-dev-zero", "api": "load_map", "args": {"path": "/dev/zero"}, "codes": [2], "says": ["device"]},
    # outputs
    {
        "id": "out-is-directory",
        "files": {**ring_map(), "d.usdc": {"dir": True}},
        "argv": ["build", "ring.yaml", "-o", "d.usdc"],
        "codes": [2],
        "says": ["directory"],
        "one_line": True,
    },
    {
        "id": "out-255-byte-name",
        "files": ring_map(),
        "argv": ["build", "ring.yaml", "-o", "x" * 250 + ".usdc"],
        "codes": [0],
    },
    {
        "id": "out-256-byte-name",
        "files": ring_map(),
        "argv": ["build", "ring.yaml", "-o", "x" * 251 + ".usdc"],
        "codes": [2],
        "one_line": True,
    },
    {
        "id": "preview-overwrites-its-yaml",
        "files": ring_map(),
        "argv": ["preview", "ring.yaml", "-o", "ring.yaml"],
        "codes": [2],
        "says": ["would overwrite the input"],
    },  # refused by the CLI's output guard, before any work
    {
        "id": "preview-overwrites-its-image",
        "files": ring_map(),
        "argv": ["preview", "ring.yaml", "-o", "ring.png"],
        "codes": [2],
        "says": ["overwrite"],
    },
    {
        "id": "build-overwrites-its-image",
        "files": ring_map(),
        "argv": ["build", "ring.yaml", "--usda", "-o", "ring.png"],
        "codes": [2],
    },
    {
        "id": "generate-out-is-a-file",
        "files": {"spec.json": text(json.dumps(SPEC_OK)), "f": text("x")},
        "argv": ["generate", "--spec", "spec.json", "-o", "f"],
        "codes": [2],
        "says": ["not a directory"],
    },
    {
        "id": "preview-usd-nan-points",
        "files": {"s.usda": text(NAN_USDA)},
        "argv": ["preview", "s.usda", "-o", "p.png"],
        "codes": [2],
        "target": "p.png",
    },
    {
        "id": "preview-usd-bad-indices",
        "files": {"s.usda": text(BAD_INDEX_USDA)},
        "argv": ["preview", "s.usda", "-o", "p.png"],
        "codes": [2],
        "target": "p.png",
    },
    {
        "id": "drive-gif-is-directory",
        "files": {**ring_map(), "g.gif": {"dir": True}},
        "argv": ["drive", "ring.yaml", "--gif", "g.gif"],
        "codes": [2],
        "says": ["directory"],
        "one_line": True,
    },
    {
        "id": "drive-gif-overwrites-map",
        "files": ring_map(),
        "argv": ["drive", "ring.yaml", "--gif", "ring.yaml"],
        "codes": [2],
        "says": ["overwrite"],
    },
    # CLI numbers
    {
        "id": "drive-max-time-nan",
        "files": ring_map(),
        "argv": ["drive", "ring.yaml", "--max-time", "nan"],
        "codes": [2],
        "says": ["--max-time"],
    },
    {
        "id": "drive-fps-0",
        "files": ring_map(),
        "argv": ["drive", "ring.yaml", "--fps", "0"],
        "codes": [2],
        "says": ["--fps"],
    },
    {
        "id": "generate-seed-2^64",
        "files": {"spec.json": text(json.dumps(SPEC_OK))},
        "argv": ["generate", "--spec", "spec.json", "--seed", str(2**64)],
        "codes": [2],
        "says": ["--seed"],
    },
    # spec files
    _spec_case("spec-lap-length-true", text(json.dumps({"lap_length_m": True})), says=["lap_length_m"]),
    _spec_case("spec-utf16", text(json.dumps(SPEC_OK), "utf-16"), says=["UTF-8"], one_line=True),
    _spec_case("spec-not-utf8", b64(b'{"name": "\xff\xfe\xfa"}'), says=["UTF-8"], one_line=True),
    _spec_case("spec-deep-json", text("[" * 100000 + "]" * 100000), one_line=True),
    _spec_case("spec-is-fifo", {"fifo": True}, says=["FIFO"]),
    # the core's door (Python API)
    {"id": "analyse-curve-repeated", "api": "analyse_curve", "args": {"points": [[0, 0]] * 5}, "codes": [2]},
    {
        "id": "analyse-curve-nan",
        "api": "analyse_curve",
        "args": {"points": [[0, 0], [1, 0], [float("nan"), 1]]},
        "codes": [2],
    },
    # the polyline toolbox: budgets and hostile coordinates
    {
        "id": "resample-spacing-1e-300",
        "api": "polyline",
        "args": {"fn": "resample_closed", "points": [[0, 0], [1, 0], [0, 1]], "args": [1e-300]},
        "codes": [2],
        "says": ["spacing"],
    },
    {
        "id": "self-intersections-1e300",
        "api": "polyline",
        "args": {"fn": "self_intersections", "points": [[-1e300, 0], [1e300, 1], [1e300, -1e300], [0, 1e300]]},
        "codes": [0],
    },
    {
        "id": "self-intersections-all-on-one-point",
        "api": "polyline",
        "args": {"fn": "self_intersections", "points": [[1, 1]] * 1000},
        "codes": [0],
    },
    {
        "id": "min-radius-span-nan",
        "api": "polyline",
        "args": {"fn": "min_radius", "points": [[0, 0], [1, 0], [0, 1]], "args": [float("nan")]},
        "codes": [2],
        "says": ["span_m"],
    },
    {
        "id": "distance-transform-huge",
        "api": "distance_transform",
        "args": {"h": 100000, "w": 100000},
        "codes": [2],
        "says": ["pixel budget"],
    },
    {
        "id": "extract-corridor-wall-offset--5",
        "files": ring_map(),
        "api": "extract_corridor",
        "args": {"map_yaml": "ring.yaml", "params": {"wall_offset_m": -5}},
        "codes": [2],
        "says": ["wall_offset_m"],
    },
    {
        "id": "measure-map-resolution-1e-300",
        "api": "measure_map",
        "args": {"resolution": 1e-300, "origin": [0, 0, 0]},
        "codes": [2],
    },
    {
        "id": "measure-map-origin-1e300",
        "api": "measure_map",
        "args": {"resolution": 0.05, "origin": [1e300, 0, 0]},
        "codes": [2],
    },
    # a corridor error names the map file
    {
        "id": "corridor-error-names-file",
        "files": {"m.yaml": text(map_yaml("m.png")), "m.png": b64(ring_png())},
        "argv": ["build", "m.yaml", "-o", "o.usdc", "--start=0,0"],
        "codes": [2],
        "says": ["m.yaml"],
    },
]

"""ROS map reading (nav2 rules, every format) and writing, on maps written here and on
a few shared public maps."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from roboracer_arena.errors import InvalidArgumentError, MapFormatError, MapIOError
from roboracer_arena.maps.occupancy import FREE, OCCUPIED, UNKNOWN, OccupancyMap, load_map, save_map

# white, black, mid-grey 205, dark grey 60 in a 2 x 2 image
GREYS = np.array([[255, 0], [205, 60]], dtype=np.uint8)
TRINARY = np.array([[FREE, OCCUPIED], [UNKNOWN, OCCUPIED]], dtype=np.uint8)


def write_yaml(path: Path, image: str, extra: str = "") -> Path:
    path.write_text(f"image: {image}\nresolution: 0.1\norigin: [1.0, -2.0, 0.5]\n{extra}")
    return path


@pytest.mark.parametrize(
    "mode",
    ["L", "RGB", "I;16"],
)
def test_png_layouts_without_alpha(tmp_path: Path, mode: str) -> None:
    if mode == "RGB":
        img = Image.fromarray(np.stack([GREYS] * 3, axis=-1), "RGB")
    elif mode == "I;16":
        img = Image.fromarray(GREYS.astype(np.uint16) * 257).convert("I;16")
    else:
        img = Image.fromarray(GREYS, "L")
    img.save(tmp_path / "m.png")
    m = load_map(write_yaml(tmp_path / "m.yaml", "m.png"))
    np.testing.assert_array_equal(m.data, TRINARY)
    assert (m.resolution, m.origin) == (0.1, (1.0, -2.0, 0.5))
    assert m.meta.image_format == "png"
    assert m.meta.image_bit_depth == (16 if mode == "I;16" else 8)


@pytest.mark.parametrize("mode", ["LA", "RGBA"])
def test_alpha_is_averaged_in_trinary_and_marks_unknown_in_scale(tmp_path: Path, mode: str) -> None:
    alpha = np.array([[255, 0], [255, 255]], dtype=np.uint8)
    chans = [GREYS] * (1 if mode == "LA" else 3) + [alpha]
    Image.fromarray(np.stack(chans, axis=-1), mode).save(tmp_path / "a.png")
    tri = load_map(write_yaml(tmp_path / "t.yaml", "a.png")).data
    # nav2: shade = mean(R, G, B, A): black+transparent → 0 → occupied; 205 opaque → free
    np.testing.assert_array_equal(tri, [[FREE, OCCUPIED], [FREE, UNKNOWN]])
    scale = load_map(write_yaml(tmp_path / "s.yaml", "a.png", "mode: scale\n")).data
    np.testing.assert_array_equal(scale, [[FREE, UNKNOWN], [UNKNOWN, OCCUPIED]])


def test_pgm_ascii_and_16_bit_binary(tmp_path: Path) -> None:
    (tmp_path / "a.pgm").write_bytes(b"P2\n# comment\n2 2\n255\n255 0\n205 60\n")
    body = b"".join((int(v) * 257).to_bytes(2, "big") for v in GREYS.ravel())
    (tmp_path / "b.pgm").write_bytes(b"P5\n2 2\n65535\n" + body)
    for name in ("a.pgm", "b.pgm"):
        m = load_map(write_yaml(tmp_path / f"{name}.yaml", name))
        np.testing.assert_array_equal(m.data, TRINARY)
        assert m.meta.image_format == "pgm"
        assert set(m.meta.defaulted) == {"mode", "negate", "occupied_thresh", "free_thresh"}


def test_negate_thresholds_and_raw(tmp_path: Path) -> None:
    Image.fromarray(GREYS, "L").save(tmp_path / "g.png")
    neg = load_map(write_yaml(tmp_path / "n.yaml", "g.png", "negate: 1\n")).data
    np.testing.assert_array_equal(neg, [[OCCUPIED, FREE], [OCCUPIED, UNKNOWN]])
    loose = load_map(write_yaml(tmp_path / "l.yaml", "g.png", "occupied_thresh: 0.9\nfree_thresh: 0.3\n")).data
    np.testing.assert_array_equal(loose, [[FREE, OCCUPIED], [FREE, UNKNOWN]])
    Image.fromarray(np.array([[0, 100, 50, 200]], np.uint8), "L").save(tmp_path / "r.png")
    raw = load_map(write_yaml(tmp_path / "r.yaml", "r.png", "mode: raw\n")).data
    np.testing.assert_array_equal(raw, [[FREE, OCCUPIED, UNKNOWN, UNKNOWN]])


def test_one_by_one_map_and_round_trip(tmp_path: Path) -> None:
    Image.fromarray(np.array([[254]], np.uint8), "L").save(tmp_path / "one.png")
    one = load_map(write_yaml(tmp_path / "one.yaml", "one.png"))
    assert one.shape == (1, 1) and one.data[0, 0] == FREE
    rng = np.random.default_rng(3)
    data = rng.choice(np.array([FREE, OCCUPIED, UNKNOWN], np.uint8), size=(7, 11))
    m = OccupancyMap(data, 0.05, (-1.25, 3.5, -0.25))
    for fmt in ("png", "pgm"):
        y = m.save(tmp_path / "out" / f"rt_{fmt}.yaml", image_format=fmt)
        back = load_map(y)
        np.testing.assert_array_equal(back.data, data)
        assert (back.resolution, back.origin) == (0.05, (-1.25, 3.5, -0.25))
        assert back.meta.image_format == fmt
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == [
        "rt_pgm.pgm",
        "rt_pgm.yaml",
        "rt_png.png",
        "rt_png.yaml",
    ]
    with pytest.raises(InvalidArgumentError, match="trinary"):
        save_map(np.full((2, 2), 255, np.uint8), 0.05, (0, 0, 0), tmp_path / "bad.yaml")
    assert not (tmp_path / "bad.yaml").exists()


def test_broken_files_raise_typed_errors_naming_the_problem(tmp_path: Path) -> None:
    Image.fromarray(GREYS, "L").save(tmp_path / "ok.png")
    with pytest.raises(MapFormatError, match="does not exist"):
        load_map(write_yaml(tmp_path / "a.yaml", "missing.png"))
    (tmp_path / "corrupt.png").write_bytes(b"\x89PNG\r\n\x1a\nnot really")
    with pytest.raises(MapFormatError, match="corrupt PNG"):
        load_map(write_yaml(tmp_path / "b.yaml", "corrupt.png"))
    (tmp_path / "c.yaml").write_text("image: ok.png\nresolution: .nan\norigin: [0, 0, 0]\n")
    with pytest.raises(MapFormatError, match="resolution"):
        load_map(tmp_path / "c.yaml")
    (tmp_path / "d.yaml").write_text("image: ok.png\norigin: [0, 0, 0]\n")
    with pytest.raises(MapFormatError, match="missing required key 'resolution'"):
        load_map(tmp_path / "d.yaml")
    with pytest.raises(MapIOError, match="nothere.yaml"):
        load_map(tmp_path / "nothere.yaml")


def test_shared_maps_load(sources: Path) -> None:
    berlin = load_map(sources / "f1tenth-gym/maps/berlin.yaml")
    assert berlin.shape == (600, 600) and berlin.resolution == 0.05
    corner = load_map(sources / "bdevan5-f1tenth-benchmarks/maps/CornerHall.yaml")
    assert corner.meta.mode == "trinary" and corner.meta.image_channels == 4
    spa = load_map(sources / "f1tenth-racetracks/Spa/Spa_map.yaml")
    assert spa.shape == (2000, 2000) and (spa.data == FREE).mean() > 0.9  # thin-line map
    assert load_map(sources / "f1tenth-gym/maps/berlin.yaml").data.shape == (600, 600)


def test_porto_yaml_names_a_missing_image_and_the_error_suggests_the_right_one(sources: Path) -> None:
    with pytest.raises(MapFormatError, match=r"map\.pgm.*does not exist.*image: porto\.pgm"):
        load_map(sources / "f1tenth-simulator/maps/porto.yaml")


def test_the_meta_is_a_typed_read_only_object_that_pickles(tmp_path: Path) -> None:
    """Issue 37: the meta crosses as ``_core.MapMeta`` (closed domains as their names),
    not a dict; a loaded map still pickles (it rides along to worker processes)."""
    import pickle

    from roboracer_arena import _core

    Image.fromarray(GREYS, "L").save(tmp_path / "m.png")
    m = load_map(write_yaml(tmp_path / "m.yaml", "m.png", "mode: scale\n"))
    meta = m.meta
    assert isinstance(meta, _core.MapMeta)
    assert (meta.image_format, meta.mode, meta.image_channels, meta.negate) == ("png", "scale", 1, False)
    assert meta.yaml_path == str(tmp_path / "m.yaml") and m.image_path == tmp_path / "m.png"
    assert "mode" not in meta.defaulted and "negate" in meta.defaulted
    with pytest.raises(AttributeError):
        meta.mode = "raw"  # type: ignore[misc]
    assert repr(meta).startswith(f"MapMeta(yaml_path={str(tmp_path / 'm.yaml')!r}, image_path=")
    back = pickle.loads(pickle.dumps(m))
    assert repr(back.meta) == repr(meta) and np.array_equal(back.data, m.data)


def test_a_map_made_in_memory_has_no_meta_and_no_image() -> None:
    m = OccupancyMap(TRINARY, 0.1, (0.0, 0.0, 0.0))
    assert m.meta is None
    with pytest.raises(InvalidArgumentError, match="no image file"):
        _ = m.image_path

"""BuildConfig: defaults, TOML/JSON loading, and errors that name the file and the field."""

from __future__ import annotations

import json

import pytest

from roboracer_arena.config.build import BuildConfig
from roboracer_arena.errors import ArenaError, ConfigError

# The Rust BuildParams field names the geometry section must mirror exactly.
RUST_BUILD_PARAMS = {
    "wall_height_m",
    "wall_offset_m",
    "tube_diameter_m",
    "tube_segments",
    "ring_spacing_m",
    "ring_width_m",
    "ring_scale",
    "floor_margin_m",
    "simplify_tolerance_m",
    "smoothing_iterations",
    "centreline_spacing_m",
}


def test_defaults_follow_the_paper():
    cfg = BuildConfig()
    assert cfg.geometry.tube_diameter_m == 0.33
    assert cfg.physics.static_friction == cfg.physics.dynamic_friction == 0.83
    assert cfg.usd_format == "usdc"
    assert set(cfg.geometry_params()) == RUST_BUILD_PARAMS


def test_every_field_documents_its_default():
    for model in (
        BuildConfig,
        type(BuildConfig().geometry),
        type(BuildConfig().materials),
        type(BuildConfig().physics),
    ):
        for name, f in model.model_fields.items():
            if name in {"geometry", "materials", "physics"}:
                continue
            assert f.description and len(f.description) > 20, f"{model.__name__}.{name} lacks a reason"


def test_toml(tmp_path):
    p = tmp_path / "build.toml"
    p.write_text(
        'usd_format = "usda"\n[geometry]\ntube_diameter_m = 0.25\nwall_height_m = 0.4\n'
        "[physics]\nstatic_friction = 0.9\n[materials]\ntextures = false\nfloor_colour = [0.1, 0.2, 0.3]\n"
    )
    cfg = BuildConfig.from_file(p)
    assert cfg.usd_format == "usda"
    assert cfg.geometry.tube_diameter_m == 0.25 and cfg.geometry.wall_height_m == 0.4
    assert cfg.physics.static_friction == 0.9 and cfg.physics.dynamic_friction == 0.83
    assert cfg.materials.textures is False and cfg.materials.floor_colour == (0.1, 0.2, 0.3)


def test_json_round_trip(tmp_path):
    cfg = BuildConfig.from_dict({"geometry": {"ring_spacing_m": 2.0}, "physics": {"restitution": 0.5}})
    p = tmp_path / "build.json"
    p.write_text(cfg.model_dump_json())
    assert BuildConfig.from_file(p) == cfg


@pytest.mark.parametrize(
    "text, suffix, field",
    [
        ("[geometry]\ntube_diameter_m = -1\n", ".toml", "geometry.tube_diameter_m"),
        ("[geometry]\ntube_diamter_m = 0.3\n", ".toml", "geometry.tube_diamter_m"),
        ('{"physics": {"static_friction": "slippery"}}', ".json", "physics.static_friction"),
        ('{"usd_format": "obj"}', ".json", "usd_format"),
        ('{"materials": {"duct_colour": [1, 1]}}', ".json", "materials.duct_colour"),
    ],
)
def test_bad_field_names_file_and_field(tmp_path, text, suffix, field):
    p = tmp_path / f"bad{suffix}"
    p.write_text(text)
    with pytest.raises(ConfigError) as e:
        BuildConfig.from_file(p)
    msg = str(e.value)
    assert str(p) in msg and field in msg
    assert isinstance(e.value, ArenaError)


def test_syntax_errors_and_missing_file(tmp_path):
    bad_toml = tmp_path / "x.toml"
    bad_toml.write_text("[geometry\n")
    with pytest.raises(ConfigError, match="x.toml: not valid TOML"):
        BuildConfig.from_file(bad_toml)
    bad_json = tmp_path / "x.json"
    bad_json.write_text("{")
    with pytest.raises(ConfigError, match=r"x.json: .*not valid JSON \(line 1"):
        BuildConfig.from_file(bad_json)
    with pytest.raises(ConfigError, match="cannot read"):
        BuildConfig.from_file(tmp_path / "missing.toml")
    (tmp_path / "list.json").write_text(json.dumps([1, 2]))
    with pytest.raises(ConfigError, match="must be a table/object"):
        BuildConfig.from_file(tmp_path / "list.json")


def test_geometry_defaults_equal_the_rust_build_params():
    """One source of truth: the Rust BuildParams defaults; BuildConfig.geometry mirrors them."""
    from roboracer_arena.maps.corridor import DEFAULT_PARAMS

    assert BuildConfig().geometry_params() == DEFAULT_PARAMS

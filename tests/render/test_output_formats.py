"""Output formats come from the extension and are checked before any work: a wrong one
is bad input (exit 2, naming the supported extensions) before a map is read or a lap
driven; ``.jpg`` writes real JPEG."""

from __future__ import annotations

import pytest
from PIL import Image

from roboracer_arena.cli import EXIT_BAD_INPUT, main
from roboracer_arena.foundation.paths import tracks_dir

SMALL = "gen-l040-w12-h2c1s1-clo-s0"


@pytest.fixture
def no_driving(monkeypatch):
    """Make any attempt to build an env (i.e. to start driving) fail the test."""
    from roboracer_arena.envs import single

    def refuse(*a, **k):
        raise AssertionError("the env was built before the output format was checked")

    monkeypatch.setattr(single.RoboRacerEnv, "__init__", refuse)


def test_preview_writes_real_jpeg(tmp_path, capsys):
    yaml = tracks_dir() / "generated" / SMALL / "map.yaml"
    for name in ("p.jpg", "p.jpeg", "p.png"):
        assert main(["preview", str(yaml), "-o", str(tmp_path / name)]) == 0
        with Image.open(tmp_path / name) as im:
            assert im.format == ("PNG" if name.endswith("png") else "JPEG")


def test_preview_refuses_an_unknown_extension_before_reading_the_map(tmp_path, capsys):
    missing = tmp_path / "no-such-map.yaml"  # the format error must come first
    assert main(["preview", str(missing), "-o", str(tmp_path / "p.bmp")]) == EXIT_BAD_INPUT
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "'.bmp'" in err and ".png" in err and ".jpg" in err
    assert not (tmp_path / "p.bmp").exists()
    assert main(["preview", str(missing), "-o", str(tmp_path / "noext")]) == EXIT_BAD_INPUT


def test_drive_rejects_the_video_format_before_driving(tmp_path, capsys, no_driving):
    assert main(["drive", SMALL, "--gif", str(tmp_path / "x.avi")]) == EXIT_BAD_INPUT
    err = capsys.readouterr().err
    assert "'.avi'" in err and ".gif" in err and ".mp4" in err


def test_drive_mp4_without_the_video_extra_fails_before_driving(tmp_path, capsys, no_driving, monkeypatch):
    from roboracer_arena.render import formats

    monkeypatch.setattr(formats, "_importable", lambda module: False)
    assert main(["drive", SMALL, "--gif", str(tmp_path / "x.mp4")]) == EXIT_BAD_INPUT
    assert "video" in capsys.readouterr().err and not (tmp_path / "x.mp4").exists()


def test_record_episode_and_sheet_check_the_format_first(tmp_path, capsys, monkeypatch):
    from roboracer_arena.errors import ConfigError
    from roboracer_arena.render.video import record_episode

    class NoEnv:
        def reset(self, **kw):
            raise AssertionError("the episode ran before the format was checked")

    with pytest.raises(ConfigError, match="unsupported video format"):
        record_episode(NoEnv(), lambda obs: None, tmp_path / "x.webm")
    assert main(["tracks", "sheet", "-o", str(tmp_path / "s.tiff"), "--limit", "1"]) == EXIT_BAD_INPUT
    assert "'.tiff'" in capsys.readouterr().err

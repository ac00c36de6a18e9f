"""Class 8: an interrupted ``drive --mcap`` used to leave no file at the target and a
large unreadable hidden temporary beside it, and ``McapEpisodeRecorder`` leaked its
temporary on any exception. Now SIGINT and SIGTERM alike finish the recording (whole
and readable up to the interrupt), and every other exit path removes the temporary."""

from __future__ import annotations

import gc
import signal
import time

import pytest

from .conftest import cli, strays

pytestmark = pytest.mark.timeout(120)


def _readable(path) -> int:
    from mcap.reader import make_reader

    with open(path, "rb") as f:
        return sum(1 for _ in make_reader(f).iter_messages())


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM], ids=["SIGINT", "SIGTERM"])
def test_an_interrupted_drive_keeps_a_whole_recording(ellipse_map, tmp_path, sig):
    pytest.importorskip("mcap")
    out = tmp_path / "run.mcap"
    p = cli("drive", str(ellipse_map), "--laps", "200", "--mcap", str(out), "--json", cwd=tmp_path)
    deadline = time.monotonic() + 60
    while not strays(tmp_path) and time.monotonic() < deadline:  # recording has started
        time.sleep(0.05)
    time.sleep(3.0)  # driving by now
    p.send_signal(sig)
    _, err = p.communicate(timeout=60)
    assert p.returncode == 130, err
    assert "Traceback" not in err
    assert _readable(out) > 0 and strays(tmp_path) == []


def test_the_episode_recorder_never_leaks_its_temporary(ellipse_map, tmp_path):
    pytest.importorskip("mcap")
    from roboracer_arena.envs.single import RoboRacerEnv
    from roboracer_arena.ros2.episode_recorder import McapEpisodeRecorder

    env = McapEpisodeRecorder(RoboRacerEnv(track=str(ellipse_map)), tmp_path / "a.mcap")
    env.reset(seed=0)
    assert strays(tmp_path)  # the temporary is there while recording
    env.abort()
    assert strays(tmp_path) == [] and not (tmp_path / "a.mcap").exists()

    def crash() -> None:  # an exception escapes; nobody calls close() or abort()
        rec = McapEpisodeRecorder(RoboRacerEnv(track=str(ellipse_map)), tmp_path / "b.mcap")
        rec.reset(seed=0)
        raise RuntimeError("boom")

    with pytest.raises(RuntimeError):
        crash()
    gc.collect()
    assert strays(tmp_path) == [] and not (tmp_path / "b.mcap").exists()


def test_a_failed_drive_removes_its_recording(ellipse_map, tmp_path):
    pytest.importorskip("mcap")
    from roboracer_arena.drivers import drive_laps
    from roboracer_arena.ros2.episode_recorder import McapEpisodeRecorder

    class Boom(McapEpisodeRecorder):
        def step(self, action):
            raise ValueError("boom")

    with pytest.raises(ValueError):
        drive_laps(str(ellipse_map), 1, env_wrapper=lambda e: Boom(e, tmp_path / "c.mcap"))
    assert strays(tmp_path) == [] and not (tmp_path / "c.mcap").exists()

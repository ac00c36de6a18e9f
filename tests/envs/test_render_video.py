import numpy as np
import pytest
from PIL import Image

from roboracer_arena.drivers import PurePursuitDriver
from roboracer_arena.envs.single import RoboRacerEnv
from roboracer_arena.errors import ConfigError
from roboracer_arena.render.video import record_episode, write_video


def test_render_returns_an_rgb_image_with_the_car(oval):
    env = RoboRacerEnv(
        track=oval, render_mode="rgb_array", render_size=300, reset_poses="grid", sim={"lidar": {"num_beams": 109}}
    )
    env.reset(seed=0)
    img = env.render()
    assert img.dtype == np.uint8 and img.ndim == 3 and img.shape[2] == 3 and max(img.shape[:2]) == 300
    red = (img[..., 0] > 180) & (img[..., 1] < 80) & (img[..., 2] < 80)
    assert red.sum() > 10  # the vehicle is drawn
    assert RoboRacerEnv(track=oval, sim={"lidar": {"num_beams": 9}}).render() is None


def test_record_episode_writes_a_gif(oval, tmp_path):
    env = RoboRacerEnv(
        track=oval, render_mode="rgb_array", render_size=200, time_limit_s=1.0, sim={"lidar": {"num_beams": 109}}
    )
    driver = PurePursuitDriver.for_env(env)
    res = record_episode(env, driver.act, tmp_path / "ep.gif", seed=0, every=2)
    assert res["truncated"] and res["steps"] == 20
    with Image.open(tmp_path / "ep.gif") as im:
        assert im.n_frames == len(res["frames"]) == 11


def test_write_video_rejects_unknown_formats(tmp_path):
    with pytest.raises(ConfigError, match="unsupported"):
        write_video([np.zeros((4, 4, 3), np.uint8)], tmp_path / "x.avi")
    with pytest.raises(ConfigError, match="no frames"):
        write_video([], tmp_path / "x.gif")


def test_write_mp4(tmp_path):
    pytest.importorskip("imageio_ffmpeg")  # the 'video' extra
    import imageio.v3 as iio

    frames = [np.full((101, 99, 3), 20 * i, np.uint8) for i in range(6)]
    path = write_video(frames, tmp_path / "x.mp4", fps=10)
    back = iio.imread(path)
    assert back.shape == (6, 112, 112, 3)

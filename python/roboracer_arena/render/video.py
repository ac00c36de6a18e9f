"""Write episodes to GIF (Pillow) or MP4 (imageio with an ffmpeg/pyav backend, the
``video`` extra), atomically."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import ConfigError
from ..foundation.fileio import atomic_path
from .formats import video_format


def write_video(frames: Sequence[np.ndarray], path: str | Path, fps: float = 20.0) -> Path:
    """Write (H, W, 3) uint8 frames to ``path`` (``.gif`` or ``.mp4``); returns the path."""
    path = Path(path)
    suffix = video_format(path)
    if not frames:
        raise ConfigError(f"{path}: no frames to write")
    if suffix == ".gif":
        from PIL import Image

        imgs = [Image.fromarray(np.asarray(f, dtype=np.uint8)) for f in frames]
        pal = [im.convert("P", palette=Image.Palette.ADAPTIVE, colors=64) for im in imgs]
        with atomic_path(path) as tmp:
            pal[0].save(
                tmp,
                format="GIF",
                save_all=True,
                append_images=pal[1:],
                duration=max(20, round(1000 / fps)),
                loop=0,
                optimize=False,
            )
        return path
    if suffix == ".mp4":
        import imageio.v3 as iio  # present: video_format checked the 'video' extra

        with atomic_path(path) as tmp:
            try:
                iio.imwrite(tmp, np.stack([_pad16(f) for f in frames]), fps=fps, extension=".mp4")
            except Exception as e:  # imageio raises plain errors when no ffmpeg/pyav plugin is present
                raise ConfigError(
                    f"{path}: cannot write MP4 ({e}); install imageio-ffmpeg or av, or write a .gif"
                ) from e
    return path


def _pad16(f: np.ndarray) -> np.ndarray:
    """Pad to multiples of 16 pixels (the codec's macro block) by repeating the edge."""
    h, w = f.shape[:2]
    return np.pad(np.asarray(f, dtype=np.uint8), ((0, -h % 16), (0, -w % 16), (0, 0)), mode="edge")


def record_episode(
    env: Any,
    policy: Callable[[Any], Any],
    path: str | Path | None = None,
    max_steps: int = 10_000,
    seed: int | None = None,
    every: int = 1,
    options: dict[str, Any] | None = None,
) -> dict[str, Any]:
    """Run one episode of a single env (``render_mode="rgb_array"``) with ``policy(obs)``,
    keep every ``every``-th frame and write them to ``path`` if given. Returns a summary
    with the frames, steps, total reward, the final info and whether it terminated."""
    if path is not None:
        video_format(path)  # a bad extension fails before the episode runs
    obs, info = env.reset(seed=seed, options=options)
    frames: list[np.ndarray] = [env.render()]
    total, steps, terminated, truncated = 0.0, 0, False, False
    while steps < max_steps and not (terminated or truncated):
        obs, reward, terminated, truncated, info = env.step(policy(obs))
        total += float(reward)
        steps += 1
        if steps % every == 0 or terminated or truncated:
            frames.append(env.render())
    if path is not None:
        fps = env.metadata.get("render_fps", 20) / every
        write_video(frames, path, fps=fps)
    return {
        "frames": frames,
        "steps": steps,
        "reward": total,
        "info": info,
        "terminated": bool(terminated),
        "truncated": bool(truncated),
    }

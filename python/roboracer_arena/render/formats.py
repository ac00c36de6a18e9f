"""Output formats of pictures and videos, decided by the file extension and checked before
any work is done (a bad ``-o`` fails at once, not after a whole lap has been driven)."""

from __future__ import annotations

from pathlib import Path

from ..errors import ConfigError

#: Picture extensions and the Pillow format each is written in.
IMAGE_FORMATS = {".png": "PNG", ".jpg": "JPEG", ".jpeg": "JPEG"}
#: Video extensions (``.mp4`` needs the ``video`` extra).
VIDEO_FORMATS = (".gif", ".mp4")


def image_format(path: str | Path) -> str:
    """The Pillow format for the picture ``path`` (from its extension); raises
    :class:`ConfigError` naming the supported extensions otherwise."""
    suffix = Path(path).suffix.lower()
    fmt = IMAGE_FORMATS.get(suffix)
    if fmt is None:
        raise ConfigError(
            f"{path}: unsupported picture format {suffix or '(no extension)'!r}; use one of {', '.join(IMAGE_FORMATS)}"
        )
    return fmt


def video_format(path: str | Path) -> str:
    """``".gif"`` or ``".mp4"`` for the video ``path``; raises :class:`ConfigError` for any
    other extension, and for ``.mp4`` when the ``video`` extra (imageio) is missing."""
    suffix = Path(path).suffix.lower()
    if suffix not in VIDEO_FORMATS:
        raise ConfigError(
            f"{path}: unsupported video format {suffix or '(no extension)'!r} (use {' or '.join(VIDEO_FORMATS)})"
        )
    if suffix == ".mp4" and not (_importable("imageio") and (_importable("imageio_ffmpeg") or _importable("av"))):
        raise ConfigError(
            f"{path}: MP4 output needs the 'video' extra (pip install roboracer-arena[video]); or write a .gif"
        )
    return suffix


def _importable(module: str) -> bool:
    from importlib.util import find_spec

    return find_spec(module) is not None

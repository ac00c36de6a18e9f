"""Procedural PNG textures for the stage, drawn with numpy + PIL and written atomically.

Textures are deterministic (fixed seed) and named by their content parameters, so two
stages built into the same folder share one file and a rebuild rewrites identical bytes.
"""

from __future__ import annotations

import io
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np
from PIL import Image

from ..fileio import atomic_write_bytes

TEXTURE_DIR = "textures"


@dataclass(frozen=True)
class Texture:
    """A texture to write: relative asset path (from the stage's folder) and PNG bytes."""

    relpath: str
    png: bytes

    def write(self, stage_dir: Path) -> Path:
        """Write atomically under ``stage_dir``, skipping the write if identical bytes are there."""
        path = stage_dir / self.relpath
        try:
            if path.stat().st_size == len(self.png) and path.read_bytes() == self.png:
                return path
        except OSError:
            pass
        atomic_write_bytes(path, self.png)
        return path


def _png(rgb: np.ndarray) -> bytes:
    buf = io.BytesIO()
    Image.fromarray(np.ascontiguousarray(rgb, dtype=np.uint8), mode="RGB").save(buf, format="PNG", compress_level=6)
    return buf.getvalue()


def _srgb8(colour: tuple[float, float, float]) -> np.ndarray:
    """Linear RGB in [0, 1] → 8-bit sRGB (UsdUVTexture decodes 8-bit PNGs as sRGB)."""
    c = np.clip(np.asarray(colour, dtype=np.float64), 0.0, 1.0)
    s = np.where(c <= 0.0031308, 12.92 * c, 1.055 * np.power(c, 1 / 2.4) - 0.055)
    return np.round(s * 255.0)


@lru_cache(maxsize=16)
def floor_texture(colour: tuple[float, float, float], size: int, seed: int = 7) -> Texture:
    """Hall-floor speckle: the base colour with smooth low-contrast noise and fine grain,
    tileable (noise is built on a periodic grid)."""
    rng = np.random.default_rng(seed)
    # periodic low-frequency noise: sum of a few random Fourier modes
    t = np.arange(size, dtype=np.float32) / size
    low = np.zeros((size, size), dtype=np.float32)
    for _ in range(6):  # separable modes: cos(a + b) = cos a cos b - sin a sin b
        kx, ky = rng.integers(1, 5, size=2)
        phase = rng.uniform(0, 2 * np.pi)
        ax, ay = 2 * np.pi * kx * t + phase, 2 * np.pi * ky * t
        low += np.outer(np.cos(ay), np.cos(ax)) - np.outer(np.sin(ay), np.sin(ax))
    low /= np.abs(low).max() or 1.0
    grain = rng.random((size, size), dtype=np.float32) - 0.5
    shade = 1.0 + 0.06 * low + 0.08 * grain
    rgb = _srgb8(colour)[None, None, :] * shade[..., None]
    return Texture(f"{TEXTURE_DIR}/floor_{_hex(colour)}_{size}.png", _png(np.clip(rgb, 0, 255)))


@lru_cache(maxsize=16)
def duct_texture(colour: tuple[float, float, float], size: int) -> Texture:
    """Air-duct foil: fine ribs across the tube (along texture u) with a soft highlight."""
    u = (np.arange(size) + 0.5) / size
    ribs = 0.88 + 0.12 * (0.5 + 0.5 * np.cos(2 * np.pi * 16 * u))  # 16 ribs per tile
    v = (np.arange(size) + 0.5) / size
    sheen = 0.92 + 0.08 * np.cos(2 * np.pi * v)
    shade = ribs[None, :] * sheen[:, None]
    rgb = _srgb8(colour)[None, None, :] * shade[..., None]
    return Texture(f"{TEXTURE_DIR}/duct_{_hex(colour)}_{size}.png", _png(np.clip(rgb, 0, 255)))


def _hex(colour: tuple[float, float, float]) -> str:
    return "".join(f"{int(v):02x}" for v in _srgb8(colour))

"""Procedural PNG textures for the stage, drawn with numpy + PIL (written with the stage, see ``stage.write_stage``).

Textures are single-channel *shade* maps stored as raw (linear) values around
:data:`SHADE_MEAN`; the material multiplies them by its colour through the UsdUVTexture
``scale`` input. So one texture serves every colour, the files stay small, and a
renderer without textures shows the same mean colour (the texture's ``fallback``).
They are deterministic (fixed seed) and named by their parameters, so stages built into
one folder share the files and a rebuild rewrites identical bytes (or skips the write).
"""

from __future__ import annotations

import io
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np
from PIL import Image, PngImagePlugin  # noqa: F401  (imported here, not inside a timed build)

TEXTURE_DIR = "textures"
SHADE_MEAN = 0.9  # mean texel value; the material's scale is colour / SHADE_MEAN


@dataclass(frozen=True)
class Texture:
    """A texture to write: relative asset path (from the stage's folder) and PNG bytes."""

    relpath: str
    png: bytes

    def present(self, stage_dir: Path) -> bool:
        """Whether ``stage_dir`` already holds this texture with identical bytes (then a
        build shares it instead of rewriting it)."""
        path = stage_dir / self.relpath
        try:
            return path.stat().st_size == len(self.png) and path.read_bytes() == self.png
        except OSError:
            return False


def _png(shade: np.ndarray) -> bytes:
    buf = io.BytesIO()
    img = np.clip(np.round(shade * 255.0), 0, 255).astype(np.uint8)
    Image.fromarray(img, mode="L").save(buf, format="PNG", compress_level=6)
    return buf.getvalue()


@lru_cache(maxsize=8)
def floor_texture(size: int, seed: int = 7) -> Texture:
    """Hall-floor speckle: smooth low-contrast mottling plus fine grain, tileable (the
    mottling is a sum of periodic Fourier modes)."""
    rng = np.random.default_rng(seed)
    t = np.arange(size, dtype=np.float32) / size
    low = np.zeros((size, size), dtype=np.float32)
    for _ in range(6):  # separable modes: cos(a + b) = cos a cos b - sin a sin b
        kx, ky = rng.integers(1, 5, size=2)
        phase = rng.uniform(0, 2 * np.pi)
        ax, ay = 2 * np.pi * kx * t + phase, 2 * np.pi * ky * t
        low += np.outer(np.cos(ay), np.cos(ax)) - np.outer(np.sin(ay), np.sin(ax))
    low /= np.abs(low).max() or 1.0
    grain = rng.random((size, size), dtype=np.float32) - 0.5
    shade = SHADE_MEAN * (1.0 + 0.05 * low + 0.08 * grain)
    return Texture(f"{TEXTURE_DIR}/floor_speckle_{size}.png", _png(shade))


@lru_cache(maxsize=8)
def duct_texture(size: int, ribs: int = 16) -> Texture:
    """Air-duct foil: ``ribs`` fine ribs per tile across the tube (along u)."""
    u = (np.arange(size, dtype=np.float32) + 0.5) / size
    rib = 1.0 + 0.08 * np.cos(2 * np.pi * ribs * u)
    shade = np.broadcast_to(SHADE_MEAN * rib[None, :], (size, size))
    return Texture(f"{TEXTURE_DIR}/duct_ribs_{size}.png", _png(shade))

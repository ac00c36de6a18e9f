"""Building blocks of hostile cases: map files (YAML + image bytes), a small valid ring
map, PNG/PGM headers declaring any size, and the case dict the worker runs."""

from __future__ import annotations

import base64
import io
import struct
import zlib

from PIL import Image

from builder.ringmap import ring_raster

RESOLUTION, ORIGIN = 0.05, "[-5.0, -5.0, 0.0]"


def b64(data: bytes) -> dict:
    return {"b64": base64.b64encode(data).decode()}


def text(s: str, encoding: str = "utf-8") -> dict:
    return {"text": s, "encoding": encoding}


def ring_png(size: int = 120) -> bytes:
    buf = io.BytesIO()
    Image.fromarray(ring_raster(size), mode="L").save(buf, format="PNG")
    return buf.getvalue()


def map_yaml(image: str = "ring.png", resolution: object = RESOLUTION, origin: object = ORIGIN, extra: str = "") -> str:
    return f"image: {image}\nresolution: {resolution}\norigin: {origin}\n{extra}"


def ring_map(**yaml_fields) -> dict:
    """Files of a valid ring map (``ring.yaml`` + ``ring.png``), YAML fields overridable."""
    return {"ring.png": b64(ring_png()), "ring.yaml": text(map_yaml(**yaml_fields))}


def png_declaring(width: int, height: int) -> bytes:
    """A valid-CRC PNG whose IHDR declares ``width`` × ``height`` grey pixels over one
    tiny IDAT: decoders that trust the header allocate it all."""

    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    ihdr = struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(b"\0\0")) + chunk(b"IEND", b"")


def pgm_declaring(width: int, height: int, maxval: int = 255, ascii: bool = True) -> bytes:
    return f"{'P2' if ascii else 'P5'}\n{width} {height}\n{maxval}\n".encode() + (b"0 0 0\n" if ascii else b"\0\0\0\0")


def build_case(cid: str, files: dict, *extra_args: str, **kw) -> dict:
    """``build ring.yaml -o out.usdc`` (the output is the target: absent on failure)."""
    return {
        "id": cid,
        "files": files,
        "argv": ["build", "ring.yaml", "-o", "out.usdc", *extra_args],
        "target": "out.usdc",
        **kw,
    }

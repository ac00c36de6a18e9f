"""The policy file: a numpy ``.npz`` archive (no pickles) holding

* ``header``: UTF-8 JSON (a uint8 array) with ``format`` = ``"roboracer-arena-policy"``,
  ``version`` = 1, ``spec`` (:class:`~.policy.PolicySpec`: observation, network and action),
  ``env`` (the env settings the policy needs: control rate, lidar beams, field of view
  and range) and ``training`` (provenance: recipe, tracks, held-out tracks, seed,
  generations, env-steps, seconds, learning curve);
* ``w0``, ``b0``, ``w1``, ``b1``: the network's layers (float64), shapes from the spec;
* optionally ``adam_m`` and ``adam_v``: the optimiser state, so ``train --resume`` continues
  exactly where a checkpoint left off.

Files are written atomically (a temporary file beside the target, then a rename), so an
interrupted write leaves the previous file whole. Reading refuses, with
:class:`~roboracer_arena.errors.PolicyFileError` naming the file: anything but a regular
file, over 256 MiB, not an npz, a pickle inside, a missing or malformed header, an unknown
format or version, layers of the wrong shape or with non-finite values.
"""

from __future__ import annotations

import io
import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from pydantic import ValidationError

from ..errors import MapIOError, PolicyFileError
from ..foundation.fileio import atomic_write_bytes, parse_json, read_regular_bytes
from .policy import LAYERS, PolicySpec, act, pack, unpack

FORMAT = "roboracer-arena-policy"
VERSION = 1
MAX_BYTES = 256 * 1024 * 1024
_HEADER_MAX = 4 * 1024 * 1024


@dataclass
class Policy:
    """A trained policy: its spec, flat parameters, the env settings it needs and where it
    came from. :meth:`act` maps lidar and odometry to ``[steer rad, speed m/s]``."""

    spec: PolicySpec
    theta: np.ndarray
    env: dict[str, Any] = field(default_factory=dict)
    training: dict[str, Any] = field(default_factory=dict)
    optimiser: dict[str, np.ndarray] | None = None

    def act(self, scan_m: Any, speed: Any, steer: Any, base: Any = None) -> np.ndarray:
        """Commands (N, 2) for N cars: scans (N, num_beams) in metres, speed, steer (N,),
        and with a base controller its command (N, 2)."""
        return act(self.spec, self.theta, np.atleast_2d(scan_m), np.atleast_1d(speed), np.atleast_1d(steer), base)

    def header(self) -> dict[str, Any]:
        return {
            "format": FORMAT,
            "version": VERSION,
            "spec": self.spec.model_dump(mode="json"),
            "env": self.env,
            "training": self.training,
        }

    def to_bytes(self) -> bytes:
        arrays = {k: np.ascontiguousarray(v) for k, v in unpack(self.spec, self.theta).items()}
        if self.optimiser is not None:
            arrays.update({f"adam_{k}": np.asarray(v, np.float64) for k, v in self.optimiser.items()})
        header = json.dumps(self.header(), sort_keys=True, allow_nan=False).encode()
        buf = io.BytesIO()
        arrays["header"] = np.frombuffer(header, dtype=np.uint8)
        savez: Any = np.savez  # numpy's stub types **arrays as its keyword flags
        savez(buf, **arrays)
        return buf.getvalue()

    def save(self, path: str | Path) -> Path:
        """Write the policy to ``path`` atomically (conventionally ``*.npz``)."""
        atomic_write_bytes(path, self.to_bytes())
        return Path(path)


def load_policy(path: str | Path) -> Policy:
    """Read a policy file (see the module docstring); :class:`PolicyFileError` if it is not one."""
    path = Path(path)
    try:
        data = read_regular_bytes(path, "policy file", MAX_BYTES)
    except MapIOError as e:
        raise PolicyFileError(str(e)) from None
    return policy_from_bytes(data, path)


def policy_from_bytes(data: bytes, where: str | Path = "<bytes>") -> Policy:
    """:func:`load_policy` of a file's bytes (``where`` names it in errors)."""

    def bad(why: str) -> PolicyFileError:
        return PolicyFileError(f"{where}: not a usable policy file: {why}")

    if not data.startswith(b"PK"):
        raise bad("not an npz archive (no zip signature)")
    try:
        npz = np.load(io.BytesIO(data), allow_pickle=False)
        if not isinstance(npz, np.lib.npyio.NpzFile):
            raise bad("it holds one array, not an npz archive")
        with npz:
            arrays = {k: npz[k] for k in npz.files}
    except Exception as e:
        if isinstance(e, PolicyFileError):
            raise
        raise bad(
            f"not a readable npz archive ({str(e).splitlines()[0][:120] if str(e) else type(e).__name__})"
        ) from None
    raw = arrays.get("header")
    if raw is None or raw.dtype != np.uint8 or raw.ndim != 1 or raw.size > _HEADER_MAX:
        raise bad("no header (a 1-D uint8 array of JSON)")
    try:
        text = raw.tobytes().decode("utf-8")
    except UnicodeDecodeError:
        raise bad("the header is not UTF-8") from None
    header = parse_json(text, where, "policy header", PolicyFileError)
    if not isinstance(header, dict):
        raise bad("the header is not a JSON object")
    if header.get("format") != FORMAT:
        raise bad(f"format is {header.get('format')!r}, expected {FORMAT!r}")
    if header.get("version") != VERSION:
        raise bad(f"format version {header.get('version')!r} is not supported (this release reads {VERSION})")
    try:
        spec = PolicySpec.model_validate(header.get("spec"))
    except ValidationError as e:
        err = e.errors()[0]
        loc = ".".join(str(p) for p in err["loc"]) or "spec"
        raise bad(f"spec.{loc}: {err['msg']}") from None
    for key in ("env", "training"):
        if not isinstance(header.get(key, {}), dict):
            raise bad(f"header.{key} is not a JSON object")
    layers = {}
    for name, shape in spec.shapes().items():
        a = arrays.get(name)
        if a is None:
            raise bad(f"layer {name} is missing")
        if a.shape != shape or a.dtype.kind != "f":
            raise bad(f"layer {name} is {a.dtype} {a.shape}, the spec needs float {shape}")
        if not np.isfinite(a).all():
            raise bad(f"layer {name} holds non-finite values")
        layers[name] = a
    theta = pack(spec, layers)
    opt = None
    if "adam_m" in arrays and "adam_v" in arrays:
        m, v = arrays["adam_m"], arrays["adam_v"]
        if m.shape != theta.shape or v.shape != theta.shape or not (np.isfinite(m).all() and np.isfinite(v).all()):
            raise bad("the optimiser state does not match the layers")
        opt = {"m": m.astype(np.float64), "v": v.astype(np.float64)}
    extra = set(arrays) - {"header", *LAYERS, "adam_m", "adam_v"}
    if extra:
        raise bad(f"unknown arrays {sorted(extra)[:4]}")
    return Policy(spec, theta, dict(header.get("env", {})), dict(header.get("training", {})), opt)

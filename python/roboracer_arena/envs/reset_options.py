"""Parse ``reset(options=...)`` of the single and the vector env.

Keys (all optional):

* ``"track_ids"`` (vector: (E,) ints; single: one int) or ``"track_id"`` (one int for
  every reset env): the track of each reset env, an index into ``env.tracks``;
* ``"poses"``: start poses x, y, yaw (map frame, m and rad) -- single env (V, 3), or (3,)
  with one vehicle; vector env (E, V, 3), or (E, 3) with one vehicle per env. Rows of envs
  that are not reset are ignored. The poses are used as given (no start noise).
* ``"speeds"``: forward start speeds (m/s) -- single env (V,) or a number; vector env
  (E, V) or (E,): a rolling start (default: ``start_speed_noise`` draws, else at rest).
* ``"reset_mask"`` (vector env only, handled there): which envs to reset.

Other keys are ignored with a warning (wrappers may pass their own options through).
"""

from __future__ import annotations

import warnings
from collections.abc import Mapping
from typing import Any

import numpy as np

from ..errors import ConfigError

KNOWN = ("track_id", "track_ids", "poses", "speeds", "reset_mask")


def reset_options(
    options: Mapping[str, Any] | None, num_envs: int, vehicles: int, num_tracks: int, single: bool
) -> tuple[np.ndarray | None, np.ndarray | None, np.ndarray | None]:
    """(track_ids (E,), poses (E, V, 3), speeds (E, V)), each None when not given."""
    if not options:
        return None, None, None
    unknown = [k for k in options if k not in KNOWN]
    if unknown:  # other keys may be meant for wrappers (gymnasium passes options through): warn only
        warnings.warn(f"reset options {unknown} are not used by RoboRacerArena (it reads {list(KNOWN)})", stacklevel=3)
    if "track_id" in options and "track_ids" in options:
        raise ConfigError("reset options: give track_id or track_ids, not both")
    ids = None
    raw = options.get("track_ids", options.get("track_id"))
    if raw is not None:
        arr = np.asarray(raw)
        if arr.ndim == 0 or (single and arr.size == 1):
            arr = np.full(num_envs, arr.reshape(-1)[0])
        if arr.shape != (num_envs,) or not np.issubdtype(arr.dtype, np.integer):
            raise ConfigError(f"reset option track_ids must be an int or {num_envs} ints, got {raw!r}")
        if (arr < 0).any() or (arr >= num_tracks).any():
            raise ConfigError(f"reset option track_ids {arr.tolist()} out of range (0..{num_tracks - 1})")
        ids = arr.astype(np.int64)
    poses = None
    if options.get("poses") is not None:
        p = np.asarray(options["poses"], dtype=np.float64)
        want = (num_envs, vehicles, 3)
        if single:
            p = p[None]
        if vehicles == 1 and p.shape == (num_envs, 3):
            p = p[:, None]
        if p.shape != want:
            shape = ((vehicles, 3) if vehicles > 1 else "(3,)") if single else want
            raise ConfigError(f"reset option poses must have shape {shape}, got {np.shape(options['poses'])}")
        poses = p
    speeds = None
    if options.get("speeds") is not None:
        sp = np.asarray(options["speeds"], dtype=np.float64)
        if single and sp.ndim <= 1 and sp.size in (1, vehicles):
            sp = np.broadcast_to(sp, (vehicles,))[None]
        elif vehicles == 1 and sp.shape == (num_envs,):
            sp = sp[:, None]
        if sp.shape != (num_envs, vehicles):
            raise ConfigError(
                f"reset option speeds must have shape {(vehicles,) if single else (num_envs, vehicles)}, "
                f"got {np.shape(options['speeds'])}"
            )
        speeds = sp
    return ids, poses, speeds


def reset_mask(options: Mapping[str, Any] | None, num_envs: int) -> np.ndarray | None:
    """The ``reset_mask`` option as (E,) bools, or None when not given. Only booleans (or
    0/1 integers) of the right length are accepted: a string, floats or a wrong length is
    a :class:`ConfigError`, never "reset everything"."""
    raw = None if not options else options.get("reset_mask")
    if raw is None:
        return None
    arr = np.asarray(raw) if not isinstance(raw, (str, bytes)) else np.asarray([raw])
    ok_kind = arr.dtype.kind == "b" or (arr.dtype.kind in "iu" and bool(((arr == 0) | (arr == 1)).all()))
    if not ok_kind or arr.shape != (num_envs,):
        raise ConfigError(f"reset option reset_mask must be {num_envs} booleans, got {raw!r:.80}")
    return arr.astype(bool)
